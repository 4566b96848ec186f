// One sample of the model: where it lands on the grids, the bins' kernels, and the prediction for a
// tracer sample.
#include "model_image_steps.hpp"

#include <algorithm>
#include <cmath>

#include "airr/core/cancel.hpp"
#include "airr/core/low_discrepancy.hpp"
#include "airr/core/random.hpp"
#include "airr/render/parallel_rows.hpp"

namespace airr::model_image_steps {

// A grid's bilinear surface at node point `t` (black beyond the grid), its nodes read by texel(x, y):
// RGB, or the one channel of a grey display's grid.
template <typename V, typename Texel>
V bilinear_on(int width, int height, const Texel& texel, const glm::dvec2& t) {
  const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= width || y0 + 1 >= height) return V(0.0f);
  const float fx = float(t.x - x0), fy = float(t.y - y0);
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                  glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

static auto rgb_texel(const image_rgb& m) {
  return [&m](int x, int y) {
    const float* p = m.at(x, y);
    return glm::vec3(p[0], p[1], p[2]);
  };
}

glm::vec3 bilinear(const image_rgb& m, const glm::dvec2& t) {
  return bilinear_on<glm::vec3>(m.width, m.height, rgb_texel(m), t);
}

// Where the model sends one sample: the grid and the offset in its nodes from the ideal point (the
// pixel jitter included), and its throughput; no grid when it is absorbed, misses the half mirror
// or lands beyond the kernels. Both the kernels and the predictions go through here.
static bin_landing landing_of(const model_image& m, const model_bin& b, const glm::dvec2& jitter,
                              const retro_sample& rs) {
  if (!(rs.weight > 0) || !rs.retroreflected) return {};
  const auto landing = psf_landing_of(b.chief, rs);
  if (!landing) return {};
  const glm::dvec3& delta = landing->offset;
  const glm::dvec2 mm =
      glm::dvec2(glm::dot(delta, b.chief.src.u), glm::dot(delta, b.chief.src.v)) + b.jitter_mm * (jitter - 0.5);
  for (int g : {model_fine, model_tail}) {
    const model_grid& grid = m.grids[g];
    const glm::dvec2 t(mm.x / grid.node_w, -mm.y / grid.node_h);  // node rows run down the display
    if (std::abs(t.x) < grid.radius - 1 && std::abs(t.y) < grid.radius - 1) return {t, rs.weight * m.hm_factor, g};
  }
  return {};
}

// An offset between whole nodes spreads over the four around it with bilinear weights, in the
// kernels and in the predictions alike, so that the kernels' mean is exactly the predictions'.
template <typename F>
void for_each_corner(const glm::dvec2& t, F&& f) {
  const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
  const double fx = t.x - x0, fy = t.y - y0;
  f(x0, y0, (1 - fx) * (1 - fy));
  f(x0 + 1, y0, fx * (1 - fy));
  f(x0, y0 + 1, (1 - fx) * fy);
  f(x0 + 1, y0 + 1, fx * fy);
}

template <typename V, typename Texel>
V spread_bilinear_on(int width, int height, const Texel& texel, const glm::dvec2& base, const glm::dvec2& t) {
  const glm::dvec2 b = glm::floor(base), n = glm::floor(t);
  const int x0 = int(b.x + n.x), y0 = int(b.y + n.y);
  if (x0 < 0 || y0 < 0 || x0 + 2 >= width || y0 + 2 >= height) {
    V sum(0.0f);
    for_each_corner(t, [&](int x, int y, double c) {
      sum += bilinear_on<V>(width, height, texel, base + glm::dvec2(x, y)) * float(c);
    });
    return sum;
  }
  auto weights = [](double f_base, double f_node) {
    return std::array<float, 3>{float((1 - f_node) * (1 - f_base)),
                                float((1 - f_node) * f_base + f_node * (1 - f_base)), float(f_node * f_base)};
  };
  const auto wx = weights(base.x - b.x, t.x - n.x), wy = weights(base.y - b.y, t.y - n.y);
  V sum(0.0f);
  for (int j = 0; j < 3; ++j) {
    V row(0.0f);
    for (int i = 0; i < 3; ++i) row += texel(x0 + i, y0 + j) * wx[std::size_t(i)];
    sum += row * wy[std::size_t(j)];
  }
  return sum;
}

glm::vec3 spread_bilinear(const image_rgb& grid, const glm::dvec2& base, const glm::dvec2& t) {
  return spread_bilinear_on<glm::vec3>(grid.width, grid.height, rgb_texel(grid), base, t);
}

glm::vec3 spread_bilinear(const model_grid& grid, const glm::dvec2& base, const glm::dvec2& t) {
  if (grid.grey.empty()) return spread_bilinear(grid.padded, base, t);
  const int width = grid.padded.width;
  const float* grey = grid.grey.data();
  const auto texel = [grey, width](int x, int y) { return grey[std::size_t(y) * std::size_t(width) + std::size_t(x)]; };
  return glm::vec3(spread_bilinear_on<float>(width, grid.padded.height, texel, base, t));
}

std::vector<std::vector<bin_landing>> bin_landings(const model_image& m, std::uint64_t samples, std::uint64_t seed,
                                                   detail::row_workers threads, const std::atomic<bool>* cancel) {
  const std::size_t bins = m.bins.size();
  std::vector<const retro_at_incidence*> at(bins);
  for (std::size_t k = 0; k < bins; ++k) at[k] = m.bins[k].sampler.get();
  std::vector<std::vector<bin_landing>> landed(bins, std::vector<bin_landing>(samples));
  const kernel_sequence sequence(seed);
  constexpr std::uint64_t block = 4096;
  detail::parallel_rows(int((samples + block - 1) / block), threads, [&](int b0, int b1) {
    std::vector<retro_sample> rs(bins);
    for (std::uint64_t i = std::uint64_t(b0) * block; i < std::min(samples, std::uint64_t(b1) * block); ++i) {
      if (i % block == 0 && cancel_requested(cancel)) return;
      glm::dvec2 jitter;
      retro_samples u;
      sequence.at(i, jitter, u);
      sample_at_each(at, u, rs);
      for (std::size_t k = 0; k < bins; ++k) landed[k][i] = landing_of(m, m.bins[k], jitter, rs[k]);
    }
  });
  if (cancel_requested(cancel)) return {};
  return landed;
}

std::array<cv::Mat, 2> bin_kernels(const model_image& m, const std::vector<bin_landing>& landed,
                                   detail::row_workers threads, const std::atomic<bool>* cancel,
                                   std::vector<fine_sample>* fine, std::uint64_t fine_count) {
  auto zero = [&] {
    std::array<cv::Mat, 2> k;
    for (int g : {model_fine, model_tail}) {
      const int n = 2 * m.grids[g].radius + 1;
      k[std::size_t(g)] = cv::Mat(n, n, CV_64F, cv::Scalar(0));
    }
    return k;
  };
  const std::uint64_t samples = landed.size();
  constexpr std::uint64_t block = 65536;  // few partial kernels: each is as large as the kernel
  const std::size_t blocks = std::size_t((samples + block - 1) / block);
  std::vector<std::array<cv::Mat, 2>> parts(blocks);
  std::vector<std::vector<fine_sample>> first_fine(fine ? blocks : 0);
  auto block_kernels = [&](std::size_t k) {
    std::array<cv::Mat, 2> part = zero();
    const std::uint64_t end = std::min<std::uint64_t>(samples, (k + 1) * block);
    for (std::uint64_t i = k * block; i < end; ++i) {
      const bin_landing& o = landed[i];
      if (o.grid < 0) continue;
      if (fine && i < fine_count && o.grid == model_fine) first_fine[k].push_back({o.nodes, o.w});
      cv::Mat& kernel = part[std::size_t(o.grid)];
      const int r = m.grids[o.grid].radius;
      for_each_corner(o.nodes, [&](int x, int y, double c) { kernel.at<double>(y + r, x + r) += o.w * c; });
    }
    return part;
  };
  detail::parallel_rows(int(blocks), threads, [&](int b0, int b1) {
    for (int k = b0; k < b1 && !cancel_requested(cancel); ++k) {
      parts[std::size_t(k)] = block_kernels(std::size_t(k));
    }
  });
  std::array<cv::Mat, 2> sum = zero(), out;
  for (const auto& part : parts) {
    if (part[0].empty()) continue;  // cancelled
    for (std::size_t g = 0; g < 2; ++g) sum[g] += part[g];
  }
  for (std::size_t g = 0; g < 2; ++g) sum[g].convertTo(out[g], CV_32F, 1.0 / double(samples));
  for (auto& part : first_fine) fine->insert(fine->end(), part.begin(), part.end());
  return out;
}

}  // namespace airr::model_image_steps

namespace airr {

using namespace model_image_steps;

kernel_sequence::kernel_sequence(std::uint64_t seed) : seed_(seed) {
  pcg32 rotation_rng = sample_rng(0, 0, seed ^ 0x6b65726eu);
  for (double& r : rotation_) r = rotation_rng.next_double();
}

void kernel_sequence::at(std::uint64_t i, glm::dvec2& jitter, retro_samples& u) const {
  const std::array<double, 6> q = r6_point(i, rotation_);
  jitter = {q[0], q[1]};
  u.lobe = {q[2], q[3]};
  u.shift = {q[4], q[5]};
  u.more = sample_rng(i, 0, seed_ ^ 0x6d6f7265u);
}

glm::vec3 model_prediction(const model_image& m, int px, int py, const glm::dvec2& jitter, const retro_samples& u) {
  if (m.pixels.empty()) return model_prediction(m, model_pixel_at(m, px, py), jitter, u);
  return model_prediction(m, m.pixels[std::size_t(py) * m.image.width + px], jitter, u);
}

glm::vec3 model_prediction(const model_image& m, const model_pixel& p, const glm::dvec2& jitter,
                           const retro_samples& u) {
  if (!p.ok) return glm::vec3(0.0f);
  const std::size_t count = p.mix > 0 ? 2 : 1;
  const std::array<const retro_at_incidence*, 2> at{
      m.bins[std::size_t(p.bin)].sampler.get(), count == 2 ? m.bins[std::size_t(p.bin) + 1].sampler.get() : nullptr};
  std::array<retro_sample, 2> rs;
  sample_at_each(std::span(at.data(), count), u, rs);
  auto one = [&](std::size_t k) {
    const bin_landing o = landing_of(m, m.bins[std::size_t(p.bin) + k], jitter, rs[k]);
    if (o.grid < 0) return glm::vec3(0.0f);
    return grid_value(m.grids[o.grid], p.node[o.grid], o.nodes) * float(o.w * p.profile);
  };
  glm::vec3 v = one(0) * float(1 - p.mix);
  if (count == 2) v += one(1) * float(p.mix);
  return v;
}

}  // namespace airr
