// The display on the model image's grids, and their correlation with a bin's kernel.
#include "model_image_steps.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "airr/core/cancel.hpp"

namespace airr::model_image_steps {

cv::Mat display_texels(const scene& s, const image_rgb* display, int max_texels) {
  cv::Mat m;
  if (display) {
    m = cv::Mat(display->height, display->width, CV_32FC3, const_cast<float*>(display->rgb.data()));
  } else {
    const part_frame src = source_frame(s);
    const double longer = std::max(src.width, src.height);
    m = cv::Mat(std::max(1, int(std::lround(max_texels * src.height / longer))),
                std::max(1, int(std::lround(max_texels * src.width / longer))), CV_32FC3,
                cv::Scalar::all(white_radiance(s.source)));
  }
  const int longer = std::max(m.cols, m.rows);
  if (longer > max_texels) {
    const double f = double(max_texels) / longer;
    cv::Mat small;
    cv::resize(m, small, cv::Size(std::max(1, int(std::lround(m.cols * f))), std::max(1, int(std::lround(m.rows * f)))),
               0, 0, cv::INTER_AREA);
    m = small;
  }
  if (display) {
    // Into a new matrix: `m` may still be the caller's texture itself.
    cv::Mat scaled;
    m.convertTo(scaled, CV_32F, white_radiance(s.source));
    return scaled;
  }
  return m;
}

// The texels' bilinear surface (edges clamped, as the tracer reads its texture) sampled `refine`
// times more densely: nodes at texel coordinates origin + j / refine. With an even `refine` the
// nodes start half a texel out and include every texel centre, so the refined grid's bilinear
// surface is the texels' own, exactly.
// Empty when `cancel` is set before it is done (a display's grid takes a fifth of a second).
static image_rgb refined_grid(const cv::Mat& texels, int refine, double& origin, const std::atomic<bool>* cancel) {
  origin = refine % 2 == 0 ? -0.5 : 0.0;
  image_rgb out;
  out.width = int(std::lround((texels.cols - 1 - 2 * origin) * refine)) + 1;
  out.height = int(std::lround((texels.rows - 1 - 2 * origin) * refine)) + 1;
  out.rgb.resize(std::size_t(out.width) * out.height * 3);
  auto texel = [&](int x, int y) {
    const cv::Vec3f& v = texels.at<cv::Vec3f>(std::clamp(y, 0, texels.rows - 1), std::clamp(x, 0, texels.cols - 1));
    return glm::vec3(v[0], v[1], v[2]);
  };
  for (int j = 0; j < out.height; ++j) {
    if (j % 64 == 0 && cancel_requested(cancel)) return {};
    const double ty = origin + double(j) / refine;
    const int y0 = int(std::floor(ty));
    const float fy = float(ty - y0);
    for (int i = 0; i < out.width; ++i) {
      const double tx = origin + double(i) / refine;
      const int x0 = int(std::floor(tx));
      const float fx = float(tx - x0);
      const glm::vec3 v = glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                                   glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
      std::copy_n(&v.x, 3, out.at(i, j));
    }
  }
  return out;
}

static image_rgb pad(const image_rgb& img, int radius) {
  image_rgb out;
  out.width = img.width + 2 * radius;
  out.height = img.height + 2 * radius;
  out.rgb.assign(std::size_t(out.width) * out.height * 3, 0.0f);
  for (int y = 0; y < img.height; ++y) std::copy_n(img.at(0, y), 3 * img.width, out.at(radius, y + radius));
  return out;
}

static bool is_grey(const image_rgb& img) {
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
    if (img.rgb[i] != img.rgb[i + 1] || img.rgb[i] != img.rgb[i + 2]) return false;
  }
  return true;
}

grid_spectrum spectrum_of(const image_rgb& padded, const std::atomic<bool>* cancel) {
  grid_spectrum out;
  out.width = padded.width;
  out.height = padded.height;
  out.fft_width = cv::getOptimalDFTSize(padded.width);
  out.fft_height = cv::getOptimalDFTSize(padded.height);
  const int n = is_grey(padded) ? 1 : 3;
  const std::size_t reals = std::size_t(out.fft_width) * out.fft_height;
  for (int c = 0; c < n; ++c) {
    if (cancel_requested(cancel)) return {};
    fft_buffer<float> channel = real_buffer(reals);
    std::fill_n(channel.data.get(), reals, 0.0f);
    for (int y = 0; y < padded.height; ++y) {
      const float* src = padded.at(0, y) + c;
      float* dst = channel.data.get() + std::size_t(y) * out.fft_width;
      for (int x = 0; x < padded.width; ++x) dst[x] = src[3 * x];
    }
    fft_buffer<std::complex<float>> spectrum = complex_buffer(std::size_t(out.fft_height) * (out.fft_width / 2 + 1));
    fft_forward(out.fft_width, out.fft_height, channel.data.get(), spectrum.data.get());
    out.channels.push_back(std::move(spectrum));
  }
  return out;
}

namespace {

template <class T>
void fit(fft_buffer<T>& b, std::size_t n, fft_buffer<T> (*make)(std::size_t)) {
  if (b.size != n) b = make(n);
}

}  // namespace

correlated_grid correlate(const grid_spectrum& grid, const cv::Mat& kernel, correlate_scratch& scratch,
                          const std::atomic<bool>* cancel) {
  const int w = grid.fft_width, h = grid.fft_height, r = kernel.rows / 2;
  const std::size_t reals = std::size_t(w) * h, complexes = std::size_t(h) * (w / 2 + 1);
  // The kernel's rows, offsets 0 to r then -r to -1 (the transform's first and last rows), each
  // with offset o at index o modulo the transform's width.
  fit(scratch.rows, std::size_t(w) * (2 * r + 1), real_buffer);
  std::fill_n(scratch.rows.data.get(), scratch.rows.size, 0.0f);
  for (int y = -r; y <= r; ++y) {
    const float* row = kernel.ptr<float>(y + r);
    float* dst = scratch.rows.data.get() + std::size_t(y >= 0 ? y : 2 * r + 1 + y) * w;
    for (int x = -r; x <= r; ++x) dst[(x + w) % w] = row[x + r];
  }
  fit(scratch.kernel_spectrum, complexes, complex_buffer);
  fft_forward_end_rows(w, h, r + 1, r, scratch.rows.data.get(), scratch.kernel_spectrum.data.get());
  fit(scratch.product, complexes, complex_buffer);
  correlated_grid out;
  out.cols = grid.width;
  out.rows = grid.height;
  out.stride = w;
  // Correlation: the grid's spectrum times the kernel's conjugate, back, scaled by 1 / (w h).
  const float scale = 1.0f / float(reals);
  const std::complex<float>* k = scratch.kernel_spectrum.data.get();
  std::complex<float>* product = scratch.product.data.get();
  for (const auto& channel : grid.channels) {
    if (cancel_requested(cancel)) return {};
    for (std::size_t i = 0; i < complexes; ++i) product[i] = channel.data[i] * std::conj(k[i]) * scale;
    fft_buffer<float> values;
    if (!scratch.spare_values.empty() && scratch.spare_values.back().size == reals) {
      values = std::move(scratch.spare_values.back());
      scratch.spare_values.pop_back();
    } else {
      values = real_buffer(reals);
    }
    fft_inverse(w, h, product, values.data.get());
    out.channels.push_back(std::move(values));
  }
  return out;
}

void correlate_scratch::take_back(correlated_grid&& done) {
  for (auto& c : done.channels) spare_values.push_back(std::move(c));
  done.channels.clear();
}

grid_mapping make_grid(model_grid& grid, const cv::Mat& texels, int refine, double reach_mm, const part_frame& src,
                       const std::atomic<bool>* cancel) {
  grid_mapping map;
  const image_rgb nodes = refined_grid(texels, refine, map.origin, cancel);
  grid.node_w = src.width / texels.cols / refine;
  grid.node_h = src.height / texels.rows / refine;
  grid.radius = std::clamp(int(std::ceil(reach_mm / std::min(grid.node_w, grid.node_h))) + 1, 2, 2048);
  grid.edges_on_nodes = refine % 2 == 0;  // the nodes start half a texel out: at the display's edge
  if (!nodes.rgb.empty()) grid.padded = pad(nodes, grid.radius);
  if (!grid.padded.rgb.empty() && is_grey(grid.padded)) {
    grid.grey.resize(grid.padded.rgb.size() / 3);
    for (std::size_t i = 0; i < grid.grey.size(); ++i) grid.grey[i] = grid.padded.rgb[3 * i];
  }
  map.cols = texels.cols;
  map.rows = texels.rows;
  map.width = src.width;
  map.height = src.height;
  map.refine = refine;
  map.radius = grid.radius;
  return map;
}

}  // namespace airr::model_image_steps
