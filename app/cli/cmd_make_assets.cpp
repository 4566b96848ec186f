// airr make-assets --dir DIR: regenerates the glTF models, test charts and scenes shipped in assets/
// (`--dir assets` in the source tree; installed assets are never rewritten in place).
#include <filesystem>

#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/test_charts.hpp"
#include "airr/models/corner_cube.hpp"
#include "airr/models/retro_model.hpp"
#include "cli/commands.hpp"

void add_make_assets_command(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("make-assets",
                                 "Regenerate the panel model, test charts, default scene and ideal bench in assets/");
  cmd->add_option("--dir", *dir, "Directory to write them into (the source tree's assets/ to update them)")->required();
  cmd->callback([dir] {
    namespace fs = std::filesystem;
    fs::create_directories(fs::path(*dir) / "models");
    fs::create_directories(fs::path(*dir) / "charts");
    const std::string panel = *dir + "/models/panel.gltf";
    airr::save_gltf_mesh(airr::make_unit_panel(), panel);
    airr::save_gltf_mesh(airr::make_corner_cube(), *dir + "/models/corner_cube.gltf");
    airr::save_gltf_mesh(airr::make_corner_cube_tile(0.1), *dir + "/models/corner_cube_tile.gltf");
    const airr::image_metadata meta{{"airr:generator", "airr make-assets"}};
    airr::write_image(*dir + "/charts/test_chart.png", airr::make_test_chart(), meta);
    airr::write_image(*dir + "/charts/slanted_edge.png", airr::make_slanted_edge_chart(), meta);
    fs::create_directories(fs::path(*dir) / "scenes");
    // The reference layout (D = 150 mm, tilt 0) with the ideal retroreflector: the sharp bench.
    airr::scene ideal;
    ideal.source.image = "../charts/test_chart.png";
    airr::save_scene(ideal, *dir + "/scenes/ideal_bench.json");
    // The same layout with a real sheet, RF-Ay, so the first image shows its blur.
    airr::scene rf_ay = ideal;
    rf_ay.sheet().model = {.type = "sinc_shift", .values = {}};
    airr::set_model_value(rf_ay.sheet().model, "preset", "rf-ay");
    airr::save_scene(rf_ay, *dir + "/scenes/default.json");
    std::fprintf(stderr,
                 "wrote %s, models/corner_cube.gltf, models/corner_cube_tile.gltf, charts/test_chart.png, "
                 "charts/slanted_edge.png, "
                 "scenes/default.json, scenes/ideal_bench.json in %s\n",
                 panel.c_str(), dir->c_str());
  });
}
