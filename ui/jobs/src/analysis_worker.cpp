#include "airr/ui/jobs/analysis_worker.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_grid.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/prop_hits.hpp"

namespace airr::ui {

using clock_type = std::chrono::steady_clock;
static double ms_since(clock_type::time_point t0) {
  return std::chrono::duration<double, std::milli>(clock_type::now() - t0).count();
}

predicted_plots compute_predicted(const scene& s, std::uint64_t generation, const predicted_params& p,
                                  retro_model_list models) {
  predicted_plots out;
  out.generation = generation;
  try {
    const auto t0 = clock_type::now();
    if (models.empty()) models = make_sheet_models(s);
    const double pixel_mm = make_camera(s).mm_per_pixel;
    const psf_samples psf = scene_psf(s, models, p.psf_samples);
    const auto curve = analysis::psf_mtf(psf, {.max_lp_per_mm = 2.0, .points = 41, .pixel_mm = pixel_mm});
    out.lp_per_mm = curve.lp_per_mm;
    out.mtf = curve.mtf;
    const mtf_summary summary = psf_route_mtf(psf, pixel_mm);
    out.mtf50 = summary.mtf50_lp_per_mm.value_or(0.0);
    out.mean_mtf = summary.mean_mtf;
    out.r50_mm = energy_radius(psf);
    out.brightness = psf.brightness();
    // Cross-section: offsets within a thin horizontal band through the centre, binned along x.
    const double half_range = std::max(4.0 * out.r50_mm, 0.5), band = std::max(out.r50_mm / 4.0, 0.01);
    analysis::psf_section section = analysis::psf_cross_section(psf, half_range, band, 61);
    out.psf_x_mm = std::move(section.x_mm);
    out.psf_density = std::move(section.density);
    out.psf_ms = ms_since(t0);

    const auto t1 = clock_type::now();
    for (double d = 150; d <= 300 + 1e-9; d += 25) {
      out.sweep_d_mm.push_back(d);
      try {
        scene sd = s;
        set_floating_distance(sd, d);
        check_layout(sd, "mean MTF against D");
        // Built again at each D: a per-render lookup follows the sheet's chief ray there.
        const psf_samples pd = scene_psf(sd, make_sheet_models(sd), p.sweep_psf_samples);
        out.sweep_mean_mtf.push_back(psf_route_mtf(pd, make_camera(sd).mm_per_pixel).mean_mtf);
        out.sweep_reasons.emplace_back();
      } catch (const std::exception& e) {
        // A distance at which the layout is no layout: a gap in the curve, with its reason.
        out.sweep_mean_mtf.push_back(std::numeric_limits<double>::quiet_NaN());
        out.sweep_reasons.push_back(e.what());
      }
    }
    out.sweep_ms = ms_since(t1);

  } catch (const std::exception& e) {
    out.error = e.what();
  }
  // The viewing zone even when the aerial image's centre is not seen from the observer: it shows
  // where it is.
  try {
    const auto t2 = clock_type::now();
    eye_grid g;
    g.kind = eye_grid::shape::sphere;
    g.distance_mm = std::max(1.0, glm::length(observer_position(s) - aerial_image_center(s)));
    g.nx = g.ny = p.zone_grid;
    g.x_min = g.y_min = -p.zone_reach_deg;
    g.x_max = g.y_max = p.zone_reach_deg;
    // Redrawn on every edit: the midpoint rule's half the cost is worth more than its last percent.
    out.zone = geometric_viewing_zone(s, g, scene_prop_hits(s), p.zone_rows, {}, nullptr, false);
    out.zone_ms = ms_since(t2);
  } catch (const std::exception&) {
    out.zone = {};
  }
  return out;
}

measured_plots measure_render_mtf(const render_snapshot& snap, const scene& s) {
  measured_plots out;
  out.generation = snap.generation;
  out.spp = snap.spp;
  if (!snap.rgb || snap.spp == 0) return out;
  const cv::Mat lum = snapshot_luminance(snap);
  // The whole source (an edge chart), then its quadrants (the test chart's edge is top left).
  const double regions[][4] = {{0.1, 0.1, 0.9, 0.9},
                               {0.05, 0.05, 0.45, 0.45},
                               {0.55, 0.05, 0.95, 0.45},
                               {0.05, 0.55, 0.45, 0.95},
                               {0.55, 0.55, 0.95, 0.95}};
  for (const auto& r : regions) {
    const cv::Rect roi = aerial_image_roi(s, r[0], r[1], r[2], r[3]);
    if (roi.width < 20 || roi.height < 20) continue;
    try {
      const auto curve = analysis::slanted_edge_mtf(lum, {.roi = roi});
      if (std::abs(curve.edge_angle_deg) < 1.0 || std::abs(curve.edge_angle_deg) > 15.0) continue;
      out.found = true;
      out.lp_per_mm = analysis::to_lp_per_mm(curve.cycles_per_pixel, snap.mm_per_pixel);
      out.mtf = curve.mtf;
      out.edge_angle_deg = curve.edge_angle_deg;
      out.mean_mtf = analysis::mean_mtf(curve, snap.mm_per_pixel).value;
      if (snap.odd_rgb) {
        try {
          const auto even = analysis::slanted_edge_mtf(snapshot_luminance(snap, snap.even_rgb()), {.roi = roi});
          const auto odd = analysis::slanted_edge_mtf(snapshot_luminance(snap, *snap.odd_rgb), {.roi = roi});
          if (even.mtf.size() == curve.mtf.size() && odd.mtf.size() == curve.mtf.size()) {
            out.mtf_sigma = analysis::mtf_sigma_from_halves(even.mtf, odd.mtf);
            out.readable_lp_per_mm = analysis::readable_up_to(out.lp_per_mm, out.mtf_sigma, measured_mtf_max_sigma);
          }
        } catch (const std::exception&) {
          // A half too noisy to find the edge in: nothing is readable yet.
        }
      }
      return out;
    } catch (const std::exception& e) {
      out.note = e.what();
    }
  }
  if (out.note.empty()) out.note = "no slanted edge in the source";
  return out;
}

analysis_worker::analysis_worker() {
  worker_ = std::thread([this] { run(); });
}

analysis_worker::~analysis_worker() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

void analysis_worker::submit_scene(const scene& s, std::uint64_t generation, retro_model_list models) {
  std::lock_guard lock(mutex_);
  pending_scene_ = scene_request{s, generation, std::move(models)};
  changed_.notify_all();
}

void analysis_worker::submit_render(const render_snapshot& snap, const scene& s) {
  std::lock_guard lock(mutex_);
  pending_render_.emplace(snap, s);
  changed_.notify_all();
}

std::shared_ptr<const predicted_plots> analysis_worker::predicted() const {
  std::lock_guard lock(mutex_);
  return predicted_;
}

std::shared_ptr<const measured_plots> analysis_worker::measured() const {
  std::lock_guard lock(mutex_);
  return measured_;
}

std::shared_ptr<const bokeh_plots> analysis_worker::bokeh() const {
  std::lock_guard lock(mutex_);
  return bokeh_;
}

void analysis_worker::wait_idle() const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !busy_ && !pending_scene_ && !pending_render_ && !pending_bokeh_; });
}

void analysis_worker::run() {
  // The plots follow the window and the model image's first look (less so than the tracer does).
  lower_thread_priority(5);
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || pending_scene_ || pending_render_ || pending_bokeh_; });
    if (stopping_) return;
    busy_ = true;
    if (pending_scene_) {
      scene_request request = std::move(*pending_scene_);
      pending_scene_.reset();
      lock.unlock();
      auto result = std::make_shared<const predicted_plots>(
          compute_predicted(request.layout, request.generation, {}, request.models));
      lock.lock();
      predicted_ = std::move(result);
      bokeh_r50_ = predicted_->error.empty() ? std::optional<double>(predicted_->r50_mm) : std::nullopt;
      pending_bokeh_ = std::move(request);
    } else if (pending_render_) {
      auto [snap, s] = std::move(*pending_render_);
      pending_render_.reset();
      lock.unlock();
      auto result = std::make_shared<const measured_plots>(measure_render_mtf(snap, s));
      lock.lock();
      measured_ = std::move(result);
    } else {
      scene_request request = std::move(*pending_bokeh_);
      pending_bokeh_.reset();
      lock.unlock();
      std::optional<bokeh_plots> result = compute_bokeh(
          request.layout, request.generation, {}, std::move(request.models),
          [this] {
            std::lock_guard stop_lock(mutex_);
            return stopping_ || pending_scene_.has_value();
          },
          bokeh_r50_);
      lock.lock();
      if (result) bokeh_ = std::make_shared<const bokeh_plots>(std::move(*result));
    }
    busy_ = false;
    changed_.notify_all();
  }
}

}  // namespace airr::ui
