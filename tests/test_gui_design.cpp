// The design windows under Xvfb: the Optimise window's search finds what `airr optimise` finds for
// the same spec and applies it as one step that undo takes back; a Pareto front is plotted; the
// Tolerance window shows a histogram per metric; the Ghosts window shows a class and draws its paths.
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "gui_test_support.hpp"
#include "test_helpers.hpp"

using namespace airr;
using namespace airr::test::gui;

namespace {

double saved_tilt(const std::string& path) {
  const auto j = nlohmann::json::parse(std::ifstream(path));
  return j.at("retroreflectors").at(0).at("pose").at("pitch_deg").get<double>();
}

// A spec over the default scene's tilt with the given objectives and more members.
void write_spec(const std::string& path, const std::string& objectives, const std::string& more = "") {
  std::ofstream(path) << R"({"format": "airr-design", "version": 1, "scene": ")" << default_scene_path()
                      << R"(", "variables": [{"key": "tilt_deg", "min": 5, "max": 40}], "objectives": [)" << objectives
                      << R"(], "search": {"global_evaluations": 15, "local_evaluations": 15, "psf_samples": 5000}, )"
                      << more << R"("tolerances": [{"key": "tilt_deg", "sd": 0.5}], "tolerance": {"samples": 60}})";
}

}  // namespace

TEST(GuiDesign, TheOptimisedLayoutIsAppliedAsOneUndoableStep) {
  test::temp_dir dir;
  write_spec(dir.file("spec.json"), R"({"metric": "r50_mm", "goal": "minimise"})");
  const test::command_result cli = test::run_cli("optimise " + dir.file("spec.json") + " -o " + dir.file("cli.json"));
  ASSERT_EQ(cli.exit_code, 0) << cli.out;
  const double want = saved_tilt(dir.file("cli.json"));

  const std::string common =
      default_scene_path() + " --design " + dir.file("spec.json") + " --optimise --apply-optimised";
  const studio_run applied = run_studio(
      dir, common + " --frames 3 --save-as " + dir.file("applied.json") + " --screenshot " + dir.file("a.png"));
  ASSERT_EQ(applied.status, 0) << applied.log;
  const studio_run undone = run_studio(dir, common + " --undo 1 --frames 3 --save-as " + dir.file("undone.json"));
  ASSERT_EQ(undone.status, 0) << undone.log;
  std::printf("airr optimise: tilt %.6f deg; the window applied %.6f, and after undo %.6f\n", want,
              saved_tilt(dir.file("applied.json")), saved_tilt(dir.file("undone.json")));
  EXPECT_NEAR(saved_tilt(dir.file("applied.json")), want, 1e-9);
  EXPECT_NEAR(want, 32, 5) << "the r50 optimum lies near 32 deg (tests/test_design_optimise.cpp)";
  EXPECT_EQ(saved_tilt(dir.file("undone.json")), 0.0) << "the default scene's tilt";
  const auto regions = nlohmann::json::parse(std::ifstream(dir.file("a.png.json"))).at("regions");
  EXPECT_TRUE(regions.contains("optimise_window"));
}

TEST(GuiDesign, TheParetoFrontAndTheHistogramsArePlotted) {
  test::temp_dir dir;
  write_spec(dir.file("spec.json"),
             R"({"metric": "r50_mm", "goal": "minimise"}, {"metric": "size_z_mm", "goal": "minimise"})",
             R"("pareto": {"points": 4}, )");
  for (const char* job : {"optimise", "tolerance"}) {
    const std::string shot = dir.file(std::string(job) + ".png");
    const studio_run run = run_studio(dir, default_scene_path() + " --design " + dir.file("spec.json") + " --" + job +
                                               " --frames 3 --screenshot " + shot);
    ASSERT_EQ(run.status, 0) << run.log;
    const rgb8_image img = read_png(shot);
    const auto regions = nlohmann::json::parse(std::ifstream(shot + ".json"));
    if (std::string(job) == "optimise") {
      // The front in the palette's first colour, the evaluations grey.
      const auto front = region(regions, "optimise_front");
      EXPECT_GT(curve_pixels(img, front, {80, 160, 255}), 50);
      EXPECT_GT(curve_pixels(img, front, {150, 150, 150}), 20);
    } else {
      // A histogram of each metric (r50 and the depth).
      for (const char* h : {"tolerance_histogram_0", "tolerance_histogram_1"})
        EXPECT_GT(curve_pixels(img, region(regions, h), {80, 160, 255}), 50) << h;
    }
  }
}

// The Ghosts window on a layout with a mirror prop that shows the display to the observer: the
// table lists the mirror's class; shown, it takes the render view's place (dimmer than the whole
// image) and a few of its paths are drawn, magenta, in the 3D and the layout views, which have
// none before.
TEST(GuiDesign, TheGhostsWindowShowsAClassAndDrawsItsPaths) {
  test::temp_dir dir;
  scene s = test::display_in_mirror_scene(dir, 96);
  s.observer.fov_deg = 30;
  std::ofstream(dir.file("scene.json")) << scene_to_json(s).dump(2);

  const auto run = [&](int shown) {
    const std::string shot = dir.file("ghosts" + std::to_string(shown) + ".png");
    const studio_run r = run_studio(dir, dir.file("scene.json") + " --ghosts --ghost-class " + std::to_string(shown) +
                                             " --frames 3 --screenshot " + shot);
    EXPECT_EQ(r.status, 0) << r.log;
    return std::pair{read_png(shot), nlohmann::json::parse(std::ifstream(shot + ".json"))};
  };
  const auto [none, none_notes] = run(0);
  const auto& classes = none_notes.at("ghosts").at("classes");
  int mirror = 0;
  for (std::size_t k = 0; k < classes.size() && !mirror; ++k)
    if (classes[k].get<std::string>().find("P#0") != std::string::npos) mirror = int(k) + 1;
  ASSERT_GT(mirror, 0) << none_notes.at("ghosts").dump();
  const auto [shown, notes] = run(mirror);
  EXPECT_EQ(notes.at("ghosts").at("shown"), mirror - 1);
  EXPECT_TRUE(notes.at("ghosts").at("render_shows_it"));
  EXPECT_TRUE(notes.at("regions").contains("ghosts_window"));
  const std::array<int, 3> magenta = {255, 0, 255};
  for (const char* view : {"layout_3d", "layout_side", "layout_top"}) {
    const int before = curve_pixels(none, region(none_notes, view), magenta);
    const int after = curve_pixels(shown, region(notes, view), magenta);
    std::printf("%s: %d magenta pixels without a class shown, %d with the mirror's\n", view, before, after);
    EXPECT_GT(after, before + 30) << view;
  }
  const auto mean_level = [](const rgb8_image& img, const std::array<int, 4>& r) {
    double sum = 0;
    int n = 0;
    for (int y = r[1]; y < r[3]; ++y)
      for (int x = r[0]; x < r[2]; ++x, ++n) sum += img.at(x, y)[0] + img.at(x, y)[1] + img.at(x, y)[2];
    return sum / std::max(1, n);
  };
  const double whole = mean_level(none, region(none_notes, "render_image"));
  const double mirror_only = mean_level(shown, region(notes, "render_image"));
  std::printf("render view's mean level: %.1f the whole image, %.1f the mirror's class\n", whole, mirror_only);
  EXPECT_LT(mirror_only, whole);
  EXPECT_GT(mirror_only, 0.5);
}
