// Design specs and the optimiser (issue 34): specs are read strictly; the optimiser finds the
// minimum a sweep finds, keeps to a bounding-box limit (ending on it), reports a spec nobody can
// meet as infeasible naming the constraint, and gives the same answer on 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <tbb/global_control.h>

#include "airr/core/assets.hpp"
#include "airr/design/metrics.hpp"
#include "airr/design/search.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/sweep.hpp"
#include "polygon_visible_fraction.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A spec over the default scene with the given variables, objectives and more (JSON members).
std::string spec_text(const std::string& members, const std::string& scene_path = default_scene_path()) {
  return R"({"format": "airr-design", "version": 1, "scene": ")" + scene_path + R"(", )" + members + "}";
}

}  // namespace

TEST(DesignSpec, BadSpecsAreOneLineErrorsNamingTheField) {
  test::temp_dir dir;
  auto error_for = [&](const std::string& members) {
    write_text(dir.file("spec.json"), spec_text(members));
    return test::error_of([&] { load_design_spec(dir.file("spec.json")); });
  };
  const std::string var = R"("variables": [{"key": "floating_distance_mm", "min": 120, "max": 300}], )";
  const std::string obj = R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}])";
  write_text(dir.file("good.json"), spec_text(var + obj));
  const design_spec good = load_design_spec(dir.file("good.json"));
  EXPECT_EQ(good.variables.size(), 1u);
  EXPECT_EQ(good.eyes_mm.size(), 1u);

  const auto expect = [&](const std::string& error, const std::vector<std::string>& parts) {
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_NE(error.find("spec.json"), std::string::npos) << error;
    for (const std::string& p : parts) EXPECT_NE(error.find(p), std::string::npos) << error;
  };
  expect(error_for(var + obj + R"(, "colour": 1)"), {"colour", "unknown key"});
  expect(error_for(R"("variables": [{"key": "floating_distance_mm", "min": 300, "max": 300}], )" + obj),
         {"variables[0].max", "empty"});
  expect(error_for(R"("variables": [{"key": "floating_distance_mm", "min": NaN, "max": 300}], )" + obj),
         {"malformed JSON"});
  expect(error_for(R"("variables": [{"key": "half_mirror.pose.twist", "min": 0, "max": 1}], )" + obj),
         {"variables[0].key"});
  expect(error_for(var + R"("objectives": [{"metric": "sharpness", "goal": "maximise"}])"),
         {"objectives[0].metric", "unknown metric 'sharpness'", "visible_fraction"});
  expect(error_for(var + R"("objectives": [])"), {"objectives", "must not be empty"});
  expect(error_for(var + obj + R"(, "constraints": [{"metric": "size_z_mm"}])"), {"constraints[0]", "min, a max"});
  expect(error_for(var + obj + R"(, "search": {"global_evaluations": 0})"), {"search.global_evaluations"});
  expect(error_for(var + obj + R"(, "pareto": {"points": 5})"), {"pareto.points", "exactly two objectives"});
  expect(error_for(var + obj + R"(, "eye_zone": {"x": [-10, 10], "y": [-10, 10], "n": [30, 30]})"),
         {"eye_zone.n", "at most 400"});
  expect(
      error_for(var + R"("objectives": [{"metric": "visible_fraction", "goal": "maximise", "over": "share_above"}])"),
      {"objectives[0].threshold", "missing"});
  // Wrong types, missing keys, negative and huge sizes, a truncated file.
  const std::vector<std::pair<std::string, std::vector<std::string>>> more = {
      {R"("variables": [{"key": "floating_distance_mm", "min": "120", "max": 300}], )" + obj,
       {"variables[0].min", "must be a number"}},
      {R"("variables": [{"key": "floating_distance_mm", "max": 300}], )" + obj, {"variables[0].min", "missing"}},
      {R"("variables": {"key": "floating_distance_mm"}, )" + obj, {"variables", "must be an array of objects"}},
      {R"("variables": [7], )" + obj, {"variables[0]", "must be a JSON object"}},
      {var + R"("objectives": [{"metric": 3, "goal": "maximise"}])", {"objectives[0].metric", "must be a string"}},
      {var + R"("objectives": [{"metric": "r50_mm"}])", {"objectives[0].goal", "missing"}},
      {var + R"("objectives": [{"metric": "r50_mm", "goal": "minimise", "weight": -1}])",
       {"objectives[0].weight", "must be positive"}},
      {var + obj + R"(, "tolerance": {"samples": -5})", {"tolerance.samples", "must be 10 to 1000000"}},
      {var + obj + R"(, "tolerance": {"samples": 1000000000000})",
       {"tolerance.samples: must be 10 to 1000000 (is 1000000000000)"}},
      {var + obj + R"(, "tolerance": {"seed": -1})", {"tolerance.seed", "-1"}},
      {var + obj + R"(, "search": {"psf_samples": 1e15})", {"search.psf_samples"}},
      {var + obj + R"(, "search": {"psf_samples": 999})", {"search.psf_samples: must be 1000 to 100000000 (is 999)"}},
      {var + obj + R"(, "search": {"local_evaluations": 2.5})", {"search.local_evaluations", "must be an integer"}},
      {var + obj + R"(, "pareto": {"points": 100000000000})", {"pareto.points: must be 3 to 101 (is 100000000000)"}},
      {var + obj + R"(, "eye_zone": {"x": [-10, 10], "y": [-10, 10], "n": [1e300, 1e300]})", {"eye_zone.n"}},
      {var + obj + R"(, "eye_zone": {"x": [-10, 10], "y": [-10, 10], "n": [-1, 3]})", {"eye_zone.n"}},
      {var + obj + R"(, "eye_zone": {"x": [-10], "y": [-10, 10], "n": [2, 2]})", {"eye_zone.x", "[first, last]"}},
      {var + obj + R"(, "eyes_mm": [[1, 2]])", {"eyes_mm[0]", "[x, y, z]"}},
      {var + obj + R"(, "eyes_mm": [[1, 2, "3"]])", {"eyes_mm[0]", "[x, y, z]"}},
      {var + obj + R"(, "eyes_mm": [[1, 2, 1e999]])", {"malformed JSON"}},
      {var + obj + R"(, "eyes_mm": "observer")", {"eyes_mm", "non-empty array"}},
      {var + obj + R"(, "tolerances": [{"key": "floating_distance_mm", "sd": 0}])", {"tolerances[0].sd", "positive"}},
      {var + obj + R"(, "tolerances": [{"key": "floating_distance_mm", "distribution": "cauchy", "sd": 1}])",
       {"tolerances[0].distribution"}},
  };
  for (const auto& [members, parts] : more) expect(error_for(members), parts);
  const std::string text = spec_text(var + obj);
  write_text(dir.file("spec.json"), text.substr(0, text.size() / 2));
  expect(test::error_of([&] { load_design_spec(dir.file("spec.json")); }), {"malformed JSON"});
  write_text(dir.file("spec.json"), "");
  expect(test::error_of([&] { load_design_spec(dir.file("spec.json")); }), {});
}

// A spec written as text reads back the same, over a scene at hand too (as the designer runs it).
TEST(DesignSpec, WrittenTextReadsBackTheSame) {
  test::temp_dir dir;
  write_text(
      dir.file("spec.json"),
      spec_text(R"("variables": [{"key": "tilt_deg", "min": 10, "max": 40}], "eyes_mm": [[1, 2, 450]], )"
                R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}, )"
                R"({"metric": "visible_fraction", "goal": "maximise", "over": "min", "weight": 2}], )"
                R"("constraints": [{"metric": "size_z_mm", "max": 350}, {"metric": "brightness", "min": 0.1}, )"
                R"({"metric": "visible_fraction", "over": "share_above", "threshold": 0.8, "min": 0.5}], )"
                R"("eye_zone": {"shape": "sphere", "distance_mm": 400, "x": [-20, 20], "y": [0, 10], "n": [3, 2]}, )"
                R"("pareto": {"points": 5}, "search": {"seed": 7, "global_evaluations": 20}, )"
                R"("tolerances": [{"key": "tilt_deg", "sd": 0.5}, {"key": "floating_distance_mm", )"
                R"("distribution": "uniform", "half_width": 2, "percent": true}], "tolerance": {"samples": 50})"));
  const design_spec a = load_design_spec(dir.file("spec.json"));
  const std::string text = design_spec_text(a);
  write_text(dir.file("again.json"), text);
  for (const design_spec& b : {load_design_spec(dir.file("again.json")), parse_design_spec(text, "window", a.base)}) {
    EXPECT_EQ(design_spec_text(b), text);
    EXPECT_TRUE(b.base == a.base);
    ASSERT_EQ(b.constraints.size(), 3u);
    EXPECT_EQ(b.constraints[2].over, over_eyes::share_above);
    EXPECT_EQ(b.constraints[2].threshold, 0.8);
    ASSERT_TRUE(b.eye_zone);
    EXPECT_EQ(b.eye_zone->kind, eye_grid::shape::sphere);
    EXPECT_EQ(design_eyes(b).size(), 7u);
    EXPECT_EQ(b.constraints[1].min, 0.1);
    EXPECT_FALSE(b.constraints[1].max);
    EXPECT_EQ(b.objectives[1].over, over_eyes::min);
    EXPECT_EQ(b.front.points, 5);
    EXPECT_TRUE(b.tolerances[1].uniform && b.tolerances[1].percent);
  }
  EXPECT_NE(test::error_of([&] {
              parse_design_spec(R"({"format": "airr-design", "version": 1})", "window", a.base);
            }).find("window: objectives: missing"),
            std::string::npos);
}

namespace {

design_spec spec_from(const test::temp_dir& dir, const std::string& members,
                      const std::string& scene_path = default_scene_path()) {
  write_text(dir.file("spec.json"), spec_text(members, scene_path));
  return load_design_spec(dir.file("spec.json"));
}

// The sweep's r50 over one axis of the default scene (the model PSF route, the spec's samples).
sweep_result r50_sweep(const std::string& axis) {
  sweep_params p;
  p.axes = {parse_sweep_axis(axis)};
  p.psf_route = true;
  p.psf_samples = design_search{}.psf_samples;
  return run_sweep(load_scene(default_scene_path()), p);
}

const sweep_point& lowest_r50(const sweep_result& r) {
  return *std::min_element(r.points.begin(), r.points.end(),
                           [](const sweep_point& a, const sweep_point& b) { return a.r50_mm < b.r50_mm; });
}

}  // namespace

// Maximising the visible fraction at one eye over the half mirror's pitch and the sheet's tilt, for
// a sheet too short to fill the view: the answer is where the polygon clipping of the parts'
// projections (polygon_visible_fraction.hpp) peaks, found on a 0.1 deg grid and refined to 0.005.
TEST(DesignOptimise, MaximisingTheVisibleFractionLandsOnTheGeometricOptimum) {
  test::temp_dir dir;
  scene s = load_scene(default_scene_path());
  s.sheet().height_mm = 60;
  save_scene(rebase_scene_paths(s, dir.path.string()), dir.file("short-sheet.json"));
  const glm::dvec3 eye(20, 40, 450);
  auto truth = [&](double mirror, double tilt) {
    scene t = s;
    t.half_mirror.pose.pitch_deg = mirror;
    t.sheet().pose.pitch_deg = tilt;
    return test::polygon_visible_fraction(t, eye);
  };
  double best = -1, best_m = 0, best_t = 0;
  for (double step : {0.1, 0.005}) {
    const double m0 = step == 0.1 ? 35 : best_m - 0.2, m1 = step == 0.1 ? 55 : best_m + 0.2;
    const double t0 = step == 0.1 ? -20 : best_t - 0.2, t1 = step == 0.1 ? 20 : best_t + 0.2;
    for (double m = m0; m <= m1 + 1e-9; m += step) {
      for (double t = t0; t <= t1 + 1e-9; t += step) {
        const double f = truth(m, t);
        if (f > best) best = f, best_m = m, best_t = t;
      }
    }
  }
  // A strict peak inside the ranges.
  for (const auto& [dm, dt] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
    EXPECT_LT(truth(best_m + dm, best_t + dt), best - 1e-5) << dm << " " << dt;
  const design_result r = optimise_design(
      spec_from(dir,
                R"("variables": [{"key": "half_mirror.pose.pitch_deg", "min": 35, "max": 55}, )"
                R"({"key": "retroreflectors.0.pose.pitch_deg", "min": -20, "max": 20}], "eyes_mm": [[20, 40, 450]], )"
                R"("objectives": [{"metric": "visible_fraction", "goal": "maximise"}], )"
                R"("search": {"global_evaluations": 60, "local_evaluations": 200})",
                dir.file("short-sheet.json")));
  const design_trial& got = r.best_trial();
  std::printf(
      "geometry: mirror %.3f deg, tilt %.3f deg (fraction %.6f); optimiser: %.3f, %.3f (%.6f), %zu evaluations\n",
      best_m, best_t, best, got.x[0], got.x[1], got.evaluation.objective_values[0], r.trials.size());
  EXPECT_NEAR(got.x[0], best_m, 0.2);
  EXPECT_NEAR(got.x[1], best_t, 0.2);
  EXPECT_NEAR(got.evaluation.objective_values[0], best, 1e-4);
}

// Minimising r50 over D or over the tilt lands on the sweep's minimum: at D's sweep minimum (an end
// of the range, as the blur grows with D), and over the tilt at a value no worse than the best of
// a 1 deg sweep.
TEST(DesignOptimise, MinimisingR50LandsOnTheSweepsMinimum) {
  test::temp_dir dir;
  const std::string obj = R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}], )";
  const std::string search = R"("search": {"global_evaluations": 40, "local_evaluations": 30})";
  const design_result by_d = optimise_design(
      spec_from(dir, R"("variables": [{"key": "floating_distance_mm", "min": 100, "max": 300}], )" + obj + search));
  const sweep_result d_sweep = r50_sweep("floating_distance=100:300:5");
  const sweep_point& d_min = lowest_r50(d_sweep);
  const design_trial& d_best = by_d.best_trial();
  std::printf("over D: optimiser %.2f mm (r50 %.5f), sweep %.0f mm (r50 %.5f), %zu evaluations\n", d_best.x[0],
              d_best.evaluation.objective_values[0], d_min.floating_distance_mm, d_min.r50_mm, by_d.trials.size());
  EXPECT_NEAR(d_best.x[0], d_min.floating_distance_mm, 5.0);
  EXPECT_LE(d_best.evaluation.objective_values[0], d_min.r50_mm + 1e-4);

  const design_result by_tilt =
      optimise_design(spec_from(dir, R"("variables": [{"key": "tilt_deg", "min": 15, "max": 40}], )" + obj + search));
  const sweep_result t_sweep = r50_sweep("tilt=15:40:1");
  const sweep_point& t_min = lowest_r50(t_sweep);
  const design_trial& t_best = by_tilt.best_trial();
  std::printf("over the tilt: optimiser %.2f deg (r50 %.5f), sweep %.0f deg (r50 %.5f)\n", t_best.x[0],
              t_best.evaluation.objective_values[0], t_min.tilt_deg, t_min.r50_mm);
  EXPECT_LE(t_best.evaluation.objective_values[0], t_min.r50_mm + 1e-4);
  EXPECT_NEAR(t_best.x[0], t_min.tilt_deg, 5.0);
}

// A size limit that excludes the unconstrained optimum (r50 falls with the tilt up to about 30
// deg, while the tilted sheet deepens the device): the result lies on the limit. A limit nobody
// can meet is reported as infeasible, naming the constraint.
TEST(DesignOptimise, ABoundingBoxLimitIsKeptAndAnImpossibleOneIsNamed) {
  test::temp_dir dir;
  scene at_20 = load_scene(default_scene_path());
  at_20.sheet().pose.pitch_deg = 20;
  const double limit = device_size_mm(at_20).z;
  const std::string members = R"("variables": [{"key": "tilt_deg", "min": 0, "max": 40}], )"
                              R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}], )"
                              R"("constraints": [{"metric": "size_z_mm", "max": )" +
                              std::to_string(limit) +
                              R"(}], "search": {"global_evaluations": 40, "local_evaluations": 30})";
  const design_result r = optimise_design(spec_from(dir, members));
  const design_trial& best = r.best_trial();
  std::printf("limit %.3f mm: tilt %.3f deg, size_z %.3f mm, r50 %.5f\n", limit, best.x[0],
              best.evaluation.constraint_values[0], best.evaluation.objective_values[0]);
  EXPECT_TRUE(best.evaluation.feasible());
  EXPECT_LE(best.evaluation.constraint_values[0], limit);
  EXPECT_NEAR(best.evaluation.constraint_values[0], limit, 0.5);
  EXPECT_NEAR(best.x[0], 20.0, 0.3);

  const std::string impossible = R"("variables": [{"key": "tilt_deg", "min": 0, "max": 40}], )"
                                 R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}], )"
                                 R"("constraints": [{"metric": "size_z_mm", "max": 10}], )"
                                 R"("search": {"global_evaluations": 20, "local_evaluations": 10})";
  write_text(dir.file("impossible.json"), spec_text(impossible));
  const test::command_result cli =
      test::run_cli("optimise " + dir.file("impossible.json") + " -o " + dir.file("best.json"));
  // The search's account, and one error line.
  EXPECT_NE(cli.exit_code, 0) << cli.out;
  const std::size_t at = cli.out.find("error: ");
  ASSERT_NE(at, std::string::npos) << cli.out;
  const std::string error = cli.out.substr(at, cli.out.find('\n', at) - at);
  for (const char* part : {"impossible.json", "infeasible", "size_z_mm"})
    EXPECT_NE(error.find(part), std::string::npos) << cli.out;
  EXPECT_FALSE(std::filesystem::exists(dir.file("best.json")));
}

// A plate prop standing across the path of the sheet's top edge: the sheet cuts it once tilted
// beyond 20 deg, the more the further. Kept out of it, the search for the least r50 (which
// lies beyond 20 deg, as the bounding-box test shows) ends on 20 deg.
TEST(DesignOptimise, PartsKeepOutOfProps) {
  test::temp_dir dir;
  scene s = load_scene(default_scene_path());
  s.sheet().pose.pitch_deg = 20;
  glm::dvec3 edge(0, 0, -1e9);  // the middle of the edge that rises as the sheet tilts
  for (const glm::dvec3& c : corners(retroreflector_frame(s))) edge = c.z > edge.z ? c : edge;
  edge.x = 0;
  prop_params plate;  // the 1 m unit panel at 0.04: 40 mm square, in the plane x = 0, above the edge
  plate.mesh = asset_dir() + "/models/panel.gltf";
  plate.scale = 0.04;
  plate.pose = pose_from_rotation(glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0)),
                                  edge + glm::dvec3(0, 0, 20));
  s.props.push_back(plate);
  auto cut_at = [&](double tilt) {
    scene t = s;
    t.sheet().pose.pitch_deg = tilt;
    return prop_cut_length_mm(t);
  };
  // The sheet's middle line from the plate's lower edge up to the sheet's own edge.
  const double h = 0.5 * s.sheet().height_mm, rise = h * std::sin(glm::radians(20.0));
  for (double tilt : {21.0, 22.0}) {  // (the line meets the plate's lower edge within its width)
    const double expected = (h * std::sin(glm::radians(tilt)) - rise) / std::sin(glm::radians(tilt));
    EXPECT_NEAR(cut_at(tilt), expected, 1e-6) << tilt;
  }
  EXPECT_EQ(cut_at(19.9), 0.0);
  EXPECT_EQ(cut_at(0), 0.0);

  s.sheet().pose.pitch_deg = 0;
  save_scene(rebase_scene_paths(s, dir.path.string()), dir.file("plate.json"));
  const std::string members = R"("variables": [{"key": "tilt_deg", "min": 0, "max": 40}], )"
                              R"("objectives": [{"metric": "r50_mm", "goal": "minimise"}], )"
                              R"("constraints": [{"metric": "prop_cut_mm", "max": 0}], )"
                              R"("search": {"global_evaluations": 40, "local_evaluations": 30})";
  const design_result r = optimise_design(spec_from(dir, members, dir.file("plate.json")));
  const design_trial& best = r.best_trial();
  std::printf("kept out of the plate: tilt %.3f deg, cut %.4f mm, r50 %.5f\n", best.x[0],
              best.evaluation.constraint_values[0], best.evaluation.objective_values[0]);
  EXPECT_TRUE(best.evaluation.feasible());
  EXPECT_EQ(best.evaluation.constraint_values[0], 0.0);
  EXPECT_NEAR(best.x[0], 20.0, 0.3);
}

// The same spec and seed give the same search on one thread and on two.
TEST(DesignOptimise, OneAndTwoThreadsGiveTheSameResult) {
  test::temp_dir dir;
  const design_spec spec = spec_from(
      dir, R"("variables": [{"key": "tilt_deg", "min": 0, "max": 40}, {"key": "floating_distance_mm", "min": 120, )"
           R"("max": 300}], "objectives": [{"metric": "mean_mtf", "goal": "maximise"}], )"
           R"("search": {"seed": 5, "global_evaluations": 30, "local_evaluations": 20})");
  design_result one, two;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = optimise_design(spec);
  }
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    two = optimise_design(spec);
  }
  ASSERT_EQ(one.trials.size(), two.trials.size());
  for (std::size_t i = 0; i < one.trials.size(); ++i) {
    EXPECT_EQ(one.trials[i].x, two.trials[i].x) << i;
    EXPECT_EQ(one.trials[i].evaluation.score, two.trials[i].evaluation.score) << i;
  }
  EXPECT_EQ(one.best, two.best);
}

// A front's searches run as shared items (as an MPI job's ranks run them: out of order, their
// trials travelling as numbers) give the same trials, front and best as run in turn; layouts that
// are none keep their reasons.
TEST(DesignOptimise, AFrontsSearchesSharedGiveTheSameFront) {
  test::temp_dir dir;
  const design_spec spec = spec_from(
      dir,
      R"("variables": [{"key": "tilt_deg", "min": 0, "max": 60}, )"
      R"({"key": "retroreflectors.0.pose.center_mm.2", "min": -300, "max": 0}], )"
      R"("objectives": [{"metric": "size_y_mm", "goal": "minimise"}, {"metric": "size_z_mm", "goal": "minimise"}], )"
      R"("constraints": [{"metric": "size_x_mm", "max": 1000}], )"
      R"("pareto": {"points": 4}, "search": {"global_evaluations": 25, "local_evaluations": 10})");
  std::size_t items = 0;
  const item_share last_first = [&](std::size_t n, std::size_t width, const item_compute& compute) {
    std::vector<double> all(n * width, -1.0);
    for (std::size_t i = n; i-- > 0;) compute(i, all.data() + i * width);
    items += n;
    return all;
  };
  const design_result in_turn = optimise_design(spec), shared = optimise_design(spec, {}, nullptr, last_first);
  EXPECT_EQ(items, 6u);  // 2 + 2 + 2 searches in three waves
  EXPECT_EQ(design_trials_csv(spec, shared), design_trials_csv(spec, in_turn));
  EXPECT_EQ(design_front_csv(spec, shared), design_front_csv(spec, in_turn));
  EXPECT_EQ(shared.best, in_turn.best);
  ASSERT_EQ(shared.trials.size(), in_turn.trials.size());
  int invalid = 0;
  for (std::size_t i = 0; i < shared.trials.size(); ++i) {
    EXPECT_EQ(shared.trials[i].phase, in_turn.trials[i].phase);
    EXPECT_EQ(shared.trials[i].problem, in_turn.trials[i].problem);
    EXPECT_EQ(shared.trials[i].evaluation.broken, in_turn.trials[i].evaluation.broken);
    invalid += !in_turn.trials[i].valid;
  }
  EXPECT_GT(invalid, 0);  // the sheet moved into the half mirror: reasons rebuilt from the layout
  std::printf("%zu trials, %d of them no valid layout, %zu on the front\n", in_turn.trials.size(), invalid,
              in_turn.front.size());
}

// A Pareto front of the device's height and depth over the sheet's tilt: a front that is not
// convex (weighted sums would find its ends alone). Against the front of a 0.01 deg sweep: the
// same ends, no layout of the sweep better in both by more than 0.05 mm, and no gap wider than
// 1.5 levels.
TEST(DesignOptimise, TheParetoFrontOfTwoObjectivesIsTheSweepsFront) {
  test::temp_dir dir;
  const design_spec spec = spec_from(
      dir,
      R"("variables": [{"key": "tilt_deg", "min": 0, "max": 60}], )"
      R"("objectives": [{"metric": "size_y_mm", "goal": "minimise"}, {"metric": "size_z_mm", "goal": "minimise"}], )"
      R"("pareto": {"points": 9}, "search": {"global_evaluations": 30, "local_evaluations": 30})");
  const design_result r = optimise_design(spec);
  std::vector<glm::dvec2> sweep, front;
  for (double t = 0; t <= 60 + 1e-9; t += 0.01) {
    scene s = spec.base;
    s.sheet().pose.pitch_deg = t;
    const glm::dvec3 size = device_size_mm(s);
    sweep.push_back({size.y, size.z});
  }
  std::vector<glm::dvec2> sweep_front;
  for (const glm::dvec2& p : sweep) {
    const bool dominated = std::any_of(sweep.begin(), sweep.end(), [&](const glm::dvec2& q) {
      return q.x <= p.x && q.y <= p.y && (q.x < p.x || q.y < p.y);
    });
    if (!dominated) sweep_front.push_back(p);
  }
  for (int i : r.front) {
    const std::vector<double>& v = r.trials[std::size_t(i)].evaluation.objective_values;
    front.push_back({v[0], v[1]});
  }
  ASSERT_GE(front.size(), 9u);
  const auto [y_lo, y_hi] = std::minmax_element(sweep_front.begin(), sweep_front.end(),
                                                [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x; });
  std::printf("front: %zu layouts from %zu evaluations; sweep front %zu of %zu, height %.3f-%.3f mm\n", front.size(),
              r.trials.size(), sweep_front.size(), sweep.size(), y_lo->x, y_hi->x);
  EXPECT_NEAR(front.front().x, y_lo->x, 0.05);
  EXPECT_NEAR(front.front().y, y_lo->y, 0.05);
  EXPECT_NEAR(front.back().x, y_hi->x, 0.05);
  EXPECT_NEAR(front.back().y, y_hi->y, 0.05);
  for (const glm::dvec2& p : front) {
    for (const glm::dvec2& q : sweep) EXPECT_FALSE(q.x < p.x - 0.05 && q.y < p.y - 0.05) << p.x << " " << p.y;
  }
  const double z_range = y_lo->y - y_hi->y, level = z_range / 8;
  double widest = 0;
  for (std::size_t i = 1; i < front.size(); ++i) widest = std::max(widest, std::abs(front[i].y - front[i - 1].y));
  std::printf("widest gap in depth %.3f mm, levels %.3f mm apart\n", widest, level);
  EXPECT_LE(widest, 1.5 * level);

  // The command writes the front beside the scene: a CSV row per layout of it, and a plot.
  const test::command_result cli = test::run_cli("optimise " + dir.file("spec.json") + " -o " + dir.file("best.json"));
  ASSERT_EQ(cli.exit_code, 0) << cli.out;
  std::ifstream csv(dir.file("best_pareto.csv"));
  std::string line;
  std::size_t rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, front.size() + 1);
  EXPECT_GT(std::filesystem::file_size(dir.file("best_pareto.png")), 10000u);
}

// A zone of eyes: its eyes are the viewing zone's grid (row by row), and over them a metric's mean
// and its share above a threshold are those of the eyes taken one at a time.
TEST(DesignSpec, AZoneOfEyesIsTheViewingZonesGrid) {
  test::temp_dir dir;
  const design_spec zone =
      spec_from(dir, R"("eye_zone": {"distance_mm": 300, "x": [-120, 120], "y": [-60, 60], "n": [5, 3]}, )"
                     R"("objectives": [{"metric": "visible_fraction", "goal": "maximise"}, )"
                     R"({"metric": "visible_fraction", "goal": "maximise", "over": "share_above", "threshold": 0.9}])");
  ASSERT_TRUE(zone.eyes_mm.empty());
  const std::vector<glm::dvec3> eyes = design_eyes(zone);
  ASSERT_EQ(eyes.size(), 15u);
  EXPECT_EQ(eyes[7], eye_position(zone.base, *zone.eye_zone, 0, 0));
  EXPECT_EQ(eyes[14], eye_position(zone.base, *zone.eye_zone, 120, 60));
  const design_evaluation e = evaluate_design(zone, zone.base);
  double sum = 0;
  int above = 0;
  const viewing_parts parts(zone.base);
  for (const glm::dvec3& eye : eyes) {
    const double v = visible_fraction(parts, eye);
    sum += v;
    above += v >= 0.9;
  }
  std::printf("zone of 15 eyes: mean visible fraction %.5f, share at least 0.9: %.4f (%d eyes)\n",
              e.objective_values[0], e.objective_values[1], above);
  EXPECT_NEAR(e.objective_values[0], sum / 15, 1e-12);
  EXPECT_EQ(e.objective_values[1], above / 15.0);
  EXPECT_GT(above, 0);
  EXPECT_LT(above, 15);
}
