#include "airr/measure/viewing_zone_full.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "airr/core/cancel.hpp"
#include "airr/core/color.hpp"
#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/aerial_outline.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/render/interleaved_image.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/parallel_rows.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/prop_hits.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct eye_render {
  double aerial = 0, stray = 0, direct = 0;  // mean luminance of each inside the aerial outline
  contrast_summary seen;                     // the aerial image against the rest, wholly inside it
  double stray_ratio() const { return aerial > 0 ? stray / aerial : nan; }
};

// The eye's render: small, through a pinhole, its field holding the aerial image with a quarter
// to spare.
void frame_eye_render(scene& eye, const part_frame& aerial, const full_zone_params& p) {
  eye.observer.width = eye.observer.height = p.render_size;
  eye.observer.lens = observer_lens::pinhole;
  const double reach = 0.5 * std::hypot(aerial.width, aerial.height) * 1.25;
  eye.observer.fov_deg =
      degrees(2 * std::atan(reach / std::max(1.0, glm::length(observer_position(eye) - aerial.center))));
}

// The scene seen from `eye` (looking at the aerial image's centre) in the eye's render.
scene seen_from(const scene& s, const glm::dvec3& eye, const full_zone_params& p) {
  scene at = s;
  const part_frame aerial = aerial_image_frame(s);
  at.observer.placement = observer_placement::look_at;
  at.observer.position_mm = {eye.x, eye.y, eye.z};
  at.observer.look_at_mm = {aerial.center.x, aerial.center.y, aerial.center.z};
  frame_eye_render(at, aerial, p);
  return at;
}

// The components' mean luminance per sample over the aerial image's outline as the eye sees it,
// and the contrast there.
eye_render outline_means(const std::vector<float>& components, const pinhole_camera& cam,
                         const std::array<glm::dvec2, 4>& outline, std::uint64_t spp,
                         const std::vector<double>& thresholds = {}) {
  const int w = cam.width, h = cam.height;
  eye_render out;
  int inside = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!inside_quad(outline, x + 0.5, y + 0.5)) continue;
      ++inside;
      const float* c = components.data() + 3 * component_count * (std::size_t(y) * w + x);
      auto luminance = [&](int comp) {
        const float* v = c + 3 * comp;
        return rec709_luminance(v[0], v[1], v[2]);
      };
      out.aerial += luminance(component_aerial);
      for (int comp = 0; comp < component_count; ++comp)
        if (comp != component_aerial) out.stray += luminance(comp);  // the room's light too
      out.direct += luminance(component_direct);
    }
  }
  const double n = double(inside) * double(spp);
  if (n > 0) {
    out.aerial /= n;
    out.stray /= n;
    out.direct /= n;
  }
  out.seen = contrast_inside(components, w, h, outline, thresholds, 1.0 / double(spp));
  return out;
}

// A small render of the aerial image from the eye, split into components: the aerial image and
// everything else, averaged over the aerial image's outline as the eye sees it.
eye_render render_from(tracer_scene& ts, const embree_device& device, const scene& eye_scene, const full_zone_params& p,
                       const std::atomic<bool>* cancel) {
  build_tracer_scene(ts, device, eye_scene, ts.retro);
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(std::size_t(w) * h * 3, 0.0f), components(component_count * sums.size(), 0.0f);
  const std::atomic<bool> never{false};
  std::uint64_t rays = 0;
  trace_rows(ts, 0, h, 0, p.render_spp, sums, cancel ? *cancel : never, rays, nullptr, &components);
  return outline_means(components, ts.camera, aerial_outline(eye_scene, ts.camera), p.render_spp,
                       p.contrast_thresholds);
}

// The luminance of the display's emitting area, face on: its white's radiance times its image's mean.
double display_luminance(const tracer_scene& ts) {
  double mean = 1;
  if (ts.texture) {
    const image_rgb& img = *ts.texture;
    double sum = 0;
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        const float* v = img.at(x, y);
        sum += rec709_luminance(v[0], v[1], v[2]);
      }
    }
    mean = sum / (double(img.width) * img.height);
  }
  return white_radiance(ts.layout.source) * mean;
}

}  // namespace

eye_view_metrics eye_view_from(const scene& s, const glm::dvec3& eye, const std::vector<std::string>& expressions,
                               const full_zone_params& p) {
  auto layers = std::make_shared<path_layers>();
  for (const std::string& e : expressions)
    layers->layers.push_back({"ghost", path_expression::parse(e).bound(s, true)});
  const scene at = seen_from(s, eye, p);
  tracer_scene ts;
  ts.use_model_image = false;
  if (!expressions.empty()) ts.layers = layers;
  const embree_device device;
  build_tracer_scene(ts, device, at, make_sheet_models(s));
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(std::size_t(w) * h * 3), components(component_count * sums.size()),
      layer_sums(expressions.empty() ? 0 : layers->count() * sums.size());
  const std::atomic<bool> never{false};
  std::uint64_t rays = 0;
  trace_rows(ts, 0, h, 0, p.render_spp, sums, never, rays, nullptr, &components, nullptr,
             expressions.empty() ? nullptr : &layer_sums);
  const std::array<glm::dvec2, 4> outline = aerial_outline(at, ts.camera);
  eye_view_metrics out;
  const eye_render r = outline_means(components, ts.camera, outline, p.render_spp, p.contrast_thresholds);
  out.stray_ratio = r.stray_ratio();
  out.seen = r.seen;
  const image_rgb aerial = interleaved_image(components.data(), w, h, component_count, component_aerial);
  const glm::dvec2 aerial_centroid = luminance_centroid(aerial);
  for (std::size_t k = 0; k < expressions.size(); ++k) {
    const image_rgb ghost = interleaved_image(layer_sums.data(), w, h, layers->count(), k);
    double aerial_in = 0, ghost_in = 0;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (!inside_quad(outline, x + 0.5, y + 0.5)) continue;
        const float *a = aerial.at(x, y), *g = ghost.at(x, y);
        aerial_in += rec709_luminance(a[0], a[1], a[2]);
        ghost_in += rec709_luminance(g[0], g[1], g[2]);
      }
    }
    ghost_seen seen;
    seen.ratio = aerial_in > 0 ? ghost_in / aerial_in : nan;
    const glm::dvec2 g = luminance_centroid(ghost);
    seen.separation_arcmin =
        std::isfinite(aerial_centroid.x) && std::isfinite(g.x) ? separation_arcmin(ts.camera, aerial_centroid, g) : nan;
    out.ghosts.push_back(seen);
  }
  return out;
}

std::vector<double> contrast_shown(const full_zone_map& m, double& top) {
  top = 1;
  for (double v : m.contrast) top = std::isfinite(v) ? std::max(top, v) : top;
  for (double t : m.thresholds) top = std::max(top, t);
  std::vector<double> shown = m.contrast;
  for (double& v : shown) v = std::min(v, top);
  return shown;
}

double legible_share(const full_zone_map& m, std::size_t k) {
  const std::vector<double>& share = m.contrast_share.at(k);
  if (share.empty()) return 0;
  std::size_t legible = 0;
  for (double v : share) legible += v >= legible_image_share;
  return double(legible) / double(share.size());
}

double stray_light_ratio(const scene& s, const glm::dvec3& eye, const full_zone_params& p) {
  return eye_view_from(s, eye, {}, p).stray_ratio;
}

ghost_seen ghost_from_eye(const scene& s, const glm::dvec3& eye, const std::string& expression,
                          const full_zone_params& p) {
  return eye_view_from(s, eye, {expression}, p).ghosts.front();
}

full_zone_map full_viewing_zone(const scene& s, const eye_grid& g, const full_zone_params& p,
                                const std::function<void(int, int)>& progress, const std::atomic<bool>* cancel,
                                const item_share& share) {
  check_eye_grid(g);
  if (p.render_size < 8 || p.render_size > 1024 || p.render_spp < 1 || p.render_spp > 65536 || p.psf_samples < 100 ||
      p.rows_per_eye < 1) {
    throw input_error("viewing zone: full-pass parameters out of range");
  }
  if (p.contrast_thresholds.size() > 16) throw input_error("viewing zone: at most 16 contrast thresholds");
  for (double t : p.contrast_thresholds)
    if (!std::isfinite(t) || t < 1 || t > 1e6) throw input_error("viewing zone: a contrast threshold is 1 to 1e6");
  if (s.retroreflectors.empty()) throw input_error("viewing zone: no retroreflector, no aerial image");
  {
    // Each worker renders one eye and takes its PSF at a time; the maps hold seven numbers an eye
    // and one a contrast threshold (twice when shared).
    const std::uint64_t workers = std::max(1u, std::thread::hardware_concurrency());
    const std::uint64_t eyes = std::uint64_t(g.nx) * std::uint64_t(g.ny), side = std::uint64_t(p.render_size);
    const std::uint64_t need =
        measuring_process_bytes + eyes * 16 * (9 + p.contrast_thresholds.size()) +
        workers * (traced_pixels_memory_need(side * side, component_count) + psf_memory_need(p.psf_samples));
    check_memory_need("viewing zone: " + std::to_string(eyes) + " eyes of " + std::to_string(p.psf_samples) +
                          " PSF samples and a " + std::to_string(side) + " x " + std::to_string(side) + " render each",
                      need);
  }
  const auto t0 = std::chrono::steady_clock::now();
  full_zone_map out;
  out.grid = g;
  const std::size_t n = std::size_t(g.nx) * g.ny;
  out.visible.assign(n, 0.0);
  out.brightness.assign(n, nan);
  out.mean_mtf.assign(n, nan);
  out.stray_ratio.assign(n, nan);
  out.direct.assign(n, nan);
  out.luminance.assign(n, 0.0);
  out.contrast.assign(n, 1.0);
  out.thresholds = p.contrast_thresholds;
  out.contrast_share.assign(p.contrast_thresholds.size(), std::vector<double>(n, 0.0));
  out.char_height_mm.assign(n, nan);
  out.char_arcmin.assign(n, nan);
  const viewing_parts parts(s, scene_prop_hits(s));
  const retro_model_list models = make_sheet_models(s);
  const embree_device device;
  const part_frame aerial = aerial_image_frame(s);
  // Eyes run in parallel, each on a tracer scene of its worker's own (taken from a pool and
  // rebuilt in place for the eye), rendering its rows on that worker alone.
  std::mutex mutex;
  std::vector<std::unique_ptr<tracer_scene>> pool;
  int done = 0;
  auto one_eye = [&](std::size_t e, tracer_scene& ts) {
    const int i = int(e % std::size_t(g.nx)), j = int(e / std::size_t(g.nx));
    scene eye = s;
    place_observer(eye, g, g.x_at(i), g.y_at(j));
    frame_eye_render(eye, aerial, p);
    out.visible[e] = visible_fraction(parts, observer_position(eye), p.rows_per_eye);
    // Every eye is rendered: the display may be seen directly where the aerial image is not.
    const eye_render r = render_from(ts, device, eye, p, cancel);
    out.direct[e] = r.direct / display_luminance(ts);
    out.luminance[e] = r.seen.aerial_luminance;
    out.contrast[e] = r.seen.contrast;
    for (std::size_t k = 0; k < out.contrast_share.size(); ++k) out.contrast_share[k][e] = r.seen.share_above[k];
    if (out.visible[e] > 0) {
      out.brightness[e] = r.aerial;
      out.stray_ratio[e] = r.stray_ratio();
      try {
        const psf_samples psf = scene_psf(eye, models, p.psf_samples);
        out.mean_mtf[e] = psf_route_mtf(psf, 0.0).mean_mtf;
        const legible_character c = psf_legible_character(eye, psf, r.seen.contrast, p.legibility);
        out.char_height_mm[e] = c.height_mm;
        out.char_arcmin[e] = c.arcmin;
      } catch (const input_error&) {
        // The chief ray through the aerial image's centre misses every sheet from here.
      }
    }
  };
  auto take = [&] {
    std::unique_ptr<tracer_scene> ts;
    {
      std::lock_guard lock(mutex);
      if (!pool.empty()) ts = std::move(pool.back()), pool.pop_back();
    }
    if (!ts) {
      ts = std::make_unique<tracer_scene>();
      ts->use_model_image = false;  // a few spp per eye: the model image would cost more than it saves
      ts->retro = models;
    }
    return ts;
  };
  auto give_back = [&](std::unique_ptr<tracer_scene> ts) {
    std::lock_guard lock(mutex);
    pool.push_back(std::move(ts));
  };
  auto count_done = [&] {
    std::lock_guard lock(mutex);
    ++done;
    if (progress) progress(done, int(n));
  };
  if (share) {
    // Each eye's numbers as a shared item (an MPI job's ranks); every caller gets them all.
    std::vector<std::vector<double>*> maps = {&out.visible,     &out.brightness,     &out.mean_mtf,
                                              &out.stray_ratio, &out.direct,         &out.luminance,
                                              &out.contrast,    &out.char_height_mm, &out.char_arcmin};
    for (auto& m : out.contrast_share) maps.push_back(&m);
    const std::size_t count = maps.size();
    const std::vector<double> values = share(n, count, [&](std::size_t e, double* o) {
      std::unique_ptr<tracer_scene> ts = take();
      one_eye(e, *ts);
      give_back(std::move(ts));
      for (std::size_t k = 0; k < count; ++k) o[k] = (*maps[k])[e];
      count_done();
    });
    for (std::size_t e = 0; e < n; ++e)
      for (std::size_t k = 0; k < count; ++k) (*maps[k])[e] = values[count * e + k];
  } else {
    detail::parallel_rows(int(n), 0, [&](int e0, int e1) {
      std::unique_ptr<tracer_scene> ts = take();
      for (int e = e0; e < e1 && !cancel_requested(cancel); ++e) {
        one_eye(std::size_t(e), *ts);
        count_done();
      }
      give_back(std::move(ts));
    });
  }
  if (cancel_requested(cancel)) return {};
  double best = 0;
  for (double b : out.brightness) {
    if (std::isfinite(b)) best = std::max(best, b);
  }
  for (double& b : out.brightness) {
    if (std::isfinite(b)) b = best > 0 ? b / best : nan;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace airr
