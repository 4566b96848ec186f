// The bokeh views: the 2D model PSF, through focus, and the spot matrix across the aerial image,
// each against a truth of its own (geometry, the PSF's samples, the model at another angle).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "airr/analysis/bokeh.hpp"
#include "airr/analysis/psf_grid.hpp"
#include "airr/core/csv_table.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/psf_focus.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/traced_psf.hpp"
#include "airr/models/retro_model.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

scene preset_bench(const std::string& preset, const std::string& lookup = "per_ray") {
  scene s = test::uniform_source_scene(50, 128);
  s.sheet().model.type = "sinc_shift";
  set_model_value(s.sheet().model, "preset", preset);
  set_model_value(s.sheet().model, "lookup", lookup);
  return s;
}

double polygon_area(const std::vector<cv::Point2d>& p) {
  double twice = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const cv::Point2d& a = p[i];
    const cv::Point2d& b = p[(i + 1) % p.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return std::abs(twice) / 2;
}

double hull_area(const psf_samples& psf) {
  std::vector<cv::Point2f> pts;
  for (const glm::dvec2& o : psf.offset_mm) pts.emplace_back(float(o.x), float(o.y));
  std::vector<cv::Point2f> hull;
  cv::convexHull(pts, hull);
  return cv::contourArea(hull);
}

}  // namespace

// An exact retroreflector returns every ray through the aerial point: at an offset z along the
// chief ray the spot is the sheet seen from the aerial point (its corners projected through it),
// scaled by z over the distance; at z = 0 it has no width.
TEST(Bokeh, IdealSheetThroughFocusIsTheSheetSeenFromTheAerialPoint) {
  scene s = test::uniform_source_scene(50, 64);
  s.sheet().width_mm = s.sheet().height_mm = 100;
  s.sheet().pose.pitch_deg = 15;  // a tilted sheet: its spot is a trapezoid
  check_layout(s, "test");
  const glm::dvec3 p = aerial_image_center(s);
  const focus_bundle b = sample_focus_bundle(s, make_sheet_models(s), {.samples = 60000, .seed = 5}, p);
  const glm::dvec3 axis = glm::normalize(make_camera(s).position - p);

  const psf_samples waist = cut_focus_bundle(b, 0.0);
  double widest = 0;
  for (const glm::dvec2& o : waist.offset_mm) widest = std::max(widest, glm::length(o));
  EXPECT_LT(widest, 1e-6);

  for (double z : {-20.0, 10.0, 30.0}) {
    std::vector<cv::Point2d> expected;
    for (const glm::dvec3& c : corners(retroreflector_frame(s))) {
      const glm::dvec3 x = p + (p - c) * (z / glm::dot(p - c, axis)) - (p + z * axis);
      expected.emplace_back(glm::dot(x, b.x_axis), glm::dot(x, b.y_axis));
    }
    const double truth = polygon_area(expected), measured = hull_area(cut_focus_bundle(b, z));
    std::printf("z %+.0f mm: spot %.4f mm^2, the sheet seen from the aerial point %.4f mm^2 (%+.3f%%)\n", z, measured,
                truth, 100 * (measured / truth - 1));
    EXPECT_NEAR(measured / truth, 1.0, 0.03)
        << "z " << z << " mm: spot " << measured << " mm^2, sheet seen " << truth << " mm^2";
  }
}

// The picture holds the PSF's brightness, and its middle row reads as the cross-section binned
// from the same samples (the picture's bilinear weights smooth it a little).
TEST(Bokeh, PictureIntegratesToTheBrightnessAndItsMiddleRowIsTheCrossSection) {
  const scene s = preset_bench("rf-ay");
  const psf_samples psf = sample_psf(s, make_sheet_models(s), {.samples = 400000, .seed = 7});
  const double half = analysis::psf_picture_half_width(psf, true);
  const int size = 257;
  const analysis::psf_grid g = analysis::psf_to_grid(psf, size, 2 * half / size);
  std::printf("picture holds %.4f of the brightness %.6f\n", g.integral() / psf.brightness(), psf.brightness());
  EXPECT_NEAR(g.integral() / psf.brightness(), 1.0, 0.005);

  const double r50 = energy_radius(psf);
  const int bins = 2 * int(std::ceil(2 * r50 / g.mm_per_pixel)) + 1;  // one per pixel over +-2 r50
  const double band = g.mm_per_pixel;
  const analysis::psf_section section = analysis::psf_cross_section(psf, 0.5 * bins * g.mm_per_pixel, band, bins);
  const int mid = size / 2;
  double total = 0;
  for (double w : psf.weight) total += w;
  double worst = 0;
  for (int b = 0; b < bins; ++b) {
    const double row = g.at(mid - bins / 2 + b, mid) / psf.brightness();
    // The section bin's count and its binomial spread.
    const double count = section.density[b] * (2 * band * g.mm_per_pixel) * psf.offset_mm.size();
    const double sigma = section.density[b] / std::sqrt(std::max(count, 1.0));
    EXPECT_NEAR(row, section.density[b], 4 * sigma + 0.05 * section.density[b])
        << "x " << section.x_mm[b] << " mm (" << count << " samples)";
    worst = std::max(worst, std::abs(row - section.density[b]) / std::max(sigma, 1e-12));
  }
  std::printf("middle row against the cross-section over +-2 r50 (%d bins): at most %.2f sd apart\n", bins, worst);
}

// Across the image: with per-ray lookup each point's PSF follows its own incidence on a tilted
// sheet, so a corner's r50 moves from the centre's the way the model moves with that angle; with
// per-render lookup the whole image uses one angle and the corners agree with the centre.
TEST(Bokeh, SpotMatrixFollowsThePerRayAngle) {
  const psf_params p{.samples = 100000, .seed = 11};
  for (const char* preset : {"rf-an", "rf-ay"}) {
    scene s = preset_bench(preset, "per_ray");
    s.sheet().pose.pitch_deg = 20;
    const analysis::spot_matrix m = analysis::compute_spot_matrix(s, make_sheet_models(s), 3, p, 65);
    const analysis::field_spot& centre = m.spots[4];
    ASSERT_TRUE(centre.missed.empty()) << centre.missed;
    int predicted_corners = 0;
    for (int k : {0, 2, 6, 8}) {
      const analysis::field_spot& corner = m.spots[k];
      ASSERT_TRUE(corner.missed.empty()) << corner.missed;
      // The model with its angle fixed, at the corner: at the corner's incidence it is the
      // corner's PSF; against the centre's incidence it isolates what the angle changes.
      auto at_angle = [&](double deg) {
        const model_setting setting{.base_dir = s.base_dir, .chief_incidence_deg = deg};
        retro_model_params fixed = s.sheet().model;
        set_model_value(fixed, "lookup", "per_render");
        const retro_model_list models{make_retro_model(fixed, setting)};
        return energy_radius(sample_psf(s, models, p, corner.point));
      };
      const double own_angle = at_angle(corner.incidence_deg);
      const double predicted = own_angle - at_angle(centre.incidence_deg);
      const double seen = corner.r50_mm - centre.r50_mm;
      EXPECT_GT(std::abs(corner.incidence_deg - centre.incidence_deg), 3.0);
      EXPECT_NEAR(corner.r50_mm / own_angle, 1.0, 0.02) << preset << " corner " << k;
      std::printf("%s corner %d: r50 %.4f mm at %.2f deg, centre %.4f mm at %.2f deg, the angle alone %+.4f mm\n",
                  preset, k, corner.r50_mm, corner.incidence_deg, centre.r50_mm, centre.incidence_deg, predicted);
      // Where the angle's own effect is below 1% of the blur, its sign is not a prediction.
      if (std::abs(predicted) < 0.01 * centre.r50_mm) continue;
      ++predicted_corners;
      EXPECT_GT(predicted * seen, 0) << preset << " corner " << k << ": r50 " << corner.r50_mm << " mm at "
                                     << corner.incidence_deg << " deg, centre " << centre.r50_mm
                                     << " mm; the angle alone changes it by " << predicted << " mm";
    }
    EXPECT_GE(predicted_corners, 2) << preset;

    // One angle for the whole image. Untilted, so that the corners' paths to the sheet are within
    // 1% of the centre's (tilted 20 deg they differ by +-5%, and the blur with them).
    const scene fixed = preset_bench(preset, "per_render");
    const analysis::spot_matrix f = analysis::compute_spot_matrix(fixed, make_sheet_models(fixed), 3, p, 65);
    for (int k : {0, 2, 6, 8})
      EXPECT_NEAR(f.spots[k].r50_mm / f.spots[4].r50_mm, 1.0, 0.02) << preset << " per_render corner " << k;
  }
}

// The bundle's waist seen from the whole sheet agrees with the observer's PSF at the aerial
// point when the model does not change across the sheet (per-render lookup).
TEST(Bokeh, ThroughFocusWaistMatchesTheObserversPsf) {
  const scene s = preset_bench("rf-ay", "per_render");
  const retro_model_list models = make_sheet_models(s);
  const analysis::through_focus tf =
      analysis::compute_through_focus(s, models, {-4, -2, 0, 2, 4}, {.samples = 100000, .seed = 3}, 65);
  const double observer_r50 = energy_radius(sample_psf(s, models, {.samples = 100000, .seed = 3}));
  EXPECT_NEAR(tf.planes[2].r50_mm / observer_r50, 1.0, 0.05);
  EXPECT_NEAR(tf.best_offset_mm, 0.0, 1.0);
  EXPECT_GT(tf.planes[0].r50_mm, tf.planes[2].r50_mm);
  EXPECT_GT(tf.planes[4].r50_mm, tf.planes[2].r50_mm);
}

// `airr psf` writes the 2D PSF as an image whose pixel size and brightness read back, the through
// focus table as CSV, and the spot matrix; bad requests are one-line errors.
TEST(Bokeh, CommandWritesThePictures) {
  const test::temp_dir dir;
  const std::string scene_path = test::scene_file(dir, [](nlohmann::json& j) {
    j["retroreflectors"][0]["model"] = {{"type", "sinc_shift"}, {"preset", "rf-ay"}};
  });
  const auto r =
      test::run_cli("psf " + scene_path + " --samples 50000 --image " + dir.file("psf.exr") + " --png " +
                    dir.file("psf.png") + " --focus=-6:6:3 --focus-csv " + dir.file("focus.csv") + " --focus-strip " +
                    dir.file("strip.png") + " --field 3 --field-png " + dir.file("field.png"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto printed = r.out.find("\nbrightness: ");
  ASSERT_NE(printed, std::string::npos) << r.out;
  const double brightness = std::stod(r.out.substr(printed + 13));
  const loaded_image img = load_image(dir.file("psf.exr"));
  ASSERT_TRUE(img.mm_per_pixel.has_value());
  const image_metadata meta = read_image_metadata(dir.file("psf.exr"));
  EXPECT_NEAR(std::stod(meta.at("airr:psf_brightness")), brightness, 0.003 * brightness);
  double sum = 0;
  for (std::size_t i = 0; i < img.pixels.rgb.size(); i += 3) sum += img.pixels.rgb[i];
  EXPECT_NEAR(sum * *img.mm_per_pixel * *img.mm_per_pixel / brightness, 1.0, 0.005);
  EXPECT_EQ(img.pixels.width % 2, 1);
  const csv_table focus = read_csv_table(dir.file("focus.csv"));
  EXPECT_EQ(focus.rows.size(), 5u);
  for (const char* png : {"psf.png", "strip.png", "field.png"})
    EXPECT_GT(std::filesystem::file_size(dir.file(png)), 5000u) << png;
  EXPECT_NE(r.out.find("best focus:"), std::string::npos) << r.out;

  test::expect_one_line_error(test::run_cli("psf " + scene_path + " --focus=4:-4:1"),
                              {"--focus", "start is above end"});
  test::expect_one_line_error(test::run_cli("psf " + scene_path + " --pixels 64 --png " + dir.file("x.png")),
                              {"--pixels", "odd"});
  test::expect_one_line_error(test::run_cli("psf " + scene_path), {"nothing to write"});
}

// The floating distance x tilt map holds at each grid point what `airr psf` says of that layout.
TEST(Bokeh, DistanceTiltMapEqualsThePsfAtItsPoints) {
  const test::temp_dir dir;
  const std::string scene_path = test::scene_file(dir, [](nlohmann::json& j) {
    j["retroreflectors"][0]["model"] = {{"type", "sinc_shift"}, {"preset", "rf-an"}};
  });
  const auto sweep = test::run_cli(
      "sweep " + scene_path + " --psf --samples 20000 --vary floating_distance=150:250:50 --vary tilt=0:30:10 -o " +
      dir.file("map.csv") + " --png " + dir.file("map.png"));
  ASSERT_EQ(sweep.exit_code, 0) << sweep.out;
  EXPECT_GT(std::filesystem::file_size(dir.file("map.png")), 5000u);
  const csv_table map = read_csv_table(dir.file("map.csv"));
  ASSERT_EQ(map.rows.size(), 12u);
  const int d_col = map.column("floating_distance_mm"), t_col = map.column("tilt_deg");
  const int r50_col = map.column("r50_mm"), mtf_col = map.column("mean_mtf_0_1");
  for (std::size_t row : {0u, 5u, 7u, 11u}) {
    const std::vector<double>& v = map.rows[row];
    char sets[128];
    std::snprintf(sets, sizeof sets, " --set floating_distance_mm=%.10g --set tilt_deg=%.10g", v[d_col], v[t_col]);
    const auto psf = test::run_cli("psf " + scene_path + " --samples 20000 -o " + dir.file("p.csv") + sets);
    ASSERT_EQ(psf.exit_code, 0) << psf.out;
    const auto r50_at = psf.out.find("50%-energy radius: "), mtf_at = psf.out.find("mean MTF over (0, 1] lp/mm: ");
    ASSERT_NE(r50_at, std::string::npos);
    ASSERT_NE(mtf_at, std::string::npos);
    EXPECT_NEAR(std::stod(psf.out.substr(r50_at + 19)), v[r50_col], 6e-5) << sets;
    EXPECT_NEAR(std::stod(psf.out.substr(mtf_at + 28)), v[mtf_col], 6e-6) << sets;
  }
  test::expect_one_line_error(
      test::run_cli("sweep " + scene_path + " --psf --vary tilt=0:30:10 --png " + dir.file("x.png")),
      {"--png", "--vary for both"});
}

// The tracer's own PSF (a 0.5 mm disc, the plain path tracer at 4096 spp on a 65-pixel grid)
// against the model blurred by the same disc, read alike off both pictures. RF-AN's r50 lies where
// its cumulative energy is flat (between the core and the shift ring): 1% of the energy moves it
// by 3-5%, so both sides need many samples.
TEST(Bokeh, TracedPsfAgreesWithTheModel) {
  for (const char* preset : {"rf-ay", "rf-an"}) {
    const scene s = preset_bench(preset);
    const psf_samples psf = sample_psf(s, make_sheet_models(s), {.samples = 400000, .seed = 5, .stratified = false});
    const int size = 65;
    const double pixel = 2 * analysis::psf_picture_half_width(psf, false) / size;
    const analysis::psf_grid model = analysis::psf_to_grid(analysis::blur_by_disc(psf, 0.5, 5), size, pixel);
    const traced_psf traced = trace_psf(s, size, pixel, {.disc_mm = 0.5, .spp = 4096, .seed = 5});
    const double r50_model = analysis::grid_energy_radius(model),
                 r50_traced = analysis::grid_energy_radius(traced.grid);
    const double mtf_model = analysis::grid_mean_mtf(model), mtf_traced = analysis::grid_mean_mtf(traced.grid);
    std::printf("%s: r50 %.4f mm (model x disc) vs %.4f mm (traced); mean MTF %.4f vs %.4f; held %.5f vs %.5f\n",
                preset, r50_model, r50_traced, mtf_model, mtf_traced, model.integral(), traced.grid.integral());
    EXPECT_NEAR(r50_traced / r50_model, 1.0, 0.05) << preset;
    EXPECT_NEAR(mtf_traced, mtf_model, 0.02) << preset;
    EXPECT_NEAR(traced.grid.integral() / model.integral(), 1.0, 0.02) << preset;
  }
}
