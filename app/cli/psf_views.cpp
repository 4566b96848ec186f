#include "cli/psf_views.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "airr/analysis/bokeh.hpp"
#include "airr/analysis/plot_png.hpp"
#include "airr/analysis/psf_grid.hpp"
#include "airr/analysis/psf_png.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf_focus.hpp"
#include "airr/measure/traced_psf.hpp"
#include "cli/progress_bar.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

airr::image_rgb grid_image(const airr::analysis::psf_grid& g) {
  airr::image_rgb img{g.size, g.size, std::vector<float>(std::size_t(g.size) * g.size * 3)};
  for (int row = 0; row < g.size; ++row)
    for (int col = 0; col < g.size; ++col) std::fill_n(img.at(col, row), 3, float(g.at(col, row)));
  return img;
}

// The grid's density as a grey linear image (and other grids of its size as layers), with what a
// reader needs to use it.
void write_grid_image(const std::string& path, const airr::analysis::psf_grid& g, airr::image_metadata meta,
                      const std::vector<std::pair<std::string, const airr::analysis::psf_grid*>>& layers = {}) {
  meta[airr::mm_per_pixel_attribute] = fmt("%.10g", g.mm_per_pixel);
  meta["airr:psf_units"] =
      "per mm^2 of the aerial-image plane; integrates to the aerial radiance per unit source radiance";
  meta["airr:psf_center"] = "the middle pixel's centre is the ideal image point; x right, y up";
  std::vector<airr::image_rgb> layer_images;
  for (const auto& [name, grid] : layers) layer_images.push_back(grid_image(*grid));
  std::vector<airr::image_layer> named;
  for (std::size_t i = 0; i < layers.size(); ++i) named.push_back({layers[i].first, &layer_images[i]});
  airr::write_image(path, grid_image(g), meta, 1.0f, named);
}

std::string sheet_summary(const airr::scene& s) {
  std::string out;
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    if (i) out += " + ";
    out += s.retroreflectors[i].model.type;
  }
  return out;
}

}  // namespace

// The picture of `psf` on a square of half-width `half` mm, with what it holds printed.
static airr::analysis::psf_grid psf_picture(const airr::psf_samples& psf, int pixels, double half, const char* what) {
  const auto t0 = std::chrono::steady_clock::now();
  airr::analysis::psf_grid g = airr::analysis::psf_to_grid(psf, pixels, 2 * half / pixels);
  std::printf(
      "2D PSF %s: %d x %d pixels of %.5g mm (+-%.4g mm), holding %.4f%% of the brightness, peak %.6g per "
      "mm^2 (%.3f s)\n",
      what, g.size, g.size, g.mm_per_pixel, g.half_width_mm(),
      psf.brightness() > 0 ? 100 * g.integral() / psf.brightness() : 0.0, g.peak(), seconds_since(t0));
  return g;
}

// The model, the model blurred by the disc, the tracer's render of the disc and their difference,
// on the picture's grid.
static void write_traced_comparison(const airr::scene& s, const airr::psf_samples& psf, const psf_picture_options& o,
                                    const traced_options& t) {
  namespace an = airr::analysis;
  const double half = o.half_width_mm > 0 ? o.half_width_mm : an::psf_picture_half_width(psf, false);
  const int pixels = o.pixels ? o.pixels : 129;
  const an::psf_grid model = psf_picture(psf, pixels, half, "picture");
  const an::psf_grid blurred = an::psf_to_grid(an::blur_by_disc(psf, t.disc_mm, s.seed), pixels, 2 * half / pixels);
  progress_bar bar("traced PSF");
  const airr::traced_psf traced =
      airr::trace_psf(s, pixels, model.mm_per_pixel, {.disc_mm = t.disc_mm, .spp = t.spp, .seed = s.seed},
                      [&](double f) { f < 1.0 ? bar.update(f) : bar.finish(); });
  an::psf_grid difference = traced.grid;
  for (std::size_t i = 0; i < difference.density.size(); ++i) difference.density[i] -= blurred.density[i];
  an::psf_grid magnitude = difference;
  for (double& d : magnitude.density) d = std::abs(d);

  const double r50_model = an::grid_energy_radius(blurred), r50_traced = an::grid_energy_radius(traced.grid);
  const double mtf_model = an::grid_mean_mtf(blurred), mtf_traced = an::grid_mean_mtf(traced.grid);
  std::printf("traced PSF: a %.4g mm disc (%.5g mm^2 drawn), %llu spp, plain path tracer, pinhole observer (%.2f s)\n",
              t.disc_mm, traced.disc_area_mm2, static_cast<unsigned long long>(traced.spp), traced.seconds);
  std::printf(
      "  on the picture's grid:  r50 %.5g mm (model x disc) vs %.5g mm (traced), %+.2f%%; mean MTF over (0, "
      "1] lp/mm %.5f vs %.5f, %+.4f; brightness held %.6g vs %.6g\n",
      r50_model, r50_traced, 100 * (r50_traced / r50_model - 1), mtf_model, mtf_traced, mtf_traced - mtf_model,
      blurred.integral(), traced.grid.integral());
  if (!o.image.empty()) {
    write_grid_image(o.image, model,
                     {{"airr:psf", "model PSF on the aerial-image plane (layers: model_disc, traced, difference)"},
                      {"airr:psf_brightness", fmt("%.10g", psf.brightness())},
                      {"airr:psf_held", fmt("%.10g", model.integral())},
                      {"airr:traced_disc_mm", fmt("%.10g", t.disc_mm)},
                      {"airr:traced_spp", std::to_string(t.spp)},
                      {"airr:sheets", sheet_summary(s)}},
                     {{"model_disc", &blurred}, {"traced", &traced.grid}, {"difference", &difference}});
    std::printf("wrote %s\n", o.image.c_str());
  }
  if (!o.png.empty()) {
    const std::string title = "model and tracer: " + sheet_summary(s) + ", D " +
                              fmt("%g mm", airr::floating_distance(s)) + ", tilt " +
                              fmt("%g deg", s.sheet().pose.pitch_deg) + ", disc " + fmt("%g mm", t.disc_mm) + ", " +
                              std::to_string(t.spp) + " spp";
    an::write_psf_panels_png(o.png,
                             {{&model, "model, r50 " + fmt("%.3g mm", airr::energy_radius(psf))},
                              {&blurred, "model x disc, r50 " + fmt("%.3g mm", r50_model)},
                              {&traced.grid, "traced, r50 " + fmt("%.3g mm", r50_traced)},
                              {&magnitude, "|traced - model x disc|"}},
                             {.title = title, .columns = 4});
    std::printf("wrote %s\n", o.png.c_str());
  }
}

void write_psf_pictures(const airr::scene& s, const airr::psf_samples& psf, const psf_picture_options& o,
                        const traced_options& traced) {
  namespace an = airr::analysis;
  if (traced.on) return write_traced_comparison(s, psf, o, traced);
  const double r50 = airr::energy_radius(psf, 0.5);
  if (!o.image.empty()) {
    const double half = o.half_width_mm > 0 ? o.half_width_mm : an::psf_picture_half_width(psf, true);
    int pixels = o.pixels;
    if (pixels == 0) pixels = 2 * std::clamp(int(std::ceil(4 * half / std::max(r50, 1e-9))), 64, 512) + 1;
    write_grid_image(o.image, psf_picture(psf, pixels, half, "image"),
                     {{"airr:psf", "model PSF on the aerial-image plane"},
                      {"airr:psf_brightness", fmt("%.10g", psf.brightness())},
                      {"airr:psf_r50_mm", fmt("%.10g", r50)},
                      {"airr:sheets", sheet_summary(s)}});
    std::printf("wrote %s\n", o.image.c_str());
  }
  if (!o.png.empty()) {
    const double half = o.half_width_mm > 0 ? o.half_width_mm : an::psf_picture_half_width(psf, false);
    const an::psf_grid g = psf_picture(psf, o.pixels ? o.pixels : 129, half, "picture");
    char title[200];
    std::snprintf(title, sizeof title, "model PSF: %s, D %g mm, tilt %g deg, r50 %.4g mm (%.1f%% shown)",
                  sheet_summary(s).c_str(), airr::floating_distance(s), s.sheet().pose.pitch_deg, r50,
                  psf.brightness() > 0 ? 100 * g.integral() / psf.brightness() : 0.0);
    an::write_psf_panels_png(o.png, {{&g, "aerial-image plane"}},
                             {.title = title, .panel_width = 640, .panel_height = 560});
    std::printf("wrote %s\n", o.png.c_str());
  }
}

void run_through_focus(const airr::scene& s, const airr::retro_model_list& models, const std::vector<double>& offsets,
                       std::uint64_t samples, int pixels, const focus_options& o) {
  namespace an = airr::analysis;
  const auto t0 = std::chrono::steady_clock::now();
  const an::through_focus tf =
      an::compute_through_focus(s, models, offsets, {.samples = samples, .seed = s.seed, .stratified = false}, pixels);
  const double seconds = seconds_since(t0);
  for (const airr::psf_sheet_share& share : tf.sheets)
    if (!share.missed.empty())
      std::printf("through focus: sheet %zu adds nothing: %s\n", share.sheet, share.missed.c_str());
  std::printf(
      "through focus (the bundle from the display point of the aerial image's centre, over every sheet; "
      "offsets along the chief ray, positive towards the observer):\n");
  std::printf("  offset_mm    r50_mm    r80_mm  peak_per_mm2\n");
  std::string csv = "offset_mm,r50_mm,r80_mm,peak_per_mm2\n";
  for (const an::focus_plane& p : tf.planes) {
    std::printf("  %9.4g %9.5g %9.5g  %12.6g\n", p.offset_mm, p.r50_mm, p.r80_mm, p.peak_per_mm2);
    char row[128];
    std::snprintf(row, sizeof row, "%.10g,%.10g,%.10g,%.10g\n", p.offset_mm, p.r50_mm, p.r80_mm, p.peak_per_mm2);
    csv += row;
  }
  std::printf("best focus: %.4g mm (smallest r50)\n", tf.best_offset_mm);
  std::printf("through-focus time: %.3f s for %zu planes, %llu rays per sheet\n", seconds, tf.planes.size(),
              static_cast<unsigned long long>(samples));
  if (!o.csv.empty()) {
    airr::write_file_atomic(o.csv, csv);
    std::printf("wrote %s\n", o.csv.c_str());
  }
  if (!o.plot.empty()) {
    an::write_focus_plot_png(
        o.plot, tf, "through focus: " + sheet_summary(s) + ", best focus " + fmt("%.3g", tf.best_offset_mm) + " mm");
    std::printf("wrote %s\n", o.plot.c_str());
  }
  if (!o.strip.empty()) {
    // At most nine planes, evenly picked, the ends included.
    const std::size_t n = tf.planes.size(), shown = std::min<std::size_t>(n, 9);
    std::vector<an::psf_panel> panels;
    std::vector<std::string> labels;
    for (std::size_t k = 0; k < shown; ++k) {
      const std::size_t i = shown == 1 ? 0 : k * (n - 1) / (shown - 1);
      const an::focus_plane& p = tf.planes[i];
      panels.push_back({&p.grid, fmt("z %+.3g mm", p.offset_mm) + fmt(", r50 %.3g mm", p.r50_mm)});
    }
    an::write_psf_panels_png(o.strip, panels,
                             {.title = "through focus: " + sheet_summary(s) + " (each of unit weight)",
                              .columns = int(panels.size()),
                              .value_title = "log10 density (1/mm^2, unit weight)"});
    std::printf("wrote %s\n", o.strip.c_str());
  }
}

void run_spot_matrix(const airr::scene& s, const airr::retro_model_list& models, std::uint64_t samples, int pixels,
                     const field_options& o) {
  namespace an = airr::analysis;
  const auto t0 = std::chrono::steady_clock::now();
  const an::spot_matrix m =
      an::compute_spot_matrix(s, models, o.n, {.samples = samples, .seed = s.seed, .stratified = false}, pixels);
  const double seconds = seconds_since(t0);
  std::printf("spot matrix (%d x %d over the central 90%% of the aerial image, as the observer sees it):\n", m.n, m.n);
  std::string csv = "row,col,x_mm,y_mm,r50_mm,brightness,incidence_deg\n";
  for (const an::field_spot& spot : m.spots) {
    if (!spot.missed.empty()) {
      std::printf("  row %d col %d (%+.4g, %+.4g) mm: %s\n", spot.row, spot.col, spot.x_mm, spot.y_mm,
                  spot.missed.c_str());
      csv += std::to_string(spot.row) + "," + std::to_string(spot.col) + fmt(",%.10g", spot.x_mm) +
             fmt(",%.10g,,,\n", spot.y_mm);
      continue;
    }
    std::printf("  row %d col %d (%+.4g, %+.4g) mm: r50 %.5g mm, brightness %.6g, incidence %.4g deg\n", spot.row,
                spot.col, spot.x_mm, spot.y_mm, spot.r50_mm, spot.brightness, spot.incidence_deg);
    char row[200];
    std::snprintf(row, sizeof row, "%d,%d,%.10g,%.10g,%.10g,%.10g,%.10g\n", spot.row, spot.col, spot.x_mm, spot.y_mm,
                  spot.r50_mm, spot.brightness, spot.incidence_deg);
    csv += row;
  }
  std::printf("spot-matrix time: %.3f s\n", seconds);
  if (!o.csv.empty()) {
    airr::write_file_atomic(o.csv, csv);
    std::printf("wrote %s\n", o.csv.c_str());
  }
  if (!o.png.empty()) {
    std::vector<an::psf_panel> panels;
    for (const an::field_spot& spot : m.spots) {
      const std::string where = fmt("(%+.3g, ", spot.x_mm) + fmt("%+.3g) mm", spot.y_mm);
      panels.push_back(
          {&spot.grid, spot.missed.empty() ? where + fmt(", r50 %.3g mm", spot.r50_mm) : where + ": not reached"});
    }
    an::write_psf_panels_png(
        o.png, panels,
        {.title = "spot matrix: " + sheet_summary(s) + ", D " + fmt("%g mm", airr::floating_distance(s)) + ", tilt " +
                  fmt("%g deg", s.sheet().pose.pitch_deg),
         .columns = m.n});
    std::printf("wrote %s\n", o.png.c_str());
  }
}
