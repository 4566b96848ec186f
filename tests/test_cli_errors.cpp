// The airr command line on bad input: non-zero exit and one line naming the file and the field.
#include <fstream>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "test_helpers.hpp"

using namespace airr;

using test::expect_one_line_error;
using test::scene_file;

TEST(CliErrors, MalformedJson) {
  test::temp_dir dir;
  const std::string path = dir.file("bad.json");
  std::ofstream(path) << "{\"source\": ";
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")), {path, "malformed JSON"});
}

TEST(CliErrors, UnknownKey) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["observer"]["zoom"] = 2; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")),
                        {path, "observer.zoom", "unknown key"});
}

TEST(CliErrors, MissingGltf) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["retroreflectors"][0]["mesh"] = "gone.gltf"; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")),
                        {path, "retroreflectors[0].mesh", "gone.gltf"});
}

TEST(CliErrors, MalformedGltf) {
  test::temp_dir dir;
  std::ofstream(dir.file("broken.gltf")) << "{\"asset\": ";
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["source"]["mesh"] = "broken.gltf"; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")),
                        {"broken.gltf", "malformed glTF"});
}

TEST(CliErrors, MissingImage) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["source"]["image"] = "absent.png"; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")),
                        {path, "source.image", "absent.png"});
}

TEST(CliErrors, UnreadableImage) {
  test::temp_dir dir;
  std::ofstream(dir.file("fake.png")) << "not a png at all";
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["source"]["image"] = "fake.png"; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")), {"fake.png"});
}

TEST(CliErrors, NanSize) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json&) {});
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png") + " --set source.width_mm=nan"),
                        {"source.width_mm", "finite"});
}

TEST(CliErrors, NegativeSize) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) { j["half_mirror"]["height_mm"] = -300; });
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png")),
                        {path, "half_mirror.height_mm", "positive"});
}

TEST(CliErrors, ResolutionAboveCap) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json&) {});
  expect_one_line_error(test::run_cli("render " + path + " -o " + dir.file("o.png") + " --set observer.height=1000000"),
                        {"observer.height", "must be in"});
}

TEST(CliErrors, MissingSceneFile) {
  test::temp_dir dir;
  expect_one_line_error(test::run_cli("render " + dir.file("nope.json") + " -o " + dir.file("o.png")),
                        {"nope.json", "not found"});
}

TEST(CliRender, WritesImageWithMetadata) {
  test::temp_dir dir;
  const auto path = scene_file(dir, [](nlohmann::json& j) {
    j["observer"]["width"] = 48;
    j["observer"]["height"] = 40;
  });
  for (const std::string ext : {".exr", ".png"}) {
    const std::string out = dir.file("render" + ext);
    const auto r = test::run_cli("render " + path + " -o " + out + " --spp 4 --seed 9 --set tilt_deg=10");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const image_metadata meta = read_image_metadata(out);
    EXPECT_EQ(meta.at("airr:spp"), "4");
    EXPECT_EQ(meta.at("airr:seed"), "9");
    const scene layout = scene_from_json(nlohmann::json::parse(meta.at("airr:layout")), out);
    EXPECT_EQ(layout.sheet().pose.pitch_deg, 10);
    EXPECT_EQ(layout.observer.width, 48);
    EXPECT_NEAR(std::stod(meta.at("airr:mm_per_pixel")), 2 * 300 * std::tan(7 * M_PI / 180) / 40, 1e-12);
    const image_rgb img = load_image(out).pixels;
    EXPECT_EQ(img.width, 48);
    EXPECT_EQ(img.height, 40);
  }
}

TEST(CliRender, DefaultSceneRenders) {
  test::temp_dir dir;
  const auto r = test::run_cli("render " + airr::default_scene_path() + " -o " + dir.file("d.exr") +
                               " --spp 1 --set observer.width=32 --set observer.height=32");
  EXPECT_EQ(r.exit_code, 0) << r.out;
}

TEST(CliErrors, ViewzoneWritesItsMapAndNamesBadGrids) {
  test::temp_dir dir;
  const std::string path = scene_file(dir, [](nlohmann::json&) {});
  const auto ok = test::run_cli("viewzone " + path + " --grid 5 --rows 16 -o " + dir.file("zone.csv") + " --png " +
                                dir.file("zone.png"));
  ASSERT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("zone.png")));
  std::ifstream csv(dir.file("zone.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header, "x_mm,y_mm,eye_x_mm,eye_y_mm,eye_z_mm,visible_fraction");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 25);
  expect_one_line_error(test::run_cli("viewzone " + path + " --sphere --y -10 95 -o " + dir.file("z.csv")),
                        {"viewing zone", "elevations"});
  expect_one_line_error(test::run_cli("viewzone " + path + " --x 10 -10 -o " + dir.file("z.csv")),
                        {"viewing zone", "low to high"});
}

// A glTF layout's notes reach stderr: the render says which observer it used.
TEST(CliRender, GltfLayoutSaysWhichObserverItUsed) {
  test::temp_dir dir;
  const std::string layout = dir.file("layout.glb");
  const auto exported = test::run_cli("export-gltf " + scene_file(dir, [](nlohmann::json&) {}) + " -o " + layout);
  ASSERT_EQ(exported.exit_code, 0) << exported.out;
  const auto r = test::run_cli("render " + layout + " -o " + dir.file("o.png") +
                               " --spp 1 --set observer.width=16 --set observer.height=16");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("note: " + layout + ": observer: the scene extras' airr.observer, where the node 'Observer'"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("observer (orbit) at (0, 0, 450) mm"), std::string::npos) << r.out;
}
