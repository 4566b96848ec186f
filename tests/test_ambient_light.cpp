// Ambient light: the room around the device, a uniform surround of luminance L_a (spec section
// 11). Seen at the aerial image, the half mirror reflects R L_a of it and passes T L_a of what lies
// behind; a sheet returns T T L_a of it towards the eye; a diffuse prop in the open shows
// albedo x L_a. The room's light is its own component and leaves the display's components alone.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "plate_mesh.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The ideal bench, its display's white at 500 cd/m2, in a room of `room` cd/m2, seen from the
// default observer through a narrow field about the aerial image's centre.
scene bench_in_room(double room) {
  scene s = test::white_bench(500, 16);
  s.environment.room.luminance_cd_m2 = room;
  s.observer.fov_deg = 2;
  return s;
}

render_snapshot render_with_layers(const scene& s, const std::vector<std::string>& layers, std::uint64_t spp) {
  render_session session(s, {.threads = 2,
                             .target_spp = spp,
                             .components = true,
                             .layers = std::make_shared<const path_layers>(parse_layer_arguments(layers, s, {}))});
  return session.wait_for(0, spp);
}

// The mean of the green channel (a neutral room: every channel alike) over the whole image.
double mean_green(const image_rgb& img) {
  double sum = 0;
  for (std::size_t i = 1; i < img.rgb.size(); i += 3) sum += img.rgb[i];
  return sum / double(img.rgb.size() / 3);
}

}  // namespace

TEST(AmbientLight, TheHalfMirrorReflectsRTimesTheRoomAndPassesTTimesWhatLiesBehind) {
  scene s = bench_in_room(100);
  s.half_mirror.reflectance = 0.3;
  s.half_mirror.transmittance = 0.6;
  // The sheet moved out of the view: behind the half mirror lies the room itself.
  s.sheet().pose.center_mm = {2000, 0, -150};
  const render_snapshot snap = render_with_layers(s, {"veil=A:room H:r E", "through=A:room H:t E"}, 4);
  const double veil = mean_green(snap.layer_image(0)), through = mean_green(snap.layer_image(1));
  const double room = mean_green(snap.component_image(component_room));
  std::printf("room 100 cd/m2, R 0.3, T 0.6: reflection %.5f, through %.5f, room component %.5f cd/m2\n", veil, through,
              room);
  EXPECT_NEAR(veil, 0.3 * 100, 1e-3);
  EXPECT_NEAR(through, 0.6 * 100, 1e-3);
  EXPECT_NEAR(room, 0.9 * 100, 1e-3);
  // Nothing of the display's light reaches this view with the sheet away.
  EXPECT_EQ(mean_green(snap.component_image(component_aerial)), 0.0);
}

TEST(AmbientLight, TheSheetReturnsTheRoomTowardsTheEyeAndTheAerialImageStaysAsItWas) {
  const scene lit = bench_in_room(100), dark = bench_in_room(0);
  const std::vector<std::string> layers = {"veil=A:room H:r E", "returned=A:room H:t S0:retro H:t E"};
  const render_snapshot a = render_with_layers(lit, layers, 4);
  const double veil = mean_green(a.layer_image(0)), returned = mean_green(a.layer_image(1));
  std::printf(
      "ideal bench in a 100 cd/m2 room: veiling reflection %.5f (R L = 50), returned by the sheet %.5f "
      "(T T L = 25), the aerial image %.4f cd/m2\n",
      veil, returned, mean_green(a.component_image(component_aerial)));
  EXPECT_NEAR(veil, 50, 1e-3);
  EXPECT_NEAR(returned, 25, 0.01 * 25);
  // The room's light is kept apart: the display's components are those of the dark room, to the bit.
  const render_snapshot b = render_with_layers(dark, layers, 4);
  for (int k = 0; k < component_count; ++k) {
    if (k == component_room) continue;
    const image_rgb x = a.component_image(k), y = b.component_image(k);
    ASSERT_EQ(x.rgb.size(), y.rgb.size());
    EXPECT_EQ(std::memcmp(x.rgb.data(), y.rgb.data(), x.rgb.size() * sizeof(float)), 0) << component_names[k];
  }
  EXPECT_EQ(mean_green(b.component_image(component_room)), 0.0);
  // The room is unpolarized: a linear polarizer before the eye passes half of it (the plain half
  // mirror and the ideal sheet keep the state).
  scene analyzed = lit;
  analyzed.observer.analyzer_deg = 30;
  const render_snapshot p = render_with_layers(analyzed, layers, 4);
  EXPECT_NEAR(mean_green(p.layer_image(0)), 0.5 * veil, 1e-3);
  EXPECT_NEAR(mean_green(p.layer_image(1)), 0.5 * returned, 0.01 * 25);
}

TEST(AmbientLight, ADiffusePropInTheOpenShowsItsAlbedoTimesTheRoom) {
  test::temp_dir dir;
  // A plate between the observer and the device, facing the observer: its front sees only the room.
  test::write_plate(test::plate(2, 300, -40, 40, -40, 40), dir.file("card.glb"));
  scene s = bench_in_room(0);
  s.environment.room.illuminance_lux = 500;  // an office: the surround at 500 / pi cd/m2
  prop_params card;
  card.name = "card";
  card.mesh = dir.file("card.glb");
  card.surface = prop_surface::diffuse;
  card.albedo = {0.4, 0.4, 0.4};
  s.props.push_back(card);
  check_scene(s, "card");
  const render_snapshot snap = render_with_layers(s, {"card=A:room P:card E"}, 4);
  const double card_luminance = mean_green(snap.layer_image(0));
  std::printf("diffuse card, albedo 0.4, in a 500 lx room: %.5f cd/m2 (E albedo / pi = %.5f)\n", card_luminance,
              500 * 0.4 / std::numbers::pi);
  EXPECT_NEAR(card_luminance, 500 * 0.4 / std::numbers::pi, 1e-3);
  EXPECT_NEAR(mean_green(snap.component_image(component_room)), card_luminance, 1e-3);
}

TEST(AmbientLight, TheRoomIsSavedWhenSetAndBadValuesAreClearErrors) {
  test::temp_dir dir;
  scene s = bench_in_room(0);
  EXPECT_FALSE(scene_to_json(s, json_form::saved).contains("environment"));
  s.environment.room.illuminance_lux = 10000;
  EXPECT_NEAR(room_luminance(s.environment.room), 10000 / std::numbers::pi, 1e-9);
  const std::string path = dir.file("lit.json");
  save_scene(s, path);
  EXPECT_EQ(load_scene(path).environment, s.environment);

  const auto negative = test::run_cli("render " + path + " -o " + dir.file("x.png") +
                                      " --spp 1 --set environment.room.illuminance_lux=-500");
  test::expect_one_line_error(negative, {path, "environment.room.illuminance_lux", "-500"});
  const auto both = test::run_cli("render " + path + " -o " + dir.file("x.png") +
                                  " --spp 1 --set environment.room.luminance_cd_m2=100");
  test::expect_one_line_error(both, {path, "environment.room", "not both"});
  const auto relative =
      test::run_cli("render " + path + " -o " + dir.file("x.png") + " --spp 1 --set source.luminance_cd_m2=0");
  test::expect_one_line_error(relative, {path, "environment", "source.luminance_cd_m2"});
  const auto nan = test::run_cli("render " + path + " -o " + dir.file("x.png") +
                                 " --spp 1 --set environment.room.illuminance_lux=nan");
  EXPECT_NE(nan.exit_code, 0);
  EXPECT_NE(nan.out.find("environment.room.illuminance_lux"), std::string::npos) << nan.out;

  // The room as a component of `airr render`, in cd/m2.
  const auto ok = test::run_cli("render " + path + " -o " + dir.file("room.exr") +
                                " --spp 1 --component room --set observer.width=8 --set observer.height=8");
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
}
