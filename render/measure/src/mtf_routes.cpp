#include "airr/measure/mtf_routes.hpp"

#include <algorithm>
#include <cmath>

#include "airr/analysis/image_read.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

psf_samples scene_psf(const scene& s, std::uint64_t samples) { return scene_psf(s, make_sheet_models(s), samples); }

psf_samples scene_psf(const scene& s, const retro_model_list& models, std::uint64_t samples) {
  return sample_psf(s, models, {.samples = samples, .seed = s.seed});
}

mtf_summary psf_route_mtf(const psf_samples& psf, double pixel_mm) {
  mtf_summary m;
  m.mm_per_pixel = pixel_mm;
  if (psf.offset_mm.empty()) return m;  // no light arrives: nothing to resolve
  m.mean_mtf = analysis::psf_mean_mtf(psf, 1.0, pixel_mm);
  // Search MTF50 up to the sampling frequency, as the edge route does (1 cycle/pixel); the
  // optics alone are searched up to 4 lp/mm.
  const double top = pixel_mm > 0 ? 1.0 / pixel_mm : 4.0;
  const auto curve = analysis::psf_mtf(psf, {.max_lp_per_mm = top, .points = 161, .pixel_mm = pixel_mm});
  if (const double f = analysis::psf_mtf50(curve); f > 0) m.mtf50_lp_per_mm = f;
  return m;
}

double display_pixel_mm(const scene& s) {
  if (s.source.image.empty()) return 0;
  const auto img = cached_image_pixels(resolve_scene_path(s, s.source.image));
  return std::max(s.source.width_mm / img->width, s.source.height_mm / img->height);
}

legible_character psf_legible_character(const scene& s, const psf_samples& psf, double contrast,
                                        const legibility_criterion& criterion) {
  const double distance_mm = glm::length(observer_position(s) - aerial_image_center(s));
  constexpr double top = 20;  // lp/mm: finer than any eye resolves at reading distance
  if (psf.offset_mm.empty())
    return smallest_legible_character([](double) { return 0.0; }, top, contrast, distance_mm, 0, criterion);
  const auto x = analysis::psf_mtf(psf, {.max_lp_per_mm = top, .points = 801});
  const auto y = analysis::psf_mtf(psf, {.max_lp_per_mm = top, .points = 801, .along_y = true});
  const auto mtf_at = [&](double f) {
    const double at = std::clamp(f / top * 800, 0.0, 800.0);
    const std::size_t i = std::min<std::size_t>(std::size_t(at), 799);
    const double t = at - double(i);
    return std::min((1 - t) * x.mtf[i] + t * x.mtf[i + 1], (1 - t) * y.mtf[i] + t * y.mtf[i + 1]);
  };
  return smallest_legible_character(mtf_at, top, contrast, distance_mm, display_pixel_mm(s), criterion);
}

scene with_edge_chart(scene s, const std::string& chart_path) {
  s.source.image = chart_path;
  return s;
}

cv::Rect aerial_image_roi(const scene& s, double u0, double v0, double u1, double v1) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s);
  const pinhole_camera cam = make_camera(s);
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double u : {u0, u1}) {
    for (double v : {v0, v1}) {
      const glm::dvec3 p = part_point(src, (u - 0.5) * src.width, (0.5 - v) * src.height);
      const glm::dvec2 q = camera_project(cam, mirror_point(p, hm.center, hm.n));
      x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
    }
  }
  const int left = std::max(0, int(std::ceil(x0))), top = std::max(0, int(std::ceil(y0)));
  const int right = std::min(cam.width, int(std::floor(x1))), bottom = std::min(cam.height, int(std::floor(y1)));
  return {left, top, std::max(0, right - left), std::max(0, bottom - top)};
}

cv::Rect source_image_roi(const scene& s, double fraction) {
  const cv::Rect r =
      aerial_image_roi(s, 0.5 - 0.5 * fraction, 0.5 - 0.5 * fraction, 0.5 + 0.5 * fraction, 0.5 + 0.5 * fraction);
  if (r.width < 8 || r.height < 8) throw input_error("edge MTF: the source's image is not in the camera's view");
  return r;
}

cv::Mat snapshot_luminance(const render_snapshot& snap) { return snapshot_luminance(snap, *snap.rgb); }

cv::Mat snapshot_luminance(const render_snapshot& snap, const std::vector<float>& rgb_values) {
  cv::Mat rgb(snap.height, snap.width, CV_32FC3, const_cast<float*>(rgb_values.data()));
  return analysis::rec709_luminance(rgb);
}

mtf_summary edge_route_mtf(const scene& s, const render_snapshot& snap, double roi_fraction) {
  const auto curve = analysis::slanted_edge_mtf(snapshot_luminance(snap), {.roi = source_image_roi(s, roi_fraction)});
  mtf_summary m;
  m.mm_per_pixel = snap.mm_per_pixel;
  m.mean_mtf = analysis::mean_mtf(curve, snap.mm_per_pixel).value;
  if (const auto m50 = analysis::mtf50(curve, snap.mm_per_pixel)) m.mtf50_lp_per_mm = m50->lp_per_mm;
  return m;
}

}  // namespace airr
