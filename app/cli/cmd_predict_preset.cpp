// airr predict-preset --sheet prism.json -o preset.json [--data DIR] [--setup device.json] ...
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "airr/analysis/preset_prediction.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/models/preset.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/mpi_job.hpp"

namespace {

namespace fs = std::filesystem;

struct options {
  std::string sheet, output, data, setup;
  airr::analysis::prediction_params p;
};

void run(const options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const airr::sheet_description sheet = airr::load_sheet(opt.sheet);
  const airr::scene bench = airr::analysis::synthesis_bench_file(opt.setup);
  const std::string data = opt.data.empty() ? fs::path(opt.output).replace_extension("").string() + "_bench" : opt.data;

  const mpi_job& job = this_job();
  std::optional<progress_bar> bar;
  if (job.root()) bar.emplace(job.size > 1 ? "predict (" + std::to_string(job.size) + " ranks)" : "predict");
  const rank_folder folder(data);
  const airr::item_share share = job_share();
  const auto r = airr::analysis::predict_preset(
      sheet, bench, folder.path(), opt.p,
      [&](const airr::analysis::fit_progress& f) {
        if (bar) bar->update(f.fraction, f.stage);
        return true;
      },
      share);
  const auto agreement =
      airr::analysis::compare_prediction(sheet, r.preset, bench, r.preset.theta_deg, opt.p.synthesis, share);
  if (!bar) return;
  bar->finish("fitted");
  airr::save_preset(r.preset, opt.output);

  std::printf("preset predicted for %s (%s) from the bench's measurements in %s\n", sheet.name.c_str(),
              sheet.model.type.c_str(), data.c_str());
  std::printf("c = %.5f mm, R = %g mm, shift table: %s\n", r.preset.c_mm, r.preset.reference_distance_mm,
              r.preset.shift_table.empty() ? "the shipped corner cube's" : "the sheet's own, beside the preset");
  std::printf("%8s %10s %9s %13s %13s %11s %11s\n", "tilt_deg", "a_per_mm", "mu", "mean_mtf_expl", "mean_mtf_pred",
              "bright_expl", "bright_pred");
  for (std::size_t i = 0; i < agreement.size(); ++i) {
    const auto& g = agreement[i];
    const double mu = r.preset.mu.size() == 1 ? r.preset.mu[0] : r.preset.mu[i];
    std::printf("%8g %10.5f %9.5f %13.4f %13.4f %11.5f %11.5f\n", g.tilt_deg, r.preset.a_per_mm[i], mu,
                g.explicit_mean_mtf, g.predicted_mean_mtf, g.explicit_brightness, g.predicted_brightness);
  }
  std::printf(
      "mean MTF over (0, 1] lp/mm at D 150 mm with a 0.25 mm pixel and a %g mm LSF window; brightness "
      "per unit display radiance, all light that reaches the display plane\n",
      opt.p.synthesis.lsf_window_mm);
  std::printf("wrote %s\n", opt.output.c_str());
  std::printf("run time: %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace

void add_predict_preset_command(CLI::App& app) {
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("predict-preset",
                                 "Predict a sinc-shift preset for a sheet described by its geometry: measure the "
                                 "explicit sheet model on a simulated bench and fit the preset to it");
  cmd->add_option("--sheet", opt->sheet, "Sheet file (format airr-sheet; see assets/sheets)")->required();
  cmd->add_option("-o,--output", opt->output, "Preset file to write")->required();
  cmd->add_option("--data", opt->data,
                  "Folder for the bench's simulated measurements (fit.json, curves, images); default: beside the "
                  "preset, <preset name>_bench");
  cmd->add_option("--setup", opt->setup,
                  "The bench (a scene; its sheets after the first are the first's mirror images in the half "
                  "mirror); default the default layout");
  cmd->add_option("--samples", opt->p.synthesis.samples, "PSF samples per simulated measurement (default 1000000)")
      ->check(CLI::Range(std::uint64_t(100), std::uint64_t(100000000)));
  cmd->add_option("--fit-samples", opt->p.fit.psf_samples, "PSF samples per simulation of the fit (default 200000)")
      ->check(CLI::Range(std::uint64_t(100), std::uint64_t(100000000)));
  cmd->add_option("--seed", opt->p.synthesis.seed, "Random seed of the measurements (default 7)");
  cmd->add_flag(
      "--shipped-shift-table", [opt](std::int64_t) { opt->p.sheet_shifts = false; },
      "Read the shipped corner cube's shift table (inside a prism sheet's plate) instead of tracing the "
      "sheet's own");
  cmd->add_option("--lsf-window-mm", opt->p.synthesis.lsf_window_mm,
                  "Half-width of the bench's LSF window in mm: its region of interest (default 5; 0: none)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->callback([opt] { run(*opt); });
}
