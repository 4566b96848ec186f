#include "airr/render/render_session.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/parallel_rows.hpp"

namespace airr {

image_rgb render_snapshot::image() const {
  image_rgb img;
  img.width = width;
  img.height = height;
  if (rgb)
    img.rgb = *rgb;
  else
    img.rgb.assign(std::size_t(width) * height * 3, 0.0f);
  return img;
}

image_rgb render_snapshot::component_image(int component) const {
  image_rgb img;
  if (!components || component < 0 || component >= component_count) return img;
  img.width = width;
  img.height = height;
  img.rgb.resize(std::size_t(width) * height * 3);
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
    std::copy_n(components->data() + 3 * (component_count * i + std::size_t(component)), 3, img.rgb.data() + 3 * i);
  }
  return img;
}

std::vector<image_rgb> render_snapshot::component_images() const {
  std::vector<image_rgb> out;
  for (int k = 0; k < component_count && components; ++k) out.push_back(component_image(k));
  return out;
}

std::vector<float> render_snapshot::even_rgb() const {
  if (!rgb || !odd_rgb || spp < 2) return {};
  // Samples 0 .. spp-1: spp / 2 odd-numbered ones, the rest even-numbered.
  const double odd_n = double(spp / 2), even_n = double(spp - spp / 2);
  std::vector<float> even(rgb->size());
  for (std::size_t i = 0; i < even.size(); ++i) {
    even[i] = float((double(spp) * (*rgb)[i] - odd_n * (*odd_rgb)[i]) / even_n);
  }
  return even;
}

render_session::render_session(const scene& s, session_params p) : params_(p), target_spp_(p.target_spp) {
  build_tracer_scene(scene_, device_, s);
  update_model_image(scene_, nullptr, params_.quick_model_image);
  snapshot_.width = scene_.camera.width;
  snapshot_.height = scene_.camera.height;
  snapshot_.mm_per_pixel = scene_.camera.mm_per_pixel;
  worker_ = std::thread([this] { run(); });
  if (params_.first_look) first_look_worker_ = std::thread([this] { run_first_look(); });
}

render_session::~render_session() { stop(); }

void render_session::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    cancel_ = true;
  }
  changed_.notify_all();
  first_look_cancel_ = true;
  if (worker_.joinable()) worker_.join();
  if (first_look_worker_.joinable()) first_look_worker_.join();
}

std::uint64_t render_session::edit(const scene& s, retro_model_list models) {
  std::lock_guard lock(mutex_);
  ++generation_;
  edit_time_ = std::chrono::steady_clock::now();
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

void render_session::run_first_look() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || first_look_; });
    if (stopping_) return;
    const first_look_request request = std::move(*first_look_);
    first_look_.reset();
    first_look_cancel_ = false;
    lock.unlock();
    try {
      const scene& s = request.layout;
      const std::string path = resolve_scene_path(s, s.source.image);
      const std::shared_ptr<const image_rgb> texture = path.empty() ? nullptr : cached_image_pixels(path);
      const retro_model_list models = request.models.empty() ? make_sheet_models(s) : request.models;
      const preview_size size{s.observer.width, s.observer.height, make_camera(s).mm_per_pixel};
      image_rgb first = model_image_first_look(s, models, texture.get(), &first_look_cancel_);
      if (!first.rgb.empty()) {
        publish_preview(request.generation, std::move(first.rgb), size, preview_kind::first_look);
        if (params_.view_model_image && !view_taken_over(request.generation)) {
          const auto view =
              compute_layout_model_image(s, models, texture.get(), model_image_params::for_view(), &first_look_cancel_);
          if (view) publish_preview(request.generation, view->image.rgb, size, preview_kind::model_image);
        }
      }
    } catch (const std::exception&) {
      // The tracer's worker reports what is wrong with the edit; its coarse preview serves.
    }
    lock.lock();
  }
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

std::string estimate_name(const render_snapshot& snap) {
  if (snap.model_image) return snap.first_look ? "model image (first look)" : "model image";
  if (snap.preview) return "tracer (preview)";
  return "tracer at " + std::to_string(snap.spp) + " spp";
}

void lower_thread_priority(int nice) {
  thread_local bool done = false;
  if (done) return;
  done = true;
  ::setpriority(PRIO_PROCESS, pid_t(::syscall(SYS_gettid)), nice);
}

bool render_session::render_wave(std::uint64_t first, std::uint64_t count, std::vector<double>& sums,
                                 std::vector<double>& odd_sums, std::vector<double>* component_sums,
                                 std::uint64_t& rays) {
  const int h = scene_.camera.height;
  std::atomic<std::uint64_t> total_rays{0};
  std::atomic<bool> complete{true};
  detail::parallel_rows(h, params_.threads, [&](int y0, int y1) {
    if (params_.background_priority) lower_thread_priority();
    std::uint64_t local = 0;
    if (!trace_rows(scene_, y0, y1, first, count, sums, cancel_, local, &odd_sums, component_sums)) complete = false;
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

bool render_session::view_taken_over(std::uint64_t gen) const {
  std::lock_guard lock(mutex_);
  return gen != generation_ || (snapshot_.generation == gen && (!snapshot_.preview || !snapshot_.error.empty()));
}

void render_session::publish_preview(std::uint64_t gen, std::vector<float> rgb, const preview_size& size,
                                     preview_kind kind) {
  auto shared = std::make_shared<const std::vector<float>>(std::move(rgb));
  const bool model_image = kind != preview_kind::traced;
  std::lock_guard lock(mutex_);
  if (gen != generation_) return;
  if (snapshot_.generation == gen) {
    // Traced samples replace previews and are never replaced by one; a model image replaces the
    // coarse traced preview and the first look, not the other way round; a refused edit shows none.
    if (!snapshot_.preview || !snapshot_.error.empty() || (snapshot_.model_image && !model_image) ||
        (snapshot_.model_image && !snapshot_.first_look && kind == preview_kind::first_look)) {
      return;
    }
  } else {
    if (model_image) before_first_look_ = snapshot_;  // shown again if the tracer refuses this edit
    snapshot_.error.clear();                          // an earlier edit's refusal
  }
  snapshot_.generation = gen;
  snapshot_.model_image = model_image;
  snapshot_.first_look = kind == preview_kind::first_look;
  snapshot_.edit_seconds = seconds_since_edit();
  snapshot_.spp = 0;
  snapshot_.preview = true;
  snapshot_.width = size.width;
  snapshot_.height = size.height;
  snapshot_.mm_per_pixel = size.mm_per_pixel;
  snapshot_.rgb = std::move(shared);
  snapshot_.odd_rgb.reset();
  snapshot_.components.reset();
  snapshot_.rays = 0;
  snapshot_.seconds = 0;
  changed_.notify_all();
}

void render_session::publish(std::uint64_t gen, std::uint64_t spp, const std::vector<double>& sums,
                             const std::vector<double>& odd_sums, const std::vector<double>& component_sums,
                             std::uint64_t rays, double seconds) {
  // Each pixel's estimate is the model image's value plus the mean of its samples.
  const std::vector<float>* model = scene_.model ? &scene_.model->image.rgb : nullptr;
  auto rgb = std::make_shared<std::vector<float>>(sums.size());
  const double inv = spp ? 1.0 / double(spp) : 0.0;
  for (std::size_t i = 0; i < sums.size(); ++i) (*rgb)[i] = float(sums[i] * inv + (model ? (*model)[i] : 0.0f));
  std::shared_ptr<std::vector<float>> odd;
  if (spp >= 2) {
    const double inv_odd = 1.0 / double(spp / 2);  // spp / 2 of samples 0 .. spp-1 are odd-numbered
    odd = std::make_shared<std::vector<float>>(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
      (*odd)[i] = float(odd_sums[i] * inv_odd + (model ? (*model)[i] : 0.0f));
    }
  }
  std::shared_ptr<std::vector<float>> components;
  if (!component_sums.empty()) {
    // The model image belongs to the aerial image.
    components = std::make_shared<std::vector<float>>(component_sums.size());
    for (std::size_t p = 0; p < sums.size() / 3; ++p) {
      for (int k = 0; k < component_count; ++k) {
        for (int c = 0; c < 3; ++c) {
          const std::size_t i = 3 * (component_count * p + std::size_t(k)) + std::size_t(c);
          const float m = model && k == component_aerial ? (*model)[3 * p + std::size_t(c)] : 0.0f;
          (*components)[i] = float(component_sums[i] * inv + m);
        }
      }
    }
  }
  std::lock_guard lock(mutex_);
  if (gen != generation_) return;  // an edit arrived meanwhile: this result is stale
  snapshot_.generation = gen;
  snapshot_.spp = spp;
  snapshot_.width = scene_.camera.width;
  snapshot_.height = scene_.camera.height;
  snapshot_.mm_per_pixel = scene_.camera.mm_per_pixel;
  snapshot_.rgb = std::move(rgb);
  snapshot_.odd_rgb = std::move(odd);
  snapshot_.components = std::move(components);
  snapshot_.preview = false;
  snapshot_.model_image = false;
  snapshot_.first_look = false;
  snapshot_.edit_seconds = seconds_since_edit();
  snapshot_.rays = rays;
  snapshot_.seconds = seconds;
  changed_.notify_all();
}

void render_session::run() {
  using clock = std::chrono::steady_clock;
  std::vector<double> sums, wave, odd_sums, odd_wave, component_sums, component_wave;
  std::uint64_t gen = 0, spp = 0, rays = 0, next_wave = 1;
  bool model_pending = false;  // the model image of the layout in scene_ is still to be computed
  double seconds = 0;
  auto reset_sums = [&] {
    sums.assign(std::size_t(scene_.camera.width) * scene_.camera.height * 3, 0.0);
    odd_sums = sums;
    component_sums.assign(params_.components ? component_count * sums.size() : 0, 0.0);
  };
  reset_sums();

  while (true) {
    std::uint64_t count = 0;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || pending_ || (!paused_ && spp < target_spp_); });
      if (stopping_) return;
      if (pending_) {
        const scene s = std::move(*pending_);
        retro_model_list models = std::exchange(pending_models_, {});
        pending_.reset();
        gen = generation_;
        cancel_ = false;
        lock.unlock();
        std::string error;
        try {
          build_tracer_scene(scene_, device_, s, std::move(models));
        } catch (const std::exception& e) {
          error = e.what();
        }
        reset_sums();
        spp = rays = 0;
        seconds = 0;
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
        model_pending = error.empty();
        continue;
      }
      cancel_ = false;
      if (model_pending) {
        lock.unlock();
        update_model_image(scene_, &cancel_, params_.quick_model_image);
        lock.lock();
        if (cancel_) continue;  // an edit or a pause came first: computed again when the worker resumes
        model_pending = false;
      }
      count = std::min({next_wave, params_.max_wave_spp, target_spp_ - spp});
    }
    const auto t0 = clock::now();
    wave = sums;  // a cancelled wave leaves the accumulation untouched
    odd_wave = odd_sums;
    component_wave = component_sums;
    std::uint64_t wave_rays = 0;
    const bool done =
        render_wave(spp, count, wave, odd_wave, params_.components ? &component_wave : nullptr, wave_rays);
    if (!done) continue;
    sums.swap(wave);
    odd_sums.swap(odd_wave);
    component_sums.swap(component_wave);
    spp += count;
    rays += wave_rays;
    seconds += std::chrono::duration<double>(clock::now() - t0).count();
    next_wave = std::min(2 * next_wave, params_.max_wave_spp);  // capped: doubling forever would overflow
    publish(gen, spp, sums, odd_sums, component_sums, rays, seconds);
  }
}

}  // namespace airr
