// General layouts through the tracer: the aerial image forms at the analytic mirror image for
// random poses, the thin lens blurs by the thin-lens formula, the display's emission profile shows
// at the angle its light leaves towards the half mirror, and version 1 and 2 files render alike.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// Luminance centroid and second moments over a window of the image.
struct moments {
  double x = 0, y = 0, var_x = 0, var_y = 0, total = 0;
};
moments window_moments(const render_snapshot& snap, int x0, int y0, int x1, int y1) {
  moments m;
  auto value = [&](int x, int y) {
    const float* p = snap.rgb->data() + 3 * (std::size_t(y) * snap.width + x);
    return (p[0] + p[1] + p[2]) / 3.0;
  };
  x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, snap.width), y1 = std::min(y1, snap.height);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double v = value(x, y);
      m.total += v;
      m.x += v * (x + 0.5);
      m.y += v * (y + 0.5);
    }
  }
  if (m.total <= 0) return m;
  m.x /= m.total;
  m.y /= m.total;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const double v = value(x, y);
      m.var_x += v * (x + 0.5 - m.x) * (x + 0.5 - m.x);
      m.var_y += v * (y + 0.5 - m.y) * (y + 0.5 - m.y);
    }
  }
  m.var_x /= m.total;
  m.var_y /= m.total;
  return m;
}

}  // namespace

TEST(GeneralLayout, AerialImageFormsAtTheAnalyticMirrorImage) {
  pcg32 rng(2024, 11);
  int tested = 0, attempts = 0;
  double worst = 0;
  while (tested < 20 && attempts < 200) {
    ++attempts;
    scene s = test::random_general_layout(rng);
    const double alpha = s.half_mirror.pose.pitch_deg;
    s.observer.fov_deg = 8;
    s.seed = attempts;
    try {
      check_scene(s, "random layout");
    } catch (const input_error&) {
      continue;  // parts that meet: draw another layout
    }
    // A sheet reaching past the half mirror's plane would form a second, partial aerial image (by
    // reflection first, like the second sheet of a two-sheet device), whose brightness would pull
    // the centroid: the sheet's top edge comes down until the sheet is wholly behind the mirror.
    auto sheet_behind = [&] {
      const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s);
      for (double su : {-0.5, 0.5}) {
        for (double sv : {-0.5, 0.5}) {
          if (glm::dot(part_point(rr, su * rr.width, sv * rr.height) - hm.center, hm.n) >= 0) return false;
        }
      }
      return true;
    };
    while (!sheet_behind() && s.sheet().height_mm > 100) {
      const glm::dvec3 c = retroreflector_frame(s).center - 10.0 * retroreflector_frame(s).v;
      s.sheet().height_mm -= 20;
      s.sheet().pose.center_mm = {c.x, c.y, c.z};
    }
    const glm::dvec3 eye = observer_position(s), a = aerial_image_center(s);
    const auto p1 = hit_part(half_mirror_frame(s), eye, glm::normalize(a - eye));
    if (!sheet_behind() || !p1 || !hit_part(retroreflector_frame(s), *p1, glm::normalize(a - eye))) continue;
    const pinhole_camera cam = make_camera(s);
    const glm::dvec2 expected =
        camera_project(cam, mirror_point(source_frame(s).center, half_mirror_frame(s).center, half_mirror_frame(s).n));
    // The aerial image alone: the render minus the same render with a sheet that absorbs, which
    // removes the display seen directly through the half mirror where it overlaps.
    render_snapshot snap = test::render_to(s, 16);
    scene dark = s;
    set_model_value(dark.sheet().model, "mu", 0.0);
    const render_snapshot stray = test::render_to(dark, 16);
    auto aerial_only = std::make_shared<std::vector<float>>(*snap.rgb);
    for (std::size_t i = 0; i < aerial_only->size(); ++i) (*aerial_only)[i] -= (*stray.rgb)[i];
    snap.rgb = aerial_only;
    const int r = 14;
    const moments m =
        window_moments(snap, int(expected.x) - r, int(expected.y) - r, int(expected.x) + r, int(expected.y) + r);
    ASSERT_GT(m.total, 0) << "layout " << attempts;
    const double err = std::hypot(m.x - expected.x, m.y - expected.y);
    worst = std::max(worst, err);
    std::printf("layout %2d: mirror %.1f deg, display pitch %.1f, observer az %.1f el %.1f: centroid error %.3f px\n",
                attempts, alpha, s.source.pose.pitch_deg, s.observer.azimuth_deg, s.observer.elevation_deg, err);
    EXPECT_LT(err, 0.5) << "layout " << attempts << ": alpha " << alpha << ", observer az " << s.observer.azimuth_deg
                        << " el " << s.observer.elevation_deg << ", centroid (" << m.x << ", " << m.y << ") vs ("
                        << expected.x << ", " << expected.y << ")";
    ++tested;
  }
  EXPECT_EQ(tested, 20);
  std::printf("mirror image: %d layouts (%d drawn), worst centroid error %.3f px\n", tested, attempts, worst);
}

TEST(GeneralLayout, ThinLensBlurFollowsTheThinLensFormula) {
  // A 1 mm square at 300 mm, pixels of 0.1 mm on the aerial-image plane.
  scene s = test::uniform_source_scene(1.0, 96);
  s.observer.fov_deg = degrees(2 * std::atan(0.1 * 96 / 2 / 300));
  const render_snapshot pin = test::render_to(s, 64);
  const moments mp = window_moments(pin, 0, 0, 96, 96);
  apply_observer_preset(s, observer_preset::paper_camera);  // 50 mm at f/4, focused on the image
  const render_snapshot sharp = test::render_to(s, 64);
  const moments ms = window_moments(sharp, 0, 0, 96, 96);
  std::printf("pinhole spot variance %.3f px^2, thin lens in focus %.3f px^2\n", 0.5 * (mp.var_x + mp.var_y),
              0.5 * (ms.var_x + ms.var_y));
  EXPECT_LE(ms.var_x + ms.var_y, 1.01 * (mp.var_x + mp.var_y));
  EXPECT_NEAR(ms.x, mp.x, 0.05);

  for (double focus : {250.0, 360.0}) {
    s.observer.focus_distance_mm = focus;
    const render_snapshot blurred = test::render_to(s, 256);
    const moments mb = window_moments(blurred, 0, 0, 96, 96);
    // A uniform disc of diameter d has variance d^2 / 16 per axis; the square and the pixel add theirs.
    const double measured = 4 * std::sqrt(0.5 * (mb.var_x + mb.var_y - mp.var_x - mp.var_y));
    const pinhole_camera c = make_camera(s);
    const double z = 300, aperture = 50.0 / 4.0;
    const double disc_mm = aperture * std::abs(z - focus) / z;
    const double px_on_focus_plane = 2 * focus * c.tan_half_fov / c.height;
    const double expected = disc_mm / px_on_focus_plane;
    std::printf("focus %.0f mm: blur disc %.3f px, thin-lens formula %.3f px (%+.2f%%)\n", focus, measured, expected,
                100 * (measured / expected - 1));
    EXPECT_NEAR(measured / expected, 1.0, 0.03) << "focus " << focus;
  }
}

TEST(GeneralLayout, EmissionProfileShowsAtTheAngleTheLightLeaves) {
  const std::string profile_path = asset_dir() + "/displays/lcd_typical.csv";
  const emission_profile profile = read_emission_profile(profile_path);
  struct layout_case {
    const char* name;
    double alpha, display_tilt, azimuth, elevation;
  };
  for (const layout_case& c :
       {layout_case{"observer raised 20 deg", 45, 0, 0, 20}, layout_case{"display tilted 15 deg", 45, 15, 0, 0},
        layout_case{"mirror at 40, display -10, observer 15 deg aside", 40, -10, 15, 5}}) {
    scene s = test::posed_layout(c.alpha, {0, 0, 150}, c.display_tilt, 30.0);
    s.observer.azimuth_deg = c.azimuth;
    s.observer.elevation_deg = c.elevation;
    s.observer.width = s.observer.height = 48;
    check_scene(s, c.name);
    const render_snapshot lambertian = test::render_to(s, 16);
    s.source.emission_profile = profile_path;
    const render_snapshot shaped = test::render_to(s, 16);

    const pinhole_camera cam = make_camera(s);
    const glm::dvec3 a = aerial_image_center(s);
    const glm::dvec2 p = camera_project(cam, a);
    const int x = int(p.x), y = int(p.y);
    const double ratio = window_moments(shaped, x - 2, y - 2, x + 3, y + 3).total /
                         window_moments(lambertian, x - 2, y - 2, x + 3, y + 3).total;
    // The light that ends in the centre pixel leaves the display along the camera ray mirrored in the half mirror.
    const glm::dvec3 leaving = reflect(glm::normalize(a - cam.position), half_mirror_frame(s).n);
    const double theta = degrees(std::acos(glm::dot(leaving, source_frame(s).n)));
    const double expected = profile.at(theta);
    std::printf("%s: leaves at %.2f deg, brightness ratio %.4f, profile %.4f (%+.2f%%)\n", c.name, theta, ratio,
                expected, 100 * (ratio / expected - 1));
    EXPECT_NEAR(ratio / expected, 1.0, 0.02) << c.name;
    EXPECT_GT(theta, 4.0) << c.name;  // the case tests an angle, not the normal
  }
}

TEST(GeneralLayout, DefaultSceneRendersBitIdenticallyThroughVersion1And2) {
  const std::string v1_path = std::string(AIRR_TEST_DATA_DIR) + "/scene_v1/default.json";
  scene v1 = parse_scene(read_text_file(v1_path), v1_path, asset_dir() + "/scenes");
  test::temp_dir dir;
  save_scene(rebase_scene_paths(v1, dir.path.string()), dir.file("v2.json"));
  ASSERT_EQ(nlohmann::json::parse(read_text_file(dir.file("v2.json"))).at("version"), 2);
  scene v2 = load_scene(dir.file("v2.json"));
  v1.observer.width = v1.observer.height = v2.observer.width = v2.observer.height = 48;
  const render_snapshot a = test::render_to(v1, 8), b = test::render_to(v2, 8);
  ASSERT_EQ(a.rgb->size(), b.rgb->size());
  EXPECT_TRUE(*a.rgb == *b.rgb);
  double sum = 0;
  for (float v : *a.rgb) sum += v;
  EXPECT_GT(sum, 0);
}
