#include "airr/analysis/fit_simulation.hpp"

#include "airr/core/geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "airr/layout/layout.hpp"

namespace airr::analysis {

namespace {

double hamming(double t) { return 0.54 + 0.46 * std::cos(std::numbers::pi * t); }

}  // namespace

psf_mtf_curve measured_like_mtf(const psf_samples& psf, const psf_mtf_params& params, double window_half_width_mm,
                                bool along_y) {
  auto axis = [&](std::size_t i) { return along_y ? psf.offset_mm[i].y : psf.offset_mm[i].x; };
  double centre = 0;
  if (window_half_width_mm > 0) {
    // The measurement centres its window on the edge, the LSF's windowed centroid.
    for (int iter = 0; iter < 8; ++iter) {
      double sw = 0, sx = 0;
      for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
        const double t = (axis(i) - centre) / window_half_width_mm;
        if (std::abs(t) >= 1) continue;
        sw += psf.weight[i] * hamming(t);
        sx += psf.weight[i] * hamming(t) * axis(i);
      }
      if (sw > 0) centre = sx / sw;
    }
  }
  // psf_mtf's estimator on its frequency grid, with the phase advanced by a recurrence: one sine
  // and cosine per sample instead of one per sample and frequency (the fit evaluates it often).
  // Four samples' recurrences run side by side: each is a chain of dependent multiplications.
  const int n = std::max(1, params.points);
  const double df = params.max_lp_per_mm / std::max(1, n - 1);
  std::vector<double> re(std::size_t(n), 0.0), im(std::size_t(n), 0.0);
  constexpr int lanes = 4;
  std::array<double, lanes> z_re{}, z_im{}, step_re{}, step_im{};
  int pending = 0;
  auto advance = [&] {
    for (int k = 0; k < n; ++k) {
      double sum_re = 0, sum_im = 0;
      for (int j = 0; j < lanes; ++j) {
        sum_re += z_re[j];
        sum_im += z_im[j];
        const double next_re = z_re[j] * step_re[j] - z_im[j] * step_im[j];
        z_im[j] = z_re[j] * step_im[j] + z_im[j] * step_re[j];
        z_re[j] = next_re;
      }
      re[std::size_t(k)] += sum_re;
      im[std::size_t(k)] += sum_im;
    }
  };
  double total = 0;
  for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
    const double x = axis(i) - centre;
    double w = psf.weight[i];
    if (window_half_width_mm > 0) {
      const double t = x / window_half_width_mm;
      if (std::abs(t) >= 1) continue;
      w *= hamming(t);
    }
    total += w;
    const double phase = -2.0 * std::numbers::pi * df * x;
    step_re[pending] = std::cos(phase);
    step_im[pending] = std::sin(phase);
    z_re[pending] = w;
    z_im[pending] = 0;
    if (++pending == lanes) {
      advance();
      pending = 0;
    }
  }
  if (pending > 0) {
    // The lanes left empty carry no weight.
    for (int j = pending; j < lanes; ++j) z_re[j] = z_im[j] = 0;
    advance();
  }
  psf_mtf_curve curve;
  for (int k = 0; k < n; ++k) {
    const double f = df * k;
    double m = total > 0 ? std::hypot(re[std::size_t(k)], im[std::size_t(k)]) / total : 0.0;
    if (params.pixel_mm > 0 && f > 0) {
      const double u = std::numbers::pi * f * params.pixel_mm;
      m *= std::abs(std::sin(u) / u);
    }
    curve.lp_per_mm.push_back(f);
    curve.mtf.push_back(m);
  }
  return curve;
}

cv::Mat white_square_image(const scene& s, const psf_samples& psf, double width_mm, double height_mm) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s);
  const pinhole_camera cam = make_camera(s);
  auto aerial = [&](const glm::dvec3& p) { return mirror_point(p, hm.center, hm.n); };
  // The square's ideal image, a rectangle in pixel coordinates (x right, y down).
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double su : {-0.5, 0.5}) {
    for (double sv : {-0.5, 0.5}) {
      const glm::dvec2 q = camera_project(cam, aerial(src.center + su * width_mm * src.u + sv * height_mm * src.v));
      x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
    }
  }
  // An offset on the aerial-image plane (x right, y up) moves the image by this many pixels.
  const glm::dvec3 c = aerial(src.center);
  const glm::dvec2 p0 = camera_project(cam, c);
  const glm::dvec2 jx = camera_project(cam, c + glm::dvec3(1, 0, 0)) - p0,
                   jy = camera_project(cam, c + glm::dvec3(0, 1, 0)) - p0;

  // Splat the PSF bilinearly onto integer pixel shifts that can bring light into the frame.
  const int W = cam.width, H = cam.height;
  const int mx0 = int(std::floor(-x1)) - 1, mx1 = int(std::ceil(W - x0)) + 1;
  const int my0 = int(std::floor(-y1)) - 1, my1 = int(std::ceil(H - y0)) + 1;
  const int kw = mx1 - mx0 + 1, kh = my1 - my0 + 1;
  std::vector<double> kernel(std::size_t(kw) * kh, 0.0);
  for (std::size_t k = 0; k < psf.offset_mm.size(); ++k) {
    const glm::dvec2 shift = psf.offset_mm[k].x * jx + psf.offset_mm[k].y * jy;
    const double fx = std::floor(shift.x), fy = std::floor(shift.y), tx = shift.x - fx, ty = shift.y - fy;
    if (fx < mx0 || fx + 1 > mx1 || fy < my0 || fy + 1 > my1) continue;
    const std::size_t ix = std::size_t(int(fx) - mx0), iy = std::size_t(int(fy) - my0);
    kernel[iy * kw + ix] += psf.weight[k] * (1 - tx) * (1 - ty);
    kernel[iy * kw + ix + 1] += psf.weight[k] * tx * (1 - ty);
    kernel[(iy + 1) * kw + ix] += psf.weight[k] * (1 - tx) * ty;
    kernel[(iy + 1) * kw + ix + 1] += psf.weight[k] * tx * ty;
  }
  // Fraction of pixel [p, p + 1) the shifted rectangle covers along one axis.
  auto overlap = [](double p, double lo, double hi) { return std::max(0.0, std::min(p + 1, hi) - std::max(p, lo)); };
  // The square's coverage is separable: sum over shifts of K(mx, my) ox(i - mx) oy(j - my).
  std::vector<double> rows(std::size_t(kh) * W, 0.0);  // [my][i]
  for (int my = 0; my < kh; ++my) {
    const double* krow = kernel.data() + std::size_t(my) * kw;
    if (std::all_of(krow, krow + kw, [](double v) { return v == 0; })) continue;
    for (int i = 0; i < W; ++i) {
      double sum = 0;
      for (int mx = 0; mx < kw; ++mx) {
        if (krow[mx] != 0) sum += krow[mx] * overlap(i - (mx + mx0), x0, x1);
      }
      rows[std::size_t(my) * W + i] = sum;
    }
  }
  cv::Mat img(H, W, CV_64FC1, cv::Scalar(0));
  const double scale = psf.launched ? white_radiance(s.source) / double(psf.launched) : 0.0;
  for (int j = 0; j < H; ++j) {
    double* out = img.ptr<double>(j);
    for (int my = 0; my < kh; ++my) {
      const double oy = overlap(j - (my + my0), y0, y1);
      if (oy == 0) continue;
      const double* r = rows.data() + std::size_t(my) * W;
      for (int i = 0; i < W; ++i) out[i] += oy * r[i];
    }
    for (int i = 0; i < W; ++i) out[i] *= scale;
  }
  return img;
}

}  // namespace airr::analysis
