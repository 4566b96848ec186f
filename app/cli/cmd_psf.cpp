// airr psf SCENE [-o psf.csv] [--plot psf.png] [--image psf.exr] [--png psf.png] [--focus A:B:STEP ...]
//          [--field N ...] [--samples N] [--no-pixel] [--max-lp F] [--points N] [--set key=value ...]
#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "airr/analysis/plot_png.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf_focus.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "cli/commands.hpp"
#include "cli/psf_views.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string psf_csv(const airr::analysis::psf_mtf_curve& c) {
  std::string out = "lp_per_mm,mtf\n";
  char row[64];
  for (std::size_t i = 0; i < c.mtf.size(); ++i) {
    std::snprintf(row, sizeof row, "%.10g,%.10g\n", c.lp_per_mm[i], c.mtf[i]);
    out += row;
  }
  return out;
}

// What each sheet adds: its model, its path and chief ray, its brightness (or why it adds none).
void print_sheets(const airr::scene& s, const airr::psf_samples& psf) {
  for (const airr::psf_sheet_share& share : psf.sheets) {
    const airr::retro_model_params& model = s.retroreflectors[share.sheet].model;
    if (!share.missed.empty()) {
      std::printf("sheet %zu: %s, not reached: %s\n", share.sheet, model.type.c_str(), share.missed.c_str());
      continue;
    }
    std::printf(
        "sheet %zu: %s, %s the half mirror, %.6g mm from the aerial image, chief-ray incidence %.4g deg, "
        "brightness %.6g\n",
        share.sheet, model.type.c_str(), share.by_reflection ? "by reflection in" : "through", share.rr_distance_mm,
        share.incidence_deg, share.brightness);
    if (airr::find_field(airr::find_retro_model_kind(model.type).fields, "lookup")) {
      const std::string lookup = airr::read_model_values(model).text("lookup");
      if (lookup == "per_render") {
        std::printf("  angle lookup: per_render, at the sheet's chief-ray incidence %.4g deg\n",
                    airr::sheet_chief_incidence_deg(s, share.sheet));
      } else {
        std::printf("  angle lookup: %s\n", lookup.c_str());
      }
    }
  }
}

}  // namespace

void add_psf_command(CLI::App& app) {
  struct options {
    std::string scene_path, csv, plot;
    std::uint64_t samples = 100000;
    std::vector<std::string> sets;
    bool no_pixel = false;
    double max_lp = 2.0;
    int points = 101;
    psf_picture_options picture;
    focus_options focus;
    field_options field;
    traced_options traced;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("psf", "MTF of the model PSF on the aerial-image plane (no tracer)");
  cmd->add_option("scene", opt->scene_path, "Scene JSON file")->required();
  cmd->add_option("-o,--output", opt->csv, "CSV file of the MTF to write (lp_per_mm,mtf)");
  cmd->add_option("--plot", opt->plot, "Also write a PNG plot of the MTF");
  cmd->add_option("--samples", opt->samples, "Rays traced through the retroreflector (default 100000)")
      ->check(CLI::Range(100, 100000000));
  cmd->add_flag("--no-pixel", opt->no_pixel,
                "The optics alone; by default the camera pixel's aperture is included, as a render measures it");
  cmd->add_option("--max-lp", opt->max_lp, "Highest frequency in the CSV, lp/mm (default 2)")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--points", opt->points, "Frequencies in the CSV, 0 .. max evenly spaced (default 101)")
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--image", opt->picture.image,
                  "Write the 2D model PSF as an image (EXR: density per mm^2, mm per pixel in its metadata)");
  cmd->add_option("--png", opt->picture.png, "Write the 2D model PSF as a log-scaled picture with mm axes");
  cmd->add_option("--pixels", opt->picture.pixels,
                  "Pixels per side of the PSF pictures (odd; default 129, and for --image enough for r50 to span 4)")
      ->check(CLI::Range(3, 4095));
  cmd->add_option("--extent", opt->picture.half_width_mm,
                  "Half-width of the 2D PSF picture in mm (default: the square holding 99.8% of it)")
      ->check(CLI::Range(1e-6, 1e4));
  cmd->add_flag("--traced", opt->traced.on,
                "With --image/--png: also render a small disc on the display with the tracer and set it beside the "
                "model blurred by the same disc, on the picture's grid");
  cmd->add_option("--disc-mm", opt->traced.disc_mm, "--traced: the disc's diameter on the display (default 0.2 mm)")
      ->check(CLI::Range(1e-4, 1e3));
  cmd->add_option("--traced-spp", opt->traced.spp, "--traced: samples per pixel (default 256)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--focus", opt->focus.range,
                  "Through focus: planes at offsets start:end:step mm along the chief ray (+ towards the observer)");
  cmd->add_option("--focus-csv", opt->focus.csv, "Through focus: CSV of offset, r50, r80 and peak");
  cmd->add_option("--focus-plot", opt->focus.plot, "Through focus: PNG plot of r50 and r80 against the offset");
  cmd->add_option("--focus-strip", opt->focus.strip, "Through focus: PNG strip of the PSFs (at most nine planes)");
  cmd->add_option("--field", opt->field.n, "Spot matrix: model PSFs at N x N points over the aerial image")
      ->check(CLI::Range(1, 9));
  cmd->add_option("--field-csv", opt->field.csv, "Spot matrix: CSV of each point's r50");
  cmd->add_option("--field-png", opt->field.png, "Spot matrix: PNG of the PSFs, each with its r50");
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. retroreflectors.0.model.preset=rf-ay");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);
    if (opt->csv.empty() && opt->plot.empty() && opt->picture.image.empty() && opt->picture.png.empty() &&
        opt->focus.range.empty() && opt->field.n == 0) {
      throw airr::input_error("psf: nothing to write: give -o, --plot, --image, --png, --focus or --field");
    }
    if (opt->picture.pixels && opt->picture.pixels % 2 == 0)
      throw airr::input_error("psf: --pixels must be odd (the middle pixel is the ideal point)");
    if (opt->focus.range.empty() && !(opt->focus.csv + opt->focus.plot + opt->focus.strip).empty())
      throw airr::input_error("psf: --focus-csv, --focus-plot and --focus-strip need --focus start:end:step");
    if (opt->traced.on && opt->picture.image.empty() && opt->picture.png.empty())
      throw airr::input_error("psf: --traced needs --image or --png");
    if (opt->field.n == 0 && !(opt->field.csv + opt->field.png).empty())
      throw airr::input_error("psf: --field-csv and --field-png need --field N");
    const std::vector<double> focus_offsets =
        opt->focus.range.empty() ? std::vector<double>{} : airr::parse_focus_offsets(opt->focus.range);
    const airr::retro_model_list models = airr::make_sheet_models(s);
    const double pixel_mm = opt->no_pixel ? 0.0 : airr::make_camera(s).mm_per_pixel;

    const auto t0 = std::chrono::steady_clock::now();
    const airr::psf_samples psf = airr::scene_psf(s, models, opt->samples);
    const double t_sample = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const auto curve =
        airr::analysis::psf_mtf(psf, {.max_lp_per_mm = opt->max_lp, .points = opt->points, .pixel_mm = pixel_mm});
    const double t_curve = seconds_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const airr::mtf_summary m = airr::psf_route_mtf(psf, pixel_mm);
    const double r50 = airr::energy_radius(psf);
    const double t_summary = seconds_since(t2);

    print_sheets(s, psf);
    std::printf("50%%-energy radius: %.4f mm\n", r50);
    if (pixel_mm > 0)
      std::printf("pixel aperture: %.6g mm on the aerial-image plane (included; --no-pixel for the optics alone)\n",
                  pixel_mm);
    else
      std::printf("pixel aperture: none (optics alone)\n");
    std::printf("mean MTF over (0, 1] lp/mm: %.5f\n", m.mean_mtf);
    if (m.mtf50_lp_per_mm)
      std::printf("MTF50: %.5g lp/mm\n", *m.mtf50_lp_per_mm);
    else
      std::printf("MTF50: not reached (MTF stays above 0.5 up to %g lp/mm)\n", pixel_mm > 0 ? 1.0 / pixel_mm : 4.0);
    std::printf("brightness: %.6g (aerial radiance per unit source radiance%s)\n", psf.brightness(),
                psf.sheets.size() > 1 ? "; the sum of the sheets'" : "");
    if (airr::in_cd_m2(s.source)) {
      std::printf("aerial image luminance: %.6g cd/m2 (the display's white at %.6g cd/m2)\n",
                  psf.brightness() * s.source.luminance_cd_m2, s.source.luminance_cd_m2);
    }
    {
      // In the dark (no ambient light's contrast), from the scene's observer.
      const double distance = glm::length(airr::observer_position(s) - airr::aerial_image_center(s));
      const airr::legible_character c =
          airr::psf_legible_character(s, psf, std::numeric_limits<double>::infinity(), airr::legibility_criterion{});
      std::printf(
          "smallest legible character: %.4g mm (%.3g arcmin from the observer, %.0f mm away; bounded by the %s)\n",
          c.height_mm, c.arcmin, distance, airr::to_string(c.limit));
    }
    std::printf("samples: %llu launched, %zu reach the source plane\n", static_cast<unsigned long long>(psf.launched),
                psf.offset_mm.size());
    std::printf("time: %.3f s (sampling %.3f s, %d-point MTF curve %.3f s, mean MTF, MTF50 and radius %.3f s)\n",
                t_sample + t_curve + t_summary, t_sample, opt->points, t_curve, t_summary);

    if (!opt->csv.empty()) {
      airr::write_file_atomic(opt->csv, psf_csv(curve));
      std::printf("wrote %s\n", opt->csv.c_str());
    }
    if (!opt->plot.empty()) {
      std::vector<airr::analysis::plot_series> series;
      char label[96];
      if (pixel_mm > 0)
        std::snprintf(label, sizeof label, "model PSF x %.3g mm pixel aperture", pixel_mm);
      else
        std::snprintf(label, sizeof label, "model PSF (optics alone)");
      series.push_back({label, curve.lp_per_mm, curve.mtf, {}});
      if (pixel_mm > 0) {
        const auto optics = airr::analysis::psf_mtf(psf, {.max_lp_per_mm = opt->max_lp, .points = opt->points});
        series.push_back({"model PSF (optics alone)", optics.lp_per_mm, optics.mtf, {}});
      }
      airr::analysis::plot_params pp;
      char title[128];
      std::snprintf(title, sizeof title, "model PSF MTF (%s, D %g mm, tilt %g deg, %llu samples)",
                    s.sheet().model.type.c_str(), airr::floating_distance(s), s.sheet().pose.pitch_deg,
                    static_cast<unsigned long long>(psf.launched));
      pp.title = title;
      pp.y_title = "MTF (unitless)";
      pp.x_min = 0.0;
      pp.y_min = 0.0;
      pp.y_max = 1.05;
      airr::analysis::write_plot_png(opt->plot, series, pp);
      std::printf("wrote %s\n", opt->plot.c_str());
    }
    if (!opt->picture.image.empty() || !opt->picture.png.empty()) {
      // Pictures from independent samples: their noise shows as noise, not as the lattice of
      // the sequence the numbers above use.
      write_psf_pictures(s, airr::sample_psf(s, models, {.samples = opt->samples, .seed = s.seed, .stratified = false}),
                         opt->picture, opt->traced);
    }
    if (!opt->focus.range.empty())
      run_through_focus(s, models, focus_offsets, opt->samples, opt->picture.pixels ? opt->picture.pixels : 129,
                        opt->focus);
    if (opt->field.n > 0)
      run_spot_matrix(s, models, opt->samples, opt->picture.pixels ? opt->picture.pixels : 129, opt->field);
  });
}
