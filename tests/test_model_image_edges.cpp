// The model image at the display's edges, where the fine grid's nodes put them: a prediction steps
// to black at the edge as the tracer's display does, and the model image is still the mean of the
// predictions it is made of.
#include <cmath>

#include <gtest/gtest.h>

#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The mean of pixel (x, y)'s predictions over the first n samples of the bins' kernel sequence.
glm::dvec3 mean_prediction(const model_image& m, int x, int y, std::uint64_t n, std::uint64_t seed) {
  const kernel_sequence sequence(seed);
  glm::dvec3 sum(0.0);
  for (std::uint64_t i = 0; i < n; ++i) {
    glm::dvec2 jitter;
    retro_samples u;
    sequence.at(i, jitter, u);
    sum += glm::dvec3(model_prediction(m, x, y, jitter, u));
  }
  return sum / double(n);
}

// The default scene's model image at size x size with one angle bin, `samples` kernel samples (all
// of them counted at the edges) and the given refine: whether its edges lie on nodes, its peak, and
// the largest difference between one of `pixels` and the mean of its predictions from those samples.
struct identity_check {
  bool made = false, edges_on_nodes = false;
  double peak = 0, worst = 0;
};
identity_check check_identity(int size, int refine, std::uint64_t samples,
                              const std::vector<std::pair<int, int>>& pixels) {
  const scene s = test::chart_scene("rf-ay", size);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  model_image_params p;
  p.angle_bins = 1;
  p.psf_samples = p.edge_samples = samples;
  p.texel_refine = refine;
  const auto m = compute_model_image(s, ts.retro.front(), ts.texture.get(), p);
  identity_check out;
  if (!m) return out;
  out.made = true;
  out.edges_on_nodes = m->grids[model_fine].edges_on_nodes;
  for (float v : m->image.rgb) out.peak = std::max(out.peak, double(v));
  for (const auto& [x, y] : pixels) {
    const glm::dvec3 mean = mean_prediction(*m, x, y, samples, s.seed);
    for (int c = 0; c < 3; ++c) out.worst = std::max(out.worst, std::abs(mean[c] - double(m->image.at(x, y)[c])));
  }
  return out;
}

}  // namespace

// With one angle bin and every kernel sample counted at the edges, each pixel's value is exactly
// the mean of its predictions from those samples: across the display's left and right edges, and
// at a corner, where the predictions step and the kernels' bilinear surface alone would ramp.
TEST(ModelImageEdges, EachPixelIsTheMeanOfItsPredictions) {
  std::vector<std::pair<int, int>> pixels;
  for (int x = 0; x < 64; ++x) pixels.emplace_back(x, 20);
  pixels.insert(pixels.end(), {{10, 10}, {11, 53}, {53, 10}, {53, 53}, {32, 9}, {32, 54}});
  const identity_check r = check_identity(64, 4, 40000, pixels);
  ASSERT_TRUE(r.made);
  EXPECT_TRUE(r.edges_on_nodes);
  EXPECT_GT(r.peak, 0.1);
  std::printf("worst difference %.3g of the peak %.4g\n", r.worst / r.peak, r.peak);
  EXPECT_LT(r.worst, 2e-5 * r.peak);
}

// The odd refines put the edges between nodes: no step there, and the same identity without it.
TEST(ModelImageEdges, GridsWithEdgesBetweenNodesRampAsBefore) {
  std::vector<std::pair<int, int>> pixels;
  for (int x = 0; x < 48; x += 3) pixels.emplace_back(x, 24);
  const identity_check r = check_identity(48, 3, 20000, pixels);
  ASSERT_TRUE(r.made);
  EXPECT_FALSE(r.edges_on_nodes);
  EXPECT_GT(r.peak, 0.1);
  EXPECT_LT(r.worst, 2e-5 * r.peak);
}
