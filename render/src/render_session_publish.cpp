// A render session's publishing: its sums turned into a snapshot's images.
#include <atomic>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "airr/render/parallel_rows.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

bool render_session::publish(std::uint64_t gen, std::uint64_t spp, accumulation& acc, std::uint64_t rays,
                             double seconds) {
  bool images = true;
  if (params_.final_images_only) {
    std::lock_guard lock(mutex_);
    images = spp >= target_spp_;
    if (!images && gen == generation_) {
      snapshot_.generation = gen;
      snapshot_.spp = spp;
      snapshot_.rays = rays;
      snapshot_.seconds = seconds;
      snapshot_.edit_seconds = seconds_since_edit();
      changed_.notify_all();
    }
  }
  if (!images) return true;
  // Each pixel's estimate is the model image's value plus the mean of its samples less their
  // predictions: those summed beside the samples, or (none kept) made now. A render that
  // publishes only at its target turns its sums into the images in place (the memory of one set
  // of them less), row by row: a row done is not done again after a pause.
  const bool in_place = params_.final_images_only;
  const std::vector<float>* model = scene_.model ? &scene_.model->image.rgb : nullptr;
  const bool predictions_kept = !acc.predictions.all.empty();
  const int w = scene_.camera.width;
  auto made = [&](const std::vector<float>& sums, bool wanted) {
    return !wanted || in_place ? nullptr : std::make_shared<std::vector<float>>(sums.size());
  };
  std::shared_ptr<std::vector<float>> rgb = made(acc.sums, true), odd = made(acc.odd_sums, spp >= 2),
                                      components = made(acc.component_sums, !acc.component_sums.empty()),
                                      layers = made(acc.layer_sums, !acc.layer_sums.empty());
  float* rgb_out = rgb ? rgb->data() : acc.sums.data();
  float* odd_out = odd ? odd->data() : spp >= 2 ? acc.odd_sums.data() : nullptr;
  float* components_out = components ? components->data() : acc.component_sums.data();
  float* layers_out = layers ? layers->data() : acc.layer_sums.data();
  const std::size_t layer_count = acc.layer_sums.empty() ? 0 : scene_.layers->count();
  const std::uint64_t variate = layer_count ? model_layers(scene_) : 0;
  const bool with_components = !acc.component_sums.empty();
  component_slots layout = acc.slots;  // kept past `acc`, emptied below when the sums become the images
  const double inv = spp ? 1.0 / double(spp) : 0.0;
  const double inv_odd = spp >= 2 ? 1.0 / double(spp / 2) : 0.0;  // spp / 2 of samples 0 .. spp-1 are odd-numbered
  if (in_place) acc.rows_published.resize(std::size_t(scene_.camera.height), 0);
  std::atomic<bool> complete{true};
  detail::parallel_rows(scene_.camera.height, params_.threads, [&](int y0, int y1) {
    if (params_.background_priority) lower_thread_priority();
    for (int y = y0; y < y1; ++y) {
      if (cancel_.load(std::memory_order_relaxed)) {
        complete = false;
        return;
      }
      if (in_place && acc.rows_published[std::size_t(y)]) continue;
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x), j = 3 * p;
        pixel_predictions predicted;
        if (predictions_kept) {
          for (int c = 0; c < 3; ++c) {
            predicted.all[c] = acc.predictions.all[j + std::size_t(c)];
            predicted.odd[c] = acc.predictions.odd[j + std::size_t(c)];
          }
        } else if (model) {
          predicted = predict_pixel(scene_, x, y, 0, acc.row_spp[std::size_t(y)]);
        }
        for (int c = 0; c < 3; ++c) {
          const float m = model ? (*model)[j + std::size_t(c)] : 0.0f;
          rgb_out[j + std::size_t(c)] = float((acc.sums[j + std::size_t(c)] - predicted.all[c]) * inv + m);
          if (odd_out)
            odd_out[j + std::size_t(c)] = float((acc.odd_sums[j + std::size_t(c)] - predicted.odd[c]) * inv_odd + m);
        }
        // The model image and its predictions belong to the aerial image, and to the layers that
        // carry the control variate.
        for (int k = 0; with_components && k < component_count; ++k) {
          const bool aerial = k == component_aerial;
          const int at = acc.slots.slot[std::size_t(k)];
          if (at < 0) continue;
          for (int c = 0; c < 3; ++c) {
            const std::size_t i = 3 * (std::size_t(acc.slots.count) * p + std::size_t(at)) + std::size_t(c);
            const double v = (acc.component_sums[i] - (aerial ? predicted.all[c] : 0.0)) * inv;
            components_out[i] = float(v + (model && aerial ? (*model)[j + std::size_t(c)] : 0.0f));
          }
        }
        for (int k = 0; with_components && k < acc.slots.luminaires; ++k) {
          const std::size_t i = 3 * (std::size_t(acc.slots.count) * p + std::size_t(acc.slots.first_luminaire + k));
          for (std::size_t c = 0; c < 3; ++c) components_out[i + c] = float(acc.component_sums[i + c] * inv);
        }
        for (std::size_t k = 0; k < layer_count; ++k) {
          const bool modelled = variate >> k & 1;
          for (int c = 0; c < 3; ++c) {
            const std::size_t i = 3 * (layer_count * p + k) + std::size_t(c);
            const double v = (acc.layer_sums[i] - (modelled ? predicted.all[c] : 0.0)) * inv;
            layers_out[i] = float(v + (model && modelled ? (*model)[j + std::size_t(c)] : 0.0f));
          }
        }
      }
      if (in_place) acc.rows_published[std::size_t(y)] = 1;
    }
  });
  if (!complete) return false;  // cancelled while the predictions were made: owed
  if (in_place) {
    // The sums are the images now; nothing more is traced into them.
    rgb = std::make_shared<std::vector<float>>(std::move(acc.sums));
    if (spp >= 2) odd = std::make_shared<std::vector<float>>(std::move(acc.odd_sums));
    if (with_components) components = std::make_shared<std::vector<float>>(std::move(acc.component_sums));
    if (layer_count) layers = std::make_shared<std::vector<float>>(std::move(acc.layer_sums));
    acc = accumulation{};
  }
  std::vector<std::string> layer_names;
  for (std::size_t k = 0; k < layer_count; ++k) layer_names.push_back(scene_.layers->name(k));
  std::lock_guard lock(mutex_);
  if (gen != generation_) return true;  // an edit arrived meanwhile: this result is stale
  snapshot_.generation = gen;
  snapshot_.spp = spp;
  snapshot_.width = scene_.camera.width;
  snapshot_.height = scene_.camera.height;
  snapshot_.mm_per_pixel = scene_.camera.mm_per_pixel;
  snapshot_.rgb = std::move(rgb);
  snapshot_.odd_rgb = std::move(odd);
  if (params_.final_images_only) {
    snapshot_.shown = snapshot_.rgb;
  } else {
    show_best();
  }
  snapshot_.components = std::move(components);
  snapshot_.component_layout = layout;
  snapshot_.layers = std::move(layers);
  snapshot_.layer_names = std::move(layer_names);
  snapshot_.preview = false;
  snapshot_.edit_seconds = seconds_since_edit();
  snapshot_.rays = rays;
  snapshot_.seconds = seconds;
  changed_.notify_all();
  return true;
}

}  // namespace airr
