#include "airr/render/render_session.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <new>
#include <utility>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/parallel_rows.hpp"

namespace airr {

render_session::render_session(const scene& s, session_params p) : params_(p), target_spp_(p.target_spp) {
  scene_.stokes = p.stokes;
  scene_.layers = p.layers;
  scene_.model_pixels_kept = !p.final_images_only;  // its predictions are made at the target
  build_tracer_scene(scene_, device_, s);
  update_model_image(scene_, params_.build_cancel, params_.quick_model_image);
  snapshot_.width = scene_.camera.width;
  snapshot_.height = scene_.camera.height;
  snapshot_.mm_per_pixel = scene_.camera.mm_per_pixel;
  // The opening layout's view-quality model image: shown until traced samples join it, and the
  // first edit's first look (moved), so made before an edit can land.
  std::shared_ptr<const layout_model_image> opening_view;
  if (params_.first_look && params_.view_model_image) {
    try {
      opening_view = compute_layout_model_image(s, scene_.retro, scene_.texture.get(), model_image_params::for_view(),
                                                params_.build_cancel);
    } catch (const std::exception&) {
      // The tracer's samples serve; its worker reports what is wrong with the layout.
    }
    if (opening_view) {
      publish_preview(0, opening_view->image.rgb,
                      {scene_.camera.width, scene_.camera.height, scene_.camera.mm_per_pixel},
                      preview_kind::model_image);
    }
  }
  latest_view_ = std::move(opening_view);
  latest_view_texture_ = scene_.texture;
  worker_ = std::thread([this] { run(); });
  if (params_.first_look) {
    first_look_worker_ = std::thread([this] { run_first_look(); });
    view_worker_ = std::thread([this] { run_view_images(); });
  }
}

render_session::~render_session() { stop(); }

void render_session::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    cancel_ = true;
    model_cancel_->store(true);
  }
  changed_.notify_all();
  first_look_cancel_ = true;
  view_cancel_ = true;
  if (worker_.joinable()) worker_.join();
  if (first_look_worker_.joinable()) first_look_worker_.join();
  if (view_worker_.joinable()) view_worker_.join();
}

std::uint64_t render_session::edit(const scene& s, retro_model_list models) {
  std::lock_guard lock(mutex_);
  ++generation_;
  edit_time_ = std::chrono::steady_clock::now();
  model_cancel_->store(true);  // the control variate of a layout that is going
  if (params_.first_look) {
    first_look_ = first_look_request{s, models, generation_};
    first_look_cancel_ = true;  // the one in progress, if any, is stale
  }
  pending_ = s;
  pending_models_ = std::move(models);
  cancel_ = true;
  changed_.notify_all();
  return generation_;
}

double render_session::seconds_since_edit() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - edit_time_).count();
}

void render_session::set_paused(bool paused) {
  std::lock_guard lock(mutex_);
  paused_ = paused;
  if (paused) cancel_ = true;  // the unfinished wave is redone on resume
  changed_.notify_all();
}

void render_session::set_target_spp(std::uint64_t spp) {
  std::lock_guard lock(mutex_);
  target_spp_ = spp;
  changed_.notify_all();
}

render_snapshot render_session::snapshot() const {
  std::lock_guard lock(mutex_);
  return snapshot_;
}

render_snapshot render_session::wait_for(std::uint64_t gen, std::uint64_t spp) const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] {
    return stopping_ || (snapshot_.generation == gen &&
                         (snapshot_.spp >= spp || snapshot_.spp >= target_spp_ || !snapshot_.error.empty()));
  });
  return snapshot_;
}

render_snapshot render_session::wait_for(std::uint64_t gen, std::uint64_t spp,
                                         std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] {
    return stopping_ || (snapshot_.generation == gen &&
                         (snapshot_.spp >= spp || snapshot_.spp >= target_spp_ || !snapshot_.error.empty()));
  });
  return snapshot_;
}

void render_session::show_best() {
  const bool have_model = model_shown_ && model_generation_ == snapshot_.generation;
  const double w =
      have_model ? model_image_weight(*model_shown_, *snapshot_.rgb, snapshot_.odd_rgb.get(), snapshot_.spp) : 0.0;
  snapshot_.model_weight = w;
  snapshot_.model_image = w > 0;
  snapshot_.first_look = w > 0 && model_shown_first_look_;
  if (w == 0) {
    snapshot_.shown = snapshot_.rgb;
  } else if (w == 1) {
    snapshot_.shown = model_shown_;
  } else {
    auto mix = std::make_shared<std::vector<float>>(snapshot_.rgb->size());
    const std::vector<float>&model = *model_shown_, &traced = *snapshot_.rgb;
    for (std::size_t i = 0; i < mix->size(); ++i) (*mix)[i] = float(w * model[i] + (1 - w) * traced[i]);
    snapshot_.shown = std::move(mix);
  }
}

render_snapshot render_session::wait_until(const std::function<bool(const render_snapshot&)>& ready) const {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return stopping_ || ready(snapshot_); });
  return snapshot_;
}

void lower_thread_priority(int nice) {
  thread_local bool done = false;
  if (done) return;
  done = true;
  ::setpriority(PRIO_PROCESS, pid_t(::syscall(SYS_gettid)), nice);
}

template <class Body>
void render_session::traced_rows(const Body& body) const {
  const int h = scene_.camera.height;
  const int first = std::clamp(params_.first_row, 0, h);
  const int end = params_.end_row > 0 ? std::clamp(params_.end_row, first, h) : h;
  detail::parallel_rows(end - first, params_.threads, [&](int y0, int y1) { body(first + y0, first + y1); });
}

bool render_session::render_wave(std::uint64_t end, accumulation& acc, std::uint64_t& rays) {
  std::atomic<std::uint64_t> total_rays{0};
  std::atomic<bool> complete{true};
  traced_rows([&](int y0, int y1) {
    if (params_.background_priority) lower_thread_priority();
    std::uint64_t local = 0;
    for (int y = y0; y < y1; ++y) {
      std::uint64_t& done = acc.row_spp[std::size_t(y)];
      if (done >= end) continue;
      if (!trace_rows(scene_, y, y + 1, done, end - done, acc.sums, cancel_, local, &acc.odd_sums,
                      params_.components ? &acc.component_sums : nullptr, &acc.predictions,
                      params_.layers ? &acc.layer_sums : nullptr, acc.slots)) {
        complete = false;
        break;
      }
      done = end;
    }
    total_rays += local;
  });
  rays += total_rays;
  return complete && !cancel_;
}

bool render_session::render_preview(std::vector<float>& rgb, std::uint64_t& rays) {
  const int w = scene_.camera.width, h = scene_.camera.height, n = params_.preview_stride;
  rgb.assign(std::size_t(w) * h * 3, 0.0f);
  std::atomic<std::uint64_t> total{0};
  detail::parallel_rows((h + n - 1) / n, params_.threads, [&](int r0, int r1) {
    if (params_.background_priority) lower_thread_priority();
    std::uint64_t local = 0;
    for (int r = r0; r < r1 && !cancel_.load(std::memory_order_relaxed); ++r) {
      for (int x0 = 0; x0 < w; x0 += n) {
        const glm::vec3 L = model_value(scene_, x0, r * n) +
                            estimate_sample(scene_, x0, r * n, 0, pixel_sequence_rotation(scene_, x0, r * n), local);
        for (int y = r * n; y < std::min(h, (r + 1) * n); ++y) {
          for (int x = x0; x < std::min(w, x0 + n); ++x) {
            float* p = rgb.data() + 3 * (std::size_t(y) * w + x);
            p[0] = L.x;
            p[1] = L.y;
            p[2] = L.z;
          }
        }
      }
    }
    total += local;
  });
  rays += total;
  return !cancel_;
}

void render_session::run() {
  while (true) {
    try {
      run_loop();
      return;
    } catch (const std::exception& e) {
      // An allocation (or anything else) that failed mid-render: the snapshot says why over the
      // last image, and the worker waits for the next edit instead of ending the process.
      std::unique_lock lock(mutex_);
      snapshot_.generation = generation_;
      snapshot_.error = failure_message(e, "render");
      changed_.notify_all();
      changed_.wait(lock, [&] { return stopping_ || pending_; });
      if (stopping_) return;
    }
  }
}

void render_session::run_loop() {
  using clock = std::chrono::steady_clock;
  accumulation acc;
  std::uint64_t gen = 0, spp = 0, rays = 0, next_wave = 1;
  double seconds = 0;
  bool publish_owed = false;  // a publish cut short (a pause): its images are made on resume
  // The control variate's model image of the layout in scene_, computed beside the tracer from its
  // first wave on; the tracer waits for it only before the last wave of its target. The
  // predictions of the samples traced before it arrives are added then.
  std::future<std::shared_ptr<const layout_model_image>> model_coming;
  std::shared_ptr<const layout_model_image> model_arrived;  // not yet in scene_ (its predictions were cut short)
  bool model_wanted = false;                                // to start after the generation's first wave
  auto start_model = [&] {                                  // with mutex_ held
    model_wanted = false;
    model_cancel_ = std::make_shared<std::atomic<bool>>(false);
    model_coming = std::async(std::launch::async, [job = control_variate_job(scene_, params_.quick_model_image),
                                                   cancel = model_cancel_, this] {
      if (params_.background_priority) lower_thread_priority();
      return job.run(cancel.get());
    });
  };
  // Cancelled ones still finishing: an edit does not wait for them (they hold copies of what they
  // read), the worker only before it returns.
  std::vector<std::future<std::shared_ptr<const layout_model_image>>> dropped;
  auto drop_model = [&] {
    model_cancel_->store(true);
    if (model_coming.valid()) dropped.push_back(std::move(model_coming));
    std::erase_if(dropped,
                  [](const auto& f) { return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready; });
    model_arrived.reset();
  };
  auto reset_sums = [&] {
    acc.sums.assign(std::size_t(scene_.camera.width) * scene_.camera.height * 3, 0.0f);
    acc.odd_sums = acc.sums;
    // A render's images held to its end keep no sums of components its light cannot make; the
    // designer's views read all of them.
    acc.slots =
        params_.final_images_only ? possible_component_slots(scene_.ambient) : all_component_slots(scene_.ambient);
    acc.component_sums.assign(params_.components ? std::size_t(acc.slots.count) * acc.sums.size() : 0, 0.0f);
    acc.layer_sums.assign(scene_.layers ? scene_.layers->count() * acc.sums.size() : 0, 0.0f);
    // A render that publishes only at its target makes the predictions then (publish), in one
    // pass: none kept beside the samples.
    acc.predictions = params_.final_images_only ? prediction_sums{} : prediction_sums{acc.sums, acc.sums};
    acc.row_spp.assign(std::size_t(scene_.camera.height), 0);
    acc.rows_published.clear();
  };
  // The most samples a row holds: spp, or more in rows a cancelled wave finished.
  const auto rows_end = [&] {
    return acc.row_spp.empty() ? 0 : *std::max_element(acc.row_spp.begin(), acc.row_spp.end());
  };
  {
    // Entered again after a failure with an edit waiting: that edit's layout gets the sums.
    std::unique_lock lock(mutex_);
    if (!pending_) {
      lock.unlock();
      reset_sums();
    }
  }

  while (true) {
    std::uint64_t count = 0;
    {
      std::unique_lock lock(mutex_);
      // Published in place (final_images_only), the sums are gone: nothing more to trace.
      const bool traceable = !acc.row_spp.empty();
      changed_.wait(lock, [&] {
        return stopping_ || pending_ || (!paused_ && ((traceable && spp < target_spp_) || publish_owed));
      });
      if (stopping_) {
        lock.unlock();
        drop_model();
        for (auto& f : dropped) f.wait();
        return;
      }
      if (pending_) {
        const scene s = std::move(*pending_);
        retro_model_list models = std::exchange(pending_models_, {});
        pending_.reset();
        gen = generation_;
        cancel_ = false;
        lock.unlock();
        drop_model();
        std::string error;
        try {
          build_tracer_scene(scene_, device_, s, std::move(models));
        } catch (const std::exception& e) {
          error = failure_message(e, "render");
        }
        reset_sums();
        spp = rays = 0;
        seconds = 0;
        publish_owed = false;
        next_wave = 1;
        lock.lock();
        // A refusal stays said, over the last good layout's images, until an edit is applied.
        if (error.empty()) snapshot_.error.clear();
        if (!error.empty()) {
          // Keep the last good layout in the tracer and say why the edit was refused.
          if (snapshot_.generation == gen && snapshot_.model_image) snapshot_ = before_first_look_;
          snapshot_.generation = gen;
          snapshot_.error = error;
          changed_.notify_all();
        } else if (params_.preview_stride > 1 && !pending_) {
          lock.unlock();
          std::vector<float> preview;
          std::uint64_t preview_rays = 0;
          const preview_size size{scene_.camera.width, scene_.camera.height, scene_.camera.mm_per_pixel};
          if (render_preview(preview, preview_rays))
            publish_preview(gen, std::move(preview), size, preview_kind::traced);
          lock.lock();
        }
        if (error.empty() && params_.first_look && params_.view_model_image) {
          // The model image the designer sees first gets the cores: the tracer waits for it (its
          // first wave would take as long).
          changed_.wait(lock, [&] { return stopping_ || pending_ || models_shown_ >= gen; });
          if (stopping_ || pending_) continue;
        }
        model_wanted = error.empty();
        continue;
      }
      cancel_ = false;
      if (publish_owed && spp >= target_spp_) {
        lock.unlock();
        publish_owed = !publish(gen, spp, acc, rays, seconds);
        continue;
      }
      if (model_coming.valid() && model_coming.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        model_arrived = model_coming.get();
      }
      count = std::min({next_wave, params_.max_wave_spp, target_spp_ - spp});
      if (spp + count >= target_spp_ && model_wanted) start_model();  // the first wave is the last
      if (spp + count >= target_spp_ && model_coming.valid()) {
        // The last wave: the estimate that stays is the control variate's (an edit cancels the wait).
        lock.unlock();
        model_arrived = model_coming.get();
        lock.lock();
        if (pending_ || stopping_) continue;
      }
    }
    if (model_arrived) {
      // The predictions of the samples traced so far (none yet: no model image was there). Cut
      // short (an edit or a pause), they are dropped and redone.
      scene_.model = model_arrived;
      std::atomic<bool> complete{true};
      traced_rows([&](int y0, int y1) {
        if (params_.background_priority) lower_thread_priority();
        for (int y = y0; y < y1 && complete; ++y) {
          if (!add_predictions(scene_, y, y + 1, 0, acc.row_spp[std::size_t(y)], acc.predictions, cancel_))
            complete = false;
        }
      });
      if (!complete || cancel_) {
        scene_.model.reset();
        std::fill(acc.predictions.all.begin(), acc.predictions.all.end(), 0.0f);
        std::fill(acc.predictions.odd.begin(), acc.predictions.odd.end(), 0.0f);
        continue;
      }
      model_arrived.reset();
      if (spp > 0 && rows_end() == spp) publish_owed = !publish(gen, spp, acc, rays, seconds);
      continue;
    }
    const auto t0 = clock::now();
    // The rows a cancelled wave finished keep their samples: this wave brings the others level.
    const std::uint64_t end = std::max(spp + count, rows_end());
    const bool whole = render_wave(end, acc, rays);
    seconds += std::chrono::duration<double>(clock::now() - t0).count();
    if (!whole) continue;
    spp = end;
    next_wave = std::min(2 * next_wave, params_.max_wave_spp);  // capped: doubling forever would overflow
    publish_owed = !publish(gen, spp, acc, rays, seconds);
    if (model_wanted) {
      // After the first wave, which has the cores to itself.
      std::lock_guard lock(mutex_);
      start_model();
    }
  }
}

}  // namespace airr
