// The design windows under Xvfb: the Optimise window's search finds what `airr optimise` finds for
// the same spec and applies it as one step that undo takes back; a Pareto front is plotted; the
// Tolerance window shows a histogram per metric.
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/core/assets.hpp"
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
