// airr tolerance SPEC [--scene best.json] [-o samples.csv] [--png DIR]
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <tbb/global_control.h>

#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/design/tolerance.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/item_shards.hpp"
#include "cluster/mpi_job.hpp"

namespace {

namespace fs = std::filesystem;

std::atomic<bool> interrupted{false};

struct options {
  std::string spec, scene, csv, png;
  int threads = 0;
  shard_options shards;
};

// Every layout drawn: its number, each tolerance's drawn value, whether it made a layout and met
// every constraint, its metrics (empty when it made none) and its broken constraints.
std::string samples_csv(const airr::design_spec& spec, const airr::tolerance_result& r) {
  std::ostringstream out;
  out.precision(10);
  out << "sample";
  for (const airr::design_tolerance& t : spec.tolerances) out << ',' << t.key;
  out << ",valid,meets_constraints";
  for (const airr::metric_distribution& m : r.metrics) out << ',' << m.name;
  out << ",broken\n";
  for (std::size_t i = 0; i < r.layouts.size(); ++i) {
    const airr::tolerance_layout& l = r.layouts[i];
    out << i;
    for (double v : l.values) out << ',' << v;
    out << ',' << (l.valid ? 1 : 0) << ',' << (l.valid && l.broken.empty() ? 1 : 0);
    for (std::size_t m = 0; m < r.metrics.size(); ++m) {
      out << ',';
      if (l.valid) out << l.metrics[m];
    }
    out << ",\"" << airr::layout_failures(l) << "\"\n";
  }
  return out.str();
}

// One histogram per metric (40 bins over its range), as a step line.
void write_histograms(const airr::tolerance_result& r, const std::string& dir) {
  fs::create_directories(dir);
  for (std::size_t m = 0; m < r.metrics.size(); ++m) {
    const auto& d = r.metrics[m];
    if (d.values.empty()) continue;
    const airr::histogram_steps h = airr::metric_histogram(d);
    const airr::analysis::plot_series s{d.name, h.x, h.y, std::nullopt, false};
    std::string file = d.name.substr(0, d.name.find(' '));
    airr::analysis::plot_params p;
    p.title = d.name + " over " + std::to_string(d.values.size()) + " layouts";
    p.x_title = d.name.substr(0, d.name.find(' '));
    p.y_title = "layouts";
    p.y_min = 0.0;
    airr::analysis::write_plot_png(fs::path(dir) / (std::to_string(m) + "_" + file + ".png"), {s}, p);
  }
}

void report(const options& opt, const airr::design_spec& spec, const airr::tolerance_result& r, double seconds);

void run(const options& opt) {
  // The evaluations use every core unless told (the results do not depend on it).
  std::optional<tbb::global_control> threads;
  if (opt.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(opt.threads));
  const airr::design_spec spec = airr::load_design_spec(opt.spec);
  const airr::scene nominal = opt.scene.empty() ? spec.base : airr::load_scene(opt.scene);
  const mpi_job& job = this_job();
  if (const airr::item_share share = command_item_share(opt.shards)) {
    // Shared (an MPI job's ranks, a shard, a merge's partials), the layouts are taken in step: no
    // process stops on its own (mpirun ends the whole job on Ctrl-C); rank 0 reports and writes,
    // a shard writes its partial alone.
    std::optional<progress_bar> bar;
    if (job.root()) bar.emplace(job.size > 1 ? "tolerance (" + std::to_string(job.size) + " ranks)" : "tolerance");
    const airr::tolerance_result r = airr::run_tolerance(
        spec, nominal,
        [&](int done, int total) {
          if (bar) bar->update(double(done) / total);
        },
        nullptr, share);
    if (!bar || write_shard_part(opt.shards)) return;
    bar->finish("done");
    report(opt, spec, r, bar->seconds());
    return;
  }
  progress_bar bar("tolerance");
  interrupted = false;
  const auto previous = std::signal(SIGINT, [](int) { interrupted = true; });
  const airr::tolerance_result r = airr::run_tolerance(
      spec, nominal, [&](int done, int total) { bar.update(double(done) / total); }, &interrupted);
  std::signal(SIGINT, previous);
  bar.finish(r.cancelled ? "cancelled" : "done");
  report(opt, spec, r, bar.seconds());
}

// What the run found, on stdout, and the CSV and histograms.
void report(const options& opt, const airr::design_spec& spec, const airr::tolerance_result& r, double seconds) {
  std::printf("%d layouts (%d no valid layout) in %.1f s; yield %.4f (every constraint met)\n", r.samples, r.invalid,
              seconds, r.yield);
  std::printf("%-28s %12s %12s %12s %12s %12s\n", "metric", "mean", "sd", "p5", "p50", "p95");
  for (const auto& m : r.metrics)
    std::printf("%-28s %12.6g %12.6g %12.6g %12.6g %12.6g\n", m.name.c_str(), m.mean, m.sd, m.p5, m.p50, m.p95);
  std::printf("sensitivity: each metric's change per tolerance size, that tolerance alone\n%-40s", "tolerance");
  for (const auto& m : r.metrics) std::printf(" %28s", m.name.c_str());
  std::printf("\n");
  for (std::size_t t = 0; t < r.sensitivity.size(); ++t) {
    const auto& tol = spec.tolerances[t];
    char label[160];
    std::snprintf(label, sizeof label, "%s %s %g%s", tol.key.c_str(), tol.uniform ? "+-" : "sd", tol.size,
                  tol.percent ? "%" : "");
    std::printf("%-40s", label);
    for (double v : r.sensitivity[t]) std::printf(" %28.6g", v);
    std::printf("\n");
  }
  std::printf("worst layouts (sample: drawn values; what it broke):\n");
  for (std::size_t i : airr::worst_layouts(r, 5)) {
    const airr::tolerance_layout& l = r.layouts[i];
    std::printf("  %zu:", i);
    for (std::size_t t = 0; t < l.values.size(); ++t)
      std::printf(" %s=%.6g", spec.tolerances[t].key.c_str(), l.values[t]);
    const std::string broken = airr::layout_failures(l);
    std::printf("; %s\n", broken.empty() ? ("score " + airr::number_text(l.score)).c_str() : broken.c_str());
  }
  const std::string csv =
      opt.csv.empty() ? fs::path(opt.spec).replace_extension("").string() + "_tolerance.csv" : opt.csv;
  airr::write_file_atomic(csv, samples_csv(spec, r));
  std::printf("wrote %s\n", csv.c_str());
  if (!opt.png.empty()) {
    write_histograms(r, opt.png);
    std::printf("wrote the histograms into %s\n", opt.png.c_str());
  }
}

}  // namespace

void add_tolerance_command(CLI::App& app) {
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("tolerance",
                                 "Monte Carlo over a design spec's tolerances: each metric's distribution, the yield "
                                 "against the constraints, and each tolerance's sensitivity alone");
  cmd->add_option("spec", opt->spec, "Design spec with tolerances (format airr-design; see docs/design.md)")
      ->required();
  cmd->add_option("--scene", opt->scene, "The nominal layout (default the spec's scene; e.g. what optimise wrote)");
  cmd->add_option("-o,--output", opt->csv, "CSV of every layout's metrics (default: beside the spec)");
  cmd->add_option("--png", opt->png, "Folder for one histogram PNG per metric");
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  add_shard_options(cmd, opt->shards);
  cmd->callback([opt] { run(*opt); });
}
