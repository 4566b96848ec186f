// Props (glTF models placed in the layout) block light in the tracer and in both viewing-zone
// passes exactly where an independent line-of-sight computation says they do.
#include <gtest/gtest.h>

#include <cmath>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/prop_hits.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "gltf_builder.hpp"
#include "plate_mesh.hpp"
#include "test_helpers.hpp"

using namespace airr;
using airr::test::plate;
using airr::test::write_plate;

namespace {

prop_params absorber_prop(const std::string& path) {
  prop_params p;
  p.name = "hood";
  p.mesh = path;
  return p;
}

// The canonical layout's display (50 mm, facing +y at y = -150) and aerial image (z = 150).
constexpr double display_half = 25, display_y = -150, aerial_z = 150;

struct eye_class {
  bool seen_through_outline = false;  // some line through the aerial outline reaches the display
  bool hidden = false;                // every such line crosses the plate (shrunk by a margin)
  bool clear = false;                 // none crosses the plate (grown by a margin)
  glm::dvec3 aim{0.0};                // the mean outline point of those lines
};

// Lines from the eye through the aerial image's outline (grown by the render's pixel margin) on
// to the display's plane, through the half mirror; those that land on the emitting area are
// the display seen directly.
eye_class classify(const glm::dvec3& eye, const plate& hood) {
  eye_class c;
  int kept = 0, surely = 0, maybe = 0;
  const double reach = display_half + 3;
  for (int i = 0; i <= 60; ++i) {
    for (int j = 0; j <= 60; ++j) {
      const glm::dvec3 p(-reach + 2 * reach * i / 60, -reach + 2 * reach * j / 60, aerial_z);
      const glm::dvec3 d = p - eye;
      if (d.y >= 0) continue;
      const glm::dvec3 q = eye + (display_y - eye.y) / d.y * d;
      if (std::abs(q.x) > display_half || std::abs(q.z) > display_half) continue;
      ++kept;
      c.aim += p;
      surely += hood.crossed_by(eye, q, -1.0);
      maybe += hood.crossed_by(eye, q, 1.0);
    }
  }
  c.seen_through_outline = kept > 0;
  if (kept > 0) c.aim /= double(kept);
  c.hidden = kept > 0 && surely == kept;
  c.clear = maybe == 0;
  return c;
}

}  // namespace

// A lip 30 mm above the display, in front of its edge (y = -120, z from 35 to 65 mm): eyes low on the
// grid look over it at the display, eyes high up have it in the way.
TEST(Props, HoodRemovesTheDisplaySeenDirectlyExactlyWhereItIsHidden) {
  test::temp_dir dir;
  const plate hood(1, -120, -60, 60, 35, 65);  // x, then z
  write_plate(hood, dir.file("hood.glb"));

  const scene bare = test::uniform_source_scene(50, 32);
  scene hooded = bare;
  hooded.props.push_back(absorber_prop(dir.file("hood.glb")));
  check_scene(hooded, "hooded");

  eye_grid g;
  g.kind = eye_grid::shape::plane;
  g.distance_mm = 300;
  g.x_min = g.x_max = 0;
  g.nx = 1;
  g.y_min = 180, g.y_max = 450;
  g.ny = 55;
  const full_zone_params p{.rows_per_eye = 16, .render_size = 32, .render_spp = 4, .psf_samples = 100};
  const full_zone_map without = full_viewing_zone(bare, g, p);
  const full_zone_map with = full_viewing_zone(hooded, g, p);
  ASSERT_EQ(with.direct.size(), std::size_t(g.ny));

  int hidden = 0, clear = 0;
  double best_hidden = 0;
  glm::dvec3 hidden_eye(0.0), hidden_aim(0.0);
  for (int j = 0; j < g.ny; ++j) {
    const glm::dvec3 eye = eye_position(bare, g, 0, g.y_at(j));
    const eye_class c = classify(eye, hood);
    const double w = with.direct[std::size_t(j)], wo = without.direct[std::size_t(j)];
    if (!c.seen_through_outline && wo == 0 && w == 0) continue;
    std::printf("eye y %.0f mm: direct %.5f bare, %.5f hooded (%s)\n", eye.y, wo, w,
                c.hidden  ? "hidden"
                : c.clear ? "clear"
                          : "partly hidden");
    // Every eye: hidden means nothing seen, clear means the same as without the hood. The
    // classification's margins leave eyes at the zone's edges that see nothing either way.
    if (c.hidden) {
      EXPECT_EQ(w, 0) << "eye y " << eye.y << ": the hood hides the display";
      if (wo > 0) ++hidden;
      if (wo > best_hidden) best_hidden = wo, hidden_eye = eye, hidden_aim = c.aim;
    } else if (c.clear) {
      EXPECT_NEAR(w, wo, 1e-9 * wo) << "eye y " << eye.y << ": nothing in the way";
      if (wo > 0) ++clear;
    } else {
      EXPECT_LE(w, wo) << "eye y " << eye.y << ": partly hidden";
    }
  }
  // Enough eyes of both kinds see the display without the hood.
  EXPECT_GE(hidden, 2);
  EXPECT_GE(clear, 2);

  // The render from a hidden eye, aimed where it would see the display through the aerial
  // image, its field 4 mm across there (inside the lines classified): no sample of any pixel sees
  // the display directly.
  ASSERT_GT(best_hidden, 0);
  for (const scene* s : {&bare, static_cast<const scene*>(&hooded)}) {
    scene from = *s;
    from.observer.placement = observer_placement::look_at;
    from.observer.position_mm = {hidden_eye.x, hidden_eye.y, hidden_eye.z};
    from.observer.look_at_mm = {hidden_aim.x, hidden_aim.y, hidden_aim.z};
    from.observer.fov_deg = degrees(2 * std::atan(2 / glm::length(hidden_eye - hidden_aim)));
    render_session session(from, {.threads = 2, .target_spp = 4, .components = true});
    session.wait_for(0, 4);
    const image_rgb direct = session.snapshot().component_image(component_direct);
    double sum = 0;
    for (float v : direct.rgb) sum += v;
    if (s == &bare) {
      EXPECT_GT(sum, 0);
    } else {
      EXPECT_EQ(sum, 0);
    }
  }
}

// An absorbing plate 50 mm in front of the aerial image covering x >= 0: from an eye at
// (x_e, 0, 450) it hides the aerial image's points with x >= -0.2 x_e (its edge projected from the
// eye onto the image's plane z = 150 scales by 300 / 250 about the eye).
TEST(Props, PlateInFrontHidesTheProjectedPartOfTheAerialImage) {
  test::temp_dir dir;
  const plate front(2, 200, 0, 100, -100, 100);  // x, then y
  write_plate(front, dir.file("front.glb"));
  scene s;
  s.props.push_back(absorber_prop(dir.file("front.glb")));
  check_scene(s, "front");
  EXPECT_THROW(viewing_parts(s, {}), std::invalid_argument);
  const viewing_parts parts(s, scene_prop_hits(s));
  eye_grid g;
  for (double x : {-60.0, -20.0, 0.0, 30.0, 60.0}) {
    const double edge = std::clamp(-0.2 * x, -25.0, 25.0);
    EXPECT_NEAR(visible_fraction(parts, eye_position(s, g, x, 0)), (edge + 25) / 50, 1e-4) << "eye x " << x;
  }
  // Hidden, it takes no part.
  s.props.front().visible = false;
  const viewing_parts none(s, scene_prop_hits(s));
  EXPECT_NEAR(visible_fraction(none, eye_position(s, g, 30, 0)), 1.0, 1e-9);
}

// A 100 mm square absorbing plate at z = 200 mm, in front of the default layout, as the scene's
// one prop (checked, so its mesh is loaded).
class PlateInFront : public ::testing::Test {
 protected:
  void SetUp() override {
    write_plate(plate(2, 200, -50, 50, -50, 50), dir.file("plate.glb"));
    s.props.push_back(absorber_prop(dir.file("plate.glb")));
    check_scene(s, "plate");
  }
  test::temp_dir dir;
  scene s;
};

// An edit that leaves the props alone (the observer or a sheet moved) answers with the props'
// scene built before; one that moves a prop builds a new one.
TEST_F(PlateInFront, EditsThatLeaveThePropsAloneReuseTheirScene) {
  const prop_hit_function first = scene_prop_hits(s);
  const std::uint64_t builds = prop_scene_builds();
  s.observer.azimuth_deg += 10;
  s.sheet().pose.pitch_deg += 5;
  const prop_hit_function same = scene_prop_hits(s);
  EXPECT_EQ(prop_scene_builds(), builds);
  EXPECT_NEAR(same({0, 0, 400}, {0, 0, -1}, 1e9), 200, 1e-3);
  s.props.front().pose.center_mm = {200, 0, 0};
  const prop_hit_function moved = scene_prop_hits(s);
  EXPECT_EQ(prop_scene_builds(), builds + 1);
  EXPECT_NEAR(moved({200, 0, 400}, {0, 0, -1}, 1e9), 200, 1e-3);
  EXPECT_TRUE(std::isinf(moved({0, 0, 400}, {0, 0, -1}, 1e9)));
  EXPECT_NEAR(first({0, 0, 400}, {0, 0, -1}, 1e9), 200, 1e-3);  // the earlier layout's answer stands
}

// An edit that moves a prop shares the mesh's acceleration structure with the layout before it:
// each function still answers for its own layout, even after the next one is built.
TEST_F(PlateInFront, HitsOfAMovedPropFollowItAndEarlierOnesKeepTheirLayout) {
  const prop_hit_function before = scene_prop_hits(s);
  s.props.front().pose.center_mm = {200, 0, 0};
  const prop_hit_function after = scene_prop_hits(s);
  const glm::dvec3 down(0, 0, -1);
  EXPECT_NEAR(before({0, 0, 400}, down, 1e9), 200, 1e-3);
  EXPECT_TRUE(std::isinf(before({200, 0, 400}, down, 1e9)));
  EXPECT_NEAR(after({200, 0, 400}, down, 1e9), 200, 1e-3);
  EXPECT_TRUE(std::isinf(after({0, 0, 400}, down, 1e9)));
}

namespace {

// Traces `spp` samples of every pixel with the plain estimator; the per-component means.
std::vector<double> traced_components(const scene& s, std::uint64_t spp) {
  embree_device device;
  tracer_scene ts;
  ts.use_model_image = false;
  build_tracer_scene(ts, device, s);
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(std::size_t(w) * h * 3, 0.0f), comps(component_count * sums.size(), 0.0f);
  const std::atomic<bool> never{false};
  std::uint64_t rays = 0;
  trace_rows(ts, 0, h, 0, spp, sums, never, rays, nullptr, &comps);
  std::vector<double> mean(component_count, 0.0);
  for (std::size_t i = 0; i < comps.size(); ++i) mean[(i / 3) % component_count] += comps[i];
  for (double& m : mean) m /= double(sums.size()) * double(spp);
  return mean;
}

}  // namespace

// A Lambertian plate 50 mm above the display, facing it, as large (50 x 50 mm): its radiance is
// albedo x L x F, F the view factor from its centre to the display, for two parallel squares
// (Howell's catalogue, C-11): F = 4 (2 pi)^-1 (X / sqrt(1 + X^2) atan(Y / sqrt(1 + X^2)) + (X <-> Y))
// with X = Y = 25 / 50, so F = 0.23946. The camera looks at the plate's centre from below, through a
// transparent half mirror, with a field of 0.4 mm.
TEST(Props, DiffusePlateLitByTheDisplayHasTheViewFactorsRadiance) {
  test::temp_dir dir;
  const plate lid(1, -100, -25, 25, -25, 25);  // x, then z
  write_plate(lid, dir.file("lid.glb"));
  scene s = test::uniform_source_scene(50, 16);
  s.half_mirror.reflectance = 0;
  s.half_mirror.transmittance = 1;
  s.sheet().pose.center_mm = {0, 50, -150};  // out of the plate's reach below it
  s.sheet().height_mm = 200;
  prop_params p = absorber_prop(dir.file("lid.glb"));
  p.surface = prop_surface::diffuse;
  p.albedo = {0.5, 0.5, 0.5};
  s.props.push_back(p);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, -130, 300};
  s.observer.look_at_mm = {0, -100, 0};
  s.observer.fov_deg = degrees(2 * std::atan(0.2 / std::hypot(30.0, 300.0)));
  check_scene(s, "lid");
  const double X = 0.5;
  const double f = 4 / (2 * pi) * 2 * X / std::sqrt(1 + X * X) * std::atan(X / std::sqrt(1 + X * X));
  ASSERT_NEAR(f, 0.23946, 1e-5);
  // Each sample is 0 or albedo x L (its bounce reaches the display or not): a binomial mean.
  const std::uint64_t spp = 1024;
  const double n = 16.0 * 16.0 * spp, want = 0.5 * s.source.intensity * f;
  const double sigma = 0.5 * s.source.intensity * std::sqrt(f * (1 - f) / n);
  const std::vector<double> got = traced_components(s, spp);
  std::printf("plate radiance %.5f, view factor predicts %.5f (sigma %.5f)\n", got[component_rest], want, sigma);
  EXPECT_NEAR(got[component_rest], want, 4 * sigma + 0.002 * want);
  EXPECT_EQ(got[component_aerial] + got[component_direct] + got[component_reflection], 0.0);
}

// A mirror prop (reflectance 0.7, a plate at z = -60 facing the observer) shows the display to an
// observer aimed at the display's mirror image (0, -150, -120), through a transparent half
// mirror: with a 2 degree field every sample of every pixel lands on the emitting area, so every
// pixel is exactly 0.7 L, all of it light a prop scattered.
TEST(Props, MirrorPropShowsTheDisplayAtItsReflectance) {
  test::temp_dir dir;
  // The same plate twice: modelled in place, and modelled lying in y = 0 (z from 80 to 200 mm)
  // and turned into place by its pose (pitch -90 takes (x, 0, z) to (x, -z, 0)), so the prop's
  // normal must be turned by its pose too.
  write_plate(plate(2, -60, -60, 60, -200, -80), dir.file("in_place.glb"));
  write_plate(plate(1, 0, -60, 60, 80, 200), dir.file("flat.glb"));
  for (const bool turned : {false, true}) {
    scene s = test::uniform_source_scene(50, 24);
    s.half_mirror.reflectance = 0;
    s.half_mirror.transmittance = 1;
    prop_params p = absorber_prop(dir.file(turned ? "flat.glb" : "in_place.glb"));
    p.surface = prop_surface::mirror;
    p.albedo = {0.7, 0.7, 0.7};
    if (turned) {
      p.pose.pitch_deg = -90;
      p.pose.center_mm = {0, 0, -60};
    }
    s.props.push_back(p);
    s.observer.placement = observer_placement::look_at;
    s.observer.position_mm = {0, 150, 410};
    s.observer.look_at_mm = {0, -150, -120};
    s.observer.fov_deg = 2;
    check_scene(s, "mirror");
    const std::vector<double> got = traced_components(s, 16);
    EXPECT_NEAR(got[component_rest], 0.7 * s.source.intensity, 1e-5) << (turned ? "turned" : "in place");
    EXPECT_EQ(got[component_aerial] + got[component_direct] + got[component_reflection], 0.0);
    // An absorber there shows nothing.
    s.props.front().surface = prop_surface::absorber;
    EXPECT_EQ(traced_components(s, 4)[component_rest], 0.0);
  }
}
