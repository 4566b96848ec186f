// glTF meshes: write/read round trip and clear errors for bad files.
#include <fstream>

#include <gtest/gtest.h>

#include "airr/optics/assets.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/mesh_gltf.hpp"
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
