// The smallest legible character on the aerial image (spec section 11): the height whose stroke
// frequency, 2.5 cycles per character height, keeps a modulation MTF x (C - 1) / (C + 1) of at
// least 0.1, and at least 16 arcmin at the eye. A Gaussian blur has it in closed form; the ideal
// sheet leaves only the eye and the display's pixels; a blurrier sheet grows it with its PSF.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "airr/core/files.hpp"
#include "airr/core/geometry.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/legibility.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "error_of.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// The height at which a Gaussian MTF exp(-2 pi^2 sigma^2 f^2) times `kept` falls to 0.1.
double gaussian_height(double sigma, double kept) {
  const double f = std::sqrt(std::log(kept / 0.1) / (2 * std::numbers::pi * std::numbers::pi)) / sigma;
  return 2.5 / f;
}

}  // namespace

TEST(CharacterHeight, AGaussianBlurGivesTheHeightItsMtfPredicts) {
  const double sigma = 0.5;
  const auto mtf = [&](double f) { return std::exp(-2 * std::numbers::pi * std::numbers::pi * sigma * sigma * f * f); };
  const legible_character dark = smallest_legible_character(mtf, 20, inf, 300, 0);
  EXPECT_EQ(dark.limit, legibility_limit::optics);
  EXPECT_NEAR(dark.height_mm, gaussian_height(sigma, 1.0), 1e-9 * dark.height_mm);
  EXPECT_NEAR(dark.arcmin, degrees(std::atan(dark.height_mm / 300)) * 60, 1e-9);
  // At contrast 3 half the modulation is left: the MTF must reach 0.2.
  const legible_character lit = smallest_legible_character(mtf, 20, 3, 300, 0);
  EXPECT_NEAR(lit.height_mm, gaussian_height(sigma, 0.5), 1e-9 * lit.height_mm);
  EXPECT_GT(lit.height_mm, dark.height_mm);
  // Below contrast 11/9, (C - 1) / (C + 1) < 0.1: nothing is legible.
  const legible_character washed = smallest_legible_character(mtf, 20, 1.2, 300, 0);
  EXPECT_EQ(washed.limit, legibility_limit::contrast);
  EXPECT_TRUE(std::isinf(washed.height_mm));
  std::printf("Gaussian sigma 0.5 mm at 300 mm: %.4f mm (%.2f arcmin) in the dark, %.4f mm at contrast 3\n",
              dark.height_mm, dark.arcmin, lit.height_mm);
}

TEST(CharacterHeight, OnTheIdealSheetOnlyTheEyeAndThePixelsLimitIt) {
  scene s = test::white_bench(500, 16);
  const psf_samples psf = scene_psf(s, 2000);
  const double distance = glm::length(observer_position(s) - aerial_image_center(s));
  const legible_character eye = psf_legible_character(s, psf, inf, {});
  std::printf("ideal sheet at %.1f mm: %.4f mm, %.3f arcmin (%s)\n", distance, eye.height_mm, eye.arcmin,
              to_string(eye.limit));
  EXPECT_EQ(eye.limit, legibility_limit::eye);
  EXPECT_NEAR(eye.arcmin, 16, 1e-9);
  EXPECT_NEAR(eye.height_mm, distance * std::tan(radians(16.0 / 60)), 1e-9);

  // A coarse display (64 pixels across its width): 2.5 cycles need 5 pixels.
  test::temp_dir dir;
  image_rgb img;
  img.width = img.height = 64;
  img.rgb.assign(std::size_t(64 * 64 * 3), 1.0f);
  write_image(dir.file("coarse.png"), img, {});
  s.source.image = dir.file("coarse.png");
  const double pitch = std::max(s.source.width_mm, s.source.height_mm) / 64;
  const legible_character pixels = psf_legible_character(s, psf, inf, {});
  std::printf("the same with 64 pixels over %.1f mm: %.4f mm (%s)\n", s.source.width_mm, pixels.height_mm,
              to_string(pixels.limit));
  EXPECT_EQ(pixels.limit, legibility_limit::pixels);
  EXPECT_NEAR(pixels.height_mm, 5 * pitch, 1e-9);
}

TEST(CharacterHeight, ATiltedRfAnSheetGrowsItAsItsR50Predicts) {
  // A Gaussian PSF's r50 is sigma sqrt(2 ln 2) and its smallest character is proportional to
  // sigma, so between two tilts the character grows as r50 does; the RF-AN's blur keeps that
  // within 10%.
  std::vector<double> heights, radii;
  for (double tilt : {0.0, 20.0}) {
    scene s = test::chart_scene("rf-an", 16, tilt);
    s.source.image.clear();
    const psf_samples psf = scene_psf(s, 200000);
    const legible_character c = psf_legible_character(s, psf, inf, {});
    heights.push_back(c.height_mm);
    radii.push_back(energy_radius(psf, 0.5));
    std::printf("RF-AN at tilt %.0f: r50 %.4f mm, smallest character %.4f mm (%.2f arcmin, %s)\n", tilt, radii.back(),
                c.height_mm, c.arcmin, to_string(c.limit));
    EXPECT_EQ(c.limit, legibility_limit::optics);
  }
  const double grown = heights[1] / heights[0], predicted = radii[1] / radii[0];
  std::printf("grown %.4f times, r50 predicts %.4f\n", grown, predicted);
  EXPECT_GT(grown, 1.0);
  EXPECT_NEAR(grown, predicted, 0.1 * predicted);
}

TEST(CharacterHeight, TheZoneMapsItFromEachEye) {
  // The ideal sheet: from every eye that sees the aerial image, the eye's 16 arcmin bound; in a
  // 10,000 lx room the contrast (1.05) leaves too little modulation for any size.
  eye_grid g;
  g.nx = g.ny = 3;
  g.x_min = g.y_min = -60;
  g.x_max = g.y_max = 60;
  const full_zone_params p{.render_size = 16, .render_spp = 2, .psf_samples = 200};
  scene s = test::white_bench(500, 16);
  const full_zone_map dark = full_viewing_zone(s, g, p);
  s.environment.room.illuminance_lux = 10000;
  const full_zone_map bright = full_viewing_zone(s, g, p);
  int seen = 0;
  for (std::size_t e = 0; e < dark.visible.size(); ++e) {
    if (!(dark.visible[e] > 0)) continue;
    ++seen;
    EXPECT_NEAR(dark.char_arcmin[e], 16, 1e-9) << e;
    const double distance =
        glm::length(eye_position(s, g, g.x_at(int(e % 3)), g.y_at(int(e / 3))) - aerial_image_center(s));
    EXPECT_NEAR(dark.char_height_mm[e], distance * std::tan(radians(16.0 / 60)), 1e-9) << e;
    EXPECT_TRUE(std::isinf(bright.char_height_mm[e])) << e;
  }
  EXPECT_GT(seen, 0);
}

TEST(CharacterHeight, TheDesignMetricTakesTheSpecsCriterion) {
  // On the ideal bench in the dark the metric is the eye's bound from the observer; a spec asking
  // for 30 arcmin gets 30; a criterion out of range is an error naming its field.
  test::temp_dir dir;
  const std::string scene_path = dir.file("bench.json");
  save_scene(test::white_bench(500, 16), scene_path);
  const auto spec_with = [&](const std::string& members) {
    const std::string path = dir.file("spec.json");
    write_file_atomic(path, R"({"format": "airr-design", "version": 1, "scene": ")" + scene_path + R"(", )" + members +
                                R"(, "objectives": [{"metric": "char_height_mm", "goal": "minimise"}]})");
    return load_design_spec(path);
  };
  const design_spec plain = spec_with(R"("legible_contrast": 3)");
  const double distance = glm::length(observer_position(plain.base) - aerial_image_center(plain.base));
  EXPECT_NEAR(evaluate_design(plain, plain.base).objective_values[0], distance * std::tan(radians(16.0 / 60)), 1e-9);
  const design_spec strict = spec_with(R"("legibility": {"min_arcmin": 30})");
  EXPECT_EQ(strict.legibility.min_arcmin, 30);
  EXPECT_NEAR(evaluate_design(strict, strict.base).objective_values[0], distance * std::tan(radians(30.0 / 60)), 1e-9);
  EXPECT_NE(design_spec_text(strict).find("\"min_arcmin\""), std::string::npos);
  const std::string bad = test::error_of([&] { spec_with(R"("legibility": {"modulation": 2})"); });
  EXPECT_NE(bad.find("legibility.modulation"), std::string::npos) << bad;
}
