#include "airr/ui/analysis_worker.hpp"

#include <chrono>
#include <cmath>

#include <opencv2/core.hpp>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/psf.hpp"
#include "airr/optics/retro_model.hpp"

namespace airr::ui {

using clock_type = std::chrono::steady_clock;
static double ms_since(clock_type::time_point t0) {
  return std::chrono::duration<double, std::milli>(clock_type::now() - t0).count();
}

// Samples for a plot-quality PSF: enough for a smooth MTF, few enough to follow a drag.
static constexpr std::uint64_t plot_psf_samples = 8000;

predicted_plots compute_predicted(const scene& s, std::uint64_t generation) {
  predicted_plots out;
  out.generation = generation;
  try {
    const auto t0 = clock_type::now();
    const auto model = make_retro_model(s.retroreflector.model, s.base_dir);
    const double pixel_mm = make_camera(s).mm_per_pixel;
    const psf_samples psf = sample_psf(s, *model, {.samples = plot_psf_samples, .seed = s.seed});
    const auto curve = analysis::psf_mtf(psf, {.max_lp_per_mm = 2.0, .points = 41, .pixel_mm = pixel_mm});
    out.lp_per_mm = curve.lp_per_mm;
    out.mtf = curve.mtf;
    out.mtf50 = analysis::psf_mtf50(curve);
    out.mean_mtf = analysis::psf_mean_mtf(psf, 1.0, pixel_mm, 40);
    out.r50_mm = energy_radius(psf);
    out.brightness = psf.brightness();
    // Cross-section: offsets within a thin horizontal band through the centre, binned along x.
    const double half_range = std::max(4.0 * out.r50_mm, 0.5), band = std::max(out.r50_mm / 4.0, 0.01);
    const int bins = 61;
    out.psf_x_mm.resize(bins);
    out.psf_density.assign(bins, 0.0);
    double total = 0;
    for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) total += psf.weight[i];
    for (int b = 0; b < bins; ++b) out.psf_x_mm[b] = -half_range + (b + 0.5) * 2 * half_range / bins;
    for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
      const glm::dvec2 o = psf.offset_mm[i];
      if (std::abs(o.y) > band || std::abs(o.x) >= half_range) continue;
      out.psf_density[int((o.x + half_range) / (2 * half_range) * bins)] += psf.weight[i];
    }
    const double cell_area = (2 * half_range / bins) * (2 * band);
    for (double& d : out.psf_density) d = total > 0 ? d / total / cell_area : 0.0;  // per mm^2
    out.psf_ms = ms_since(t0);

    const auto t1 = clock_type::now();
    for (double d = 150; d <= 300 + 1e-9; d += 25) {
      scene sd = s;
      sd.floating_distance_mm = d;
      try {
        const psf_samples p = sample_psf(sd, *model, {.samples = plot_psf_samples / 2, .seed = s.seed});
        out.sweep_d_mm.push_back(d);
        out.sweep_mean_mtf.push_back(analysis::psf_mean_mtf(p, 1.0, make_camera(sd).mm_per_pixel, 40));
      } catch (const std::exception&) {
        // A distance at which the layout does not work is left out of the curve.
      }
    }
    out.sweep_ms = ms_since(t1);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// Pixel rectangle covering the part of the source image [u0, u1] x [v0, v1] (fractions, v down).
static cv::Rect source_region_in_image(const scene& s, double u0, double v0, double u1, double v1) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s);
  const pinhole_camera cam = make_camera(s);
  double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
  for (double u : {u0, u1}) {
    for (double v : {v0, v1}) {
      const glm::dvec3 p = src.center + (u - 0.5) * src.width * src.u + (0.5 - v) * src.height * src.v;
      const glm::dvec3 a = p - 2.0 * glm::dot(p - hm.center, hm.n) * hm.n;
      const glm::dvec2 q = camera_project(cam, a);
      x0 = std::min(x0, q.x);
      y0 = std::min(y0, q.y);
      x1 = std::max(x1, q.x);
      y1 = std::max(y1, q.y);
    }
  }
  const cv::Rect r(int(std::ceil(x0)), int(std::ceil(y0)), int(std::floor(x1 - x0)) - 1, int(std::floor(y1 - y0)) - 1);
  return r & cv::Rect(0, 0, cam.width, cam.height);
}

measured_plots measure_render_mtf(const render_snapshot& snap, const scene& s) {
  measured_plots out;
  out.generation = snap.generation;
  out.spp = snap.spp;
  if (!snap.rgb || snap.spp == 0) return out;
  cv::Mat lum(snap.height, snap.width, CV_64FC1);
  for (int y = 0; y < snap.height; ++y) {
    for (int x = 0; x < snap.width; ++x) {
      const float* p = snap.rgb->data() + 3 * (std::size_t(y) * snap.width + x);
      lum.at<double>(y, x) = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    }
  }
  // The whole source (an edge chart), then its quadrants (the test chart's edge is top left).
  const double regions[][4] = {{0.1, 0.1, 0.9, 0.9}, {0.05, 0.05, 0.45, 0.45}, {0.55, 0.05, 0.95, 0.45},
                               {0.05, 0.55, 0.45, 0.95}, {0.55, 0.55, 0.95, 0.95}};
  for (const auto& r : regions) {
    const cv::Rect roi = source_region_in_image(s, r[0], r[1], r[2], r[3]);
    if (roi.width < 20 || roi.height < 20) continue;
    try {
      const auto curve = analysis::slanted_edge_mtf(lum, {.roi = roi});
      if (std::abs(curve.edge_angle_deg) < 1.0 || std::abs(curve.edge_angle_deg) > 15.0) continue;
      out.found = true;
      out.lp_per_mm = analysis::to_lp_per_mm(curve.cycles_per_pixel, snap.mm_per_pixel);
      out.mtf = curve.mtf;
      out.edge_angle_deg = curve.edge_angle_deg;
      out.mean_mtf = analysis::mean_mtf(curve, snap.mm_per_pixel, {.max_lp_per_mm = 1.0, .samples = 40}).value;
      return out;
    } catch (const std::exception& e) {
      out.note = e.what();
    }
  }
  if (out.note.empty()) out.note = "no slanted edge in the source";
  return out;
}

analysis_worker::analysis_worker() { worker_ = std::thread([this] { run(); }); }

analysis_worker::~analysis_worker() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

void analysis_worker::submit_scene(const scene& s, std::uint64_t generation) {
  std::lock_guard lock(mutex_);
  pending_scene_.emplace(s, generation);
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

void analysis_worker::wait_idle() const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !busy_ && !pending_scene_ && !pending_render_; });
}

void analysis_worker::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || pending_scene_ || pending_render_; });
    if (stopping_) return;
    busy_ = true;
    if (pending_scene_) {
      auto [s, gen] = std::move(*pending_scene_);
      pending_scene_.reset();
      lock.unlock();
      auto result = std::make_shared<const predicted_plots>(compute_predicted(s, gen));
      lock.lock();
      predicted_ = std::move(result);
    } else {
      auto [snap, s] = std::move(*pending_render_);
      pending_render_.reset();
      lock.unlock();
      auto result = std::make_shared<const measured_plots>(measure_render_mtf(snap, s));
      lock.lock();
      measured_ = std::move(result);
    }
    busy_ = false;
    changed_.notify_all();
  }
}

}  // namespace airr::ui
