// Every sheet in every fast path: on the shipped two-sheet kiosk, the model PSF, the model image,
// sweeps and the full viewing-zone pass include the sheet across the half mirror from the display
// (reached by reflection in it) as well as the one behind it, and the tracer, which follows every
// path, agrees with their sum.
#include <gtest/gtest.h>

#include <cmath>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/sweep.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The kiosk with a uniform, Lambertian display, so that the aerial image's radiance is the model
// brightness times the display's intensity.
scene kiosk(int size = 96) {
  scene s = load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json");
  s.source.image.clear();
  s.source.emission_profile.clear();
  s.observer.width = s.observer.height = size;
  return s;
}

scene only_sheet(scene s, std::size_t sheet) {
  s.retroreflectors = {s.retroreflectors.at(sheet)};
  return s;
}

// Sheet 1 kept in place, but black: an ideal sheet that returns nothing.
scene sheet_1_absorbing(scene s) {
  s.retroreflectors.at(1).model = {.type = "ideal", .values = {{"mu", 0.0}}};
  return s;
}

double psf_brightness(const scene& s) {
  return sample_psf(s, make_sheet_models(s), {.samples = 40000, .seed = 3}).brightness();
}

using test::traced_aerial_at_centre;

}  // namespace

TEST(EverySheet, KioskModelBrightnessIsTheSumOfItsSheets) {
  const scene both = kiosk();
  const psf_samples psf = sample_psf(both, make_sheet_models(both), {.samples = 40000, .seed = 3});
  ASSERT_EQ(psf.sheets.size(), 2u);
  EXPECT_TRUE(psf.sheets[0].missed.empty()) << psf.sheets[0].missed;
  EXPECT_TRUE(psf.sheets[1].missed.empty()) << psf.sheets[1].missed;
  EXPECT_FALSE(psf.sheets[0].by_reflection);
  EXPECT_TRUE(psf.sheets[1].by_reflection);

  const double alone0 = psf_brightness(only_sheet(both, 0)), alone1 = psf_brightness(only_sheet(both, 1));
  std::printf("kiosk model brightness: both %.6f, sheet 0 alone %.6f, sheet 1 alone %.6f\n", psf.brightness(), alone0,
              alone1);
  EXPECT_GT(alone1, 0.3 * alone0) << "sheet 1 alone reaches the aerial image";
  EXPECT_NEAR(psf.brightness(), alone0 + alone1, 0.01 * psf.brightness());
  EXPECT_NEAR(psf.sheets[0].brightness, alone0, 1e-12);
  EXPECT_NEAR(psf.sheets[1].brightness, alone1, 1e-12);
}

TEST(EverySheet, TracerAgreesWithTheModelForBothSheetsAndEachAlone) {
  const scene both = kiosk();
  for (const auto& [name, s] : {std::pair{"both sheets", both}, std::pair{"sheet 0 alone", only_sheet(both, 0)},
                                std::pair{"sheet 1 alone", only_sheet(both, 1)}}) {
    const double model = psf_brightness(s) * s.source.intensity;
    const double traced = traced_aerial_at_centre(s, 64);
    std::printf("%s: traced aerial %.5f, model %.5f (%+.2f%%)\n", name, traced, model, 100 * (traced / model - 1));
    EXPECT_NEAR(traced, model, 0.03 * model) << name;
  }
}

// The kiosk as shipped emits by its LCD's profile (lcd_typical.csv): the model PSF's brightness
// counts it in each sample's direction as the tracer does (without, the model read 7% above the
// render), and so does the model image.
TEST(EverySheet, TheDisplaysEmissionProfileDimsTheModelAsItDimsTheRender) {
  scene s = load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json");
  s.source.image.clear();
  s.observer.width = s.observer.height = 96;
  ASSERT_FALSE(s.source.emission_profile.empty());
  scene lambertian = s;
  lambertian.source.emission_profile.clear();
  const double model = psf_brightness(s) * s.source.intensity;
  const double model_lambertian = psf_brightness(lambertian) * s.source.intensity;
  const double traced = traced_aerial_at_centre(s, 64);
  std::printf("kiosk with its profile: traced aerial %.5f, model %.5f (%+.2f%%), model without the profile %.5f\n",
              traced, model, 100 * (traced / model - 1), model_lambertian);
  EXPECT_LT(model, 0.97 * model_lambertian) << "the profile dims the aerial image";
  EXPECT_NEAR(traced, model, 0.01 * model);
  const auto m =
      compute_layout_model_image(s, make_sheet_models(s), nullptr, model_image_params::for_image(96, 96, true));
  ASSERT_TRUE(m);
  const glm::dvec2 c = camera_project(make_camera(s), aerial_image_center(s));
  EXPECT_NEAR(m->image.at(int(c.x), int(c.y))[1], model, 0.03 * model);
}

TEST(EverySheet, ModelImageAndFirstLookAddTheSheets) {
  const scene both = kiosk(64);
  const retro_model_list models = make_sheet_models(both);
  const auto m = compute_layout_model_image(both, models, nullptr, model_image_params::for_image(64, 64, true));
  ASSERT_TRUE(m);
  ASSERT_EQ(m->sheets.size(), 2u);
  EXPECT_TRUE(m->left_out.empty());
  const glm::dvec2 c = camera_project(make_camera(both), aerial_image_center(both));
  const double model = psf_brightness(both) * both.source.intensity;
  EXPECT_NEAR(m->image.at(int(c.x), int(c.y))[1], model, 0.03 * model);
  const image_rgb first = model_image_first_look(both, models, nullptr);
  ASSERT_EQ(first.width, 64);
  EXPECT_NEAR(first.at(int(c.x), int(c.y))[1], model, 0.05 * model);
  // Sheet 1 alone: a model image of its own, a sheet reached by reflection.
  const scene one = only_sheet(both, 1);
  const auto m1 =
      compute_layout_model_image(one, make_sheet_models(one), nullptr, model_image_params::for_image(64, 64, true));
  ASSERT_TRUE(m1);
  const double model1 = psf_brightness(one) * one.source.intensity;
  EXPECT_NEAR(m1->image.at(int(c.x), int(c.y))[1], model1, 0.03 * model1);
}

TEST(EverySheet, SweepsSeeSheetOne) {
  sweep_params p;
  p.axes = {parse_sweep_axis("floating_distance=120:160:20")};
  p.psf_route = true;
  p.psf_samples = 20000;
  const scene both = kiosk(64);
  const sweep_result with = run_sweep(both, p), without = run_sweep(only_sheet(both, 0), p),
                     absorbing = run_sweep(sheet_1_absorbing(both), p);
  ASSERT_EQ(with.points.size(), 3u);
  ASSERT_EQ(without.points.size(), 3u);
  ASSERT_EQ(absorbing.points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_EQ(with.points[i].sheet_brightness.size(), 2u);
    EXPECT_GT(with.points[i].sheet_brightness[1], 0.0);
    EXPECT_GT(with.points[i].brightness, 1.5 * without.points[i].brightness) << i;
    EXPECT_NE(with.points[i].r50_mm, without.points[i].r50_mm) << i;
    EXPECT_NE(with.points[i].mean_mtf, without.points[i].mean_mtf) << i;
    EXPECT_EQ(absorbing.points[i].brightness, without.points[i].brightness) << i;
    EXPECT_EQ(absorbing.points[i].r50_mm, without.points[i].r50_mm) << i;
    EXPECT_EQ(absorbing.points[i].mean_mtf, without.points[i].mean_mtf) << i;
  }
}

TEST(EverySheet, FullViewingZoneSeesSheetOne) {
  eye_grid g;
  g.nx = g.ny = 3;
  g.x_min = g.y_min = -60;
  g.x_max = g.y_max = 60;
  const full_zone_params p{.rows_per_eye = 16, .render_size = 24, .render_spp = 4, .psf_samples = 2000};
  const scene both = kiosk(64);
  const full_zone_map with = full_viewing_zone(both, g, p), without = full_viewing_zone(only_sheet(both, 0), g, p),
                      absorbing = full_viewing_zone(sheet_1_absorbing(both), g, p);
  ASSERT_EQ(with.mean_mtf.size(), 9u);
  int differ = 0, compared = 0;
  for (std::size_t e = 0; e < 9; ++e) {
    if (!std::isfinite(without.mean_mtf[e])) continue;
    ++compared;
    differ += with.mean_mtf[e] != without.mean_mtf[e];
    EXPECT_EQ(absorbing.mean_mtf[e], without.mean_mtf[e]) << e;
    EXPECT_EQ(absorbing.brightness[e], without.brightness[e]) << e;
    EXPECT_EQ(absorbing.stray_ratio[e], without.stray_ratio[e]) << e;
  }
  EXPECT_GT(compared, 3);
  EXPECT_GT(differ, 0) << "sheet 1 changes the blur where both sheets are seen";
}
