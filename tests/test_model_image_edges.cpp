// The model image at the display's edges, where the fine grid's nodes put them: a prediction steps
// to black at the edge as the tracer's display does, and the model image is still the mean of the
// predictions it is made of.
#include <cmath>

#include <gtest/gtest.h>

#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The mean of pixel (x, y)'s predictions over the first n samples of bin 0's kernel sequence.
glm::dvec3 mean_prediction(const model_image& m, int x, int y, std::uint64_t n, std::uint64_t seed) {
  const kernel_sequence sequence(0, seed);
  glm::dvec3 sum(0.0);
  for (std::uint64_t i = 0; i < n; ++i) {
    glm::dvec2 jitter;
    retro_samples u;
    sequence.at(i, jitter, u);
    sum += glm::dvec3(model_prediction(m, x, y, jitter, u));
  }
  return sum / double(n);
}

}  // namespace

// With one angle bin and every kernel sample counted at the edges, each pixel's value is exactly
// the mean of its predictions from those samples: across the display's left and right edges, and
// at a corner, where the predictions step and the kernels' bilinear surface alone would ramp.
TEST(ModelImageEdges, EachPixelIsTheMeanOfItsPredictions) {
  const scene s = test::chart_scene("rf-ay", 64);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  model_image_params p;
  p.angle_bins = 1;
  p.psf_samples = p.edge_samples = 40000;
  const auto m = compute_model_image(s, ts.retro.front(), ts.texture.get(), p);
  ASSERT_TRUE(m);
  ASSERT_TRUE(m->grids[model_fine].edges_on_nodes);
  double peak = 0;
  for (float v : m->image.rgb) peak = std::max(peak, double(v));
  ASSERT_GT(peak, 0.1);
  std::vector<std::pair<int, int>> pixels;
  for (int x = 0; x < 64; ++x) pixels.emplace_back(x, 20);
  pixels.insert(pixels.end(), {{10, 10}, {11, 53}, {53, 10}, {53, 53}, {32, 9}, {32, 54}});
  double worst = 0;
  for (const auto& [x, y] : pixels) {
    const glm::dvec3 mean = mean_prediction(*m, x, y, p.psf_samples, s.seed);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(mean[c] - double(m->image.at(x, y)[c])));
  }
  std::printf("worst difference %.3g of the peak %.4g\n", worst / peak, peak);
  EXPECT_LT(worst, 2e-5 * peak);
}

// The odd refines put the edges between nodes: no step there, and the same identity without it.
TEST(ModelImageEdges, GridsWithEdgesBetweenNodesRampAsBefore) {
  const scene s = test::chart_scene("rf-ay", 48);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  model_image_params p;
  p.angle_bins = 1;
  p.psf_samples = 20000;
  p.texel_refine = 3;
  const auto m = compute_model_image(s, ts.retro.front(), ts.texture.get(), p);
  ASSERT_TRUE(m);
  EXPECT_FALSE(m->grids[model_fine].edges_on_nodes);
  double worst = 0, peak = 0;
  for (float v : m->image.rgb) peak = std::max(peak, double(v));
  for (int x = 0; x < 48; x += 3) {
    const glm::dvec3 mean = mean_prediction(*m, x, 24, p.psf_samples, s.seed);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(mean[c] - double(m->image.at(x, 24)[c])));
  }
  EXPECT_LT(worst, 2e-5 * peak);
}
