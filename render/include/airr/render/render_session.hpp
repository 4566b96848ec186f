#pragma once
// A progressive render in the background: waves of growing samples per pixel on TBB, cancelled
// and restarted on every edit, publishing whole-wave snapshots that any thread may read.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "airr/layout/scene.hpp"
#include "airr/render/embree_scene.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

struct session_params {
  int threads = 0;                     // 0: all cores
  std::uint64_t target_spp = 1 << 20;  // stop after this many samples per pixel
  std::uint64_t max_wave_spp = 64;     // waves grow 1, 2, 4 ... up to this
  // After an edit, one sample on every n-th pixel in each direction is shown first (n x n blocks),
  // so an edit appears at once; it does not enter the accumulation. 1: no preview.
  int preview_stride = 4;
  // Render threads yield to the rest of the process (the designer's UI): a lower priority.
  bool background_priority = false;
  // After an edit, the model image's first look is shown before any traced sample, from a thread
  // of its own at normal priority, where the layout has one: the last view-quality model image
  // moved to the new placement (remap_layout_model_image) when the edit only moved parts a
  // little, else the coarse model_image_first_look ...
  bool first_look = false;
  // ... and then, unless traced samples came first, the model image at view quality
  // (model_image_params::for_view). The opening layout's is made by the constructor and shown
  // first: it is there before the first edit can land.
  bool view_model_image = true;
  // The tracer's control variate is the quick model image (model_image_params::for_image), so
  // that tracing starts sooner after an edit.
  bool quick_model_image = false;
  // Also accumulate the image's components (tracer.hpp, component_names), for snapshots'
  // component_image.
  bool components = false;
  // Also accumulate these path-expression layers (and the paths none selects), for snapshots'
  // layer_image.
  std::shared_ptr<const path_layers> layers = nullptr;
  // The rows traced, [first_row, end_row) (end_row 0: to the last), e.g. one shard of a render
  // split across processes; the other rows hold the model image's value alone. A pixel's estimate
  // does not depend on which rows are traced with it.
  int first_row = 0;
  int end_row = 0;
  // When set (from another thread) while the constructor computes the opening model image, that
  // stops early and the session starts without it: a caller waiting on the constructor can give
  // up (and stop the session) at once.
  const std::atomic<bool>* build_cancel = nullptr;
  // What the pixels hold: -1 the image, 0 to 3 a Stokes parameter (tracer_scene::stokes).
  int stokes = -1;
  // Only the snapshot at the target holds images (with rgb shown, unmixed); the earlier ones say
  // their spp, rays and time alone. A render that waits for its target (airr render) keeps no
  // predictions beside its sums (they are made at the target) and turns the sums into its images
  // in place: the session traces no further, even if the target is raised.
  bool final_images_only = false;
};

// An immutable picture of the accumulation after a whole wave.
struct render_snapshot {
  std::uint64_t generation = 0;  // increases with every edit
  std::uint64_t spp = 0;
  int width = 0;
  int height = 0;
  double mm_per_pixel = 0;
  std::shared_ptr<const std::vector<float>> rgb;  // mean radiance, 3 floats per pixel
  // What a viewer shows: the best estimate there is, the generation's model image and the traced
  // mean rgb mixed with model_weight (see model_image_weight).
  std::shared_ptr<const std::vector<float>> shown;
  // The mean of the odd-numbered samples alone (null before 2 spp). With even_rgb() it makes two
  // half estimates, for the noise of what is measured on the image.
  std::shared_ptr<const std::vector<float>> odd_rgb;
  std::uint64_t rays = 0;    // intersection queries so far in this generation
  double seconds = 0;        // time spent so far in this generation
  std::string error;         // set when the last edit could not be applied
  bool preview = false;      // a coarse first look at this generation (spp is 0)
  bool model_image = false;  // `shown` is, or holds, a model image (a preview, or mixed with traced samples) ...
  bool first_look = false;   // ... its first look (false: at view quality)
  double model_weight = 0;   // the model image's share of `shown`: 1 alone, 0 not at all
  double edit_seconds = 0;   // from the edit to this snapshot's publication
  // With session_params::components, RGB triples per pixel adding up to rgb, as component_layout
  // lays them out (null otherwise, and in previews): all of them, each at its own index and then
  // each luminaire's (all_component_slots), but in a session with final_images_only only those the
  // scene can have (possible_component_slots).
  std::shared_ptr<const std::vector<float>> components;
  component_slots component_layout;
  // With session_params::layers, their names (the unmatched paths' last) and as many RGB triples per
  // pixel (null otherwise, and in previews).
  std::vector<std::string> layer_names;
  std::shared_ptr<const std::vector<float>> layers;

  image_rgb image() const;
  // Layer k (of layer_names) as an image; empty without layers.
  image_rgb layer_image(std::size_t k) const;
  // One component (tracer.hpp's image_component) as an image; empty without components.
  image_rgb component_image(int component) const;
  // All of them, in image_component order, then each luminaire's own (component_layout.luminaires
  // of them), named as component_image_names says (empty without components).
  std::vector<image_rgb> component_images() const;
  std::vector<std::string> component_image_names() const;
  // The mean of the even-numbered samples, derived from rgb and odd_rgb (empty without odd_rgb).
  std::vector<float> even_rgb() const;
};

// The model image's share in the best mix of it and traced samples (their mean `rgb`, the
// odd-numbered samples' mean `odd`, `spp` samples): with s^2 the tracer's noise, measured from its
// two halves, and e^2 the model image's own error, measured as its squared distance from the traced
// mean less that noise, s^2 / (s^2 + e^2), which minimises the mix's expected squared error
// (w^2 e^2 + (1 - w)^2 s^2). 1 with fewer than 2 samples; shares within 0.001 of 0 or 1 are
// rounded to them.
double model_image_weight(const std::vector<float>& model, const std::vector<float>& rgb, const std::vector<float>* odd,
                          std::uint64_t spp);

// Which estimate a snapshot shows, for people: "model image (first look)", "model image",
// "tracer (preview)", "tracer at N spp" or, mixed, "tracer at N spp with the model image (W%)".
std::string estimate_name(const render_snapshot& snap);

// Lowers the calling thread's scheduling priority, once per thread (Linux: per-thread nice), for
// background work that should yield to the designer's window.
void lower_thread_priority(int nice = 10);

class render_session {
 public:
  // Builds the scene synchronously (throws input_error on bad files), then starts the worker.
  render_session(const scene& s, session_params p = {});
  ~render_session();
  render_session(const render_session&) = delete;
  render_session& operator=(const render_session&) = delete;

  // Replaces the layout: cancels the wave in progress, resets accumulation, restarts.
  // Returns the generation whose snapshots show the new layout.
  // `models`, when given, are the sheets' retroreflector models already built (shared, not rebuilt).
  std::uint64_t edit(const scene& s, retro_model_list models = {});
  void set_paused(bool paused);
  void set_target_spp(std::uint64_t spp);

  render_snapshot snapshot() const;
  // Blocks until generation `gen` has at least `spp` samples (or the target is reached).
  render_snapshot wait_for(std::uint64_t gen, std::uint64_t spp) const;
  // The same, waiting at most `timeout`.
  render_snapshot wait_for(std::uint64_t gen, std::uint64_t spp, std::chrono::milliseconds timeout) const;
  // Blocks until `ready` holds for the snapshot (or the session stops).
  render_snapshot wait_until(const std::function<bool(const render_snapshot&)>& ready) const;
  // Stops the worker; further snapshots stay as they are.
  void stop();

 private:
  // One generation's running sums (trace_rows): the samples' radiance, odd samples alone, by
  // component, and the model image's predictions of them apart (none kept with final_images_only); and the samples each
  // row holds (a row is traced whole or not at all, so a cancelled wave leaves some rows ahead, which the next wave
  // skips: the sums need no copy to undo it).
  struct accumulation {
    std::vector<float> sums, odd_sums, component_sums, layer_sums;
    component_slots slots;  // of component_sums
    prediction_sums predictions;
    std::vector<std::uint64_t> row_spp;
    std::vector<char> rows_published;  // turned into images in place (final_images_only)
  };
  void run();  // run_loop, and what it throws said in the snapshot
  void run_loop();
  // body(y0, y1) over the rows the session traces, in parallel.
  template <class Body>
  void traced_rows(const Body& body) const;
  // Brings every traced row to `end` samples; false when cancelled (the rows done stay done).
  bool render_wave(std::uint64_t end, accumulation& acc, std::uint64_t& rays);
  // False when cancelled (a pause, an edit or a stop) while it made the images.
  bool publish(std::uint64_t gen, std::uint64_t spp, accumulation& acc, std::uint64_t rays, double seconds);
  bool render_preview(std::vector<float>& rgb, std::uint64_t& rays);
  struct preview_size {
    int width, height;
    double mm_per_pixel;
  };
  enum class preview_kind { traced, first_look, model_image };
  // From the worker or the first-look thread; neither reads the other's scene. A traced preview
  // waits while the generation's first look is coming (held_preview_): it is shown only if none
  // comes, as the last model image is closer than one sample a block.
  void publish_preview(std::uint64_t gen, std::vector<float> rgb, const preview_size& size, preview_kind kind);
  // The first-look thread: each edit's first look, moved from latest_view_ when it can be.
  void run_first_look();
  // The view thread: the latest first-looked edit's view-quality model image. Edits do not cancel
  // it (only a stop does): while a part is dragged faster than it is made, each one finished is
  // still the next first looks' base.
  void run_view_images();
  // With mutex_ held and snapshot_ holding traced samples: shows the best mix of them and the
  // generation's model image.
  void show_best();
  // Whether generation `gen` is stale or its traced samples (or a refusal) are out: no model image
  // of it is worth computing any more.
  bool view_taken_over(std::uint64_t gen) const;
  double seconds_since_edit() const;  // with mutex_ held

  session_params params_;
  embree_device device_;
  tracer_scene scene_;  // touched only by the worker once running

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::optional<scene> pending_;  // the latest edit not yet applied
  retro_model_list pending_models_;
  std::uint64_t generation_ = 0;  // of the latest edit
  std::chrono::steady_clock::time_point edit_time_ = std::chrono::steady_clock::now();
  struct first_look_request {
    scene layout;
    retro_model_list models;
    std::uint64_t generation;
  };
  std::optional<first_look_request> first_look_;   // the latest edit's, not yet taken
  std::optional<first_look_request> view_wanted_;  // the latest first-looked edit's, not yet taken
  std::uint64_t first_looks_done_ = 0;             // the latest generation the first-look thread is done with
  std::uint64_t models_shown_ = 0;                 // ... and whose model images are done with
  // The latest view-quality model image and its display (the opening layout's is made first).
  std::shared_ptr<const layout_model_image> latest_view_;
  std::shared_ptr<const image_rgb> latest_view_texture_;
  struct held_preview {
    std::uint64_t generation;
    std::vector<float> rgb;
    preview_size size;
  };
  std::optional<held_preview> held_preview_;  // a traced preview waiting for its first look
  std::atomic<bool> first_look_cancel_{false};
  std::atomic<bool> view_cancel_{false};
  bool paused_ = false;
  bool stopping_ = false;
  std::uint64_t target_spp_;
  render_snapshot snapshot_;
  render_snapshot before_first_look_;  // what the latest first look replaced
  // The latest model image published for generation model_generation_ (and whether it is a first look).
  std::shared_ptr<const std::vector<float>> model_shown_;
  std::uint64_t model_generation_ = 0;
  bool model_shown_first_look_ = false;
  std::atomic<bool> cancel_{false};
  // Cancels the control variate's model image in progress (replaced by the worker, under mutex_).
  std::shared_ptr<std::atomic<bool>> model_cancel_ = std::make_shared<std::atomic<bool>>(false);
  std::thread worker_;
  std::thread first_look_worker_;
  std::thread view_worker_;
};

// Runs `session` (made with target_spp >= spp) until every pixel has `spp` samples, and returns that
// snapshot (`airr render`, the Python module). Between waves, and at least every `poll` when
// given, `keep_going(spp so far)` is asked; false stops the session and returns the snapshot so
// far (fewer samples). `job_spp` turns this process's samples per pixel into the job's (an MPI job:
// its slowest rank's; every rank calls it equally often). Throws input_error when the render fails.
render_snapshot render_to_spp(render_session& session, std::uint64_t spp,
                              const std::function<bool(std::uint64_t)>& keep_going = {},
                              std::chrono::milliseconds poll = std::chrono::milliseconds(0),
                              const std::function<std::uint64_t(std::uint64_t)>& job_spp = {});

}  // namespace airr
