// airr optimise SPEC -o best.json [--csv evaluations.csv]; with two objectives also the Pareto front
// (best_pareto.csv, best_pareto.png)
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <tbb/global_control.h>

#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/design/search.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/mpi_job.hpp"

namespace {

namespace fs = std::filesystem;

std::atomic<bool> interrupted{false};

struct options {
  std::string spec, output, csv;
  int threads = 0;
};

// The Pareto front of two objectives as CSV, and as a PNG over every feasible evaluation.
void write_front(const airr::design_spec& spec, const airr::design_result& r, const std::string& stem) {
  airr::write_file_atomic(stem + ".csv", airr::design_front_csv(spec, r));
  airr::analysis::plot_series all{"feasible evaluations", {}, {}, cv::Scalar(175, 175, 175), true};
  airr::analysis::plot_series front{"Pareto front", {}, {}, cv::Scalar(40, 40, 200), false};
  for (const airr::design_trial& t : r.trials) {
    if (!t.valid || !t.evaluation.feasible()) continue;
    all.x.push_back(t.evaluation.objective_values[0]);
    all.y.push_back(t.evaluation.objective_values[1]);
  }
  for (int i : r.front) {
    front.x.push_back(r.trials[std::size_t(i)].evaluation.objective_values[0]);
    front.y.push_back(r.trials[std::size_t(i)].evaluation.objective_values[1]);
  }
  airr::analysis::plot_series front_points = front;
  front_points.label.clear();
  front_points.points = true;
  auto title = [&](int i) {
    const airr::design_objective& o = spec.objectives[std::size_t(i)];
    return std::string(airr::to_string(o.metric)) + (o.maximise ? " (maximised)" : " (minimised)");
  };
  airr::analysis::plot_params p;
  p.title = "Pareto front: " + std::to_string(r.front.size()) + " layouts";
  p.x_title = title(0);
  p.y_title = title(1);
  airr::analysis::write_plot_png(stem + ".png", {all, front, front_points}, p);
  std::printf("Pareto front: %zu layouts in %s.csv and %s.png\n", r.front.size(), stem.c_str(), stem.c_str());
}

void run(const options& opt) {
  // The evaluations use every core unless told (the results do not depend on it).
  std::optional<tbb::global_control> threads;
  if (opt.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(opt.threads));
  const airr::design_spec spec = airr::load_design_spec(opt.spec);
  if (spec.variables.empty()) throw airr::input_error(opt.spec + ": variables: the optimiser needs at least one");
  const std::string csv =
      opt.csv.empty() ? fs::path(opt.output).replace_extension("").string() + "_evaluations.csv" : opt.csv;
  // In an MPI job a Pareto front's searches split across the ranks; a single search's evaluations
  // come one at a time from NLopt, so every rank runs it and rank 0 writes.
  const mpi_job& job = this_job();
  if (job.root() && job.size > 1 && spec.front.points == 0)
    std::fprintf(stderr, "note: a single search does not split across ranks; every rank runs it\n");
  progress_bar bar(job.size > 1 ? "optimise (" + std::to_string(job.size) + " ranks)" : "optimise", job.root());
  interrupted = false;
  const auto previous = std::signal(SIGINT, [](int) { interrupted = true; });
  const airr::design_result r = airr::optimise_design(
      spec,
      [&](const airr::design_progress& p) {
        char detail[128] = "";
        if (spec.front.points > 0)
          std::snprintf(detail, sizeof detail, "%d/%d, %s", p.done, p.total, p.stage.c_str());
        else if (p.have_best)
          std::snprintf(detail, sizeof detail, "%d/%d, best %.6g%s", p.done, p.total, p.best_score,
                        p.best_feasible ? "" : " (infeasible)");
        bar.update(double(p.done) / p.total, detail);
      },
      &interrupted, job_share());
  std::signal(SIGINT, previous);
  if (!job.root()) return;
  bar.finish(r.cancelled ? "cancelled" : "done");
  airr::write_file_atomic(csv, airr::design_trials_csv(spec, r));
  std::printf("%zu evaluations in %.1f s (%.2f per second); every one in %s\n", r.trials.size(), bar.seconds(),
              double(r.trials.size()) / bar.seconds(), csv.c_str());
  if (r.best < 0) throw airr::input_error(opt.spec + ": nothing was evaluated");
  const airr::design_trial& best = r.best_trial();
  if (!best.valid || !best.evaluation.feasible())
    throw airr::input_error(opt.spec + ": infeasible: no layout met the constraints; the closest breaks " +
                            best.evaluation.broken.front());
  for (std::size_t i = 0; i < spec.variables.size(); ++i)
    std::printf("%s = %.6g\n", spec.variables[i].key.c_str(), best.x[i]);
  for (std::size_t i = 0; i < spec.objectives.size(); ++i)
    std::printf("%s %s: %.6g\n", spec.objectives[i].maximise ? "maximised" : "minimised",
                airr::to_string(spec.objectives[i].metric), best.evaluation.objective_values[i]);
  for (std::size_t i = 0; i < spec.constraints.size(); ++i)
    std::printf("constraint %s: %.6g\n", airr::to_string(spec.constraints[i].metric),
                best.evaluation.constraint_values[i]);
  if (!r.front.empty()) write_front(spec, r, fs::path(opt.output).replace_extension("").string() + "_pareto");
  airr::scene s = airr::design_scene(spec, best.x);
  airr::save_scene(airr::rebase_scene_paths(s, fs::absolute(opt.output).parent_path().string()), opt.output);
  std::printf("wrote %s%s\n", opt.output.c_str(), r.cancelled ? " (the best before the search was cancelled)" : "");
}

}  // namespace

void add_optimise_command(CLI::App& app) {
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("optimise",
                                 "Search a design spec's variables for the best layout: a global search, then a local "
                                 "polish, within the spec's constraints (Ctrl-C stops it and keeps the best so far)");
  cmd->add_option("spec", opt->spec, "Design spec (format airr-design; see docs/design.md)")->required();
  cmd->add_option("-o,--output", opt->output, "Scene file to write the best layout to")->required();
  cmd->add_option("--csv", opt->csv, "CSV of every evaluation (default: beside the output, <name>_evaluations.csv)");
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  cmd->callback([opt] { run(*opt); });
}
