// The conventions of docs/conventions.md that no other test pins, each against hand-derived values:
// pose axes and angle order, observer placement, image and pixel orientation, display texture
// sampling, scene-file defaults, light from behind each part, and the viewing-zone grids.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "airr/render/embree_scene.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

void expect_vec(const glm::dvec3& got, const glm::dvec3& want, double tol = 1e-12) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

part_frame frame_of(double yaw, double pitch, double roll) {
  return pose_frame({.yaw_deg = yaw, .pitch_deg = pitch, .roll_deg = roll}, 1, 1);
}

// A layout built for the plain tracer (no model image), and a pixel's mean radiance over samples.
struct traced {
  embree_device device;
  tracer_scene ts;
  explicit traced(const scene& s) { build_tracer_scene(ts, device, s); }
  glm::dvec3 mean(int x, int y, int samples = 16) const {
    glm::dvec3 sum(0.0);
    std::uint64_t rays = 0;
    for (int i = 0; i < samples; ++i) sum += glm::dvec3(trace_sample(ts, x, y, std::uint64_t(i), rays));
    return sum / double(samples);
  }
};

// A white display 40 mm square at the origin facing +z (radiance 10), a half mirror 100 mm square
// at z = 100 facing +z (R 0.3, T 0.6), the sheet far out of view, and a look-at observer with a
// 2 degree field on 5 x 5 pixels: every sample of the middle pixel meets the same parts.
scene facing_display(const glm::dvec3& eye, const glm::dvec3& at) {
  scene s;
  s.source.pose = {.center_mm = {0, 0, 0}};
  s.source.width_mm = s.source.height_mm = 40;
  s.half_mirror.pose = {.center_mm = {0, 0, 100}};
  s.half_mirror.width_mm = s.half_mirror.height_mm = 100;
  s.half_mirror.reflectance = 0.3;
  s.half_mirror.transmittance = 0.6;
  s.sheet().pose = {.center_mm = {0, 1000, 0}};
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {eye.x, eye.y, eye.z};
  s.observer.look_at_mm = {at.x, at.y, at.z};
  s.observer.fov_deg = 2;
  s.observer.width = s.observer.height = 5;
  return s;
}

}  // namespace

TEST(Conventions, PoseAxesFollowYawPitchRollInThatOrder) {
  // No rotation: width along +x, height along +y, optical face +z. Quarter turns are exact.
  part_frame f = frame_of(0, 0, 0);
  expect_vec(f.u, {1, 0, 0}, 0);
  expect_vec(f.v, {0, 1, 0}, 0);
  expect_vec(f.n, {0, 0, 1}, 0);
  // Yaw turns about +y from +z towards +x.
  f = frame_of(90, 0, 0);
  expect_vec(f.n, {1, 0, 0}, 0);
  expect_vec(f.u, {0, 0, -1}, 0);
  // Pitch raises the normal towards +y; the height axis goes to -z.
  f = frame_of(0, 90, 0);
  expect_vec(f.n, {0, 1, 0}, 0);
  expect_vec(f.v, {0, 0, -1}, 0);
  // Roll turns the width axis towards the height axis (counter-clockwise seen from the front).
  f = frame_of(0, 0, 90);
  expect_vec(f.u, {0, 1, 0}, 0);
  expect_vec(f.v, {-1, 0, 0}, 0);
  // Yaw last, about the world's y: at roll 0 the width axis stays horizontal.
  f = frame_of(90, 30, 0);
  expect_vec(f.n, {std::cos(radians(30)), 0.5, 0});
  expect_vec(f.u, {0, 0, -1});
  // Roll first, about the part's own normal: pitch 90 then carries the rolled width axis to -z.
  f = frame_of(0, 90, 90);
  expect_vec(f.u, {0, 0, -1});
  expect_vec(f.v, {-1, 0, 0});
  expect_vec(f.n, {0, 1, 0});
}

TEST(Conventions, OrbitTurnsFromPlusZTowardsPlusXAndRaisesTowardsPlusY) {
  scene s;
  s.half_mirror.pose.pitch_deg = 35;  // the aerial image no longer faces +z: the orbit keeps the world's axes
  ASSERT_LT(aerial_image_frame(s).n.z, 0.95);
  const glm::dvec3 a = aerial_image_center(s);
  s.observer.distance_mm = 200;
  expect_vec(observer_position(s), a + glm::dvec3(0, 0, 200));
  s.observer.azimuth_deg = 90;
  expect_vec(observer_position(s), a + glm::dvec3(200, 0, 0));
  s.observer.azimuth_deg = -90;
  expect_vec(observer_position(s), a + glm::dvec3(-200, 0, 0));
  s.observer.azimuth_deg = 0;
  s.observer.elevation_deg = 30;
  const glm::dvec3 out(0, 0.5, std::cos(radians(30)));
  expect_vec(observer_position(s), a + 200.0 * out);
  // The orbiting observer looks at the aerial image's centre.
  expect_vec(observer_target(s), a);
  expect_vec(make_camera(s).forward, -out);
}

TEST(Conventions, LookAtObserverKeepsTheHorizonLevel) {
  scene s;
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {100, 200, 400};
  s.observer.look_at_mm = {0, 0, 150};
  pinhole_camera c = make_camera(s);
  expect_vec(c.position, {100, 200, 400});
  expect_vec(observer_target(s), {0, 0, 150});
  expect_vec(c.forward, glm::normalize(glm::dvec3(-100, -200, -250)));
  EXPECT_EQ(c.right.y, 0);  // right stays horizontal ...
  EXPECT_GT(c.right.x, 0);
  EXPECT_GT(c.up.y, 0);  // ... and up leans towards +y
  // Looking straight down, +x is right and the image's top is -z.
  s.observer.position_mm = {0, 500, 0};
  s.observer.look_at_mm = {0, 0, 0};
  c = make_camera(s);
  expect_vec(c.right, {1, 0, 0});
  expect_vec(c.up, {0, 0, -1});
}

TEST(Conventions, ThinLensApertureIsFOverNAndFocusDefaultsToTheAimPoint) {
  scene s;  // orbit, 300 mm from the aerial image's centre; a pinhole
  EXPECT_EQ(make_camera(s).aperture_mm, 0);
  expect_vec(make_camera_ray(make_camera(s), 10.5, 20.5, {0.9, 0.3}).origin, observer_position(s));
  s.observer.lens = observer_lens::thin_lens;  // 50 mm at f/4
  pinhole_camera c = make_camera(s);
  EXPECT_EQ(c.aperture_mm, 12.5);
  EXPECT_NEAR(c.focus_distance, 300, 1e-9);
  s.observer.focal_length_mm = 100;  // the focal length sets the aperture, not the field of view
  EXPECT_EQ(make_camera(s).aperture_mm, 25);
  EXPECT_EQ(make_camera(s).tan_half_fov, c.tan_half_fov);
  s.observer.focal_length_mm = 50;
  // A look-at observer focuses at its look-at point, wherever the aerial image is.
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, 0, 450};
  s.observer.look_at_mm = {0, 0, 50};
  EXPECT_EQ(make_camera(s).focus_distance, 400);
  s.observer.focus_distance_mm = 250;
  c = make_camera(s);
  EXPECT_EQ(c.focus_distance, 250);
  // Lens sample (0.25, 0): radius 6.25 x sqrt(0.25) along `right`, aimed at the axis 250 mm ahead.
  const camera_ray r = make_camera_ray(c, 128, 128, {0.25, 0});
  expect_vec(r.origin, {3.125, 0, 450});
  expect_vec(r.dir, glm::normalize(glm::dvec3(-3.125, 0, -250)));
  // Off the axis too, the rays of a pixel meet on the plane 250 mm ahead along `forward`.
  const glm::dvec3 d = camera_direction(c, 3, 7);
  const camera_ray off = make_camera_ray(c, 3, 7, {0.7, 0.4});
  const double t = (250 - glm::dot(off.origin - c.position, c.forward)) / glm::dot(off.dir, c.forward);
  expect_vec(off.origin + t * off.dir, c.position + d * (250 / glm::dot(d, c.forward)), 1e-9);
}

TEST(Conventions, ImagePositionsRunRightAndDownFromTheTopLeftCorner) {
  scene s;  // the observer on +z looks along -z
  s.observer.width = 200;
  s.observer.height = 100;
  const pinhole_camera c = make_camera(s);
  const glm::dvec3 corner = camera_direction(c, 0, 0);
  EXPECT_LT(corner.x, 0);  // position (0, 0), the image's top-left corner, looks up and to the left
  EXPECT_GT(corner.y, 0);
  expect_vec(camera_direction(c, 100, 50), c.forward);  // the image's centre is on the axis
  // fov_deg is vertical; the horizontal field follows from the aspect ratio (square pixels).
  const glm::dvec3 top = camera_direction(c, 100, 0), left = camera_direction(c, 0, 50);
  EXPECT_NEAR(top.y / -top.z, std::tan(radians(7)), 1e-12);
  EXPECT_NEAR(left.x / -left.z, -2 * std::tan(radians(7)), 1e-12);
  // camera_project: x to the right, y down.
  const glm::dvec2 p = camera_project(c, aerial_image_center(s) + glm::dvec3(10, 10, 0));
  EXPECT_GT(p.x, 100);
  EXPECT_LT(p.y, 50);
}

TEST(Conventions, PixelCoversTheUnitSquareRightAndBelowItsIndex) {
  // A display filling x, y in [0, 40] mm of the plane z = 0, seen along the axis from z = 300 on
  // 8 x 8 pixels of 9.2 mm there: the axis is the common corner of pixels (3, 3), (4, 3), (3, 4) and
  // (4, 4), and only (4, 3), right of it and above, sees the display, with every sample.
  scene s = facing_display({0, 0, 300}, {0, 0, 0});
  s.source.pose.center_mm = {20, 20, 0};
  s.half_mirror.pose.center_mm = {0, -1000, 0};  // out of view
  s.observer.width = s.observer.height = 8;
  s.observer.fov_deg = 14;
  const traced t(s);
  expect_vec(t.mean(4, 3), glm::dvec3(10), 1e-5);
  for (const auto& [x, y] : {std::pair{3, 3}, {3, 4}, {4, 4}}) expect_vec(t.mean(x, y), glm::dvec3(0), 0);
  // A 10 mm bezel around the emitting area now fills pixel (3, 3): it is black.
  s.source.bezel_mm = 10;
  const traced bezel(s);
  expect_vec(bezel.mean(3, 3), glm::dvec3(0), 0);
  expect_vec(bezel.mean(4, 3), glm::dvec3(10), 1e-5);
}

TEST(Conventions, DisplayTexelZeroIsTheTopLeftCornerBilinearClampedAtTheEdges) {
  test::temp_dir dir;
  image_rgb img;
  img.width = img.height = 2;
  img.rgb = {1, 0, 0, 0, 1, 0,   // row 0: red, green
             0, 0, 1, 0, 0, 0};  // row 1: blue, black
  write_image(dir.file("quad.exr"), img, {});
  scene s;  // canonical: the observer on +z faces the aerial image
  s.source.image = dir.file("quad.exr");
  s.source.width_mm = s.source.height_mm = 40;
  s.observer.width = s.observer.height = 49;  // odd: the middle pixel is centred on the axis
  const traced t(s);
  const pinhole_camera c = make_camera(s);
  // Aerial-image points 15 mm off the centre lie in the outer quarter texel of each corner, where
  // the clamped lookup is that texel alone (a wrapping one would mix in its neighbour). Each shows
  // R T mu x texel x intensity = 0.5 x 0.5 x 1 x texel x 10, the right way round (not mirrored).
  struct corner {
    double x, y;
    glm::dvec3 rgb;
  };
  for (const corner& k : {corner{-15, 15, {2.5, 0, 0}}, corner{15, 15, {0, 2.5, 0}}, corner{-15, -15, {0, 0, 2.5}},
                          corner{15, -15, {0, 0, 0}}}) {
    const glm::dvec2 p = camera_project(c, aerial_image_center(s) + glm::dvec3(k.x, k.y, 0));
    EXPECT_EQ(p.x < 24.5, k.x < 0);
    EXPECT_EQ(p.y<24.5, k.y> 0);
    expect_vec(t.mean(int(p.x), int(p.y)), k.rgb, 1e-5);
  }
  // The centre, halfway between the four texel centres: their mean (bilinear).
  expect_vec(t.mean(24, 24, 64), glm::dvec3(0.625), 0.02);
}

TEST(Conventions, SceneFileFieldsLeftOutKeepTheirPartsDefaults) {
  EXPECT_TRUE(scene_from_json(nlohmann::json::object(), "empty.json") == scene{});
  const nlohmann::json j = nlohmann::json::parse(R"({
    "source": {"width_mm": 30, "pose": {"center_mm": [0, -200, 0]}},
    "half_mirror": {"pose": {"yaw_deg": 10}},
    "retroreflectors": [{"pose": {"pitch_deg": 20}}, {"width_mm": 100}],
    "props": [{"mesh": "hood.glb"}],
    "observer": {"placement": "look_at"}
  })");
  const scene s = scene_from_json(j, "partial.json");
  ASSERT_EQ(s.retroreflectors.size(), 2u);
  ASSERT_EQ(s.props.size(), 1u);
  EXPECT_EQ(s.version, 2);
  // A pose without pitch_deg keeps the part's own default pitch, not 0.
  EXPECT_EQ(s.source.pose.pitch_deg, 90);
  EXPECT_EQ(s.source.width_mm, 30);
  EXPECT_EQ(s.source.height_mm, 50);
  EXPECT_EQ(s.half_mirror.pose.pitch_deg, 45);
  EXPECT_EQ(s.half_mirror.pose.yaw_deg, 10);
  EXPECT_EQ(s.half_mirror.width_mm, 300);
  // Every sheet starts from the sheet defaults, not from sheet 0.
  EXPECT_EQ(s.retroreflectors[0].pose.center_mm, (std::array<double, 3>{0, 0, -150}));
  EXPECT_EQ(s.retroreflectors[0].pose.pitch_deg, 20);
  EXPECT_EQ(s.retroreflectors[1].pose.pitch_deg, 0);
  EXPECT_EQ(s.retroreflectors[1].pose.center_mm, (std::array<double, 3>{0, 0, -150}));
  EXPECT_EQ(s.retroreflectors[1].width_mm, 100);
  EXPECT_EQ(s.retroreflectors[1].height_mm, 300);
  EXPECT_EQ(s.retroreflectors[1].model.type, "ideal");
  // A prop without a pose sits at the origin unturned: scale 1, an absorber, visible.
  EXPECT_TRUE(s.props[0].pose == pose{});
  EXPECT_EQ(s.props[0].scale, 1);
  EXPECT_EQ(s.props[0].surface, prop_surface::absorber);
  EXPECT_TRUE(s.props[0].visible);
  // The observer's other fields keep theirs.
  EXPECT_EQ(s.observer.position_mm, (std::array<double, 3>{0, 0, 450}));
  EXPECT_EQ(s.observer.look_at_mm, (std::array<double, 3>{0, 0, 150}));
  EXPECT_EQ(s.observer.lens, observer_lens::pinhole);
  EXPECT_FALSE(s.observer.focus_distance_mm);
  EXPECT_EQ(s.observer.fov_deg, 14);
  EXPECT_EQ(s.observer.width, 256);
  EXPECT_EQ(s.observer.height, 256);
}

TEST(Conventions, ModelsSendNothingBackForLightFromBehindTheSheet) {
  // wi and wo both point away from the sheet: the ideal sheet returns wo = wi.
  const ideal_retro ideal(0.8);
  const retro_sample front = ideal.sample({0.6, 0, 0.8}, {});
  expect_vec(front.wo, {0.6, 0, 0.8}, 0);
  EXPECT_EQ(front.weight, 0.8);
  sinc_shift_params lobe;
  lobe.a_per_mm = {0.5};
  lobe.mu = {0.9};
  lobe.c_mm = 0.0;
  lobe.reference_distance_mm = 300.0;
  const sinc_shift_retro sinc(lobe, nullptr);
  pcg32 rng(5, 1);
  for (const glm::dvec3& wi : {glm::dvec3(0.6, 0, -0.8), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 0)}) {
    EXPECT_EQ(ideal.sample(wi, {}).weight, 0.0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(sinc.sample(wi, test::random_retro_samples(rng)).weight, 0.0);
  }
}

TEST(Conventions, DisplayEmitsFromItsFrontOnlyAndEndsEveryPath) {
  // Seen from +z through the half mirror: the front, T x 10.
  expect_vec(traced(facing_display({0, 0, 300}, {0, 0, 0})).mean(2, 2), glm::dvec3(6), 1e-5);
  // Seen from -z: the back emits nothing, and lets nothing through (through it, the half mirror
  // would reflect the front: R x 10).
  expect_vec(traced(facing_display({0, 0, -300}, {0, 0, 0})).mean(2, 2), glm::dvec3(0), 0);
  // The viewing zone counts only paths that end on the display's front.
  scene s;
  s.source.pose.pitch_deg = -90;  // facing -y, away from the half mirror
  EXPECT_EQ(visible_fraction(viewing_parts(s), observer_position(s)), 0.0);
}

TEST(Conventions, HalfMirrorReflectsAndTransmitsAlikeFromBothSides) {
  for (const double yaw : {0.0, 180.0}) {  // the half mirror's normal +z, then -z
    // Through it, from +z: T x 10.
    scene s = facing_display({0, 0, 300}, {0, 0, 0});
    s.half_mirror.pose.yaw_deg = yaw;
    expect_vec(traced(s).mean(2, 2), glm::dvec3(6), 1e-5);
    // Reflected in it, from between the display and the mirror, looking at the mirror: R x 10.
    s = facing_display({0, 0, 50}, {0, 0, 100});
    s.half_mirror.pose.yaw_deg = yaw;
    expect_vec(traced(s).mean(2, 2), glm::dvec3(3), 1e-5);
  }
}

TEST(Conventions, SheetBackAbsorbsInTheTracerAndTheViewingZone) {
  // Canonical layout: the aerial image's centre shows R T mu L = 2.5 ...
  scene s;
  s.observer.fov_deg = 2;
  s.observer.width = s.observer.height = 5;
  expect_vec(traced(s).mean(2, 2), glm::dvec3(2.5), 1e-5);
  // ... and nothing once the sheet shows the half mirror its back.
  s.sheet().pose.yaw_deg = 180;
  expect_vec(traced(s).mean(2, 2), glm::dvec3(0), 0);
  // No eye sees an aerial image there in the viewing zone either.
  EXPECT_EQ(visible_fraction(viewing_parts(s), observer_position(s)), 0.0);
  // A sheet's back between the observer and the display hides it (without the sheet: T x 10 = 6).
  scene hidden = facing_display({0, 0, 300}, {0, 0, 0});
  hidden.sheet().pose = {.center_mm = {0, 0, 200}, .yaw_deg = 180};
  expect_vec(traced(hidden).mean(2, 2), glm::dvec3(0), 0);
}

TEST(Conventions, ViewingZonePlaneIsWorldXYAndTheSphereIsTheOrbit) {
  scene s;
  s.half_mirror.pose.pitch_deg = 35;  // the aerial image no longer faces +z: the grids keep the world's axes
  const glm::dvec3 a = aerial_image_center(s);
  eye_grid plane;
  plane.distance_mm = 300;
  expect_vec(eye_position(s, plane, 10, 20), a + glm::dvec3(10, 20, 300));
  eye_grid sphere = plane;
  sphere.kind = eye_grid::shape::sphere;
  expect_vec(eye_position(s, sphere, 90, 0), a + glm::dvec3(300, 0, 0));
  expect_vec(eye_position(s, sphere, 0, 30), a + 300.0 * glm::dvec3(0, 0.5, std::cos(radians(30))));
  // Columns from x_min to x_max, rows from y_min to y_max; a single point is the middle.
  eye_grid g;
  g.x_min = -100, g.x_max = 60, g.nx = 5;
  g.y_min = 10, g.y_max = 30, g.ny = 1;
  EXPECT_EQ(g.x_at(0), -100);
  EXPECT_EQ(g.x_at(1), -60);
  EXPECT_EQ(g.x_at(4), 60);
  EXPECT_EQ(g.y_at(0), 20);
  // Sphere elevations reach +-89 degrees.
  sphere.y_min = -89, sphere.y_max = 89;
  EXPECT_NO_THROW(check_eye_grid(sphere));
  sphere.y_max = 89.5;
  EXPECT_THROW(check_eye_grid(sphere), input_error);
}
