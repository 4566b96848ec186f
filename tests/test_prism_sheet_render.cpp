// The prism sheet traced as geometry, through the tracer: the aerial image forms where the mirror
// image of the display lies, as bright as the share of light the sheet retroreflects; the tile
// sheet with the same cube corners as its tile does the same.
#include <cstdio>

#include <gtest/gtest.h>

#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/models/prism_sheet.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// Centroid of the pixels brighter than half the centre's: the aerial image without the stray
// light around it.
glm::dvec2 image_centroid(const render_snapshot& snap) {
  const double half = 0.5 * test::centre_mean(snap, 3);
  glm::dvec2 sum(0);
  double n = 0;
  for (int y = 0; y < snap.height; ++y) {
    for (int x = 0; x < snap.width; ++x) {
      if ((*snap.rgb)[3 * (std::size_t(y) * snap.width + x) + 1] < half) continue;
      sum += glm::dvec2(x + 0.5, y + 0.5);
      n += 1;
    }
  }
  return sum / n;
}

}  // namespace

// At a 10 deg tilt (at normal incidence some longer paths come back exactly reversed that a
// degree off do not: no pixel would see the same sheet as the chief ray).
TEST(PrismSheetRender, TheAerialImageFormsAtTheMirrorImageAsBrightAsTheSheetReturns) {
  scene ideal = test::uniform_source_scene(12.0, 64);
  ideal.sheet().pose.pitch_deg = 10;
  scene prism = ideal;
  // Without diffraction, whose tails would carry some light past the source's edges.
  prism.sheet().model = retro_model_params{"prism_sheet", {{"wavelength_nm", 0.0}}};
  const render_snapshot a = test::render_to(ideal, 16), b = test::render_to(prism, 64);
  const glm::dvec2 ca = image_centroid(a), cb = image_centroid(b);
  EXPECT_NEAR(cb.x, ca.x, 0.25);
  EXPECT_NEAR(cb.y, ca.y, 0.25);
  // The share of light the sheet retroreflects at the chief ray's incidence.
  const glm::dvec3 wi = chief_ray_through(prism, aerial_image_frame(prism).center).wi;
  prism_sheet_geometry g;  // the model's defaults
  g.wavelength_nm = 0;
  pcg32 rng(3, 4);
  double returned = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 entry = prism_cell_point(g, {rng.next_double(), rng.next_double()});
    const prism_path p = trace_prism_sheet(g, wi, entry, rng.next_double(), rng);
    if (p.fate == prism_fate::retroreflected) returned += p.weight;
  }
  const double ratio = test::centre_mean(b, 3) / test::centre_mean(a, 3);
  std::printf("prism sheet at %.1f deg: centre %.4f of the ideal sheet's; it retroreflects %.4f\n",
              degrees(std::acos(wi.z)), ratio, returned / n);
  EXPECT_NEAR(ratio, returned / n, 0.02);
}

// The tile sheet with its shipped tile (the prism sheet's cube corners as a glTF mesh, traced by
// Embree) forms the same aerial image as the prism sheet: where, and as bright.
TEST(PrismSheetRender, TheShippedTileRendersAsThePrismSheet) {
  scene prism = test::uniform_source_scene(12.0, 64);
  prism.sheet().pose.pitch_deg = 10;
  scene tile = prism;
  prism.sheet().model = retro_model_params{"prism_sheet", {{"wavelength_nm", 0.0}}};
  tile.sheet().model = retro_model_params{"tile_sheet", {{"wavelength_nm", 0.0}}};
  const render_snapshot a = test::render_to(prism, 64), b = test::render_to(tile, 64);
  const glm::dvec2 ca = image_centroid(a), cb = image_centroid(b);
  EXPECT_NEAR(cb.x, ca.x, 0.25);
  EXPECT_NEAR(cb.y, ca.y, 0.25);
  const double ratio = test::centre_mean(b, 3) / test::centre_mean(a, 3);
  std::printf("tile sheet's centre: %.4f of the prism sheet's\n", ratio);
  EXPECT_NEAR(ratio, 1.0, 0.03);
}

// Colour fringes in the tracer: a prism sheet under the display's white returns white light (the
// channels' totals agree), but its red spreads wider than its blue, so past the aerial image's
// edge the red outweighs the blue. Each path carries one primary, so a channel's total varies with
// how many paths drew it: the 36 mm source fills about 700 pixels, which at 256 spp keeps the
// totals' ratios within 0.5% (one standard deviation over seeds 1-6; a 12 mm source at 128 spp
// varied by 2.5%) and the ratio past the edge at 1.13-1.18.
TEST(PrismSheetRender, TheDisplaysWhiteHasColourFringes) {
  scene s = test::uniform_source_scene(36.0, 64);
  s.sheet().pose.pitch_deg = 10;
  s.sheet().model =
      retro_model_params{"prism_sheet", {{"coating", std::string("metal")}, {"spectrum", std::string("display_rgb")}}};
  const render_snapshot snap = test::render_to(s, 256);
  const double half = 0.5 * test::centre_mean(snap, 3);
  glm::dvec3 total(0), outside(0);
  for (std::size_t i = 0; i < std::size_t(snap.width) * snap.height; ++i) {
    const glm::dvec3 c((*snap.rgb)[3 * i], (*snap.rgb)[3 * i + 1], (*snap.rgb)[3 * i + 2]);
    total += c;
    if (c.g < half) outside += c;
  }
  std::printf("totals R %.4g G %.4g B %.4g; past the edge R / B %.3f\n", total.r, total.g, total.b,
              outside.r / outside.b);
  EXPECT_NEAR(total.r / total.b, 1.0, 0.03);
  EXPECT_NEAR(total.g / total.b, 1.0, 0.03);
  EXPECT_GT(outside.r / outside.b, 1.08);
}
