// airr fit --data DIR -o preset.json [--samples N] [--seed S]
// airr fit --synthesise DIR [--preset rf-ay] [--setup device.json] [--samples N] [--seed S]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/mtf_csv.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "commands.hpp"
#include "progress_bar.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct options {
  std::string data, output, synthesise, preset = "rf-ay", setup;
  std::optional<std::uint64_t> samples, seed;  // unset: the mode's default
};

std::string two_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02.0f", v);
  return buf;
}

void run_fit(const options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const airr::analysis::fit_data data = airr::analysis::load_fit_data(opt.data);
  airr::analysis::fit_params p;
  p.psf_samples = opt.samples.value_or(p.psf_samples);
  p.seed = opt.seed.value_or(p.seed);

  progress_bar bar("fit");
  const auto r = airr::analysis::fit_sheet(data, p, [&](const airr::analysis::fit_progress& f) {
    if (f.fraction < 1)
      bar.update(f.fraction, f.stage);
    else
      bar.finish(f.stage);
    return true;
  });
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

// A data directory whose measurements the model PSF synthesises from a preset: MTF curves per tilt
// and distance (with a pixel's aperture), white-square images per tilt.
void run_synthesise(const options& opt) {
  const fs::path dir = opt.synthesise;
  fs::create_directories(dir);
  const airr::sheet_preset truth = airr::load_preset(opt.preset, fs::current_path().string());
  const std::uint64_t samples = opt.samples.value_or(1000000), seed = opt.seed.value_or(7);

  // The setup: the default layout, or the device's (--setup; its other sheets the first's mirror
  // images); a 40 x 40 camera of 0.4 mm pixels frames a 10 mm white square. The MTF curves are
  // measured as with 0.25 mm pixels (their aperture is in the curves).
  airr::scene setup;
  if (!opt.setup.empty()) {
    setup = airr::load_scene(opt.setup);
    airr::analysis::check_fit_sheets(setup, opt.setup);
    setup.props.clear();  // the model PSF does not see them
    setup.source.emission_profile.clear();
  }
  const std::string panel = fs::relative(fs::path(airr::asset_dir()) / "models/panel.gltf", fs::absolute(dir)).string();
  setup.source.mesh = setup.half_mirror.mesh = panel;
  for (auto& sheet : setup.retroreflectors) sheet.mesh = panel;
  setup.source.image.clear();
  const int camera_pixels = 40;
  const double camera_mm = 0.4, pixel_mm = 0.25, square_mm = 10.0;
  setup.observer.width = setup.observer.height = camera_pixels;
  setup.observer.fov_deg = airr::degrees(2.0 * std::atan(0.5 * camera_pixels * camera_mm / setup.observer.distance_mm));
  airr::save_scene(setup, (dir / "setup.json").string());
  setup = airr::load_scene((dir / "setup.json").string());

  const std::string preset_path = airr::resolve_preset_path(opt.preset, fs::current_path().string());
  auto truth_psf = [&](double tilt, double d, airr::scene& s) {
    s = airr::analysis::measurement_layout(setup, tilt, d);
    for (auto& sheet : s.retroreflectors) {
      sheet.model = {.type = "sinc_shift", .values = {}};
      airr::set_model_value(sheet.model, "preset", fs::absolute(preset_path).string());
    }
    return airr::sample_psf(s, airr::make_sheet_models(s), {.samples = samples, .seed = seed});
  };
  auto write_csv = [&](const airr::psf_samples& psf, const std::string& name) {
    const auto c =
        airr::analysis::measured_like_mtf(psf, {.max_lp_per_mm = 2.0, .points = 101, .pixel_mm = pixel_mm}, 0, false);
    airr::analysis::mtf_curve curve;
    for (std::size_t i = 0; i < c.mtf.size(); ++i) curve.cycles_per_pixel.push_back(c.lp_per_mm[i] * pixel_mm);
    curve.mtf = c.mtf;
    airr::write_file_atomic((dir / name).string(), airr::analysis::format_mtf_csv(curve, pixel_mm));
  };

  json fit = {{"format", airr::analysis::fit_data_format},
              {"version", airr::analysis::fit_data_version},
              {"name", "synthetic " + truth.name},
              {"note", "synthesised by `airr fit --synthesise` from preset " + opt.preset + " with the model PSF (" +
                           std::to_string(samples) + " samples, seed " + std::to_string(seed) +
                           "); MTF curves include a 0.25 mm pixel's aperture"},
              {"scene", "setup.json"},
              {"tilt_series", json::array()},
              {"distance_series", json::array()},
              {"white_squares", json::array()}};
  progress_bar bar("synthesise");
  const int steps = 10 + 7 + 10;
  int done = 0;
  airr::scene s;
  for (int t = 0; t <= 45; t += 5) {
    bar.update(double(done++) / steps, "tilt " + std::to_string(t));
    const auto psf = truth_psf(t, 150, s);
    const std::string csv = "tilt_" + two_digits(t) + ".csv", white = "white_" + two_digits(t) + ".exr";
    write_csv(psf, csv);
    fit["tilt_series"].push_back({{"tilt_deg", t}, {"floating_distance_mm", 150}, {"mtf_csv", csv}});

    bar.update(double(done++) / steps, "white square at tilt " + std::to_string(t));
    const cv::Mat img = airr::analysis::white_square_image(s, psf, square_mm, square_mm);
    airr::image_rgb rgb{img.cols, img.rows, std::vector<float>(std::size_t(img.total()) * 3)};
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols; ++x)
        for (int k = 0; k < 3; ++k) rgb.at(x, y)[k] = float(img.at<double>(y, x));
    char mm[64];
    std::snprintf(mm, sizeof mm, "%.17g", airr::make_camera(s).mm_per_pixel);
    airr::write_image((dir / white).string(), rgb,
                      {{"airr:mm_per_pixel", mm}, {"airr:generator", "airr fit --synthesise"}});
    fit["white_squares"].push_back({{"tilt_deg", t}, {"image", white}, {"square_mm", square_mm}});
  }
  for (int d = 150; d <= 300; d += 25) {
    bar.update(double(done++) / steps, "D " + std::to_string(d) + " mm");
    const std::string csv = "distance_" + std::to_string(d) + ".csv";
    write_csv(truth_psf(0, d, s), csv);
    fit["distance_series"].push_back({{"floating_distance_mm", d}, {"tilt_deg", 0}, {"mtf_csv", csv}});
  }
  airr::write_file_atomic((dir / "fit.json").string(), fit.dump(2) + "\n");
  bar.finish(std::to_string(steps) + " measurements");
  std::printf("wrote %s (fit.json, setup.json, 17 MTF CSVs, 10 white-square EXRs) from preset %s\n",
              dir.string().c_str(), preset_path.c_str());
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
