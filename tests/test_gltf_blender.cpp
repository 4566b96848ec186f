// glTF layouts as Blender 3.4 writes them: roles as JSON strings on the mesh data, files drawn in
// millimetres, a camera moved after export, and errors naming the Blender object (the node).
// Each file is an exported layout whose GLB JSON chunk the test rewrites as Blender would.
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "glb_file.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;
using nlohmann::json;
using test::error_of;

namespace {

int node_named(const json& doc, const std::string& name) {
  for (std::size_t k = 0; k < doc["nodes"].size(); ++k) {
    if (doc["nodes"][k].value("name", "") == name) return int(k);
  }
  ADD_FAILURE() << "no node " << name;
  return 0;
}

// As Blender's custom-property panel writes them: every airr object a JSON string, on the mesh
// data when the node has a mesh (else on the node), and on the scene. Returns how many moved.
int as_blender_strings(json& doc) {
  int moved = 0;
  for (auto& n : doc["nodes"]) {
    if (!n.contains("extras")) continue;
    const std::string text = n["extras"]["airr"].dump();
    if (n.contains("mesh")) {
      doc["meshes"][n["mesh"].get<std::size_t>()]["extras"] = {{"airr", text}};
      n.erase("extras");
      ++moved;
    } else {
      n["extras"]["airr"] = text;
    }
  }
  doc["scenes"][0]["extras"]["airr"] = doc["scenes"][0]["extras"]["airr"].dump();
  return moved;
}

// Every root under one node scaled by k: the layout drawn k times too large.
void scale_all(json& doc, double k) {
  json root = {{"name", "Units"}, {"scale", {k, k, k}}, {"children", doc["scenes"][0]["nodes"]}};
  doc["nodes"].push_back(root);
  doc["scenes"][0]["nodes"] = {doc["nodes"].size() - 1};
}

// A 20 mm cube prop, in metres.
void write_box(const std::string& path) {
  test::gltf_builder b;
  const float h = 0.01f;
  const std::vector<float> p = {-h, -h, -h, h, -h, -h, h, h, -h, -h, h, -h, -h, -h, h, h, -h, h, h, h, h, -h, h, h};
  const std::vector<std::uint32_t> idx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                          3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
  b.add_node({{"name", "Cube"}, {"mesh", b.add_mesh({{b.add_positions(p), b.add_indices(idx, 5121), -1}})}});
  b.write(path, test::gltf_builder::storage::glb);
}

// The half mirror (320 mm) is the largest part; the observer orbits at 12 degrees.
scene bench(const test::temp_dir& dir) {
  write_box(dir.file("box.glb"));
  scene s = test::uniform_source_scene(40, 64);
  s.base_dir = dir.path.string();
  s.source.intensity = 7.5;
  s.half_mirror.reflectance = 0.45;
  s.half_mirror.transmittance = 0.4;
  s.half_mirror.width_mm = 320;
  prop_params box;
  box.name = "box";
  box.mesh = "box.glb";
  box.pose.center_mm = {120, -150, 0};
  s.props = {box};
  s.observer.elevation_deg = 12;
  s.seed = 42;
  check_scene(s, "bench");
  return s;
}

// The exported bench, as dir/layout.glb.
std::string exported(const test::temp_dir& dir) {
  const std::string path = dir.file("layout.glb");
  export_gltf_layout(bench(dir), path);
  return path;
}

std::string all(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(GltfBlender, JsonStringsOnTheMeshDataReadAsNodeExtras) {
  test::temp_dir a, b;
  const std::string objects = exported(a), data = b.file("layout.glb");
  write_box(b.file("box.glb"));
  int moved = 0;
  test::rewrite_glb(objects, data, [&](json& j) { moved = as_blender_strings(j); });
  EXPECT_EQ(moved, 4) << "display, half mirror, sheet and prop move to their meshes";
  EXPECT_EQ(gltf_layout_document(data), gltf_layout_document(objects));
  const scene from_data = load_scene(data), from_objects = load_scene(objects);
  EXPECT_EQ(scene_to_json(from_data), scene_to_json(from_objects));
  // And the values are the bench's, not merely equal to each other.
  EXPECT_EQ(from_data.half_mirror.reflectance, 0.45);
  EXPECT_EQ(from_data.source.intensity, 7.5);
  EXPECT_EQ(from_data.seed, 42u);
  ASSERT_EQ(from_data.props.size(), 1u);
  EXPECT_EQ(from_data.props[0].name, "box");
}

TEST(GltfBlender, MalformedJsonStringNamesTheFileTheNodeAndTheProblem) {
  test::temp_dir dir;
  const std::string base = exported(dir), bad = dir.file("bad.glb");
  test::rewrite_glb(base, bad, [](json& j) {
    j["nodes"][node_named(j, "Half mirror")]["extras"]["airr"] = "{\"role\": \"half_mirror\", reflectance: 0.5}";
  });
  const std::string e = error_of([&] { load_scene(bad); });
  EXPECT_TRUE(has(e, bad + ": node 'Half mirror' (#1): extras airr (a JSON string): malformed JSON")) << e;
  test::rewrite_glb(base, bad, [](json& j) { j["nodes"][node_named(j, "Half mirror")]["extras"]["airr"] = "[1, 2]"; });
  const std::string not_object = error_of([&] { load_scene(bad); });
  EXPECT_TRUE(has(not_object, "node 'Half mirror' (#1): extras airr must be a JSON object")) << not_object;
}

TEST(GltfBlender, DevicesTenAndAThousandTimesTooLargeAreWarnedWithTheScale) {
  test::temp_dir dir;
  const std::string base = exported(dir);
  auto scaled = [&](double k) {
    const std::string path = dir.file("scaled_" + std::to_string(int(1000 * k)) + ".glb");
    test::rewrite_glb(base, path, [&](json& j) { scale_all(j, k); });
    return path;
  };
  const std::string normal = scaled(1), ten = scaled(10), thousand = scaled(1000), tiny = scaled(0.001);
  std::vector<std::string> notes;
  load_scene(normal, {}, notes);
  EXPECT_FALSE(has(all(notes), "warning:")) << all(notes);
  EXPECT_EQ(read_gltf_layout(normal).scale_warning, "");

  notes.clear();
  load_scene(ten, {}, notes);  // still a valid layout, only implausible
  EXPECT_TRUE(has(all(notes), "warning: " + ten + ": the half mirror is 3.2 m wide")) << all(notes);
  EXPECT_TRUE(has(all(notes), "ten times too large; scale it by 0.1 ")) << all(notes);

  const std::string big = all(read_gltf_layout(thousand).notes);
  EXPECT_TRUE(has(big, "warning: " + thousand + ": the half mirror is 320 m wide")) << big;
  EXPECT_TRUE(has(big, "drawn in millimetres; scale it by 0.001 ")) << big;
  // Too large for the scene's limits (parts within 100 m): the error carries the fix.
  const std::string e = error_of([&] { load_scene(thousand); });
  EXPECT_TRUE(has(e, "must be in [-100000, 100000]") && has(e, "; the half mirror is 320 m wide")) << e;

  const std::string small = all(read_gltf_layout(tiny).notes);
  EXPECT_TRUE(has(small, "the half mirror is 0.32 mm wide") && has(small, "scale it by 1000 ")) << small;
}

TEST(GltfBlender, ErrorsInANodesFieldsNameTheNodeAndTheFile) {
  test::temp_dir dir;
  const std::string base = exported(dir), bad = dir.file("bad.glb");
  auto error_after = [&](const std::function<void(json&)>& edit) {
    test::rewrite_glb(base, bad, edit);
    return error_of([&] { load_scene(bad); });
  };
  auto airr_of = [](json& j, const char* node) -> json& { return j["nodes"][node_named(j, node)]["extras"]["airr"]; };
  const std::string range = error_after([&](json& j) { airr_of(j, "Half mirror")["reflectance"] = 3; });
  EXPECT_TRUE(has(range, bad + ": node 'Half mirror' (#1): half_mirror.reflectance: must be in [0, 1]")) << range;
  const std::string type = error_after([&](json& j) { airr_of(j, "Display")["intensity"] = "bright"; });
  EXPECT_TRUE(has(type, bad + ": node 'Display' (#0): source.intensity: must be a number")) << type;
  const std::string prop = error_after([&](json& j) { airr_of(j, "box")["albedo"] = {2, 0, 0}; });
  EXPECT_TRUE(has(prop, bad + ": node 'box' (#3): props[0].albedo")) << prop;
  const std::string model = error_after([&](json& j) { airr_of(j, "Retroreflector 1")["model"]["type"] = "glass"; });
  EXPECT_TRUE(has(model, bad + ": node 'Retroreflector 1' (#2): retroreflectors[0].model")) << model;
  // On the mesh data, as a string: still the node (the object Blender shows).
  const std::string on_mesh = error_after([&](json& j) {
    airr_of(j, "Half mirror")["transmittance"] = -1;
    as_blender_strings(j);
  });
  EXPECT_TRUE(has(on_mesh, bad + ": node 'Half mirror' (#1): half_mirror.transmittance")) << on_mesh;
  // A --set value is the command line's, not the node's.
  const std::string set = error_of([&] { load_scene(base, {{"half_mirror.reflectance", "3"}}); });
  EXPECT_TRUE(has(set, "(with --set): half_mirror.reflectance") && !has(set, "node '")) << set;
}

TEST(GltfBlender, NodeExtrasWinOverMeshExtrasAndANoteSaysSo) {
  test::temp_dir dir;
  const std::string base = exported(dir), both = dir.file("both.glb");
  test::rewrite_glb(base, both, [](json& j) {
    const json& hm = j["nodes"][node_named(j, "Half mirror")];
    j["meshes"][hm["mesh"].get<std::size_t>()]["extras"] = {
        {"airr", json{{"role", "half_mirror"}, {"reflectance", 0.2}, {"transmittance", 0.7}}.dump()}};
  });
  std::vector<std::string> notes;
  const scene s = load_scene(both, {}, notes);
  EXPECT_EQ(s.half_mirror.reflectance, 0.45);
  EXPECT_EQ(s.half_mirror.transmittance, 0.4);
  EXPECT_TRUE(has(all(notes), "note: " + both +
                                  ": node 'Half mirror' (#1): airr extras on both the node and its mesh: "
                                  "the node's are used"))
      << all(notes);
  EXPECT_FALSE(has(all(read_gltf_layout(base).notes), "on both")) << "only when both are there";
}

TEST(GltfBlender, AMovedCameraWinsOverTheSceneExtrasUnlessTheySayOtherwise) {
  test::temp_dir dir;
  const scene s = bench(dir);
  const std::string base = dir.file("layout.glb"), moved = dir.file("moved.glb"), kept = dir.file("kept.glb");
  export_gltf_layout(s, base);
  const std::string camera = "node 'Observer' (#4)";
  // Unmoved: the extras' observer exactly (an orbit stays an orbit).
  std::vector<std::string> notes;
  EXPECT_EQ(load_scene(base, {}, notes).observer, s.observer);
  EXPECT_TRUE(has(all(notes), "observer: the scene extras' airr.observer, where the " + camera + " stands"))
      << all(notes);
  // Moved 50 mm to the right (+x) in Blender.
  test::rewrite_glb(base, moved, [](json& j) { j["nodes"][node_named(j, "Observer")]["translation"][0] = 0.05; });
  const pinhole_camera was = make_camera(s);
  notes.clear();
  const scene m = load_scene(moved, {}, notes);
  EXPECT_EQ(m.observer.placement, observer_placement::look_at);
  const glm::dvec3 at(m.observer.position_mm[0], m.observer.position_mm[1], m.observer.position_mm[2]);
  const glm::dvec3 aim(m.observer.look_at_mm[0], m.observer.look_at_mm[1], m.observer.look_at_mm[2]);
  EXPECT_LT(glm::length(at - (glm::dvec3(50, was.position.y, was.position.z))), 1e-6);
  EXPECT_NEAR(was.position.x, 0, 1e-9) << "the bench's observer starts on the axis";
  EXPECT_LT(glm::length(aim - (at + 300.0 * was.forward)), 1e-6) << "aims as far ahead, turned as before";
  EXPECT_EQ(m.observer.fov_deg, s.observer.fov_deg);
  EXPECT_EQ(m.observer.width, 64);
  EXPECT_TRUE(has(all(notes), "observer: the " + camera + ", moved from the scene extras' airr.observer"))
      << all(notes);
  // The scene extras say to use theirs.
  test::rewrite_glb(moved, kept, [](json& j) { j["scenes"][0]["extras"]["airr"]["observer_source"] = "extras"; });
  notes.clear();
  EXPECT_EQ(load_scene(kept, {}, notes).observer, s.observer);
  EXPECT_TRUE(has(all(notes), "observer: the scene extras' airr.observer (their observer_source is \"extras\"); the " +
                                  camera + " is not used"))
      << all(notes);
  test::rewrite_glb(moved, kept, [](json& j) { j["scenes"][0]["extras"]["airr"]["observer_source"] = "blender"; });
  EXPECT_TRUE(has(error_of([&] { load_scene(kept); }), "observer_source: must be \"camera\" or \"extras\""));
  // Without an observer in the extras the camera places one, aiming 300 mm ahead.
  test::rewrite_glb(moved, kept, [](json& j) { j["scenes"][0]["extras"]["airr"].erase("observer"); });
  notes.clear();
  const scene c = load_scene(kept, {}, notes);
  EXPECT_EQ(c.observer.position_mm, m.observer.position_mm);
  EXPECT_TRUE(has(all(notes), "observer: the " + camera + " (looking at a point 300 mm ahead)")) << all(notes);
}
