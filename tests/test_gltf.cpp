// glTF meshes: write/read round trip, props placed through node hierarchies, and clear errors
// naming the file and the node or accessor for bad files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(Gltf, SaveLoadRoundTrip) {
  test::temp_dir dir;
  triangle_mesh m;
  m.name = "tri";
  m.positions = {{0, 0, 0}, {1.5f, 0, 0}, {0, 2.25f, -1}, {3, 3, 3}};
  m.indices = {0, 1, 2, 1, 3, 2};
  save_gltf_mesh(m, dir.file("m.gltf"));
  const triangle_mesh back = load_gltf_mesh(dir.file("m.gltf"));
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.indices, m.indices);
}

TEST(Gltf, ShippedPanelIsTheUnitPanel) {
  const triangle_mesh shipped = load_gltf_mesh(airr::asset_dir() + "/models/panel.gltf");
  const triangle_mesh made = make_unit_panel();
  EXPECT_EQ(shipped.positions, made.positions);
  EXPECT_EQ(shipped.indices, made.indices);
}

TEST(Gltf, BadFilesGiveErrorsNamingTheFile) {
  test::temp_dir dir;
  const std::string garbage = dir.file("garbage.gltf");
  std::ofstream(garbage) << "{ this is not json";
  const std::string empty = dir.file("empty.gltf");
  std::ofstream(empty) << R"({"asset": {"version": "2.0"}})";
  const std::string badref = dir.file("badref.gltf");
  std::ofstream(badref)
      << R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}],
                              "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})";
  for (const std::string& path : {garbage, empty, badref, dir.file("missing.gltf")}) {
    try {
      load_gltf_mesh(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

namespace {

// A small prop: two triangles (one quad) and a third triangle, with every index type and a
// primitive without indices, under a Blender-like hierarchy (metres, a parent with rotation and
// non-uniform scale, a child with its own TRS).
struct hierarchy_file {
  test::gltf_builder b;
  std::vector<float> quad = {0, 0, 0, 0.02f, 0, 0, 0.02f, 0.01f, 0, 0, 0.01f, 0};
  std::vector<float> tri = {0, 0, 0.01f, 0.01f, 0, 0.01f, 0, 0.01f, 0.01f};
  glm::dmat4 parent_matrix, child_matrix;

  hierarchy_file() {
    const int q = b.add_positions(quad), t = b.add_positions(tri);
    const int red = b.add_material("red", {0.8, 0.1, 0.1, 1}, 0.0, 0.9);
    const int chrome = b.add_material("chrome", {0.9, 0.9, 0.9, 1}, 1.0, 0.05);
    const int mesh = b.add_mesh({{q, b.add_indices({0, 1, 2}, 5121), red},
                                 {q, b.add_indices({0, 2, 3}, 5123), red},
                                 {t, b.add_indices({0, 1, 2}, 5125), chrome},
                                 {t, -1, -1}});
    // Parent: translate, turn 30 degrees about y, scale (1, 2, 1).
    const glm::dquat turn = glm::angleAxis(glm::radians(30.0), glm::dvec3(0, 1, 0));
    const int parent = b.add_node({{"name", "Frame"},
                                   {"translation", {0.1, 0.2, -0.05}},
                                   {"rotation", {turn.x, turn.y, turn.z, turn.w}},
                                   {"scale", {1.0, 2.0, 1.0}}});
    // Child: a column-major matrix with a 45 degree turn about x and half scale.
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0.01, 0, 0.02)) *
                         glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(1, 0, 0)) *
                         glm::scale(glm::dmat4(1.0), glm::dvec3(0.5));
    std::vector<double> cols;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) cols.push_back(m[c][r]);
    }
    b.add_node({{"name", "Hood"}, {"mesh", mesh}, {"matrix", cols}}, parent);
    parent_matrix = glm::translate(glm::dmat4(1.0), glm::dvec3(0.1, 0.2, -0.05)) * glm::mat4_cast(turn) *
                    glm::scale(glm::dmat4(1.0), glm::dvec3(1, 2, 1));
    child_matrix = m;
  }

  // The world positions (mm) of the triangles in the file's order: quad (2), tri, tri.
  std::vector<glm::dvec3> expected_world() const {
    std::vector<glm::dvec3> out;
    auto put = [&](const std::vector<float>& v, std::initializer_list<int> idx) {
      for (int i : idx) {
        const glm::dvec4 w = parent_matrix * child_matrix * glm::dvec4(v[3 * i], v[3 * i + 1], v[3 * i + 2], 1.0);
        out.push_back(1000.0 * glm::dvec3(w));
      }
    };
    put(quad, {0, 1, 2, 0, 2, 3});
    put(tri, {0, 1, 2, 0, 1, 2});
    return out;
  }
};

std::vector<glm::dvec3> placed_triangles(const triangle_mesh& m, const glm::dmat4& xf) {
  std::vector<glm::dvec3> out;
  for (std::uint32_t i : m.indices) out.push_back(glm::dvec3(xf * glm::dvec4(glm::dvec3(m.positions[i]), 1.0)));
  return out;
}

}  // namespace

TEST(Gltf, PropFromABlenderLikeHierarchyLandsWhereTheTestComputes) {
  test::temp_dir dir;
  hierarchy_file h;
  const std::vector<glm::dvec3> want = h.expected_world();
  for (auto [how, name] : {std::pair{test::gltf_builder::storage::data_uri, "embedded.gltf"},
                           {test::gltf_builder::storage::external_bin, "external.gltf"},
                           {test::gltf_builder::storage::glb, "binary.glb"}}) {
    const std::string path = dir.file(name);
    h.b.write(path, how);
    // The node: its rigid pose times its mesh (which keeps the scale and shear).
    prop_params p;
    p.pose = gltf_node_rigid_pose(path, "Hood");
    const triangle_mesh mesh = load_prop_mesh(path, "Hood");
    ASSERT_EQ(mesh.indices.size(), 12u) << name;
    const std::vector<glm::dvec3> got = placed_triangles(mesh, prop_transform(p));
    for (std::size_t i = 0; i < want.size(); ++i) {
      EXPECT_LT(glm::length(got[i] - want[i]), 1e-3) << name << " vertex " << i;
    }
    // The same node by index, and the whole scene (already in the world's frame).
    EXPECT_EQ(load_prop_mesh(path, "#1").positions, mesh.positions) << name;
    const std::vector<glm::dvec3> whole = placed_triangles(load_prop_mesh(path, ""), glm::dmat4(1.0));
    for (std::size_t i = 0; i < want.size(); ++i) EXPECT_LT(glm::length(whole[i] - want[i]), 1e-3) << name;
    // Materials: red diffuse, chrome a mirror, the last primitive glTF's default (rough metal: diffuse).
    ASSERT_EQ(mesh.triangle_materials.size(), 4u);
    p.surface = prop_surface::material;
    EXPECT_EQ(prop_surface_of(p, mesh, 0).kind, prop_surface::diffuse);
    EXPECT_NEAR(prop_surface_of(p, mesh, 1).reflectance.x, 0.8, 1e-6);
    EXPECT_EQ(prop_surface_of(p, mesh, 2).kind, prop_surface::mirror);
    EXPECT_EQ(prop_surface_of(p, mesh, 3).kind, prop_surface::diffuse);
    p.surface = prop_surface::absorber;
    EXPECT_EQ(prop_surface_of(p, mesh, 2).kind, prop_surface::absorber);
  }
}

TEST(Gltf, MirroringNodeKeepsTheFrontFace) {
  // A node scaled by -1 in x: glTF says the winding flips with it, so the front stays +z.
  test::temp_dir dir;
  test::gltf_builder b;
  const int mesh = b.add_mesh({{b.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0}), -1, -1}});
  b.add_node({{"name", "mirrored"}, {"mesh", mesh}, {"scale", {-1.0, 1.0, 1.0}}});
  b.write(dir.file("m.gltf"), test::gltf_builder::storage::data_uri);
  const triangle_mesh m = load_prop_mesh(dir.file("m.gltf"), "");
  ASSERT_EQ(m.indices.size(), 3u);
  const glm::vec3 n = glm::cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                                 m.positions[m.indices[2]] - m.positions[m.indices[0]]);
  EXPECT_GT(n.z, 0);
}

namespace {

// The message of the input_error that loading `path` (node `node`) throws, or "" for none.
std::string load_error(const std::string& path, const std::string& node = "") {
  try {
    load_prop_mesh(path, node);
  } catch (const input_error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not an input_error: ") + e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(Gltf, MalformedFilesNameTheFileAndWhatIsWrong) {
  test::temp_dir dir;
  auto one_triangle = [](test::gltf_builder& b, std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0}) {
    const int mesh = b.add_mesh({{b.add_positions(xyz), b.add_indices({0, 1, 2}, 5123), -1}});
    b.add_node({{"name", "part"}, {"mesh", mesh}});
  };
  struct bad_case {
    std::string name, expect;
    std::function<void(test::gltf_builder&)> edit;
    test::gltf_builder::storage how = test::gltf_builder::storage::data_uri;
  };
  const std::vector<bad_case> cases = {
      {"past_end.gltf", "accessor 0",
       [&](auto& b) {
         one_triangle(b);
         b.doc["accessors"][0]["count"] = 4;
       }},
      {"absurd.gltf", "accessor 0",
       [&](auto& b) {
         one_triangle(b);
         b.doc["accessors"][0]["count"] = 1LL << 40;
       }},
      {"index.gltf", "index 2 is 7",
       [&](auto& b) {
         one_triangle(b);
         b.bin[12 * 3 + 4] = 7;  // the third index (u16 after 36 bytes of positions)
       }},
      {"nan.gltf", "vertex 1 is not finite",
       [&](auto& b) {
         one_triangle(b, {0, 0, 0, NAN, 0, 0, 0, 1, 0});
       }},
      {"no_buffer.gltf", "missing.bin", [&](auto& b) { one_triangle(b); }},
      {"missing_accessor.gltf", "accessor 9",
       [&](auto& b) {
         one_triangle(b);
         b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
       }},
      {"cycle.gltf", "node 'part' (#0): is its own child",
       [&](auto& b) {
         one_triangle(b);
         b.doc["nodes"][0]["children"] = {0};
       }},
      {"truncated.glb", "GLB", [&](auto& b) { one_triangle(b); }, test::gltf_builder::storage::glb},
      {"bad_rotation.gltf", "node 'part' (#0): rotation",
       [&](auto& b) {
         one_triangle(b);
         b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0};
       }},
  };
  for (const auto& c : cases) {
    test::gltf_builder b;
    c.edit(b);
    const std::string path = dir.file(c.name);
    if (c.name == "no_buffer.gltf") {
      b.write(path, test::gltf_builder::storage::external_bin);
      nlohmann::json j = nlohmann::json::parse(std::ifstream(path));
      j["buffers"][0]["uri"] = "missing.bin";
      std::ofstream(path) << j.dump();
    } else {
      b.write(path, c.how);
    }
    if (c.name == "truncated.glb") std::filesystem::resize_file(path, std::filesystem::file_size(path) - 9);
    const std::string e = load_error(path);
    std::printf("%s\n", e.c_str());
    EXPECT_TRUE(has(e, path)) << c.name << ": " << e;
    EXPECT_TRUE(has(e, c.expect)) << c.name << ": expected '" << c.expect << "' in: " << e;
  }
  // Node references: missing, out of range, ambiguous.
  test::gltf_builder b;
  one_triangle(b);
  b.add_node({{"name", "part"}});
  b.write(dir.file("names.gltf"), test::gltf_builder::storage::data_uri);
  EXPECT_TRUE(has(load_error(dir.file("names.gltf"), "nope"), "no node named 'nope'"));
  EXPECT_TRUE(has(load_error(dir.file("names.gltf"), "#5"), "no node #5"));
  EXPECT_TRUE(has(load_error(dir.file("names.gltf"), "part"), "more than one node is named 'part'"));
  EXPECT_EQ(load_error(dir.file("names.gltf"), "#0"), "");
}
