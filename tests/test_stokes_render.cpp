// Stokes images of the light reaching the observer (docs/polarization.md): a display's linear light
// arrives as the layout's mirrors turn it, an unpolarized display's stays unpolarized, the
// observer's polarizer sees what Malus's law makes of the Stokes images, and `airr render
// --stokes` writes them as layers.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/stokes_render.hpp"
#include "airr/render/render_session.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The mean of the green channel over the 8 x 8 pixels at the image's centre.
double centre(const image_rgb& img) {
  double sum = 0;
  for (int y = img.height / 2 - 4; y < img.height / 2 + 4; ++y)
    for (int x = img.width / 2 - 4; x < img.width / 2 + 4; ++x) sum += img.at(x, y)[1];
  return sum / 64;
}

scene bench(light_state state, double angle_deg = 0) {
  scene s = test::uniform_source_scene(50, 48);
  s.source.polarization = {.state = state, .angle_deg = angle_deg};
  return s;
}

}  // namespace

// On the bench the display's width axis lies along the half mirror's hinge (s light at both
// passes) and its height axis in the plane of incidence; mirrors keep both, so linear light along
// the width reaches the observer along the image's right (S1 = S0), along the height along its up
// (S1 = -S0), and at 45 deg between them diagonally. Circular light stays circular; unpolarized
// light stays unpolarized.
TEST(StokesRender, TheDisplaysLightArrivesAsTheLayoutTurnsIt) {
  struct expected {
    light_state state;
    double angle_deg;
    double s1, s2, s3;  // over S0
  };
  for (const expected& e :
       {expected{light_state::linear, 0, 1, 0, 0}, expected{light_state::linear, 90, -1, 0, 0},
        expected{light_state::circular_positive, 0, 0, 0, NAN}, expected{light_state::unpolarized, 0, 0, 0, 0}}) {
    const stokes_images st = render_stokes(bench(e.state, e.angle_deg), 4, 2);
    const double s0 = centre(st.s[0]);
    const double s1 = centre(st.s[1]) / s0, s2 = centre(st.s[2]) / s0, s3 = centre(st.s[3]) / s0;
    std::printf("display %d at %g deg: S0 %.4f, S1/S0 %+.4f, S2/S0 %+.4f, S3/S0 %+.4f, dop %.4f\n", int(e.state),
                e.angle_deg, s0, s1, s2, s3, centre(st.degree));
    EXPECT_NEAR(s0, 2.5, 0.01);  // R T of the display's intensity, whatever its polarization
    EXPECT_NEAR(s1, e.s1, 1e-3);
    EXPECT_NEAR(s2, e.s2, 1e-3);
    if (std::isnan(e.s3)) {
      EXPECT_NEAR(std::abs(s3), 1, 1e-3);
    } else {
      EXPECT_NEAR(s3, e.s3, 1e-3);
    }
    EXPECT_NEAR(centre(st.degree), e.state == light_state::unpolarized ? 0 : 1, 1e-3);
  }
}

// A polarizer at angle a before the observer passes (S0 + S1 cos 2a + S2 sin 2a) / 2: the render
// through it agrees with what the Stokes images say, for light at an angle the layout turns.
TEST(StokesRender, TheObserversPolarizerSeesWhatMalussLawMakesOfThem) {
  scene s = bench(light_state::linear, 20);
  s.retroreflectors[0].films = {film_params{.axis_deg = 10, .retardance_waves = 0.1}};
  const stokes_images st = render_stokes(s, 8, 2);
  for (double a : {0.0, 30.0, 75.0, 120.0}) {
    scene seen = s;
    seen.observer.analyzer_deg = a;
    const double rendered = centre(test::render_to(seen, 8, 2).image());
    const double predicted = 0.5 * (centre(st.s[0]) + centre(st.s[1]) * std::cos(2 * radians(a)) +
                                    centre(st.s[2]) * std::sin(2 * radians(a)));
    std::printf("analyzer %5.1f deg: rendered %.4f, from the Stokes images %.4f\n", a, rendered, predicted);
    EXPECT_NEAR(rendered, predicted, 0.01 * centre(st.s[0]));
  }
}

TEST(StokesRender, TheCommandWritesTheLayers) {
  test::temp_dir dir;
  const std::string scene_path = test::scene_file(dir, [](nlohmann::json& j) {
    j["source"]["polarization"] = {{"state", "linear"}, {"angle_deg", 0}};
    j["observer"]["width"] = j["observer"]["height"] = 16;
  });
  const test::command_result r = test::run_cli("render " + scene_path + " --stokes --spp 2 -o " + dir.file("s.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(read_image_layer_names(dir.file("s.exr")), (std::vector<std::string>{"S0", "S1", "S2", "S3", "dop"}));
  const image_rgb s1 = load_image_layer(dir.file("s.exr"), "S1"), s0 = load_image_layer(dir.file("s.exr"), "S0");
  EXPECT_NEAR(centre(s1), centre(s0), 1e-4 * centre(s0));

  const test::command_result png = test::run_cli("render " + scene_path + " --stokes -o " + dir.file("s.png"));
  EXPECT_NE(png.exit_code, 0);
  EXPECT_NE(png.out.find("s.png: --stokes needs an EXR output (layers)"), std::string::npos) << png.out;
}
