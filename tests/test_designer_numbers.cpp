// The designer and the command line report the same numbers for the same scene: the designer's
// plots come from the measurement library's functions, not from a copy of them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/sweep.hpp"
#include "airr/ui/jobs/analysis_worker.hpp"
#include "airr/ui/platform/settings.hpp"
#include "airr/ui/studio/studio.hpp"
#include "gltf_builder.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

scene preset_scene() {
  scene s = test::uniform_source_scene(50, 256);
  s.sheet().model.type = "sinc_shift";
  airr::set_model_value(s.sheet().model, "preset", "rf-ay");
  return s;
}

// The number after `label` in the CLI's output.
double printed_number(const std::string& out, const std::string& label) {
  const auto at = out.find(label);
  if (at == std::string::npos) return -1;
  return std::stod(out.substr(at + label.size()));
}

}  // namespace

TEST(DesignerNumbers, PredictedPlotsEqualTheMeasurementLibrary) {
  const scene s = preset_scene();
  const std::uint64_t samples = 20000;
  const ui::predicted_plots pred = ui::compute_predicted(s, 1, {.psf_samples = samples, .sweep_psf_samples = samples});
  ASSERT_TRUE(pred.error.empty()) << pred.error;

  const psf_samples psf = scene_psf(s, samples);
  const mtf_summary m = psf_route_mtf(psf, make_camera(s).mm_per_pixel);
  EXPECT_EQ(pred.mean_mtf, m.mean_mtf);
  EXPECT_EQ(pred.mtf50, m.mtf50_lp_per_mm.value_or(0.0));
  EXPECT_EQ(pred.r50_mm, energy_radius(psf));
  EXPECT_EQ(pred.brightness, psf.brightness());

  sweep_params sp;
  sp.axes = {parse_sweep_axis("floating_distance=150:300:25")};
  sp.psf_route = true;
  sp.psf_samples = samples;
  const sweep_result r = run_sweep(s, sp);
  ASSERT_EQ(pred.sweep_mean_mtf.size(), r.points.size());
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    EXPECT_EQ(pred.sweep_d_mm[i], r.points[i].floating_distance_mm);
    EXPECT_EQ(pred.sweep_mean_mtf[i], r.points[i].mean_mtf) << "D " << r.points[i].floating_distance_mm;
  }
}

// On the shipped kiosk some floating distances of the mean-MTF curve are no layout: the curve
// keeps them as gaps with the sweep's reasons, and its other points are the sweep's.
TEST(DesignerNumbers, MeanMtfCurveKeepsTheDistancesThatAreNoLayout) {
  const scene s = load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json");
  const std::uint64_t samples = 5000;
  const ui::predicted_plots pred = ui::compute_predicted(s, 1, {.psf_samples = samples, .sweep_psf_samples = samples});
  sweep_params sp;
  sp.axes = {parse_sweep_axis("floating_distance=150:300:25")};
  sp.psf_route = true;
  sp.psf_samples = samples;
  const sweep_result r = run_sweep(s, sp);
  ASSERT_EQ(pred.sweep_d_mm.size(), r.points.size());
  ASSERT_EQ(pred.sweep_reasons.size(), r.points.size());
  int gaps = 0;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    EXPECT_EQ(pred.sweep_d_mm[i], r.points[i].floating_distance_mm);
    EXPECT_EQ(pred.sweep_reasons[i].empty(), r.points[i].valid()) << "D " << pred.sweep_d_mm[i];
    if (r.points[i].valid()) {
      EXPECT_EQ(pred.sweep_mean_mtf[i], r.points[i].mean_mtf) << "D " << pred.sweep_d_mm[i];
    } else {
      ++gaps;
      EXPECT_TRUE(std::isnan(pred.sweep_mean_mtf[i])) << "D " << pred.sweep_d_mm[i];
      std::printf("D %g mm: %s\n", pred.sweep_d_mm[i], pred.sweep_reasons[i].c_str());
    }
  }
  EXPECT_GE(gaps, 1);
  EXPECT_LT(gaps, int(r.points.size()));
}

TEST(DesignerNumbers, PredictedPlotsEqualAirrPsf) {
  test::temp_dir dir;
  const scene s = preset_scene();
  const std::string path = dir.file("scene.json");
  save_scene(s, path);
  const scene loaded = load_scene(path);
  const ui::predicted_plots pred = ui::compute_predicted(loaded, 1, {.psf_samples = 20000, .sweep_psf_samples = 2000});
  ASSERT_TRUE(pred.error.empty()) << pred.error;
  const auto run = test::run_cli("psf " + path + " -o " + dir.file("psf.csv") + " --samples 20000");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NEAR(printed_number(run.out, "mean MTF over (0, 1] lp/mm: "), pred.mean_mtf, 5e-6) << run.out;
  EXPECT_NEAR(printed_number(run.out, "50%-energy radius: "), pred.r50_mm, 5e-5) << run.out;
}

// The designer's export: an EXR carries the image's components as layers; a PNG is what the
// render view shows, here one component, named in its metadata.
TEST(DesignerNumbers, ExportWritesComponentLayersAndTheShownComponent) {
  test::temp_dir dir;
  ui::studio st;
  st.session_options.components = true;
  st.session_options.threads = 2;
  ui::studio_start(st, test::uniform_source_scene(20, 32), "");
  st.session->wait_for(st.generation, 2);
  ASSERT_TRUE(ui::studio_export_render(st, dir.file("render.exr"))) << st.status;
  EXPECT_EQ(read_image_layer_names(dir.file("render.exr")),
            (std::vector<std::string>{"aerial", "direct", "luminaires", "reflection", "rest", "room", "sun"}));
  st.view.component = component_direct;
  ASSERT_TRUE(ui::studio_export_render(st, dir.file("render.png"))) << st.status;
  EXPECT_EQ(read_image_metadata(dir.file("render.png")).at("airr:component"), "direct");
  st.view.component = -1;
  ASSERT_TRUE(ui::studio_export_render(st, dir.file("whole.png"))) << st.status;
  EXPECT_EQ(read_image_metadata(dir.file("whole.png")).count("airr:component"), 0u);
}

// Dropping a glTF model on the window adds it as a prop; a glTF file with parts in it is a layout,
// and opens instead; an unreadable one leaves the layout as it was and says why.
TEST(DesignerNumbers, DroppedGltfBecomesAPropOrOpensAsALayout) {
  test::temp_dir dir;
  ui::studio st;
  st.keep_recovery = false;
  st.session_options = {.threads = 1, .target_spp = 1};
  ui::studio_start(st, test::uniform_source_scene(50, 32), "");
  scene with_prop = st.doc;
  test::gltf_builder b;
  const int mesh = b.add_mesh({{b.add_positions({0, 0, 0, 0.1f, 0, 0, 0, 0.1f, 0}), -1, -1}});
  b.add_node({{"name", "Baffle"}, {"mesh", mesh}});
  b.write(dir.file("baffle.glb"), test::gltf_builder::storage::glb);
  ui::studio_drop_file(st, dir.file("baffle.glb"));
  ASSERT_EQ(st.doc.props.size(), 1u) << st.status;
  EXPECT_EQ(st.doc.props[0].name, "baffle");
  EXPECT_EQ(st.doc.props[0].surface, prop_surface::material);
  EXPECT_NE(st.status.find("1 triangles"), std::string::npos) << st.status;

  std::ofstream(dir.file("broken.glb")) << "glTF not really";
  ui::studio_drop_file(st, dir.file("broken.glb"));
  EXPECT_EQ(st.doc.props.size(), 1u);
  EXPECT_NE(st.status.find("broken.glb"), std::string::npos) << st.status;

  export_gltf_layout(st.doc, dir.file("layout.glb"));
  st.saved = st.doc;  // nothing unsaved: the layout opens at once
  ui::studio_drop_file(st, dir.file("layout.glb"));
  EXPECT_EQ(st.doc_path, dir.file("layout.glb")) << st.status;
  ASSERT_EQ(st.doc.props.size(), 1u);
  EXPECT_EQ(st.doc.props[0].mesh, "layout.glb");
  st.session->stop();
}

// A CAD housing dropped on the window (a STEP file) becomes a prop, tessellated at the default
// tolerance, with the colour the file gives; a damaged one leaves the layout as it was and says why.
TEST(DesignerNumbers, DroppedStepFileBecomesAProp) {
  test::temp_dir dir;
  ui::studio st;
  st.keep_recovery = false;
  st.session_options = {.threads = 1, .target_spp = 1};
  ui::studio_start(st, test::uniform_source_scene(50, 32), "");
  const std::string box = AIRR_TEST_DATA_DIR "/step/box_coloured.stp";
  ui::studio_drop_file(st, box);
  ASSERT_EQ(st.doc.props.size(), 1u) << st.status;
  EXPECT_EQ(st.doc.props[0].name, "box_coloured");
  EXPECT_EQ(st.doc.props[0].surface, prop_surface::material);
  const auto mesh = prop_mesh(st.doc, st.doc.props[0]);
  EXPECT_NE(st.status.find(std::to_string(mesh->indices.size() / 3) + " triangles"), std::string::npos) << st.status;
  ASSERT_EQ(mesh->materials.size(), 1u);
  EXPECT_NEAR(mesh->materials[0].base_color.b, 0.6038, 1e-3);  // the file's 0.8, made linear

  write_file_atomic(dir.file("broken.step"), "ISO-10303-21;\nHEADER;\nENDSEC;\n");
  ui::studio_drop_file(st, dir.file("broken.step"));
  EXPECT_EQ(st.doc.props.size(), 1u);
  EXPECT_NE(st.status.find("broken.step"), std::string::npos) << st.status;
  st.session->stop();
}

// A shipped scene opens untitled (saving asks where, never over the assets); the same scene saved
// elsewhere opens as itself.
TEST(DesignerNumbers, ShippedSceneOpensUntitledSoTheAssetsAreNeverSavedOver) {
  test::temp_dir dir;
  EXPECT_TRUE(is_shipped_asset(default_scene_path()));
  EXPECT_TRUE(is_shipped_asset(ideal_bench_scene_path()));
  EXPECT_TRUE(is_shipped_asset(asset_dir() + "/presets/../scenes/default.json"));
  EXPECT_FALSE(is_shipped_asset(dir.file("default.json")));
  EXPECT_FALSE(is_shipped_asset(""));

  ui::studio st;
  st.keep_recovery = false;
  st.session_options = {.threads = 1, .target_spp = 1};
  const scene shipped = load_scene(default_scene_path());
  ui::studio_start(st, shipped, default_scene_path());
  EXPECT_EQ(st.doc_path, "");
  EXPECT_TRUE(st.settings.recent_files.empty());
  EXPECT_FALSE(ui::studio_dirty(st));

  save_scene(rebase_scene_paths(shipped, dir.path.string()), dir.file("default.json"));
  ui::studio_start(st, load_scene(dir.file("default.json")), dir.file("default.json"));
  EXPECT_EQ(st.doc_path, dir.file("default.json"));
  st.session->stop();
}

// The designer keeps settings under $XDG_CONFIG_HOME and recovery copies under $XDG_STATE_HOME;
// unset or relative (which the XDG specification says to ignore), they default under $HOME.
TEST(DesignerNumbers, SettingsAndRecoveryLiveInTheXdgDirectories) {
  test::temp_dir dir;
  const auto restore = [](const char* name, const char* value) {
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  };
  const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "";
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* state = std::getenv("XDG_STATE_HOME");
  const std::string saved_config = config ? config : "", saved_state = state ? state : "";

  setenv("XDG_CONFIG_HOME", dir.file("config").c_str(), 1);
  setenv("XDG_STATE_HOME", dir.file("state").c_str(), 1);
  EXPECT_EQ(ui::config_dir(), dir.file("config") + "/airr-studio");
  EXPECT_EQ(ui::state_dir(), dir.file("state") + "/airr-studio");
  EXPECT_TRUE(std::filesystem::is_directory(dir.file("state") + "/airr-studio"));

  setenv("HOME", dir.file("home").c_str(), 1);
  setenv("XDG_CONFIG_HOME", "relative/config", 1);
  unsetenv("XDG_STATE_HOME");
  EXPECT_EQ(ui::config_dir(), dir.file("home") + "/.config/airr-studio");
  EXPECT_EQ(ui::state_dir(), dir.file("home") + "/.local/state/airr-studio");

  restore("HOME", home.empty() ? nullptr : home.c_str());
  restore("XDG_CONFIG_HOME", config ? saved_config.c_str() : nullptr);
  restore("XDG_STATE_HOME", state ? saved_state.c_str() : nullptr);
}

// AIRR_ASSETS overrides where the assets are; the build tree's programs use the source tree's.
TEST(DesignerNumbers, AssetsFolderFollowsAirrAssets) {
  const std::string found = asset_dir();
  EXPECT_TRUE(std::filesystem::exists(found + "/presets/rf-ay.json")) << found;
  setenv("AIRR_ASSETS", "/somewhere/else", 1);
  EXPECT_EQ(asset_dir(), "/somewhere/else");
  EXPECT_EQ(default_scene_path(), "/somewhere/else/scenes/default.json");
  EXPECT_EQ(ideal_bench_scene_path(), "/somewhere/else/scenes/ideal_bench.json");
  unsetenv("AIRR_ASSETS");
  EXPECT_EQ(asset_dir(), found);
}
