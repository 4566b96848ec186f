// airr fit --data DIR -o preset.json [--samples N] [--seed S]
// airr fit --synthesise DIR [--preset rf-ay] [--setup device.json] [--samples N] [--seed S]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/fit_synthesis.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/mpi_job.hpp"

namespace {

namespace fs = std::filesystem;

struct options {
  std::string data, output, synthesise, preset = "rf-ay", setup;
  std::optional<std::uint64_t> samples, seed;  // unset: the mode's default
};

void run_fit(const options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const airr::analysis::fit_data data = airr::analysis::load_fit_data(opt.data);
  airr::analysis::fit_params p;
  p.psf_samples = opt.samples.value_or(p.psf_samples);
  p.seed = opt.seed.value_or(p.seed);

  const mpi_job& job = this_job();
  std::optional<progress_bar> bar;
  if (job.root()) bar.emplace(job.size > 1 ? "fit (" + std::to_string(job.size) + " ranks)" : "fit");
  const auto r = airr::analysis::fit_sheet(
      data, p,
      [&](const airr::analysis::fit_progress& f) {
        if (!bar) return true;
        if (f.fraction < 1)
          bar->update(f.fraction, f.stage);
        else
          bar->finish(f.stage);
        return true;
      },
      job_share());
  if (!job.root()) return;
  airr::save_preset(r.preset, opt.output);

  const airr::analysis::fit_report& rep = r.report;
  std::printf("fit of %s (%zu tilts, %zu distances, %zu white squares; model PSF, %llu samples, seed %llu)\n",
              data.dir.c_str(), data.tilt_series.size(), data.distance_series.size(), data.white_squares.size(),
              static_cast<unsigned long long>(p.psf_samples), static_cast<unsigned long long>(p.seed));
  std::printf("%8s %10s %11s %9s %11s\n", "tilt_deg", "a_per_mm", "a_loss", "mu", "mu_loss");
  for (std::size_t i = 0; i < r.preset.theta_deg.size(); ++i) {
    const airr::analysis::fit_a_entry& a = rep.a[i];
    const double tilt = r.preset.theta_deg[i];
    std::string mu_loss = "-";
    for (const auto& m : rep.mu) {
      if (m.tilt_deg == tilt) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3e", m.loss);
        mu_loss = buf;
      }
    }
    const double mu = r.preset.mu.size() == 1 ? r.preset.mu[0] : r.preset.mu[i];
    std::printf("%8g %10.5f %11.3e %9.5f %11s%s\n", tilt, a.a_per_mm, a.loss, mu, mu_loss.c_str(),
                a.minimum_checked ? "" : "  (warning: a (1 -+ 2%) has a lower loss)");
    if (a.at_bracket_end) std::printf("         warning: a at tilt %g lies at the end of the search bracket\n", tilt);
  }
  const airr::analysis::fit_c_entry& c = rep.c;
  std::printf("c = %.5f mm, loss %.3e (slope of mean MTF against D: measured %.5g, simulated %.5g per mm)\n", c.c_mm,
              c.loss, c.slope_measured_per_mm, c.slope_simulated_per_mm);
  std::printf(
      "c with a(0) refitted at each of %d trial values: the match lies in [%.5f, %.5f] mm, a(0) %.4g .. %.4g "
      "across it%s\n",
      c.trial_c_values, c.bracket_mm[0], c.bracket_mm[1], c.a0_at_bracket_ends_per_mm[0],
      c.a0_at_bracket_ends_per_mm[1], c.converged ? "" : " (warning: not converged)");
  if (c.bound != airr::analysis::root_bound::none)
    std::printf("warning: the slope is matched only beyond the %s end of the c bracket; c is clamped there\n",
                airr::analysis::to_string(c.bound));
  if (rep.mu_note) std::printf("%s\n", rep.mu_note->c_str());
  std::printf("wrote %s\n", opt.output.c_str());
  std::printf("run time: %.2f s (%llu PSF simulations)\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              static_cast<unsigned long long>(rep.simulations));
}

// A data directory whose measurements the model PSF synthesises from a preset.
void run_synthesise(const options& opt) {
  const airr::sheet_preset truth = airr::load_preset(opt.preset, fs::current_path().string());
  const std::string preset_path = airr::resolve_preset_path(opt.preset, fs::current_path().string());
  airr::retro_model_params model{.type = "sinc_shift", .values = {}};
  airr::set_model_value(model, "preset", fs::absolute(preset_path).string());
  const airr::analysis::synthesis_params p{.samples = opt.samples.value_or(1000000), .seed = opt.seed.value_or(7)};
  const mpi_job& job = this_job();
  std::optional<progress_bar> bar;
  if (job.root()) bar.emplace("synthesise");
  const rank_folder folder(opt.synthesise);
  airr::analysis::synthesise_fit_data(
      folder.path(), airr::analysis::synthesis_bench_file(opt.setup),
      {.model = model,
       .base_dir = "",
       .name = "synthetic " + truth.name,
       .note = "synthesised by `airr fit --synthesise` from preset " + opt.preset,
       .shift_table = truth.shift_table},
      p,
      [&](const airr::analysis::fit_progress& f) {
        if (bar) bar->update(f.fraction, f.stage);
        return true;
      },
      job_share([&](std::size_t done, std::size_t n) {
        if (bar) bar->update(double(done) / double(n), "measurements");
      }));
  if (!bar) return;
  bar->finish("17 measurements");
  std::printf("wrote %s (fit.json, setup.json, 17 MTF CSVs, 10 white-square EXRs) from preset %s\n",
              opt.synthesise.c_str(), preset_path.c_str());
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("fit",
                                 "Fit the sinc-shift model's a (per tilt), c and mu (per tilt) to measurements "
                                 "and write a preset");
  auto* data = cmd->add_option("--data", opt->data, "Fit data directory holding fit.json (see assets/fit_example)");
  cmd->add_option("-o,--output", opt->output, "Preset file to write (with --data)");
  auto* synth =
      cmd->add_option("--synthesise", opt->synthesise,
                      "Instead of fitting, write a data directory synthesised from --preset by the model PSF");
  cmd->add_option("--preset", opt->preset, "With --synthesise: the preset to synthesise from (default rf-ay)");
  cmd->add_option("--setup", opt->setup,
                  "With --synthesise: the device measured (a scene; its sheets after the first are the first's "
                  "mirror images in the half mirror); default the default layout");
  cmd->add_option("--samples", opt->samples,
                  "PSF samples per simulation (fit default 200000; --synthesise default 1000000)")
      ->check(CLI::Range(std::uint64_t(100), std::uint64_t(100000000)));
  cmd->add_option("--seed", opt->seed, "Random seed of the PSF samples (fit default 1; --synthesise default 7)");
  data->excludes(synth);
  cmd->callback([opt] {
    if (!opt->synthesise.empty()) return run_synthesise(*opt);
    if (opt->data.empty()) throw airr::input_error("fit: give --data DIR (or --synthesise DIR)");
    if (opt->output.empty()) throw airr::input_error("fit: give -o preset.json for the fitted preset");
    run_fit(*opt);
  });
}
