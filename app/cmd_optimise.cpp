// airr optimise SPEC -o best.json [--csv evaluations.csv]
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/design_search.hpp"
#include "commands.hpp"
#include "progress_bar.hpp"

namespace {

namespace fs = std::filesystem;

std::atomic<bool> interrupted{false};

struct options {
  std::string spec, output, csv;
};

void run(const options& opt) {
  const airr::design_spec spec = airr::load_design_spec(opt.spec);
  if (spec.variables.empty()) throw airr::input_error(opt.spec + ": variables: the optimiser needs at least one");
  const std::string csv =
      opt.csv.empty() ? fs::path(opt.output).replace_extension("").string() + "_evaluations.csv" : opt.csv;
  progress_bar bar("optimise");
  interrupted = false;
  const auto previous = std::signal(SIGINT, [](int) { interrupted = true; });
  const airr::design_result r = airr::optimise_design(
      spec,
      [&](const airr::design_progress& p) {
        char detail[96] = "";
        if (p.have_best)
          std::snprintf(detail, sizeof detail, "%d/%d, best %.6g%s", p.done, p.total, p.best_score,
                        p.best_feasible ? "" : " (infeasible)");
        bar.update(double(p.done) / p.total, detail);
      },
      &interrupted);
  std::signal(SIGINT, previous);
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
  cmd->callback([opt] { run(*opt); });
}
