// The scene format: exact round trips, atomic saves, and one clear error per kind of bad input.
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

using test::error_of;

// Writes a scene file into dir (with the shipped models), after editing its JSON.
std::string write_scene(const test::temp_dir& dir, const std::function<void(nlohmann::json&)>& edit) {
  scene s = test::uniform_source_scene(20);
  nlohmann::json j = scene_to_json(s);
  edit(j);
  const std::string path = dir.file("scene.json");
  std::ofstream(path) << j.dump(2);
  return path;
}

}  // namespace

TEST(SceneJson, DefaultSceneRoundTripsExactly) {
  // The default scene (RF-Ay) and the ideal bench, both written by `airr make-assets`.
  for (const std::string& path : {airr::default_scene_path(), airr::ideal_bench_scene_path()}) {
    const scene a = load_scene(path);
    test::temp_dir dir;
    const std::string copy = dir.file("copy.json");
    // Relative paths are kept verbatim, so the saved text equals the shipped one.
    save_scene(a, copy);
    const nlohmann::json original = nlohmann::json::parse(read_text_file(path));
    const nlohmann::json saved = nlohmann::json::parse(read_text_file(copy));
    EXPECT_EQ(saved, scene_to_json(a)) << path;
    EXPECT_EQ(scene_to_json(scene_from_json(saved, copy)), saved) << path;
    // The shipped file is in the canonical complete form.
    EXPECT_EQ(original, saved) << path;
  }
}

TEST(SceneJson, NonDefaultValuesRoundTripBitExactly) {
  scene s = test::uniform_source_scene(12.345678901234567);
  set_floating_distance(s, 0.1 + 0.2 + 100);  // not exactly representable in decimal
  s.sheet().pose.pitch_deg = 1.0 / 3.0;
  s.sheet().pose.roll_deg = -17.25;
  s.seed = 18446744073709551615ull;
  s.source.pose.center_mm = {1e-17, -102.5, 3.25};
  s.source.pose.yaw_deg = 2.0 / 3.0;
  s.source.bezel_mm = 4.5;
  s.half_mirror.pose.pitch_deg = 38.0;
  s.retroreflectors.push_back(s.sheet());
  s.retroreflectors[1].model = {.type = "microfacet", .values = {}};
  set_model_value(s.retroreflectors[1].model, "internal_reflectance", 0.9);
  s.retroreflectors[1].pose.center_mm = {0, 250, 0};
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {10, 20, 400};
  s.observer.lens = observer_lens::thin_lens;
  s.observer.focus_distance_mm = 1.0 / 7.0 + 300;
  const nlohmann::json j = scene_to_json(s);
  const scene back = scene_from_json(nlohmann::json::parse(j.dump()), "mem");
  EXPECT_TRUE(back == s);
  EXPECT_EQ(back.retroreflectors[1].model, s.retroreflectors[1].model);
  EXPECT_EQ(back.observer, s.observer);
  EXPECT_EQ(scene_to_json(back), j);
  // Only the active model's fields are written.
  EXPECT_TRUE(j["retroreflectors"][1]["model"].contains("internal_reflectance"));
  EXPECT_FALSE(j["retroreflectors"][1]["model"].contains("preset"));
  EXPECT_FALSE(j["retroreflectors"][0]["model"].contains("internal_reflectance"));
}

TEST(SceneJson, SaveIsAtomicAndLeavesNoTemporaryFiles) {
  test::temp_dir dir;
  const std::string path = dir.file("s.json");
  std::ofstream(path) << "previous contents";
  save_scene(test::uniform_source_scene(10), path);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path)) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_NO_THROW(scene_from_json(nlohmann::json::parse(read_text_file(path)), path));
  // A save into a directory that does not exist fails without touching anything.
  EXPECT_NE(error_of([&] { save_scene(scene{}, dir.file("missing/dir/s.json")); }), "");
}

TEST(SceneJson, MalformedJsonNamesTheFile) {
  test::temp_dir dir;
  const std::string path = dir.file("broken.json");
  std::ofstream(path) << "{ \"floating_distance_mm\": 150, ";
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
}

TEST(SceneJson, UnknownKeyNamesTheField) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json& j) { j["retroreflectors"][0]["tilt"] = 5; });
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("retroreflectors[0].tilt: unknown key"), std::string::npos) << e;
  // A parameter of another model than the sheet's is unknown too.
  const auto p2 = write_scene(dir, [](nlohmann::json& j) { j["retroreflectors"][0]["model"]["eta"] = 1.5; });
  const std::string e2 = error_of([&] { load_scene(p2); });
  EXPECT_NE(e2.find("retroreflectors[0].model.eta: unknown key (not a parameter of the ideal model)"),
            std::string::npos)
      << e2;
}

TEST(SceneJson, MissingGltfNamesFieldAndFile) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json& j) { j["half_mirror"]["mesh"] = "nowhere.gltf"; });
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find("half_mirror.mesh: file not found"), std::string::npos) << e;
  EXPECT_NE(e.find("nowhere.gltf"), std::string::npos) << e;
}

TEST(SceneJson, MissingImageNamesFieldAndFile) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json& j) { j["source"]["image"] = "chart-missing.png"; });
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find("source.image: file not found"), std::string::npos) << e;
  EXPECT_NE(e.find("chart-missing.png"), std::string::npos) << e;
}

TEST(SceneJson, NegativeSizeIsRejected) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json& j) { j["source"]["width_mm"] = -5; });
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find("source.width_mm: must be positive"), std::string::npos) << e;
}

TEST(SceneJson, NanFromOverrideIsRejected) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json&) {});
  const std::string e = error_of([&] { load_scene(path, {parse_override("retroreflectors.0.pose.pitch_deg=nan")}); });
  EXPECT_NE(e.find("retroreflectors.0.pose.pitch_deg"), std::string::npos) << e;
  EXPECT_NE(e.find("finite"), std::string::npos) << e;
  const std::string e2 = error_of([&] { load_scene(path, {parse_override("floating_distance_mm=nan")}); });
  EXPECT_NE(e2.find("floating_distance_mm"), std::string::npos) << e2;
}

TEST(SceneJson, HugeNumberInFileIsRejected) {
  test::temp_dir dir;
  const std::string path = dir.file("huge.json");
  std::ofstream(path) << R"({"format": "airr-scene", "version": 1, "floating_distance_mm": 1e999})";
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find(path), std::string::npos) << e;
}

TEST(SceneJson, ResolutionAboveCapIsRejected) {
  test::temp_dir dir;
  const auto path = write_scene(dir, [](nlohmann::json& j) { j["observer"]["width"] = 100000; });
  const std::string e = error_of([&] { load_scene(path); });
  EXPECT_NE(e.find("observer.width: must be in"), std::string::npos) << e;
  // The largest accepted: 8192 a side (whether the machine has the memory is the render's to say).
  const auto path2 = write_scene(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 8192;
    j["observer"]["height"] = 8192;
  });
  EXPECT_EQ(load_scene(path2).observer.height, 8192);
  const auto path3 = write_scene(dir, [](nlohmann::json& j) { j["observer"]["height"] = 8193; });
  const std::string e3 = error_of([&] { load_scene(path3); });
  EXPECT_NE(e3.find("observer.height: must be in"), std::string::npos) << e3;
}

TEST(SceneJson, WrongTypesAndVersionsAreRejected) {
  test::temp_dir dir;
  auto p = write_scene(dir, [](nlohmann::json& j) { j["observer"]["width"] = "wide"; });
  EXPECT_NE(error_of([&] { load_scene(p); }).find("observer.width: must be an integer"), std::string::npos);
  p = write_scene(dir, [](nlohmann::json& j) { j["version"] = 99; });
  EXPECT_NE(error_of([&] { load_scene(p); }).find("version: unsupported version 99"), std::string::npos);
  p = write_scene(dir, [](nlohmann::json& j) { j["retroreflectors"][0]["model"]["type"] = "magic"; });
  EXPECT_NE(error_of([&] { load_scene(p); }).find("retroreflectors[0].model.type: unknown model 'magic'"),
            std::string::npos);
  p = write_scene(dir, [](nlohmann::json& j) { j["half_mirror"]["reflectance"] = 0.8; });
  EXPECT_NE(error_of([&] { load_scene(p); }).find("must not exceed 1"), std::string::npos);
}

TEST(SceneJson, OverridesReachFieldsTheFileOmits) {
  test::temp_dir dir;
  const std::string path = dir.file("minimal.json");
  const std::string panel = airr::asset_dir() + "/models/panel.gltf";
  std::ofstream(path) << R"({"source": {"mesh": ")" << panel << R"(", "image": ""}, "half_mirror": {"mesh": ")" << panel
                      << R"("}, "retroreflectors": [{"mesh": ")" << panel << R"("}]})";
  const scene s = load_scene(
      path, {parse_override("retroreflectors.0.pose.pitch_deg=20"), parse_override("floating_distance_mm=225"),
             parse_override("retroreflectors.0.model.type=sinc_shift"),
             parse_override("retroreflectors.0.model.preset=rf-ay")});
  EXPECT_EQ(s.sheet().pose.pitch_deg, 20);
  EXPECT_NEAR(floating_distance(s), 225, 1e-12);
  EXPECT_EQ(s.sheet().model.type, "sinc_shift");
  EXPECT_EQ(read_model_values(s.sheet().model).text("preset"), "rf-ay");
  EXPECT_EQ(load_scene(path, {parse_override("tilt_deg=12")}).sheet().pose.pitch_deg, 12);
  EXPECT_NE(
      error_of([&] { load_scene(path, {parse_override("retroreflectors.0.pose.ptch_deg=20")}); }).find("unknown key"),
      std::string::npos);
  EXPECT_NE(error_of([&] {
              load_scene(path, {parse_override("retroreflectors.3.pose.pitch_deg=20")});
            }).find("no element 'retroreflectors.3'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_override("no-equals-sign"); }), "");
}

TEST(SceneJson, PropsRoundTripAndBadValuesNameTheProp) {
  test::temp_dir dir;
  test::gltf_builder b;
  const int mesh = b.add_mesh({{b.add_positions({0, 0, 0, 0.1f, 0, 0, 0, 0.1f, 0}), -1, -1}});
  b.add_node({{"name", "Hood"}, {"mesh", mesh}});
  b.write(dir.file("hood.glb"), test::gltf_builder::storage::glb);

  scene s = test::uniform_source_scene(20);
  s.base_dir = dir.path.string();
  prop_params p;
  p.name = "hood";
  p.mesh = "hood.glb";
  p.node = "Hood";
  p.scale = 0.001;
  p.pose.center_mm = {1.0 / 3.0, -120, 40};
  p.pose.yaw_deg = 12.5;
  p.surface = prop_surface::diffuse;
  p.albedo = {0.1, 0.2, 0.3};
  p.visible = false;
  prop_params plain;
  plain.name = "plain";
  plain.mesh = "hood.glb";
  s.props = {p, plain};
  save_scene(s, dir.file("s.json"));
  const scene back = load_scene(dir.file("s.json"));
  EXPECT_EQ(back.props, s.props);
  // --set reaches a prop's fields.
  EXPECT_EQ(load_scene(dir.file("s.json"), {parse_override("props.1.surface=mirror")}).props[1].surface,
            prop_surface::mirror);

  auto edited = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = scene_to_json(s);
    edit(j);
    std::ofstream(dir.file("bad.json")) << j.dump();
    return error_of([&] { load_scene(dir.file("bad.json")); });
  };
  EXPECT_NE(edited([](auto& j) {
              j["props"][1]["albedo"] = {0.5, 2, 0.5};
            }).find("props[1].albedo"),
            std::string::npos);
  EXPECT_NE(edited([](auto& j) { j["props"][0]["surface"] = "shiny"; }).find("props[0].surface: unknown value 'shiny'"),
            std::string::npos);
  EXPECT_NE(edited([](auto& j) { j["props"][0].erase("mesh"); }).find("props[0].mesh: missing"), std::string::npos);
  EXPECT_NE(edited([](auto& j) { j["props"][0]["scale"] = 0; }).find("props[0].scale"), std::string::npos);
  EXPECT_NE(edited([](auto& j) { j["props"][0]["wings"] = 2; }).find("props[0].wings: unknown key"), std::string::npos);
  const std::string missing_node = edited([](auto& j) { j["props"][1]["node"] = "Visor"; });
  EXPECT_NE(missing_node.find("props[1]"), std::string::npos) << missing_node;
  EXPECT_NE(missing_node.find("no node named 'Visor'"), std::string::npos) << missing_node;
  const std::string missing_file = edited([](auto& j) { j["props"][0]["mesh"] = "gone.glb"; });
  EXPECT_NE(missing_file.find("props[0].mesh: file not found"), std::string::npos) << missing_file;
}
