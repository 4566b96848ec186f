// A whole layout in one glTF file: export -> import -> export round trips, a Blender-like file
// built here placing every part where the test computes, and errors naming the node.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;
using test::error_of;

namespace {

// A housing prop: a box's five faces (open at the front), 80 x 60 x 40 mm, in metres.
void write_housing(const std::string& path) {
  test::gltf_builder b;
  const float x = 0.04f, y = 0.03f, z = 0.02f;
  const std::vector<float> p = {-x, -y, -z, x, -y, -z, x, y, -z, -x, y, -z, -x, -y, z, x, -y, z, x, y, z, -x, y, z};
  const std::vector<std::uint32_t> idx = {0, 2, 1, 0, 3, 2, 0, 1, 5, 0, 5, 4, 3, 6, 2,
                                          3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
  const int grey = b.add_material("grey", {0.3, 0.3, 0.3, 1}, 0, 0.8);
  const int mesh = b.add_mesh({{b.add_positions(p), b.add_indices(idx, 5123), grey}});
  const int rig = b.add_node({{"name", "Rig"}, {"scale", {2.0, 2.0, 2.0}}});
  b.add_node({{"name", "Box"}, {"mesh", mesh}, {"translation", {0.01, 0, 0}}}, rig);
  b.write(path, test::gltf_builder::storage::glb);
}

// A layout with everything not at its default: tilted, yawed and rolled parts, two sheets, a
// bezel, a preset model, props with a node, a scale and each surface.
scene busy_layout(const test::temp_dir& dir) {
  write_housing(dir.file("housing.glb"));
  scene s = test::uniform_source_scene(40, 64);
  s.base_dir = dir.path.string();
  s.source.bezel_mm = 3;
  s.source.intensity = 7.5;
  s.source.pose.yaw_deg = 5;
  s.half_mirror.reflectance = 0.45;
  s.half_mirror.transmittance = 0.4;
  s.half_mirror.width_mm = 260;
  s.sheet().pose.pitch_deg = 17.25;
  s.sheet().pose.roll_deg = 30;
  s.sheet().model = {.type = "sinc_shift", .values = {{"preset", std::string("rf-an")}}};
  retroreflector_params second;
  second.pose.center_mm = {0, -260, 120};
  second.pose.pitch_deg = 80;
  second.pose.yaw_deg = -10;
  second.width_mm = 120;
  second.height_mm = 90;
  s.retroreflectors.push_back(second);
  prop_params housing;
  housing.name = "housing";
  housing.mesh = "housing.glb";
  housing.node = "Rig";
  housing.scale = 1.5;
  housing.pose.center_mm = {0, -170, 10};
  housing.pose.yaw_deg = 20;
  housing.pose.pitch_deg = -5;
  housing.surface = prop_surface::diffuse;
  housing.albedo = {0.2, 0.3, 0.4};
  prop_params lip = housing;
  lip.name = "lip";
  lip.node = "";
  lip.scale = 1;
  lip.surface = prop_surface::material;
  lip.pose.center_mm = {0, -110, 60};
  lip.visible = false;
  s.props = {housing, lip};
  s.observer.elevation_deg = 12;
  s.seed = 42;
  check_scene(s, "busy");
  return s;
}

void expect_same_frame(const part_frame& a, const part_frame& b, const std::string& what) {
  EXPECT_LT(glm::length(a.center - b.center), 1e-6) << what << " centre";
  EXPECT_LT(glm::length(a.u - b.u), 1e-9) << what << " u";
  EXPECT_LT(glm::length(a.n - b.n), 1e-9) << what << " n";
  EXPECT_NEAR(a.width, b.width, 1e-4) << what << " width";
  EXPECT_NEAR(a.height, b.height, 1e-4) << what << " height";
}

std::vector<glm::dvec3> prop_world(const scene& s, const prop_params& p) {
  const auto mesh = prop_mesh(s, p);
  std::vector<glm::dvec3> out;
  const glm::dmat4 xf = prop_transform(p);
  for (std::uint32_t i : mesh->indices) out.push_back(glm::dvec3(xf * glm::dvec4(glm::dvec3(mesh->positions[i]), 1.0)));
  return out;
}

void expect_same_layout(const scene& a, const scene& b, const std::string& what) {
  expect_same_frame(source_frame(a), source_frame(b), what + ": display");
  expect_same_frame(half_mirror_frame(a), half_mirror_frame(b), what + ": half mirror");
  ASSERT_EQ(a.retroreflectors.size(), b.retroreflectors.size()) << what;
  for (std::size_t i = 0; i < a.retroreflectors.size(); ++i) {
    expect_same_frame(retroreflector_frame(a, i), retroreflector_frame(b, i), what + ": sheet " + std::to_string(i));
    EXPECT_EQ(a.retroreflectors[i].model, b.retroreflectors[i].model) << what;
  }
  EXPECT_EQ(a.source.bezel_mm, b.source.bezel_mm) << what;
  EXPECT_EQ(a.source.intensity, b.source.intensity) << what;
  EXPECT_EQ(a.half_mirror.reflectance, b.half_mirror.reflectance) << what;
  EXPECT_EQ(a.half_mirror.transmittance, b.half_mirror.transmittance) << what;
  EXPECT_EQ(a.observer, b.observer) << what;
  EXPECT_EQ(a.render, b.render) << what;
  EXPECT_EQ(a.seed, b.seed) << what;
  ASSERT_EQ(a.props.size(), b.props.size()) << what;
  for (std::size_t i = 0; i < a.props.size(); ++i) {
    const prop_params &p = a.props[i], &q = b.props[i];
    EXPECT_EQ(p.name, q.name) << what;
    EXPECT_EQ(p.surface, q.surface) << what;
    EXPECT_EQ(p.albedo, q.albedo) << what;
    EXPECT_EQ(p.visible, q.visible) << what;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p.pose.center_mm[k], q.pose.center_mm[k], 1e-6) << what << " prop " << i;
    const glm::dmat3 rp = pose_rotation(p.pose), rq = pose_rotation(q.pose);
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(rp[c] - rq[c]), 1e-9) << what << " prop " << i;
    const auto wp = prop_world(a, p), wq = prop_world(b, q);
    ASSERT_EQ(wp.size(), wq.size()) << what;
    double worst = 0;
    for (std::size_t k = 0; k < wp.size(); ++k) worst = std::max(worst, glm::length(wp[k] - wq[k]));
    EXPECT_LT(worst, 1e-3) << what << " prop " << i << " triangles";
  }
}

}  // namespace

TEST(GltfLayout, ExportImportExportKeepsTheLayout) {
  test::temp_dir dir;
  const scene s = busy_layout(dir);
  for (const char* name : {"layout.glb", "layout.gltf"}) {
    const std::string path = dir.file(name);
    export_gltf_layout(s, path);
    const scene back = load_scene(path);
    expect_same_layout(s, back, name);
    EXPECT_EQ(back.props[0].node, "housing");
    // And again from the imported layout: the same file content.
    const std::string again = dir.file(std::string("again_") + name);
    export_gltf_layout(back, again);
    expect_same_layout(back, load_scene(again), std::string("again ") + name);
  }
}

TEST(GltfLayout, PosesSurviveExactly) {
  test::temp_dir dir;
  const scene s = busy_layout(dir);
  export_gltf_layout(s, dir.file("l.glb"));
  const scene back = load_scene(dir.file("l.glb"));
  // Centres within 1e-6 mm, angles as numbers (no pose here is at a gimbal pole but the display's).
  for (const auto& [a, b] : {std::pair{s.half_mirror.pose, back.half_mirror.pose},
                             {s.sheet().pose, back.sheet().pose},
                             {s.retroreflectors[1].pose, back.retroreflectors[1].pose}}) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.center_mm[k], b.center_mm[k], 1e-6);
    EXPECT_NEAR(a.yaw_deg, b.yaw_deg, 1e-9);
    EXPECT_NEAR(a.pitch_deg, b.pitch_deg, 1e-9);
    EXPECT_NEAR(a.roll_deg, b.roll_deg, 1e-9);
  }
}

// Built as Blender exports: a root turned -90 degrees about x and scaled by 0.5 (a file modelled in
// other units and Z-up), the parts below it with matrices that put them at the canonical bench's
// places (a sheet yawed and rolled), one named by the naming rule and tagged by nothing else.
TEST(GltfLayout, BlenderLikeHierarchyPlacesEveryPartWhereTheTestComputes) {
  test::temp_dir dir;
  test::gltf_builder b;
  // A rectangle in the node's xy plane, front +z, 0.2 m wide and 0.1 m high.
  const int square = b.add_mesh({{b.add_positions({-0.1f, -0.05f, 0, 0.1f, -0.05f, 0, 0.1f, 0.05f, 0, -0.1f, 0.05f, 0}),
                                  b.add_indices({0, 1, 2, 0, 2, 3}, 5121), -1}});
  const glm::dquat root_turn = glm::angleAxis(glm::radians(-90.0), glm::dvec3(1, 0, 0));
  const glm::dmat4 root_m = glm::mat4_cast(root_turn) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
  const int root = b.add_node({{"name", "Scene Root"},
                               {"rotation", {root_turn.x, root_turn.y, root_turn.z, root_turn.w}},
                               {"scale", {0.5, 0.5, 0.5}}});
  struct part {
    std::string name;
    pose where;  // in the world, mm
    nlohmann::json extras;
  };
  auto at = [](std::array<double, 3> c, double yaw, double pitch, double roll) {
    pose p;
    p.center_mm = c;
    p.yaw_deg = yaw, p.pitch_deg = pitch, p.roll_deg = roll;
    return p;
  };
  const std::vector<part> parts = {
      {"screen", at({0, -150, 0}, 0, 90, 0), {{"airr", {{"role", "display"}, {"intensity", 4.0}}}}},
      {"beam splitter", at({0, 0, 0}, 0, 45, 0), {{"airr", {{"role", "half_mirror"}, {"reflectance", 0.3}}}}},
      {"airr_retroreflector.001", at({5, 10, -150}, 8, 12, 30), nullptr},
  };
  for (const auto& p : parts) {
    // world = root x local, with the world's scale 0.5 (the mesh's 0.2 m becomes 100 mm).
    glm::dmat4 world(glm::dmat3(pose_rotation(p.where)) * 0.5);
    world[3] = glm::dvec4(glm::dvec3(p.where.center_mm[0], p.where.center_mm[1], p.where.center_mm[2]) / 1000.0, 1.0);
    const glm::dmat4 local = glm::inverse(root_m) * world;
    std::vector<double> cols;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) cols.push_back(local[c][r]);
    }
    nlohmann::json n = {{"name", p.name}, {"mesh", square}, {"matrix", cols}};
    if (!p.extras.is_null()) n["extras"] = p.extras;
    b.add_node(n, root);
  }
  b.write(dir.file("blender.glb"), test::gltf_builder::storage::glb);
  const scene s = load_scene(dir.file("blender.glb"));
  const std::vector<part_frame> got = {source_panel_frame(s), half_mirror_frame(s), retroreflector_frame(s, 0)};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const glm::dmat3 r = pose_rotation(parts[i].where);
    const glm::dvec3 centre(parts[i].where.center_mm[0], parts[i].where.center_mm[1], parts[i].where.center_mm[2]);
    EXPECT_LT(glm::length(got[i].center - centre), 1e-6) << parts[i].name;
    EXPECT_LT(glm::length(got[i].n - r[2]), 1e-9) << parts[i].name;
    EXPECT_LT(glm::length(got[i].u - r[0]), 1e-9) << parts[i].name;
    EXPECT_NEAR(got[i].width, 100, 1e-4) << parts[i].name;
    EXPECT_NEAR(got[i].height, 50, 1e-4) << parts[i].name;
  }
  EXPECT_EQ(s.source.intensity, 4.0);
  EXPECT_EQ(s.half_mirror.reflectance, 0.3);
  EXPECT_TRUE(s.props.empty());
}

TEST(GltfLayout, BadLayoutsNameTheNode) {
  test::temp_dir dir;
  auto layout = [&](const std::function<void(test::gltf_builder&, int)>& edit) {
    test::gltf_builder b;
    const int square = b.add_mesh({{b.add_positions({-0.1f, -0.1f, 0, 0.1f, -0.1f, 0, 0.1f, 0.1f, 0, -0.1f, 0.1f, 0}),
                                    b.add_indices({0, 1, 2, 0, 2, 3}, 5121), -1}});
    b.add_node({{"name", "airr_display"},
                {"mesh", square},
                {"translation", {0, -0.15, 0}},
                {"rotation", {-0.7071067811865476, 0, 0, 0.7071067811865476}}});
    b.add_node({{"name", "airr_half_mirror"},
                {"mesh", square},
                {"rotation", {-0.3826834323650898, 0, 0, 0.9238795325112867}}});
    b.add_node({{"name", "airr_retroreflector"}, {"mesh", square}, {"translation", {0, 0, -0.15}}});
    edit(b, square);
    const std::string path = dir.file("bad.glb");
    b.write(path, test::gltf_builder::storage::glb);
    return error_of([&] { load_scene(path); });
  };
  EXPECT_EQ(layout([](auto&, int) {}), "") << "the base layout loads";
  // A bent half mirror: one corner lifted 5 mm.
  const std::string bent = layout([](auto& b, int) {
    const int tent =
        b.add_mesh({{b.add_positions({-0.1f, -0.1f, 0, 0.1f, -0.1f, 0, 0.1f, 0.1f, 0.005f, -0.1f, 0.1f, 0}),
                     b.add_indices({0, 1, 2, 0, 2, 3}, 5121), -1}});
    b.doc["nodes"][1]["mesh"] = tent;
  });
  EXPECT_NE(bent.find("node 'airr_half_mirror' (#1): the half_mirror must be flat"), std::string::npos) << bent;
  const std::string none = layout([](auto& b, int) { b.doc["nodes"][0]["name"] = "screen"; });
  EXPECT_NE(none.find("no node is the display"), std::string::npos) << none;
  const std::string two = layout([](auto& b, int sq) { b.add_node({{"name", "airr_half_mirror.001"}, {"mesh", sq}}); });
  EXPECT_NE(two.find("more than one half_mirror: node 'airr_half_mirror' (#1), node 'airr_half_mirror.001' (#3)"),
            std::string::npos)
      << two;
  const std::string geometry = layout([](auto& b, int) {
    b.doc["nodes"][1]["extras"] = {{"airr", {{"width_mm", 10}}}};
  });
  EXPECT_NE(geometry.find("(#1): extras airr.width_mm"), std::string::npos) << geometry;
  const std::string bad_role = layout([](auto& b, int) {
    b.doc["nodes"][2]["extras"] = {{"airr", {{"role", "mirror"}}}};
  });
  EXPECT_NE(bad_role.find("(#2): extras airr.role must be"), std::string::npos) << bad_role;
  const std::string bad_value = layout([](auto& b, int) {
    b.doc["nodes"][1]["extras"] = {{"airr", {{"reflectance", 3}}}};
  });
  EXPECT_NE(bad_value.find("half_mirror.reflectance"), std::string::npos) << bad_value;
  EXPECT_NE(error_of([&] { export_gltf_layout(scene{}, dir.file("layout.obj")); }).find(".glb or .gltf"),
            std::string::npos);
}

// The polarization parts travel in the nodes' extras: the p-AIRR scene with a plate half mirror, a
// quarter-wave film on the sheet and an analyzer before the observer comes back field for field.
TEST(GltfLayout, PolarizationPartsSurviveTheRoundTrip) {
  test::temp_dir dir;
  const std::vector<scene_override> parts = {
      parse_override("half_mirror.kind=plate"), parse_override("half_mirror.plate.thickness_mm=2.5"),
      parse_override("half_mirror.plate.front.coating=partial_mirror"), parse_override("observer.analyzer_deg=30"),
      parse_override("source.polarization.state=circular_negative")};
  const scene s = load_scene(asset_dir() + "/scenes/p_airr.json", parts);
  const std::string path = dir.file("p_airr.glb");
  export_gltf_layout(s, path);
  const nlohmann::json a = scene_to_json(s), b = scene_to_json(load_scene(path));
  for (const char* key : {"/source/polarization", "/half_mirror/kind", "/half_mirror/plate", "/half_mirror/polarizer",
                          "/retroreflectors/0/films", "/retroreflectors/0/model", "/observer/analyzer_deg"}) {
    const nlohmann::json::json_pointer at(key);
    ASSERT_TRUE(a.contains(at)) << key;
    EXPECT_EQ(b.value(at, nlohmann::json()), a.at(at)) << key;
  }
  EXPECT_EQ(b.at("/half_mirror/plate/thickness_mm"_json_pointer), 2.5);
}
