// The image's components (spec section 8): the aerial image, the display seen directly, its
// plain reflection in the half mirror and the rest add up to the whole image, and the display seen
// directly is what remains when the sheet is taken away.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The default layout seen from 30 degrees above with a wide field: the top of the aerial image
// and, below it, the display itself. An empty `model` keeps the ideal bench's ideal sheet.
scene looking_down(const std::string& model) {
  std::vector<scene_override> o = {{"observer.elevation_deg", "30"},
                                   {"observer.fov_deg", "60"},
                                   {"observer.width", "64"},
                                   {"observer.height", "64"}};
  if (!model.empty()) {
    o.push_back({"retroreflectors.0.model.type", "\"sinc_shift\""});
    o.push_back({"retroreflectors.0.model.preset", "\"" + model + "\""});
  }
  return load_scene(ideal_bench_scene_path(), o);
}

render_snapshot render_components(const scene& s, std::uint64_t spp) {
  render_session session(s, {.threads = 2, .target_spp = spp, .components = true});
  session.wait_for(0, spp);
  return session.snapshot();
}

double peak(const std::vector<float>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST(Components, AddUpToTheWholeImage) {
  for (const std::string model : {"", "rf-an"}) {
    const render_snapshot snap = render_components(looking_down(model), 8);
    ASSERT_TRUE(snap.components) << model;
    const double scale = peak(*snap.rgb);
    ASSERT_GT(scale, 0);
    std::vector<double> energy(component_count, 0.0);
    double worst = 0;
    for (std::size_t i = 0; i < snap.rgb->size(); ++i) {
      const std::size_t px = i / 3, c = i % 3;
      double sum = 0;
      for (int k = 0; k < component_count; ++k) {
        const float v = (*snap.components)[3 * (component_count * px + std::size_t(k)) + c];
        sum += v;
        energy[std::size_t(k)] += v;
      }
      worst = std::max(worst, std::abs(sum - (*snap.rgb)[i]));
    }
    EXPECT_LT(worst, 1e-5 * scale) << model;
    // Both the aerial image and the display itself are in view.
    EXPECT_GT(energy[component_aerial], 0.05 * (energy[0] + energy[1])) << model;
    EXPECT_GT(energy[component_direct], 0.05 * (energy[0] + energy[1])) << model;
    std::printf(
        "%s: components add up to the image within %.2g of its peak; energy aerial %.4g direct %.4g "
        "reflection %.4g rest %.4g\n",
        model.empty() ? "ideal" : model.c_str(), worst / scale, energy[0], energy[1], energy[2], energy[3]);
  }
}

TEST(Components, DisplaySeenDirectlyIsTheRenderWithoutTheSheet) {
  const scene s = looking_down("rf-an");
  const render_snapshot full = render_components(s, 8);
  scene bare = s;
  bare.retroreflectors.clear();
  const render_snapshot without = render_components(bare, 8);
  const image_rgb direct = full.component_image(component_direct);
  ASSERT_EQ(direct.rgb.size(), without.rgb->size());
  const double scale = peak(*without.rgb);
  ASSERT_GT(scale, 0) << "the display should be in view";
  double worst = 0;
  for (std::size_t i = 0; i < direct.rgb.size(); ++i)
    worst = std::max(worst, double(std::abs(direct.rgb[i] - (*without.rgb)[i])));
  EXPECT_LT(worst, 1e-5 * scale);
  // Without the sheet the image has no aerial part at all.
  EXPECT_EQ(peak(without.component_image(component_aerial).rgb), 0.0f);
}

// The viewing zone's full pass on the canonical layout with RF-AN, eyes on a plane 300 mm in
// front: brightness is relative to the best eye (1 there, unset exactly where nothing is seen),
// the eye at the observer's own place has the mean MTF `airr psf --no-pixel` reports, and no
// stray path reaches the aerial image's outline in this layout.
TEST(Components, FullViewingZoneAgreesWithThePsfRouteAndHasNoStrayLight) {
  scene s = looking_down("rf-an");
  s.observer.elevation_deg = 0;
  eye_grid g;
  g.nx = g.ny = 5;
  g.x_min = g.y_min = -200;
  g.x_max = g.y_max = 200;
  const full_zone_map m = full_viewing_zone(s, g, {.rows_per_eye = 32, .render_size = 24, .render_spp = 4});
  ASSERT_EQ(m.visible.size(), 25u);
  double best = 0;
  for (std::size_t e = 0; e < 25; ++e) {
    EXPECT_EQ(std::isfinite(m.brightness[e]), m.visible[e] > 0) << e;
    if (std::isfinite(m.brightness[e])) best = std::max(best, m.brightness[e]);
    if (std::isfinite(m.stray_ratio[e])) {
      EXPECT_EQ(m.stray_ratio[e], 0.0) << e;
    }
  }
  EXPECT_DOUBLE_EQ(best, 1.0);
  // The centre eye (x = y = 0) is the observer's own orbit position at distance 300.
  scene centre = s;
  place_observer(centre, g, 0, 0);
  const double want = psf_route_mtf(scene_psf(centre, 4000), 0.0).mean_mtf;
  EXPECT_NEAR(m.mean_mtf[12], want, 1e-12);
  EXPECT_NEAR(m.visible[12], 1.0, 1e-6);
  EXPECT_EQ(m.visible[0], 0.0);  // (-200, -200): beyond the sheet
}

// The stray-light ratio of one eye, as the design metric takes it, is the full pass's number for
// that eye: 0 where no stray path reaches the aerial image's outline, and a positive share above
// the two-sheet kiosk (its second sheet's light).
TEST(Components, TheStrayLightRatioOfOneEyeIsTheFullPasss) {
  eye_grid g;
  g.nx = g.ny = 5;
  g.x_min = g.y_min = -200;
  g.x_max = g.y_max = 200;
  const full_zone_params p{.rows_per_eye = 16, .render_size = 32, .render_spp = 8};
  for (const auto& [name, s] : {std::pair{"looking down", looking_down("rf-an")},
                                std::pair{"kiosk", load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json")}}) {
    const full_zone_map m = full_viewing_zone(s, g, p);
    for (std::size_t e : {std::size_t(12), std::size_t(16), std::size_t(17)}) {
      const double one = stray_light_ratio(s, eye_position(s, g, g.x_at(int(e % 5)), g.y_at(int(e / 5))), p);
      std::printf("%s, eye %zu: stray-light ratio %.5f (full pass %.5f)\n", name, e, one, m.stray_ratio[e]);
      if (std::isnan(m.stray_ratio[e])) {
        EXPECT_TRUE(std::isnan(one));
      } else {
        EXPECT_EQ(one, m.stray_ratio[e]) << name << " eye " << e;
      }
    }
    if (std::string(name) == "kiosk") {
      EXPECT_GT(m.stray_ratio[17], 0.05);
    }
  }
}

// A render held to its end (airr render's) keeps sums of the components its scene's light can make
// alone: the others are zero images all the same, and the ones kept are the designer's session's
// numbers (the same samples), the aerial image's up to its control variate's handling.
TEST(Components, ARenderHeldToItsEndKeepsTheComponentsItsLightCanMake) {
  for (const double room : {0.0, 40.0}) {
    scene s = looking_down("rf-an");
    s.environment.room.luminance_cd_m2 = room;
    const std::uint64_t spp = 8;
    const render_snapshot shown = render_components(s, spp);
    render_session held(s, {.threads = 2, .target_spp = spp, .components = true, .final_images_only = true});
    const render_snapshot end = held.wait_for(0, spp);
    ASSERT_TRUE(end.components);
    EXPECT_EQ(end.component_layout.count, room > 0 ? 5 : 4);
    EXPECT_EQ(end.components->size(), std::size_t(end.component_layout.count) * 3 * 64 * 64);
    EXPECT_EQ(end.component_layout.slot[component_sun], -1);
    EXPECT_EQ(end.component_layout.slot[component_luminaires], -1);
    for (int k = 0; k < component_count; ++k) {
      const image_rgb a = shown.component_image(k), b = end.component_image(k);
      ASSERT_EQ(a.rgb.size(), b.rgb.size()) << component_names[k];
      double worst = 0, peak = 0;
      for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        worst = std::max(worst, double(std::abs(a.rgb[i] - b.rgb[i])));
        peak = std::max(peak, double(a.rgb[i]));
      }
      if (k == component_room) {
        EXPECT_EQ(peak > 0, room > 0);
      }
      if (k == component_direct || k == component_aerial) {
        EXPECT_GT(peak, 0) << component_names[k];
      }
      EXPECT_LE(worst, (k == component_aerial ? 1e-3 : 1e-6) * std::max(peak, 1e-30)) << component_names[k];
    }
  }
}
