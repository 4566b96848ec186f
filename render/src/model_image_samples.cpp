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

glm::vec3 bilinear(const image_rgb& m, const glm::dvec2& t) {
  const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= m.width || y0 + 1 >= m.height) return glm::vec3(0.0f);
  const float fx = float(t.x - x0), fy = float(t.y - y0);
  auto texel = [&](int x, int y) {
    const float* p = m.at(x, y);
    return glm::vec3(p[0], p[1], p[2]);
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                  glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

// Where the model sends one sample: the grid and the offset in its nodes from the ideal point (the
// pixel jitter included), and its throughput; empty when it is absorbed, misses the half mirror or
// lands beyond the kernels. Both the kernels and the predictions go through here.
struct grid_offset {
  int grid;
  glm::dvec2 nodes;
};
static std::optional<grid_offset> sample_offset(const model_image& m, const model_bin& b, const glm::dvec2& jitter,
                                                const retro_samples& u, double& weight) {
  const retro_sample rs = b.sampler->sample(u);
  if (!(rs.weight > 0) || !rs.retroreflected) return std::nullopt;
  const auto landing = psf_landing_of(b.chief, rs);
  if (!landing) return std::nullopt;
  const glm::dvec3& delta = landing->offset;
  const glm::dvec2 mm =
      glm::dvec2(glm::dot(delta, b.chief.src.u), glm::dot(delta, b.chief.src.v)) + b.jitter_mm * (jitter - 0.5);
  weight = rs.weight * m.hm_factor;
  for (int g : {model_fine, model_tail}) {
    const model_grid& grid = m.grids[g];
    const glm::dvec2 t(mm.x / grid.node_w, -mm.y / grid.node_h);  // node rows run down the display
    if (std::abs(t.x) < grid.radius - 1 && std::abs(t.y) < grid.radius - 1) return grid_offset{g, t};
  }
  return std::nullopt;
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

glm::vec3 spread_bilinear(const image_rgb& grid, const glm::dvec2& base, const glm::dvec2& t) {
  const glm::dvec2 b = glm::floor(base), n = glm::floor(t);
  const int x0 = int(b.x + n.x), y0 = int(b.y + n.y);
  if (x0 < 0 || y0 < 0 || x0 + 2 >= grid.width || y0 + 2 >= grid.height) {
    glm::vec3 sum(0.0f);
    for_each_corner(t, [&](int x, int y, double c) { sum += bilinear(grid, base + glm::dvec2(x, y)) * float(c); });
    return sum;
  }
  auto weights = [](double f_base, double f_node) {
    return std::array<float, 3>{float((1 - f_node) * (1 - f_base)),
                                float((1 - f_node) * f_base + f_node * (1 - f_base)), float(f_node * f_base)};
  };
  const auto wx = weights(base.x - b.x, t.x - n.x), wy = weights(base.y - b.y, t.y - n.y);
  glm::vec3 sum(0.0f);
  for (int j = 0; j < 3; ++j) {
    glm::vec3 row(0.0f);
    for (int i = 0; i < 3; ++i) {
      const float* v = grid.at(x0 + i, y0 + j);
      row += glm::vec3(v[0], v[1], v[2]) * wx[std::size_t(i)];
    }
    sum += row * wy[std::size_t(j)];
  }
  return sum;
}

std::array<cv::Mat, 2> bin_kernels(const model_image& m, const model_bin& b, std::size_t bin, std::uint64_t samples,
                                   std::uint64_t seed, detail::row_workers threads, const std::atomic<bool>* cancel,
                                   std::vector<fine_sample>* fine, std::uint64_t fine_count) {
  const kernel_sequence sequence(bin, seed);
  auto zero = [&] {
    std::array<cv::Mat, 2> k;
    for (int g : {model_fine, model_tail}) {
      const int n = 2 * m.grids[g].radius + 1;
      k[std::size_t(g)] = cv::Mat(n, n, CV_64F, cv::Scalar(0));
    }
    return k;
  };
  constexpr std::uint64_t block = 65536;  // few partial kernels: each is as large as the kernel
  const std::size_t blocks = std::size_t((samples + block - 1) / block);
  std::vector<std::array<cv::Mat, 2>> parts(blocks);
  std::vector<std::vector<fine_sample>> landed(fine ? blocks : 0);
  auto block_kernels = [&](std::size_t k) {
    std::array<cv::Mat, 2> part = zero();
    const std::uint64_t end = std::min<std::uint64_t>(samples, (k + 1) * block);
    for (std::uint64_t i = k * block; i < end; ++i) {
      glm::dvec2 jitter;
      retro_samples u;
      sequence.at(i, jitter, u);
      double w = 0;
      const auto o = sample_offset(m, b, jitter, u, w);
      if (!o) continue;
      if (fine && i < fine_count && o->grid == model_fine) landed[k].push_back({o->nodes, w});
      cv::Mat& kernel = part[std::size_t(o->grid)];
      const int r = m.grids[o->grid].radius;
      for_each_corner(o->nodes, [&](int x, int y, double c) { kernel.at<double>(y + r, x + r) += w * c; });
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
  for (auto& part : landed) fine->insert(fine->end(), part.begin(), part.end());
  return out;
}

}  // namespace airr::model_image_steps

namespace airr {

using namespace model_image_steps;

kernel_sequence::kernel_sequence(std::size_t bin, std::uint64_t seed) : bin_(bin), seed_(seed) {
  pcg32 rotation_rng = sample_rng(bin, 0, seed ^ 0x6b65726eu);
  for (double& r : rotation_) r = rotation_rng.next_double();
}

void kernel_sequence::at(std::uint64_t i, glm::dvec2& jitter, retro_samples& u) const {
  const std::array<double, 6> q = r6_point(i, rotation_);
  jitter = {q[0], q[1]};
  u.lobe = {q[2], q[3]};
  u.shift = {q[4], q[5]};
  u.more = sample_rng(i, bin_, seed_ ^ 0x6d6f7265u);
}

glm::vec3 model_prediction(const model_image& m, int px, int py, const glm::dvec2& jitter, const retro_samples& u) {
  if (m.pixels.empty()) return model_prediction(m, model_pixel_at(m, px, py), jitter, u);
  return model_prediction(m, m.pixels[std::size_t(py) * m.image.width + px], jitter, u);
}

glm::vec3 model_prediction(const model_image& m, const model_pixel& p, const glm::dvec2& jitter,
                           const retro_samples& u) {
  if (!p.ok) return glm::vec3(0.0f);
  auto one = [&](int k) {
    double weight = 0;
    const auto o = sample_offset(m, m.bins[std::size_t(k)], jitter, u, weight);
    if (!o) return glm::vec3(0.0f);
    return grid_value(m.grids[o->grid], p.node[o->grid], o->nodes) * float(weight * p.profile);
  };
  glm::vec3 v = one(p.bin) * float(1 - p.mix);
  if (p.mix > 0) v += one(p.bin + 1) * float(p.mix);
  return v;
}

}  // namespace airr
