#pragma once
// Plot data computed off the UI thread: the model PSF's MTF, its cross-section and the mean MTF
// against floating distance for the current layout, the slanted-edge MTF measured on the render,
// and the Bokeh tab's views (after the others, while no newer layout waits). The newest request
// wins; results carry the generation they belong to.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/render_session.hpp"
#include "airr/ui/jobs/bokeh_plots.hpp"

namespace airr::ui {

struct predicted_plots {
  std::uint64_t generation = 0;
  std::vector<double> lp_per_mm, mtf;  // PSF route, including the camera pixel's aperture
  double mean_mtf = 0, mtf50 = 0, r50_mm = 0, brightness = 0;
  std::vector<double> psf_x_mm, psf_density;       // cross-section through the PSF's centre (per mm)
  std::vector<double> sweep_d_mm, sweep_mean_mtf;  // mean MTF over (0, 1] lp/mm against D
  std::vector<std::string> sweep_reasons;          // per D: why the layout is none there (NaN), or empty
  double psf_ms = 0;                               // time for the PSF and its MTF (a plot-quality estimate)
  double sweep_ms = 0;
  // Where the aerial image can be seen: the geometric visible fraction on the observer's orbit
  // sphere (azimuth and elevation), at the observer's distance.
  viewing_zone_map zone;
  double zone_ms = 0;
  std::string error;
};

struct measured_plots {
  std::uint64_t generation = 0;
  std::uint64_t spp = 0;
  bool found = false;  // an edge was found in the render
  std::vector<double> lp_per_mm, mtf;
  // The curve's noise: its standard deviation per frequency, from the render's even- and
  // odd-sample halves (empty before 2 spp), and the frequency up to which it reads within
  // measured_mtf_max_sigma (0: not yet readable anywhere).
  std::vector<double> mtf_sigma;
  double readable_lp_per_mm = 0;
  double mean_mtf = 0, edge_angle_deg = 0;
  std::string note;
};

// The measured curve is shown where its standard deviation is at most this.
inline constexpr double measured_mtf_max_sigma = 0.03;

// PSF samples for the plots: enough for a smooth MTF, few enough to follow a drag.
struct predicted_params {
  std::uint64_t psf_samples = 8000;
  std::uint64_t sweep_psf_samples = 4000;  // per floating distance of the mean-MTF curve
  int zone_grid = 25;                      // eyes per side of the viewing-zone map ...
  int zone_rows = 32;                      // ... and rows across the aerial image per eye
  double zone_reach_deg = 60;              // azimuths and elevations within +-this
};

class analysis_worker {
 public:
  analysis_worker();
  ~analysis_worker();
  analysis_worker(const analysis_worker&) = delete;
  analysis_worker& operator=(const analysis_worker&) = delete;

  // `models` are the scene's sheets' models when the caller has built them (else built here).
  void submit_scene(const scene& s, std::uint64_t generation, retro_model_list models);
  void submit_render(const render_snapshot& snap, const scene& s);
  std::shared_ptr<const predicted_plots> predicted() const;
  std::shared_ptr<const measured_plots> measured() const;
  std::shared_ptr<const bokeh_plots> bokeh() const;
  // Blocks until the latest submitted scene's plots are published (for scripted runs).
  void wait_idle() const;

 private:
  void run();

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  struct scene_request {
    scene layout;
    std::uint64_t generation = 0;
    retro_model_list models;
  };
  std::optional<scene_request> pending_scene_;
  std::optional<std::pair<render_snapshot, scene>> pending_render_;
  std::optional<scene_request> pending_bokeh_;  // the last scene's, once its other plots are out
  std::optional<double> bokeh_r50_;             // its r50 from those plots
  std::shared_ptr<const predicted_plots> predicted_;
  std::shared_ptr<const measured_plots> measured_;
  std::shared_ptr<const bokeh_plots> bokeh_;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread worker_;
};

// Computes the predicted plots synchronously (what the worker does for one scene), with the
// measurement library's functions, so the numbers equal those of `airr psf` and `airr sweep --psf`.
predicted_plots compute_predicted(const scene& s, std::uint64_t generation, const predicted_params& p = {},
                                  retro_model_list models = {});
// Measures the slanted-edge MTF in the render, trying the source's regions in turn.
measured_plots measure_render_mtf(const render_snapshot& snap, const scene& s);

}  // namespace airr::ui
