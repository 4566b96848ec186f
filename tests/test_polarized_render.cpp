// The tracer with polarization (docs/polarization.md): a scene that does not polarize renders as
// the polarized tracer renders it, and the polarization-modulated AIRR (a reflective polarizer in
// place of the half mirror, a quarter-wave film on the sheet) gains what the analytic ceilings say.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/embree.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The bench with a uniform 50 mm display and the ideal sheet: the aerial image's centre is
// R T intensity = 2.5 with the plain half mirror.
scene bench() { return test::uniform_source_scene(50, 48); }

// The polarization-modulated AIRR on the bench: a reflective polarizer passing light along its
// height axis (reflecting the display's light polarized along the hinge, s light), and a
// quarter-wave film at 45 deg on the sheet.
scene p_airr(const scene& base, double film_waves = 0.25) {
  scene s = base;
  s.half_mirror.kind = half_mirror_kind::reflective_polarizer;
  s.half_mirror.polarizer = {.axis_deg = 90};
  derive_half_mirror_light(s.half_mirror);
  if (film_waves > 0) s.sheet().films = {film_params{.axis_deg = 45, .retardance_waves = film_waves}};
  return s;
}

double aerial_centre(const scene& s, std::uint64_t spp = 8) { return test::centre_mean(test::render_to(s, spp), 4); }

// The traced aerial component (retroreflected light alone, as the model PSF counts it) over the
// 8 x 8 pixels at the image's centre, the mean of its channels: a film's retardance is its
// design's at green alone, and the model PSF's white is the channels' mean.
double aerial_white_at_centre(const scene& s, std::uint64_t spp) {
  render_session session(s, {.threads = 2, .target_spp = spp, .components = true});
  const render_snapshot snap = session.wait_for(0, spp);
  const image_rgb aerial = snap.component_image(component_aerial);
  double sum = 0;
  int n = 0;
  for (int y = aerial.height / 2 - 4; y < aerial.height / 2 + 4; ++y) {
    for (int x = aerial.width / 2 - 4; x < aerial.width / 2 + 4; ++x) {
      const float* p = aerial.at(x, y);
      sum += (double(p[0]) + p[1] + p[2]) / 3;
      ++n;
    }
  }
  return sum / n;
}

}  // namespace

// Forced onto a scene that does not polarize, the polarized tracer sees the same samples and keeps
// each one's value: unpolarized light, mirrors that keep S0, no polarizer anywhere.
TEST(PolarizedRender, TheForcedPolarizedTracerRendersWhatThePlainOneDoes) {
  for (const std::string name : {"default", "two_sheet_kiosk"}) {
    const scene s = load_scene(asset_dir() + "/scenes/" + name + ".json");
    embree_device device;
    tracer_scene plain, forced;
    forced.force_polarized = true;
    build_tracer_scene(plain, device, s);
    build_tracer_scene(forced, device, s);
    ASSERT_FALSE(plain.polarized);
    ASSERT_TRUE(forced.polarized);
    double worst = 0, total = 0;
    std::uint64_t rays = 0;
    for (int y = 0; y < plain.camera.height; y += 7) {
      for (int x = 0; x < plain.camera.width; x += 7) {
        for (std::uint64_t i = 0; i < 4; ++i) {
          const glm::vec3 a = trace_sample(plain, x, y, i, rays), b = trace_sample(forced, x, y, i, rays);
          for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, double(std::abs(a[c] - b[c])) / std::max(1e-3f, std::abs(a[c])));
            total += a[c];
          }
        }
      }
    }
    std::printf("%s: worst relative difference %.2e over samples summing to %.1f\n", name.c_str(), worst, total);
    EXPECT_GT(total, 0);
    EXPECT_LT(worst, 1e-5) << name;
  }
}

// The analytic ceilings of p-AIRR with ideal parts: twice the half mirror's aerial image for an
// unpolarized display (half its light reflected, all of that passed), four times for a display
// polarized along the polarizer's block axis. Without the film the light comes back as it left
// and is reflected away; a display polarized along the pass axis sends (almost) nothing to the
// sheet.
TEST(PolarizedRender, PAirrGainsTwiceForUnpolarizedAndFourTimesForPolarizedLight) {
  const scene base = bench();
  const double half_mirror = aerial_centre(base);
  EXPECT_NEAR(half_mirror, 2.5, 0.025);

  const double unpolarized = aerial_centre(p_airr(base));
  scene lcd = p_airr(base);
  lcd.source.polarization = {.state = light_state::linear, .angle_deg = 0};
  const double polarized = aerial_centre(lcd);
  scene wrong_lcd = lcd;
  wrong_lcd.source.polarization.angle_deg = 90;
  const double crossed = aerial_centre(wrong_lcd);
  const double no_film = aerial_centre(p_airr(base, 0));
  scene oled = p_airr(base);
  oled.source.polarization = {.state = light_state::circular_positive};
  const double circular = aerial_centre(oled);
  std::printf(
      "aerial image centre: half mirror %.4f; p-AIRR: unpolarized %.4f (gain %.4f), linear along the block axis "
      "%.4f (gain %.4f), along the pass axis %.4f, circular %.4f, no film %.4f\n",
      half_mirror, unpolarized, unpolarized / half_mirror, polarized, polarized / half_mirror, crossed, circular,
      no_film);
  EXPECT_NEAR(unpolarized / half_mirror, 2.00, 0.02);
  EXPECT_NEAR(polarized / half_mirror, 4.00, 0.04);
  EXPECT_NEAR(circular / half_mirror, 2.00, 0.02);  // circular light is half s, half p
  // Off the axis the display's rays meet the polarizer's axes a little askew: what they leak is
  // that small.
  EXPECT_LT(crossed, 1e-3 * polarized);
  EXPECT_LT(std::abs(no_film), 1e-3 * polarized);

  // A film of the wrong retardance converts only sin^2(2 pi waves) of the light, there and back.
  const double eighth = aerial_centre(p_airr(base, 0.125));
  EXPECT_NEAR(eighth / unpolarized, std::pow(std::sin(2 * pi * 0.125), 2), 0.01);
}

// The observer's polarizer: p-AIRR's aerial light leaves polarized along the polarizer's pass
// axis (vertical in the image), so an analyzer passes cos^2 of its angle from vertical (Malus);
// the plain half mirror's aerial light is unpolarized, of which any analyzer passes half.
TEST(PolarizedRender, AnAnalyzerBeforeTheObserverFollowsMalussLaw) {
  const scene base = bench();
  const double open = aerial_centre(p_airr(base));
  for (double deg : {90.0, 60.0, 30.0, 0.0}) {
    scene s = p_airr(base);
    s.observer.analyzer_deg = deg;
    const double seen = aerial_centre(s);
    const double expected = open * std::pow(std::cos(radians(90 - deg)), 2);
    EXPECT_NEAR(seen, expected, 0.01 * open + 1e-6) << deg << " deg";
  }
  scene plain = base;
  plain.observer.analyzer_deg = 20;
  EXPECT_NEAR(aerial_centre(plain) / aerial_centre(base), 0.5, 0.01);
}

// `airr gain` prints the aerial image's brightness against the same layout with a plain half
// mirror: p-AIRR with ideal parts and an unpolarized display doubles it.
TEST(PolarizedRender, GainCommandComparesWithAPlainHalfMirror) {
  test::temp_dir dir;
  save_scene(p_airr(bench()), dir.file("p_airr.json"));
  const auto r = test::run_cli("gain " + dir.file("p_airr.json") + " --spp 2 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto at = r.out.rfind("gain: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  // Over the whole image, not the centre alone: rays off the axis meet the polarizer a little askew.
  EXPECT_NEAR(std::stod(r.out.substr(at + 6)), 2.0, 0.05) << r.out;
  EXPECT_NE(r.out.find("with a plain half mirror (R = T = 0.5, no films): "), std::string::npos) << r.out;

  // The layout as a plain half mirror leaves it: no gain.
  const auto plain = test::run_cli("gain " + dir.file("p_airr.json") +
                                   " --spp 2 --threads 2 --set half_mirror.kind=half_mirror --set "
                                   "retroreflectors.0.films=[]");
  ASSERT_EQ(plain.exit_code, 0) << plain.out;
  EXPECT_NE(plain.out.find("gain: 1.0000x"), std::string::npos) << plain.out;

  const auto bad = test::run_cli("gain " + dir.file("p_airr.json") + " --set retroreflectors.0.films.0.axis_deg=\"x\"");
  test::expect_one_line_error(bad, {dir.file("p_airr.json"), "retroreflectors[0].films[0].axis_deg: must be a number"});
}

// The model PSF follows the chief path's polarization as the tracer follows each path's: for
// p-AIRR with an LCD, on the ideal, the RF-Ay-like (aluminium) and a TIR prism sheet, the traced
// aerial image's centre is the display's intensity times the model PSF's brightness within 1%
// (the aerial component: the TIR sheet's plate also reflects the display back to the centre, and
// the quarter-wave film turns that light too), and for the TIR sheet their gains over a half mirror
// agree within 1%.
TEST(PolarizedRender, TheTracersBrightnessIsTheModelPsfs) {
  const std::vector<std::pair<std::string, std::vector<scene_override>>> sheets = {
      {"ideal", {}},
      {"RF-Ay-like",
       {{"retroreflectors.0.model.type", "prism_sheet"},
        {"retroreflectors.0.model.pitch_mm", "1.16"},
        {"retroreflectors.0.model.index", "1"},
        {"retroreflectors.0.model.plate_mm", "0"},
        {"retroreflectors.0.model.coating", "metal"},
        {"retroreflectors.0.model.face_reflectance", "0.83"}}},
      {"TIR prisms", {{"retroreflectors.0.model.type", "prism_sheet"}}},
  };
  for (const auto& [name, overrides] : sheets) {
    scene s = p_airr(bench());
    s.source.polarization = {.state = light_state::linear, .angle_deg = 0};
    s = with_overrides(s, overrides, name);
    const double psf = sample_psf(s, make_sheet_models(s), {.samples = 100000, .seed = 3}).brightness();
    const double traced = aerial_white_at_centre(s, 32) / s.source.intensity;
    scene plain = s;
    plain.half_mirror = half_mirror_params{};
    plain.half_mirror.pose = s.half_mirror.pose;
    plain.sheet().films.clear();
    plain.source.polarization = {};
    const double unpolarized = sample_psf(plain, make_sheet_models(plain), {.samples = 100000, .seed = 3}).brightness();
    const double traced_plain = aerial_white_at_centre(plain, 32) / s.source.intensity;
    std::printf(
        "%s: model PSF brightness %.5f, traced %.5f (%+.2f%%); with a half mirror %.5f, traced %.5f (%+.2f%%), "
        "gain %.3f\n",
        name.c_str(), psf, traced, 100 * (traced / psf - 1), unpolarized, traced_plain,
        100 * (traced_plain / unpolarized - 1), psf / unpolarized);
    // The TIR sheet's PSF (0.1 mm prisms, their face orders diffracting apart) reaches past the
    // 50 mm display, which the model PSF's brightness counts and the display's centre does not
    // see: for it the gain is compared.
    if (name == "TIR prisms") {
      EXPECT_NEAR((traced / traced_plain) / (psf / unpolarized), 1, 0.01) << name;
    } else {
      EXPECT_NEAR(traced / psf, 1, 0.01) << name;
      EXPECT_NEAR(traced_plain / unpolarized, 1, 0.01) << name;
    }
  }
}
