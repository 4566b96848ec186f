#pragma once
// Plot data computed off the UI thread: the model PSF's MTF, its cross-section and the mean MTF
// against floating distance for the current layout, and the slanted-edge MTF measured on the
// render. The newest request wins; results carry the generation they belong to.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "airr/optics/scene.hpp"
#include "airr/render/render_session.hpp"

namespace airr::ui {

struct predicted_plots {
  std::uint64_t generation = 0;
  std::vector<double> lp_per_mm, mtf;     // PSF route, including the camera pixel's aperture
  double mean_mtf = 0, mtf50 = 0, r50_mm = 0, brightness = 0;
  std::vector<double> psf_x_mm, psf_density;  // cross-section through the PSF's centre (per mm)
  std::vector<double> sweep_d_mm, sweep_mean_mtf;  // mean MTF over (0, 1] lp/mm against D
  double psf_ms = 0;    // time for the PSF and its MTF (a plot-quality estimate)
  double sweep_ms = 0;
  std::string error;
};

struct measured_plots {
  std::uint64_t generation = 0;
  std::uint64_t spp = 0;
  bool found = false;  // an edge was found in the render
  std::vector<double> lp_per_mm, mtf;
  double mean_mtf = 0, edge_angle_deg = 0;
  std::string note;
};

class analysis_worker {
 public:
  analysis_worker();
  ~analysis_worker();
  analysis_worker(const analysis_worker&) = delete;
  analysis_worker& operator=(const analysis_worker&) = delete;

  void submit_scene(const scene& s, std::uint64_t generation);
  void submit_render(const render_snapshot& snap, const scene& s);
  std::shared_ptr<const predicted_plots> predicted() const;
  std::shared_ptr<const measured_plots> measured() const;
  // Blocks until the latest submitted scene's plots are published (for scripted runs).
  void wait_idle() const;

 private:
  void run();

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::optional<std::pair<scene, std::uint64_t>> pending_scene_;
  std::optional<std::pair<render_snapshot, scene>> pending_render_;
  std::shared_ptr<const predicted_plots> predicted_;
  std::shared_ptr<const measured_plots> measured_;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread worker_;
};

// Computes the predicted plots synchronously (what the worker does for one scene).
predicted_plots compute_predicted(const scene& s, std::uint64_t generation);
// Measures the slanted-edge MTF in the render, trying the source's regions in turn.
measured_plots measure_render_mtf(const render_snapshot& snap, const scene& s);

}  // namespace airr::ui
