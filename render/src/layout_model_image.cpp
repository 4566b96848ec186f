#include "airr/render/layout_model_image.hpp"

#include <algorithm>
#include <chrono>

#include <opencv2/imgproc.hpp>

#include "airr/core/cancel.hpp"
#include "airr/core/error.hpp"
#include "airr/render/display_parts_image.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

// The display seen directly and in the half mirror, when p asks for them: empty when it does not,
// none is in view, or `cancel` was set (then `cancelled`).
static image_rgb display_parts(const scene& s, const std::vector<image_rgb>& texels, const model_image_params& p,
                               const std::atomic<bool>* cancel, bool& cancelled) {
  if (p.display_samples < 1 || texels.empty()) return {};
  image_rgb parts = display_parts_image(s, texels, p, cancel);
  cancelled = parts.rgb.empty();
  return parts;
}

static void add_to(image_rgb& image, const image_rgb& parts) {
  if (parts.rgb.size() != image.rgb.size()) return;
  for (std::size_t k = 0; k < image.rgb.size(); ++k) image.rgb[k] += parts.rgb[k];
}

// Whether the display seen directly and in the half mirror stay as they were: only sheets moved
// (a sheet moved into or out of the line of sight is left to the next view image).
static bool display_parts_stay(const scene& a, const scene& b) {
  return a.source == b.source && a.half_mirror == b.half_mirror && a.observer == b.observer;
}

std::shared_ptr<const layout_model_image> compute_layout_model_image(const scene& s, const retro_model_list& models,
                                                                     const image_rgb* display,
                                                                     const model_image_params& p,
                                                                     const std::atomic<bool>* cancel) {
  check_model_image_params(p);
  const auto t0 = std::chrono::steady_clock::now();
  auto out = std::make_shared<layout_model_image>();
  const std::shared_ptr<const display_grids> grids = compute_display_grids(s, display, p, cancel);
  if (!grids) return nullptr;  // cancelled
  for (std::size_t i = 0; i < models.size() && i < s.retroreflectors.size(); ++i) {
    const std::string sheet = "retroreflectors[" + std::to_string(i) + "]: ";
    std::shared_ptr<model_image> m;
    try {
      m = compute_model_image(s, models[i], display, p, cancel, i, grids);
    } catch (const input_error& e) {
      out->left_out.push_back(sheet + e.what());  // a chief ray grazing a part's edge
      continue;
    }
    if (cancel_requested(cancel)) return nullptr;
    if (!m) {
      out->left_out.push_back(sheet + "no pixel has an ideal path to it");
      continue;
    }
    if (out->image.rgb.empty()) {
      out->image = std::move(m->image);  // its width and height stay
    } else {
      for (std::size_t k = 0; k < out->image.rgb.size(); ++k) out->image.rgb[k] += m->image.rgb[k];
    }
    std::vector<float>().swap(m->image.rgb);  // the sum holds it: 12 bytes a pixel less per sheet
    out->sheets.push_back(std::move(m));
  }
  if (out->sheets.empty()) return nullptr;
  if (p.display_samples > 0) {
    std::vector<image_rgb> texels = display_parts_texels(s, display, p.display_samples);
    bool cancelled = false;
    image_rgb parts = display_parts(s, texels, p, cancel, cancelled);
    if (cancelled) return nullptr;
    add_to(out->image, parts);
    if (p.keep_correlations) {
      out->display_texels = std::move(texels);
      out->display_parts = std::move(parts);
    }
  }
  out->layout = s;
  out->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

glm::vec3 model_prediction(const layout_model_image& m, int px, int py, const glm::dvec2& jitter,
                           const retro_samples& u) {
  glm::vec3 sum(0.0f);
  for (const auto& sheet : m.sheets) sum += model_prediction(*sheet, px, py, jitter, u);
  return sum;
}

glm::vec3 model_prediction(const layout_model_image& m, const std::vector<model_pixel>& pixels,
                           const glm::dvec2& jitter, const retro_samples& u) {
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < m.sheets.size(); ++i) sum += model_prediction(*m.sheets[i], pixels[i], jitter, u);
  return sum;
}

std::vector<model_pixel> model_pixels_at(const layout_model_image& m, int px, int py) {
  std::vector<model_pixel> out;
  out.reserve(m.sheets.size());
  for (const auto& sheet : m.sheets) out.push_back(model_pixel_at(*sheet, px, py));
  return out;
}

image_rgb remap_layout_model_image(const layout_model_image& from, const scene& s, const model_image_params& p,
                                   const std::atomic<bool>* cancel, const remap_limits& limits) {
  if (!from.left_out.empty() || !differ_in_placement_alone(from.layout, s)) return {};
  image_rgb out;
  for (const auto& sheet : from.sheets) {
    image_rgb one = remap_model_image(*sheet, s, p, cancel, limits);
    if (one.rgb.empty()) return {};
    if (out.rgb.empty()) {
      out = std::move(one);
    } else {
      for (std::size_t k = 0; k < out.rgb.size(); ++k) out.rgb[k] += one.rgb[k];
    }
  }
  if (p.display_samples > 0 && display_parts_stay(from.layout, s)) {
    add_to(out, from.display_parts);
  } else {
    bool cancelled = false;
    const image_rgb parts = display_parts(s, from.display_texels, p, cancel, cancelled);
    if (cancelled) return {};
    add_to(out, parts);
  }
  return out;
}

image_rgb model_image_first_look(const scene& s, const retro_model_list& models, const image_rgb* display,
                                 const std::atomic<bool>* cancel) {
  const int w = s.observer.width, h = s.observer.height;
  int f = 4;
  while (f > 1 && (w % f != 0 || h % f != 0 || std::min(w, h) / f < 128)) f /= 2;
  scene small = s;
  small.observer.width = w / f;
  small.observer.height = h / f;
  const auto m = compute_layout_model_image(small, models, display, model_image_params::first_look(), cancel);
  if (!m) return {};
  if (f == 1) return m->image;
  image_rgb out;
  out.width = w;
  out.height = h;
  out.rgb.resize(std::size_t(w) * h * 3);
  const cv::Mat src(m->image.height, m->image.width, CV_32FC3, const_cast<float*>(m->image.rgb.data()));
  cv::Mat dst(h, w, CV_32FC3, out.rgb.data());  // resized straight into the result
  cv::resize(src, dst, dst.size(), 0, 0, cv::INTER_LINEAR);
  return out;
}

// The tracer's control variate (tracer.hpp).
model_image_job control_variate_job(const tracer_scene& ts, bool quick) {
  model_image_params p = model_image_params::for_image(ts.camera.width, ts.camera.height, quick);
  p.keep_pixels = ts.model_pixels_kept;
  return {ts.layout, ts.retro, ts.texture, p, ts.use_model_image && !ts.retro.empty()};
}

std::shared_ptr<const layout_model_image> model_image_job::run(const std::atomic<bool>* cancel) const {
  if (!wanted) return nullptr;
  return compute_layout_model_image(layout, retro, texture.get(), params, cancel);
}

void update_model_image(tracer_scene& ts, const std::atomic<bool>* cancel, bool quick) {
  ts.model.reset();
  ts.model = control_variate_job(ts, quick).run(cancel);
}

}  // namespace airr
