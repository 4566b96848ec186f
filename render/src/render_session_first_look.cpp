// The designer's session: what is shown before traced samples (the first look, the model image
// at view quality) and how it is published.
#include <algorithm>
#include <memory>
#include <string>

#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

void render_session::run_first_look() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || first_look_; });
    if (stopping_) return;
    first_look_request request = std::move(*first_look_);
    first_look_.reset();
    first_look_cancel_ = false;
    const std::shared_ptr<const layout_model_image> last_view = latest_view_;
    const std::shared_ptr<const image_rgb> last_texture = latest_view_texture_;
    lock.unlock();
    bool has_model_image = false;
    try {
      const scene& s = request.layout;
      const std::string path = resolve_scene_path(s, s.source.image);
      const std::shared_ptr<const image_rgb> texture = path.empty() ? nullptr : cached_image_pixels(path);
      if (request.models.empty()) request.models = make_sheet_models(s);
      const preview_size size{s.observer.width, s.observer.height, make_camera(s).mm_per_pixel};
      image_rgb first;
      if (last_view && last_texture == texture) {
        // The limits only gate: within the strict ones the lenient remap is the same image.
        const model_image_params view = model_image_params::for_view();
        first = remap_layout_model_image(*last_view, s, view, &first_look_cancel_, remap_limits::lenient());
      }
      if (first.rgb.empty()) first = model_image_first_look(s, request.models, texture.get(), &first_look_cancel_);
      has_model_image = !first.rgb.empty();
      if (has_model_image) publish_preview(request.generation, std::move(first.rgb), size, preview_kind::first_look);
    } catch (const std::exception&) {
      // The tracer's worker reports what is wrong with the edit; its coarse preview serves.
    }
    lock.lock();
    const std::uint64_t gen = request.generation;
    first_looks_done_ = std::max(first_looks_done_, gen);
    if (params_.view_model_image && has_model_image) {
      view_wanted_ = std::move(request);
    } else {
      models_shown_ = std::max(models_shown_, gen);
    }
    changed_.notify_all();
    // The tracer's preview waited for this first look; with none, it is shown after all.
    if (held_preview_ && held_preview_->generation == gen) {
      held_preview preview = std::move(*held_preview_);
      held_preview_.reset();
      if (!has_model_image) {
        lock.unlock();
        publish_preview(preview.generation, std::move(preview.rgb), preview.size, preview_kind::traced);
        lock.lock();
      }
    }
  }
}

void render_session::run_view_images() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return stopping_ || view_wanted_; });
    if (stopping_) return;
    const first_look_request request = std::move(*view_wanted_);
    view_wanted_.reset();
    lock.unlock();
    // Not worth making once the generation's traced samples (or a refusal) are out, unless no
    // view image is there to move for the next edits.
    if (!latest_view_ || !view_taken_over(request.generation)) {
      try {
        const scene& s = request.layout;
        const std::string path = resolve_scene_path(s, s.source.image);
        const std::shared_ptr<const image_rgb> texture = path.empty() ? nullptr : cached_image_pixels(path);
        auto view =
            compute_layout_model_image(s, request.models, texture.get(), model_image_params::for_view(), &view_cancel_);
        if (view) {
          const preview_size size{s.observer.width, s.observer.height, make_camera(s).mm_per_pixel};
          publish_preview(request.generation, view->image.rgb, size, preview_kind::model_image);
          lock.lock();
          latest_view_ = std::move(view);
          latest_view_texture_ = texture;
          lock.unlock();
        }
      } catch (const std::exception&) {
        // As for the first look.
      }
    }
    lock.lock();
    models_shown_ = std::max(models_shown_, request.generation);
    changed_.notify_all();
  }
}

bool render_session::view_taken_over(std::uint64_t gen) const {
  std::lock_guard lock(mutex_);
  return gen != generation_ ||
         (snapshot_.generation == gen && (!snapshot_.error.empty() || (!snapshot_.preview && !snapshot_.model_image)));
}

void render_session::publish_preview(std::uint64_t gen, std::vector<float> rgb, const preview_size& size,
                                     preview_kind kind) {
  std::lock_guard lock(mutex_);
  if (gen != generation_) return;
  if (kind == preview_kind::traced && params_.first_look && first_looks_done_ < gen) {
    held_preview_ = held_preview{gen, std::move(rgb), size};
    return;
  }
  auto shared = std::make_shared<const std::vector<float>>(std::move(rgb));
  const bool model_image = kind != preview_kind::traced;
  if (snapshot_.generation == gen) {
    // A model image replaces the coarse traced preview and the first look, not the other way
    // round, and is mixed with traced samples as long as it helps (show_best); a refused edit
    // shows none.
    const bool view_shown = model_shown_ && model_generation_ == gen && !model_shown_first_look_;
    if (!snapshot_.error.empty() || (snapshot_.model_image && !model_image) ||
        (view_shown && kind == preview_kind::first_look)) {
      return;
    }
    if (!snapshot_.preview && snapshot_.rgb) {
      // Traced samples are out: a model image joins them.
      if (!model_image) return;
      model_shown_ = std::move(shared);
      model_generation_ = gen;
      model_shown_first_look_ = kind == preview_kind::first_look;
      show_best();
      changed_.notify_all();
      return;
    }
  } else {
    if (model_image) before_first_look_ = snapshot_;  // shown again if the tracer refuses this edit
    snapshot_.error.clear();                          // an earlier edit's refusal
  }
  if (model_image) {
    model_shown_ = shared;
    model_generation_ = gen;
    model_shown_first_look_ = kind == preview_kind::first_look;
  }
  snapshot_.generation = gen;
  snapshot_.model_image = model_image;
  snapshot_.model_weight = model_image ? 1 : 0;
  snapshot_.first_look = kind == preview_kind::first_look;
  snapshot_.edit_seconds = seconds_since_edit();
  snapshot_.spp = 0;
  snapshot_.preview = true;
  snapshot_.width = size.width;
  snapshot_.height = size.height;
  snapshot_.mm_per_pixel = size.mm_per_pixel;
  snapshot_.rgb = shared;
  snapshot_.shown = std::move(shared);
  snapshot_.odd_rgb.reset();
  snapshot_.components.reset();
  snapshot_.layers.reset();
  snapshot_.rays = 0;
  snapshot_.seconds = 0;
  changed_.notify_all();
}

}  // namespace airr
