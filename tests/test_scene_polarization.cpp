// The scene file's polarization fields (docs/scene-format.md): they round-trip, files without them
// keep their form, --set reaches them, and bad values are one line naming the file and the field.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/formats/scene_json.hpp"
#include "test_helpers.hpp"

using namespace airr;
using nlohmann::json;

namespace {

scene polarizing_scene() {
  scene s = test::uniform_source_scene(20);
  s.source.polarization = {.state = light_state::linear, .angle_deg = 45};
  s.source.films = {film_params{.kind = film_kind::polarizer, .axis_deg = 45, .block_transmittance = 0.001}};
  s.half_mirror.kind = half_mirror_kind::reflective_polarizer;
  s.half_mirror.polarizer = {.axis_deg = 90,
                             .pass_transmittance = 0.9,
                             .pass_reflectance = 0.05,
                             .block_reflectance = 0.95,
                             .block_transmittance = 0.02};
  derive_half_mirror_light(s.half_mirror);
  s.half_mirror.films = {film_params{.face = part_face::back, .axis_deg = 10, .retardance_waves = 0.5}};
  s.sheet().films = {film_params{.axis_deg = 45, .retardance_waves = 0.25, .wavelength_nm = 560},
                     film_params{.kind = film_kind::polarizer, .axis_deg = -30, .pass_transmittance = 0.8}};
  s.observer.analyzer_deg = 12.5;
  return s;
}

}  // namespace

TEST(ScenePolarization, EveryFieldRoundTripsAndPlainScenesKeepTheirForm) {
  test::temp_dir dir;
  const scene s = polarizing_scene();
  EXPECT_TRUE(scene_polarizes(s));
  EXPECT_DOUBLE_EQ(s.half_mirror.reflectance, 0.5);     // (0.05 + 0.95) / 2
  EXPECT_DOUBLE_EQ(s.half_mirror.transmittance, 0.46);  // (0.9 + 0.02) / 2
  save_scene(s, dir.file("p.json"));
  scene back = load_scene(dir.file("p.json"));
  back.base_dir = s.base_dir;
  EXPECT_EQ(back, s);

  const json plain = scene_to_json(test::uniform_source_scene(20));
  EXPECT_FALSE(scene_polarizes(test::uniform_source_scene(20)));
  EXPECT_FALSE(plain["source"].contains("polarization"));
  EXPECT_FALSE(plain["source"].contains("films"));
  EXPECT_FALSE(plain["half_mirror"].contains("kind"));
  EXPECT_FALSE(plain["observer"].contains("analyzer_deg"));
}

TEST(ScenePolarization, SetReachesTheNewFields) {
  test::temp_dir dir;
  const std::string path = test::scene_file(dir, [](json&) {});
  const scene s =
      load_scene(path, {parse_override("source.polarization.state=circular_negative"),
                        parse_override("half_mirror.kind=reflective_polarizer"),
                        parse_override("half_mirror.polarizer.axis_deg=0"), parse_override("observer.analyzer_deg=30"),
                        parse_override("retroreflectors.0.films=[{\"axis_deg\": 45}]")});
  EXPECT_EQ(s.source.polarization.state, light_state::circular_negative);
  EXPECT_EQ(s.half_mirror.kind, half_mirror_kind::reflective_polarizer);
  EXPECT_DOUBLE_EQ(s.half_mirror.polarizer.axis_deg, 0);
  EXPECT_DOUBLE_EQ(s.half_mirror.reflectance, 0.5);
  EXPECT_DOUBLE_EQ(s.half_mirror.transmittance, 0.5);
  EXPECT_EQ(s.observer.analyzer_deg, 30.0);
  ASSERT_EQ(s.sheet().films.size(), 1u);
  EXPECT_EQ(s.sheet().films[0].kind, film_kind::retarder);
  EXPECT_DOUBLE_EQ(s.sheet().films[0].retardance_waves, 0.25);
}

TEST(ScenePolarization, BadValuesAreOneLineNamingTheFileAndTheField) {
  test::temp_dir dir;
  const json film = {{"kind", "retarder"}, {"axis_deg", 45}};
  const auto with_film = [&](json f) { return [f](json& j) { j["retroreflectors"][0]["films"] = json::array({f}); }; };
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {with_film({{"kind", "retarder"}}), "retroreflectors[0].films[0].axis_deg: missing"},
      {with_film({{"kind", "polarizer"}, {"face", "front"}}), "retroreflectors[0].films[0].axis_deg: missing"},
      {with_film({{"axis_deg", 45}, {"retardance_waves", -0.25}}),
       "retroreflectors[0].films[0].retardance_waves: must be in [0, 100] (is -0.25)"},
      {with_film({{"axis_deg", 45}, {"wavelength_nm", 55}}),
       "retroreflectors[0].films[0].wavelength_nm: must be in [200, 3000] (is 55)"},
      {with_film({{"axis_deg", 720}}), "retroreflectors[0].films[0].axis_deg: must be in [-360, 360] (is 720)"},
      {with_film({{"kind", "polarizer"}, {"axis_deg", 0}, {"pass_transmittance", 0.3}, {"block_transmittance", 0.5}}),
       "retroreflectors[0].films[0].block_transmittance: must not exceed pass_transmittance (0.3)"},
      {with_film({{"kind", "polarizer"}, {"axis_deg", 0}, {"pass_transmittance", 1.5}}),
       "retroreflectors[0].films[0].pass_transmittance: must be in [0, 1] (is 1.5)"},
      {with_film({{"kind", "wire grid"}, {"axis_deg", 0}}),
       "retroreflectors[0].films[0].kind: unknown value 'wire grid' (retarder, polarizer)"},
      {with_film({{"axis_deg", "45"}}), "retroreflectors[0].films[0].axis_deg: must be a number"},
      {with_film({{"axis_deg", 45}, {"thickness_mm", 0.1}}), "retroreflectors[0].films[0].thickness_mm: unknown key"},
      {[](json& j) {
         j["source"]["films"] = json::array();
         for (int i = 0; i < 9; ++i) j["source"]["films"].push_back({{"axis_deg", 0}});
       },
       "source.films: must be an array of at most 8 films"},
      {[](json& j) {
         j["source"]["films"] = {{"axis_deg", 0}};
       },
       "source.films: must be an array of at most 8 films"},
      {[](json& j) { j["half_mirror"]["kind"] = "reflective_polarizer"; }, "half_mirror.polarizer: missing"},
      {[](json& j) { j["half_mirror"]["kind"] = "beam splitter"; },
       "half_mirror.kind: unknown value 'beam splitter' (half_mirror, reflective_polarizer, plate)"},
      {[](json& j) {
         j["half_mirror"]["kind"] = "reflective_polarizer";
         j["half_mirror"]["polarizer"] = {{"pass_transmittance", 0.9}};
       },
       "half_mirror.polarizer.axis_deg: missing"},
      {[](json& j) {
         j["half_mirror"]["kind"] = "reflective_polarizer";
         j["half_mirror"]["polarizer"] = {{"axis_deg", 90}, {"block_reflectance", 0.9}, {"block_transmittance", 0.2}};
       },
       "half_mirror.polarizer.block_reflectance: block_transmittance + block_reflectance must not exceed 1"},
      {[](json& j) {
         j["half_mirror"]["kind"] = "reflective_polarizer";
         j["half_mirror"]["polarizer"] = {{"axis_deg", 90}, {"pass_reflectance", -0.1}};
       },
       "half_mirror.polarizer.pass_reflectance: must be in [0, 1] (is -0.1)"},
      {[](json& j) {
         j["source"]["polarization"] = {{"state", "elliptical"}};
       },
       "source.polarization.state: unknown value 'elliptical' (unpolarized, linear, circular_positive, "
       "circular_negative)"},
      {[](json& j) {
         j["source"]["polarization"] = {{"state", "linear"}, {"angle_deg", 1e6}};
       },
       "source.polarization.angle_deg: must be in [-360, 360] (is 1e+06)"},
      {[](json& j) { j["observer"]["analyzer_deg"] = "vertical"; }, "observer.analyzer_deg: must be a number"},
      {[](json& j) { j["observer"]["analyzer_deg"] = 400; }, "observer.analyzer_deg: must be in [-360, 360] (is 400)"},
  };
  for (const auto& [edit, expected] : cases) {
    const std::string path = test::scene_file(dir, edit);
    const std::string e = test::error_of([&] { load_scene(path); });
    EXPECT_NE(e.find(path + ": " + expected), std::string::npos) << "expected: " << expected << "\n     got: " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  // From --set, the value given is named too.
  const std::string path = test::scene_file(dir, [](json&) {});
  const std::string e = test::error_of([&] { load_scene(path, {parse_override("observer.analyzer_deg=nan")}); });
  EXPECT_NE(e.find("observer.analyzer_deg"), std::string::npos) << e;
  EXPECT_NE(e.find("finite"), std::string::npos) << e;
}
