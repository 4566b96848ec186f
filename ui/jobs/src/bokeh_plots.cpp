#include "airr/ui/jobs/bokeh_plots.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/measure/mtf_routes.hpp"

namespace airr::ui {

using clock_type = std::chrono::steady_clock;
static double ms_since(clock_type::time_point t0) {
  return std::chrono::duration<double, std::milli>(clock_type::now() - t0).count();
}

// Nodes every `step` from `lo` to `hi`, both widened to reach `keep` (the design's value).
static std::vector<double> nodes_around(double lo, double hi, double step, double keep) {
  lo = std::min(lo, std::floor(keep / step) * step);
  hi = std::max(hi, std::ceil(keep / step) * step);
  std::vector<double> v;
  for (double x = lo; x <= hi + 1e-9; x += step) v.push_back(x);
  return v;
}

std::optional<bokeh_plots> compute_bokeh(const scene& s, std::uint64_t generation, const bokeh_params& p,
                                         retro_model_list models, const std::function<bool()>& stop,
                                         std::optional<double> r50_mm) {
  const auto stopped = [&] { return stop && stop(); };
  bokeh_plots out;
  out.generation = generation;
  out.floating_distance_mm = floating_distance(s);
  out.tilt_deg = s.sheet().pose.pitch_deg;
  try {
    if (models.empty()) models = make_sheet_models(s);
    auto t0 = clock_type::now();
    out.r50_mm = r50_mm ? *r50_mm : energy_radius(scene_psf(s, models, p.psf_samples));
    const psf_samples picture = sample_psf(s, models, {.samples = p.psf_samples, .seed = s.seed, .stratified = false});
    out.psf = analysis::psf_to_grid(picture, p.psf_pixels,
                                    2 * analysis::psf_picture_half_width(picture, false) / p.psf_pixels);
    out.psf_ms = ms_since(t0);
    if (stopped()) return std::nullopt;

    t0 = clock_type::now();
    std::vector<double> offsets;
    for (int k = -5; k <= 5; ++k) offsets.push_back(4.0 * k);
    out.focus = analysis::compute_through_focus(
        s, models, offsets, {.samples = p.focus_samples, .seed = s.seed, .stratified = false}, p.spot_pixels);
    out.strip = {0, 3, 5, 7, 10};
    out.focus_ms = ms_since(t0);
    if (stopped()) return std::nullopt;

    t0 = clock_type::now();
    out.spots = analysis::compute_spot_matrix(
        s, models, p.spots, {.samples = p.spot_samples, .seed = s.seed, .stratified = false}, p.spot_pixels);
    out.spots_ms = ms_since(t0);
  } catch (const std::exception& e) {
    out.error = e.what();
  }

  const auto t0 = clock_type::now();
  out.map_d_mm = nodes_around(100, 300, 25, out.floating_distance_mm);
  out.map_tilt_deg = nodes_around(0, 45, 5, out.tilt_deg);
  for (double tilt : out.map_tilt_deg) {
    for (double d : out.map_d_mm) {
      if (stopped()) return std::nullopt;
      double r50 = std::numeric_limits<double>::quiet_NaN();
      try {
        scene sd = s;
        set_floating_distance(sd, d);
        sd.sheet().pose.pitch_deg = tilt;
        check_layout(sd, "blur map");
        // Built again at each point: a per-render lookup follows the sheet's chief ray there.
        r50 = energy_radius(scene_psf(sd, make_sheet_models(sd), p.map_samples));
      } catch (const std::exception&) {
        // A point where the layout does not work stays grey.
      }
      out.map_r50_mm.push_back(r50);
    }
  }
  out.map_ms = ms_since(t0);
  return out;
}

}  // namespace airr::ui
