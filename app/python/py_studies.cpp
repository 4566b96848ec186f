// airr.sweep, airr.viewzone, airr.optimise and airr.tolerance: the studies of the commands of
// those names, into numpy arrays and dicts.
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "airr/core/error.hpp"
#include "airr/design/search.hpp"
#include "airr/design/tolerance.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/sweep.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/prop_hits.hpp"
#include "py_arrays.hpp"
#include "py_calls.hpp"
#include "py_job.hpp"
#include "py_scene.hpp"

namespace py = pybind11;

namespace airr::python {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// rows x cols numbers, row by row, as a float64 array.
py::array_t<double> grid_array(const std::vector<double>& v, int rows, int cols) {
  py::array_t<double> a({rows, cols});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict sweep(const py_scene& ps, const std::vector<std::string>& vary, bool psf_route, std::uint64_t spp,
               std::uint64_t psf_samples, int threads, py::object progress) {
  sweep_params p;
  p.psf_route = psf_route;
  p.spp = spp;
  p.psf_samples = psf_samples;
  p.threads = threads;
  for (const std::string& v : vary) p.axes.push_back(parse_sweep_axis(v));
  python_job job(std::move(progress));
  std::optional<sweep_result> r;
  {
    py::gil_scoped_release released;
    try {
      r = run_sweep(ps.current(), p, [&](double f, const std::string&) { job.check(f); });
    } catch (const python_job::stop&) {
    }
  }
  job.finish();
  std::vector<double> d, t, mean, mtf50, r50, brightness;
  py::list reasons;
  for (const sweep_point& pt : r->points) {
    reasons.append(pt.reason);
    d.push_back(pt.floating_distance_mm);
    t.push_back(pt.tilt_deg);
    mean.push_back(pt.mean_mtf);
    mtf50.push_back(pt.mtf50_lp_per_mm.value_or(nan));
    r50.push_back(pt.r50_mm);
    brightness.push_back(pt.brightness);
  }
  py::dict out;
  out["floating_distance_mm"] = to_array(d);
  out["tilt_deg"] = to_array(t);
  out["mean_mtf"] = to_array(mean);
  out["mtf50_lp_per_mm"] = to_array(mtf50);
  out["reason"] = reasons;
  out["r50_mm"] = to_array(r50);
  out["brightness"] = to_array(brightness);
  py::dict slopes;
  for (const sweep_slope& s : r->slopes) slopes[py::float_(s.tilt_deg)] = s.per_mm;
  out["mean_mtf_slope_per_mm"] = slopes;
  out["csv"] = sweep_csv(*r);
  return out;
}

py::dict viewzone(const py_scene& ps, bool sphere, double distance_mm, int grid, std::optional<std::vector<double>> x,
                  std::optional<std::vector<double>> y, int rows, bool full, std::uint64_t spp, py::object progress) {
  const eye_grid g = requested_eye_grid(sphere, distance_mm, grid, x.value_or(std::vector<double>{}),
                                        y.value_or(std::vector<double>{}));
  if (rows < 1 || rows > 100000) throw input_error("viewzone: rows must be in [1, 100000]");
  const scene& s = ps.current();
  if (s.retroreflectors.empty()) throw input_error(ps.path() + ": no retroreflector, no aerial image");
  python_job job(std::move(progress));
  std::atomic<bool> cancel{false};
  const auto told = [&](int done, int total) {
    if (!job.keep_going(double(done) / total)) cancel = true;
  };
  full_zone_map map;
  {
    py::gil_scoped_release released;
    if (full) {
      map = full_viewing_zone(s, g, {.rows_per_eye = rows, .render_spp = spp}, told, &cancel);
    } else {
      const viewing_zone_map geometric = geometric_viewing_zone(s, g, scene_prop_hits(s), rows, told, &cancel);
      map.grid = geometric.grid;
      map.visible = geometric.visible;
    }
  }
  job.finish();
  py::dict out;
  std::vector<double> xs, ys;
  for (int i = 0; i < g.nx; ++i) xs.push_back(g.x_at(i));
  for (int j = 0; j < g.ny; ++j) ys.push_back(g.y_at(j));
  out[sphere ? "azimuth_deg" : "x_mm"] = to_array(xs);
  out[sphere ? "elevation_deg" : "y_mm"] = to_array(ys);
  out["visible"] = grid_array(map.visible, g.ny, g.nx);
  if (full) {
    out["brightness"] = grid_array(map.brightness, g.ny, g.nx);
    out["mean_mtf"] = grid_array(map.mean_mtf, g.ny, g.nx);
    out["stray_ratio"] = grid_array(map.stray_ratio, g.ny, g.nx);
    out["direct"] = grid_array(map.direct, g.ny, g.nx);
    out["luminance"] = grid_array(map.luminance, g.ny, g.nx);
    out["contrast"] = grid_array(map.contrast, g.ny, g.nx);
    out["char_height_mm"] = grid_array(map.char_height_mm, g.ny, g.nx);
    out["char_height_arcmin"] = grid_array(map.char_arcmin, g.ny, g.nx);
    py::dict shares, legible;
    for (std::size_t k = 0; k < map.thresholds.size(); ++k) {
      shares[py::float_(map.thresholds[k])] = grid_array(map.contrast_share[k], g.ny, g.nx);
      legible[py::float_(map.thresholds[k])] = legible_share(map, k);
    }
    out["contrast_share"] = shares;
    out["legible_share"] = legible;
  }
  return out;
}

py::dict optimise(const std::filesystem::path& spec_file, std::optional<std::filesystem::path> output,
                  py::object progress) {
  const std::string spec_path = spec_file.string();
  const design_spec spec = load_design_spec(spec_path);
  if (spec.variables.empty()) throw input_error(spec_path + ": variables: the optimiser needs at least one");
  python_job job(std::move(progress));
  std::atomic<bool> cancel{false};
  design_result r;
  {
    py::gil_scoped_release released;
    r = optimise_design(
        spec,
        [&](const design_progress& p) {
          if (!job.keep_going(double(p.done) / p.total)) cancel = true;
        },
        &cancel);
  }
  job.finish();
  if (r.best < 0) throw input_error(spec_path + ": nothing was evaluated");
  const design_trial& best = r.best_trial();
  if (output && best.valid && best.evaluation.feasible()) {
    const std::string dir = std::filesystem::absolute(*output).parent_path().string();
    save_scene(rebase_scene_paths(design_scene(spec, best.x), dir), output->string());
  }
  const std::size_t n = r.trials.size(), nv = spec.variables.size();
  std::vector<double> x, objectives, constraints, score;
  std::vector<bool> feasible, valid;
  py::list phase, problem;
  for (const design_trial& t : r.trials) {
    for (std::size_t i = 0; i < nv; ++i) x.push_back(t.x[i]);
    for (std::size_t i = 0; i < spec.objectives.size(); ++i)
      objectives.push_back(t.valid ? t.evaluation.objective_values[i] : nan);
    for (std::size_t i = 0; i < spec.constraints.size(); ++i)
      constraints.push_back(t.valid ? t.evaluation.constraint_values[i] : nan);
    score.push_back(t.evaluation.score);
    feasible.push_back(t.valid && t.evaluation.feasible());
    valid.push_back(t.valid);
    phase.append(t.phase);
    problem.append(t.problem);
  }
  py::dict out;
  py::list names;
  for (const design_variable& v : spec.variables) names.append(v.key);
  out["variables"] = names;
  out["x"] = grid_array(x, int(n), int(nv));
  out["objectives"] = grid_array(objectives, int(n), int(spec.objectives.size()));
  out["constraints"] = grid_array(constraints, int(n), int(spec.constraints.size()));
  out["score"] = to_array(score);
  out["feasible"] = feasible;
  out["valid"] = valid;
  out["phase"] = phase;
  out["problem"] = problem;
  out["best"] = r.best;
  out["best_feasible"] = best.valid && best.evaluation.feasible();
  out["broken"] = best.evaluation.broken;
  out["front"] = r.front;
  out["cancelled"] = r.cancelled;
  return out;
}

py::dict tolerance(const std::filesystem::path& spec_file, std::optional<py_scene> nominal, py::object progress) {
  const design_spec spec = load_design_spec(spec_file.string());
  python_job job(std::move(progress));
  std::atomic<bool> cancel{false};
  tolerance_result r;
  {
    py::gil_scoped_release released;
    r = run_tolerance(
        spec, nominal ? nominal->current() : spec.base,
        [&](int done, int total) {
          if (!job.keep_going(double(done) / total)) cancel = true;
        },
        &cancel);
  }
  job.finish();
  py::dict out, metrics;
  out["samples"] = r.samples;
  out["invalid"] = r.invalid;
  out["yield"] = r.yield;
  for (const metric_distribution& d : r.metrics) {
    py::dict m;
    m["values"] = to_array(d.values);
    m["mean"] = d.mean;
    m["sd"] = d.sd;
    m["p5"] = d.p5;
    m["p50"] = d.p50;
    m["p95"] = d.p95;
    metrics[py::str(d.name)] = m;
  }
  out["metrics"] = metrics;
  std::vector<double> sensitivity;
  for (const auto& row : r.sensitivity) sensitivity.insert(sensitivity.end(), row.begin(), row.end());
  out["sensitivity"] = grid_array(sensitivity, int(r.sensitivity.size()), int(r.metrics.size()));
  py::list keys;
  for (const auto& t : spec.tolerances) keys.append(t.key);
  out["tolerances"] = keys;
  std::vector<double> drawn;
  for (const tolerance_layout& l : r.layouts) drawn.insert(drawn.end(), l.values.begin(), l.values.end());
  out["drawn"] = grid_array(drawn, int(r.layouts.size()), int(spec.tolerances.size()));
  py::list worst;
  for (std::size_t i : worst_layouts(r, 5)) worst.append(i);
  out["worst"] = worst;
  return out;
}

}  // namespace

void add_study_functions(py::module_& m) {
  m.def("sweep", &sweep, py::arg("scene"), py::kw_only(), py::arg("vary"), py::arg("psf") = true, py::arg("spp") = 64,
        py::arg("psf_samples") = 100000, py::arg("threads") = 0, py::arg("progress") = py::none(),
        R"(Sweeps the floating distance and/or the sheet's tilt, as `airr sweep` does.

vary: one or two axes as `airr sweep --vary` takes them, e.g. ["floating_distance=150:300:25",
"tilt=0:30:10"] (two make a grid, the distance varying fastest). psf: measure by the model PSF
(True) or by rendering a slanted edge at spp samples per pixel (False). progress: called with the
fraction done; an exception it raises (or Ctrl+C) stops the sweep and reaches the caller.

Returns a dict of float64 arrays, one value per point: "floating_distance_mm", "tilt_deg",
"mean_mtf" (over (0, 1] lp/mm), "mtf50_lp_per_mm" (NaN where not reached), "r50_mm",
"brightness" (NaN at a point whose layout is no layout); "reason" (a list of str: why a point is
no layout, empty where it was measured); "mean_mtf_slope_per_mm" (per tilt, over its valid
points, when D varies) and "csv" (the CSV `airr sweep` writes). Raises ValueError when no point
is a layout.)");
  m.def("viewzone", &viewzone, py::arg("scene"), py::kw_only(), py::arg("sphere") = false,
        py::arg("distance_mm") = 300.0, py::arg("grid") = 21, py::arg("x") = py::none(), py::arg("y") = py::none(),
        py::arg("rows") = 64, py::arg("full") = false, py::arg("spp") = 16, py::arg("progress") = py::none(),
        R"(Where the aerial image can be seen, over a grid of eye positions, as `airr viewzone` maps it.

Eyes on a plane in front of the aerial image (x, y in mm, default -200 to 200) or on the sphere
around it (sphere=True: azimuth, elevation in degrees, default -60 to 60), grid x grid of them at
distance_mm. full=True adds the full model per eye (a small render of spp samples per pixel).

Returns a dict: the grid's "x_mm" and "y_mm" (or "azimuth_deg" and "elevation_deg"), and grid x
grid float64 arrays (row j at y[j]): "visible" (the visible fraction), and with full=True
"brightness" (relative to the best eye), "mean_mtf", "stray_ratio", "direct" (NaN where nothing
of the aerial image is seen), "luminance" (the aerial image's mean, cd/m2 when the display's is
given), "contrast" ((aerial + background) / background of the mean luminances; inf against a
dark background), "contrast_share" ({threshold: the share of the image reaching it}, thresholds
1.5, 3 and 25), "legible_share" ({threshold: the share of the eyes seeing 90% of the image at
it}) and "char_height_mm" and "char_height_arcmin" (the smallest legible character; inf where
the contrast leaves too little).)");
  m.def("optimise", &optimise, py::arg("spec"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(),
        R"(Searches a design spec's variables for the best layout, as `airr optimise` does (docs/design.md).

spec: the design spec file (format airr-design). output: where to write the best layout's scene
(when it meets the constraints). progress: called with the fraction of the evaluations done; an
exception it raises (or Ctrl+C) stops the search, and the best so far is not returned.

Returns a dict: "variables" (their keys), per trial "x" (trials x variables), "objectives",
"constraints" (NaN where the trial made no layout), "score", "feasible", "valid", "phase",
"problem"; "best" (the best trial's index), "best_feasible", "broken" (the constraints the best
breaks), "front" (the Pareto front's trials, for two objectives).)");
  m.def("tolerance", &tolerance, py::arg("spec"), py::kw_only(), py::arg("nominal") = py::none(),
        py::arg("progress") = py::none(),
        R"(The Monte Carlo tolerance study of a design spec, as `airr tolerance` runs it.

spec: the design spec file with its tolerances. nominal: the layout to perturb (a Scene; default
the spec's scene). progress: as for optimise.

Returns a dict: "samples", "invalid", "yield" (the share meeting every constraint), "metrics"
(per metric: its "values" per valid sample, "mean", "sd", "p5", "p50", "p95"), "tolerances" (their
keys), "sensitivity" (tolerances x metrics: each metric's change per tolerance size), "drawn"
(samples x tolerances: each layout's drawn values, as `airr tolerance`'s CSV has them) and "worst"
(the five worst samples' indices: no valid layout first, then the most constraints broken, then the
lowest score).)");
}

}  // namespace airr::python
