// Contrast of the aerial image against the room's light (spec section 11). On the ideal bench with
// a 500 cd/m2 display the aerial image is L R T = 125 cd/m2 and, in a room of surround luminance
// L_a, the background over it is the veil R L_a plus the room behind the observer the sheet
// returns, T T L_a: the contrast is (125 + 0.75 L_a) / (0.75 L_a) wherever the sheet lies behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/aerial_outline.hpp"
#include "airr/measure/contrast.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/render_session.hpp"
#include "error_of.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

scene bench_under(double lux) {
  scene s = test::white_bench(500, 48);
  s.environment.room.illuminance_lux = lux;
  return s;
}

double expected_contrast(double lux) {
  const double background = 0.75 * lux / std::numbers::pi;
  return (125 + background) / background;
}

}  // namespace

TEST(Contrast, OnePixelsContrastIsTheWholeOverTheBackground) {
  EXPECT_DOUBLE_EQ(pixel_contrast(125, 125), 2.0);
  EXPECT_DOUBLE_EQ(pixel_contrast(0, 10), 1.0);
  EXPECT_TRUE(std::isinf(pixel_contrast(1, 0)));
  EXPECT_DOUBLE_EQ(pixel_contrast(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(pixel_contrast(-1e-9, 4), 1.0);  // noise below 0 is no light
}

TEST(Contrast, AnOfficeGivesTheContrastTheHalfMirrorAndTheSheetPredict) {
  const scene s = bench_under(500);
  render_session session(s, {.threads = 2, .target_spp = 4, .components = true});
  const render_snapshot snap = session.wait_for(0, 4);
  ASSERT_TRUE(snap.components);
  const std::array<glm::dvec2, 4> outline = aerial_outline(s, make_camera(s));
  const contrast_summary c =
      contrast_inside(*snap.components, snap.width, snap.height, outline, default_contrast_thresholds);
  std::printf(
      "500 lx office, 500 cd/m2 display: aerial %.3f cd/m2, background %.3f cd/m2, contrast %.4f "
      "(predicted %.4f); shares at 1.5, 3, 25: %.3f %.3f %.3f over %d pixels\n",
      c.aerial_luminance, c.background_luminance, c.contrast, expected_contrast(500), c.share_above[0],
      c.share_above[1], c.share_above[2], c.pixels);
  ASSERT_GT(c.pixels, 100);
  EXPECT_NEAR(c.background_luminance, 0.75 * 500 / std::numbers::pi, 0.01 * 119.4);
  EXPECT_NEAR(c.contrast, expected_contrast(500), 0.02 * expected_contrast(500));
  EXPECT_GT(c.share_above[0], 0.9);  // 2.05: usable at 1.5 ...
  EXPECT_LT(c.share_above[1], 0.1);  // ... not at 3
  EXPECT_EQ(c.share_above[2], 0.0);

  // The map agrees with the summary: the mean of its pixels' contrast over the outline is that of
  // a uniform image, the summary's within the edge pixels' share.
  const std::vector<float> map = contrast_map(*snap.components, snap.width, snap.height, outline);
  double sum = 0;
  int n = 0;
  for (float v : map) {
    if (std::isnan(v)) continue;
    sum += v;
    ++n;
  }
  EXPECT_EQ(n, c.pixels);
  EXPECT_NEAR(sum / n, c.contrast, 0.03 * c.contrast);
}

TEST(Contrast, TheLegibleShareOfTheZoneFallsAsTheRoomBrightens) {
  eye_grid g;
  g.nx = g.ny = 5;
  g.x_min = g.y_min = -100;
  g.x_max = g.y_max = 100;
  const full_zone_params p{.render_size = 24, .render_spp = 4, .psf_samples = 200};
  std::printf("room lux  contrast at the centre eye (predicted)  legible share at 1.5 / 3 / 25\n");
  std::vector<double> shares;
  for (const double lux : {100.0, 500.0, 1000.0, 3000.0, 10000.0}) {
    const full_zone_map m = full_viewing_zone(bench_under(lux), g, p);
    const std::size_t centre = std::size_t(g.nx * g.ny / 2);
    std::printf("%8.0f  %8.4f (%.4f)  %.3f / %.3f / %.3f\n", lux, m.contrast[centre], expected_contrast(lux),
                legible_share(m, 0), legible_share(m, 1), legible_share(m, 2));
    EXPECT_NEAR(m.contrast[centre], expected_contrast(lux), 0.03 * expected_contrast(lux)) << lux;
    EXPECT_NEAR(m.luminance[centre], 125, 0.03 * 125) << lux;
    for (std::size_t k = 0; k + 1 < m.thresholds.size(); ++k)
      EXPECT_GE(legible_share(m, k), legible_share(m, k + 1)) << "a higher threshold is met by fewer eyes";
    shares.push_back(legible_share(m, 0));
  }
  for (std::size_t i = 0; i + 1 < shares.size(); ++i) EXPECT_GE(shares[i], shares[i + 1]) << i;
  EXPECT_GT(shares.front(), 0.2);
  EXPECT_EQ(shares.back(), 0.0);  // contrast 1.05 at 10,000 lx
}

// The design metrics: luminance_cd_m2 is the model PSF's brightness times the display's white;
// contrast and legible_share come from the eye's render and follow the room; over a zone,
// legible_share's share_above 0.9 is the zone's legible share `airr viewzone` prints.
TEST(Contrast, DesignMetricsAskForTheMostLegibleLayoutUnderARoom) {
  test::temp_dir dir;
  const std::string scene_path = dir.file("office.json");
  save_scene(bench_under(500), scene_path);
  const auto spec_with = [&](const std::string& members) {
    const std::string path = dir.file("spec.json");
    write_file_atomic(path,
                      R"({"format": "airr-design", "version": 1, "scene": ")" + scene_path + R"(", )" + members + "}");
    return load_design_spec(path);
  };
  const design_spec one = spec_with(
      R"("legible_contrast": 1.5, "objectives": [{"metric": "luminance_cd_m2", "goal": "maximise"},
          {"metric": "contrast", "goal": "maximise"}, {"metric": "legible_share", "goal": "maximise"}])");
  const design_evaluation e = evaluate_design(one, one.base);
  const double brightness =
      scene_psf(observer_at(one.base, observer_position(one.base)), one.search.psf_samples).brightness();
  std::printf(
      "500 lx, the observer: luminance %.4f cd/m2 (brightness x 500 = %.4f), contrast %.4f, legible share "
      "at 1.5 %.3f\n",
      e.objective_values[0], 500 * brightness, e.objective_values[1], e.objective_values[2]);
  EXPECT_DOUBLE_EQ(e.objective_values[0], 500 * brightness);
  EXPECT_NEAR(e.objective_values[1], expected_contrast(500), 0.03 * expected_contrast(500));
  EXPECT_GT(e.objective_values[2], 0.9);
  // At 3 the office is not legible (contrast 2.05).
  const design_spec strict = spec_with(R"("objectives": [{"metric": "legible_share", "goal": "maximise"}])");
  EXPECT_EQ(strict.legible_contrast, 3);
  EXPECT_LT(evaluate_design(strict, strict.base).objective_values[0], 0.1);

  // Over the zone's eyes, as the full viewing-zone pass counts them.
  const design_spec zone = spec_with(
      R"("legible_contrast": 1.5, "eye_zone": {"x": [-100, 100], "y": [-100, 100], "n": [3, 3]},
          "objectives": [{"metric": "legible_share", "goal": "maximise", "over": "share_above", "threshold": 0.9}])");
  const double zone_share = evaluate_design(zone, zone.base).objective_values[0];
  eye_grid g = *zone.eye_zone;
  const full_zone_map m =
      full_viewing_zone(zone.base, g, {.render_size = 48, .render_spp = 16, .contrast_thresholds = {1.5}});
  std::printf("legible share of a 3 x 3 zone at 1.5: design metric %.4f, viewing zone %.4f\n", zone_share,
              legible_share(m, 0));
  EXPECT_NEAR(zone_share, legible_share(m, 0), 1.0 / 9 + 1e-9);  // one eye's noise at the 90% edge at most
  EXPECT_GT(zone_share, 0);

  EXPECT_NE(test::error_of([&] {
              spec_with(R"("legible_contrast": 0.5, "objectives": [{"metric": "contrast",
      "goal": "maximise"}])");
            }).find("legible_contrast"),
            std::string::npos);
}
