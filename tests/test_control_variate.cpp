// The model image as the tracer's control variate: the estimator's mean is the plain tracer's
// (the same expectation, within the standard error), its variance is far lower where the model
// holds, and the model image is exact where it can be worked out by hand.
#include <atomic>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// Per-pixel mean and variance of one estimator's samples (green channel).
struct pixel_stats {
  std::vector<double> mean, variance;
  std::vector<int> lit;  // samples that saw light
};

pixel_stats sample_pixels(const tracer_scene& ts, int spp) {
  const int w = ts.camera.width, h = ts.camera.height;
  pixel_stats out{std::vector<double>(std::size_t(w) * h), std::vector<double>(std::size_t(w) * h),
                  std::vector<int>(std::size_t(w) * h)};
  std::uint64_t rays = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto rotation = pixel_sequence_rotation(ts, x, y);
      double sum = 0, sum2 = 0;
      int lit = 0;
      for (int i = 0; i < spp; ++i) {
        const double v = model_value(ts, x, y).y + estimate_sample(ts, x, y, std::uint64_t(i), rotation, rays).y;
        sum += v;
        sum2 += v * v;
        lit += v != 0;
      }
      const std::size_t k = std::size_t(y) * w + x;
      out.mean[k] = sum / spp;
      out.variance[k] = std::max(0.0, (sum2 - sum * sum / spp) / (spp - 1));
      out.lit[k] = lit;
    }
  }
  return out;
}

}  // namespace

class ControlVariate : public ::testing::TestWithParam<std::string> {};

TEST_P(ControlVariate, SameMeanAsThePlainTracerAndLessVariance) {
  scene s = test::chart_scene(GetParam(), 40);
  embree_device device;
  tracer_scene plain, with_model;
  plain.use_model_image = false;
  build_tracer_scene(plain, device, s);
  s.seed = 2;  // independent of the plain estimator's samples (and of its own model image's PSF)
  build_tracer_scene(with_model, device, s);
  update_model_image(plain);
  update_model_image(with_model);
  ASSERT_FALSE(plain.model);
  ASSERT_TRUE(with_model.model);
  const int spp = 128;
  const pixel_stats a = sample_pixels(plain, spp), b = sample_pixels(with_model, spp);

  // 5 x 5 blocks of pixels: z = difference of the blocks' means over its standard error, where
  // the plain estimator saw light often enough (100 samples) for its variance to be measured; where
  // light arrives only by rare tails, a sample variance says nothing.
  const int w = 40, block = 5;
  double chi2 = 0, worst = 0, diff = 0, var_sum = 0, plain_var = 0, model_var = 0, mean = 0;
  int n = 0;
  for (int by = 0; by < w / block; ++by) {
    for (int bx = 0; bx < w / block; ++bx) {
      double d = 0, se2 = 0;
      int lit = 0;
      for (int y = by * block; y < (by + 1) * block; ++y) {
        for (int x = bx * block; x < (bx + 1) * block; ++x) {
          const std::size_t k = std::size_t(y) * w + x;
          d += b.mean[k] - a.mean[k];
          lit += a.lit[k];
          se2 += (a.variance[k] + b.variance[k]) / spp;
          plain_var += a.variance[k];
          model_var += b.variance[k];
          mean += a.mean[k];
        }
      }
      diff += d;
      var_sum += se2;
      if (lit < 100) continue;
      chi2 += d * d / se2;
      worst = std::max(worst, std::abs(d) / std::sqrt(se2));
      ++n;
    }
  }
  const double npix = double(w * w);
  mean /= npix;
  std::printf("%s: %d blocks, chi-square per block %.3f, worst |z| %.2f; image mean %.5f, difference %.5f (%.2f se)\n",
              GetParam().c_str(), n, chi2 / n, worst, mean, diff / npix, diff / std::sqrt(var_sum));
  EXPECT_LT(std::abs(diff), 4 * std::sqrt(var_sum));
  EXPECT_LT(chi2 / n, 1 + 5 * std::sqrt(2.0 / n));
  EXPECT_LT(worst, 4.5);
  const double reduction = plain_var / model_var;
  std::printf("%s: relative sd per sample %.3f plain, %.3f with the model image (variance %.1fx lower)\n",
              GetParam().c_str(), std::sqrt(plain_var / npix) / mean, std::sqrt(model_var / npix) / mean, reduction);
  EXPECT_GT(reduction, 8.0);
}

INSTANTIATE_TEST_SUITE_P(Presets, ControlVariate, ::testing::Values("rf-ay", "rf-an"));

TEST(ModelImage, UniformDisplayIdealSheetIsRTmuL) {
  // An ideal sheet returns every ray to its own point: inside the display's image every pixel is
  // R x T x mu x L, outside it nothing, whatever the PSF machinery does.
  scene s = test::uniform_source_scene(40, 48);
  s.retroreflectors[0].model.type = "ideal";
  s.retroreflectors[0].model.values = {{"mu", 0.8}};
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  update_model_image(ts);
  ASSERT_TRUE(ts.model);
  const double expected = s.half_mirror.reflectance * s.half_mirror.transmittance * 0.8 * s.source.intensity;
  const image_rgb& m = ts.model->image;
  EXPECT_NEAR(m.at(m.width / 2, m.height / 2)[0], expected, 1e-4 * expected);
  EXPECT_EQ(m.at(0, 0)[0], 0.0f);
  // And the tracer's samples equal their predictions there: nothing left to estimate.
  std::uint64_t rays = 0;
  const auto rotation = pixel_sequence_rotation(ts, m.width / 2, m.height / 2);
  for (std::uint64_t i = 0; i < 16; ++i) {
    EXPECT_NEAR(estimate_sample(ts, m.width / 2, m.height / 2, i, rotation, rays).x, 0.0, 1e-4 * expected);
  }
}

// An ideal sheet returns each ray to its own point: a pixel is R x T x mu x L times the share of it
// whose ideal paths land on the display, which the plain tracer's aerial samples measure. The
// kiosk's region of paths is about twice the display's image wide: bins chosen over all of it gave
// the image's edge pixels footprints several percent from their own.
TEST(ModelImage, IdealSheetsEdgePixelsAreTheirShareOfTheDisplay) {
  scene s = load_scene(asset_dir() + "/scenes/two_sheet_kiosk.json", {{"observer.width", "128"},
                                                                      {"observer.height", "128"},
                                                                      {"source.image", "\"\""},
                                                                      {"source.emission_profile", "\"\""},
                                                                      {"retroreflectors.0.model.type", "\"ideal\""}});
  s.retroreflectors.resize(1);
  s.observer.lens = observer_lens::pinhole;
  embree_device device;
  tracer_scene plain;
  plain.use_model_image = false;
  build_tracer_scene(plain, device, s);
  const auto m = compute_model_image(s, plain.retro.front(), nullptr, model_image_params::for_image(128, 128));
  ASSERT_TRUE(m);
  const double full = s.half_mirror.reflectance * s.half_mirror.transmittance * s.source.intensity;
  int x0 = m->image.width, y0 = m->image.height, x1 = -1, y1 = -1;
  for (int y = 0; y < m->image.height; ++y) {
    for (int x = 0; x < m->image.width; ++x) {
      if (m->image.at(x, y)[1] > 0)
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
  }
  ASSERT_GE(x1, x0);
  const int spp = 1024;
  double worst = 0;
  int edge_pixels = 0;
  for (int y = std::max(0, y0 - 2); y <= std::min(m->image.height - 1, y1 + 2); ++y) {
    for (int x = std::max(0, x0 - 2); x <= std::min(m->image.width - 1, x1 + 2); ++x) {
      const auto rotation = pixel_sequence_rotation(plain, x, y);
      std::uint64_t rays = 0;
      double sum = 0;
      for (int i = 0; i < spp; ++i)
        sum += estimate_components(plain, x, y, std::uint64_t(i), rotation, rays)[component_aerial].y;
      const double share = sum / spp / full;
      edge_pixels += share > 0.02 && share < 0.98;
      worst = std::max(worst, std::abs(m->image.at(x, y)[1] / full - share));
    }
  }
  std::printf("%d edge pixels; the model's share at most %.4f from the traced one\n", edge_pixels, worst);
  EXPECT_GT(edge_pixels, 40);
  EXPECT_LT(worst, 0.01);
}

TEST(ModelImage, InterpolatedPathsMatchTracedOnes) {
  // The pixel-to-display map is projective: traced on every 4th pixel and interpolated (the view
  // image's stride, at 512 x 512), the image differs from one traced at every pixel by far less
  // than a texel's contrast.
  const scene s = test::chart_scene("rf-ay", 512);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  model_image_params every, lattice;
  every.psf_samples = lattice.psf_samples = 20000;
  lattice.path_stride = 4;
  const auto a = compute_model_image(s, ts.retro.front(), ts.texture.get(), every);
  const auto b = compute_model_image(s, ts.retro.front(), ts.texture.get(), lattice);
  ASSERT_TRUE(a && b);
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < a->image.rgb.size(); ++i) {
    worst = std::max(worst, double(std::abs(a->image.rgb[i] - b->image.rgb[i])));
    peak = std::max(peak, double(a->image.rgb[i]));
  }
  EXPECT_GT(peak, 0.1);
  EXPECT_LT(worst, 1e-3 * peak);
}

// With least_paths 128 (the view image's), an image keeps at least 128 paths a side: at 96 x 96 a
// stride of 8 traces every pixel's path, at 256 x 256 every second pixel's.
TEST(ModelImage, ASmallImageKeepsAtLeast128PathsASide) {
  // The model images of a size x size chart scene at each stride, its tracer scene built once.
  auto images_at = [](int size, std::initializer_list<int> strides) {
    const scene s = test::chart_scene("rf-ay", size);
    embree_device device;
    tracer_scene ts;
    build_tracer_scene(ts, device, s);
    std::vector<std::vector<float>> images;
    for (int stride : strides) {
      model_image_params p;
      p.psf_samples = 20000;
      p.path_stride = stride;
      p.least_paths = 128;
      const auto m = compute_model_image(s, ts.retro.front(), ts.texture.get(), p);
      images.push_back(m ? m->image.rgb : std::vector<float>{});
    }
    return images;
  };
  const auto small = images_at(96, {1, 8});
  ASSERT_FALSE(small[0].empty());
  EXPECT_TRUE(small[1] == small[0]);
  const auto large = images_at(256, {1, 2, 8});
  ASSERT_FALSE(large[0].empty());
  EXPECT_FALSE(large[1] == large[0]);
  EXPECT_TRUE(large[2] == large[1]);
}

// Without its pixels' paths kept (36 bytes a pixel), a model image traces a pixel's anew when
// asked: the same numbers, so the same predictions, and the same image.
TEST(ModelImage, PixelsTracedAnewAreTheKeptOnes) {
  const scene s = test::chart_scene("rf-ay", 64, 20);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  model_image_params kept, dropped;
  kept.psf_samples = dropped.psf_samples = 20000;
  dropped.keep_pixels = false;
  const auto a = compute_model_image(s, ts.retro.front(), ts.texture.get(), kept);
  const auto b = compute_model_image(s, ts.retro.front(), ts.texture.get(), dropped);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->pixels.size(), std::size_t(64 * 64));
  EXPECT_TRUE(b->pixels.empty());
  EXPECT_TRUE(a->image.rgb == b->image.rgb);
  int ok = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const model_pixel p = model_pixel_at(*a, x, y), q = model_pixel_at(*b, x, y);
      ASSERT_EQ(p.ok, q.ok);
      ok += p.ok;
      EXPECT_TRUE(p.node[0] == q.node[0] && p.node[1] == q.node[1] && p.profile == q.profile &&
                  p.theta_deg == q.theta_deg && p.mix == q.mix && p.bin == q.bin)
          << x << ", " << y;
    }
  }
  EXPECT_GT(ok, 64 * 64 / 4);
  const retro_samples u{{0.3, 0.6}, {0.2, 0.9}, pcg32(7, 1)};
  const glm::dvec2 jitter(0.25, 0.75);
  EXPECT_EQ(model_prediction(*a, 32, 32, jitter, u), model_prediction(*b, 32, 32, jitter, u));
  // Interpolated paths cannot be traced anew one by one.
  dropped.path_stride = 4;
  EXPECT_THROW(compute_model_image(s, ts.retro.front(), ts.texture.get(), dropped), input_error);
}

TEST(ModelImage, CancelledComputationGivesNothing) {
  const scene s = test::chart_scene("rf-an", 64);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  std::atomic<bool> cancel{true};
  EXPECT_FALSE(compute_model_image(s, ts.retro.front(), ts.texture.get(), {}, &cancel));
  EXPECT_FALSE(compute_display_grids(s, ts.texture.get(), {}, &cancel));
  EXPECT_FALSE(compute_layout_model_image(s, ts.retro, ts.texture.get(), {}, &cancel));
  cancel = false;
  EXPECT_TRUE(compute_display_grids(s, ts.texture.get(), {}, &cancel));
  EXPECT_TRUE(compute_model_image(s, ts.retro.front(), ts.texture.get(), {}, &cancel));
}

TEST(ModelImage, FirstLookIsTheModelImageCoarser) {
  // Uniform display, ideal sheet: the first look is exact too (R T mu L inside the display's image).
  scene u = test::uniform_source_scene(64, 64);
  u.retroreflectors[0].model.type = "ideal";
  u.retroreflectors[0].model.values = {{"mu", 0.8}};
  const double expected = u.half_mirror.reflectance * u.half_mirror.transmittance * 0.8 * u.source.intensity;
  const image_rgb flat = model_image_first_look(u, make_sheet_models(u), nullptr);
  ASSERT_EQ(flat.width, 64);
  ASSERT_EQ(flat.height, 64);
  EXPECT_NEAR(flat.at(32, 32)[1], expected, 1e-4 * expected);
  EXPECT_EQ(flat.at(0, 0)[1], 0.0f);

  // The chart through RF-AN: close to the full model image (coarser texels, fewer PSF samples).
  const scene s = test::chart_scene("rf-an", 256);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  update_model_image(ts);
  ASSERT_TRUE(ts.model);
  const image_rgb first = model_image_first_look(s, ts.retro, ts.texture.get());
  ASSERT_EQ(first.rgb.size(), ts.model->image.rgb.size());
  const double relative = test::relative_rms_of_signal(first.rgb, ts.model->image.rgb);
  RecordProperty("first_look_relative_rms", std::to_string(relative));
  EXPECT_LT(relative, 0.15);
  EXPECT_GT(relative, 0.0);  // it is a coarser image, not the same one
}

// The model image the designer is shown after the first look: the full model image within 1.5% (each is about 1% from
// the converged tracer: airr bench --model-error), and all of it.
TEST(ModelImage, ViewQualityIsCloseToTheFullModelImage) {
  const scene s = test::chart_scene("rf-ay", 256);
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  update_model_image(ts);
  ASSERT_TRUE(ts.model);
  const auto view = compute_layout_model_image(s, ts.retro, ts.texture.get(), model_image_params::for_view());
  ASSERT_TRUE(view);
  ASSERT_EQ(view->image.rgb.size(), ts.model->image.rgb.size());
  std::size_t lit_full = 0, lit_both = 0;
  for (std::size_t i = 0; i < view->image.rgb.size(); ++i) {
    lit_full += ts.model->image.rgb[i] > 0;
    lit_both += ts.model->image.rgb[i] > 0 && view->image.rgb[i] > 0;
  }
  const double relative = test::relative_rms_of_signal(view->image.rgb, ts.model->image.rgb);
  RecordProperty("view_relative_rms", std::to_string(relative));
  std::printf("view-quality model image against the full one: %.2f%% relative RMS\n", 100 * relative);
  EXPECT_LT(relative, 0.015);
  EXPECT_GT(relative, 0.0);  // computed on other grids, not the same image
  EXPECT_EQ(lit_both, lit_full);
}

// trace_rows sends the camera rays of a row's pixels as coherent streams; every sample must be
// the one a single ray gives (estimate_components), across a row that is not a whole number of
// streams, with the model image subtracted and the components split.
TEST(ControlVariate, StreamedCameraRaysGiveTheSamplesOfSingleRays) {
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, test::chart_scene("rf-an", 100));
  update_model_image(ts);
  ASSERT_TRUE(ts.model);
  const int w = ts.camera.width, y0 = 40, y1 = 44;
  const std::uint64_t first = 5, count = 3;
  std::vector<float> sums(std::size_t(w) * ts.camera.height * 3, 0.0f), components(component_count * sums.size(), 0.0f);
  const std::atomic<bool> never{false};
  std::uint64_t rays = 0;
  ASSERT_TRUE(trace_rows(ts, y0, y1, first, count, sums, never, rays, nullptr, &components));
  double worst = 0, largest = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto rotation = pixel_sequence_rotation(ts, x, y);
      component_radiance single{};
      for (std::uint64_t i = first; i < first + count; ++i) {
        const component_radiance c = estimate_components(ts, x, y, i, rotation, rays);
        for (int k = 0; k < component_count; ++k) single[std::size_t(k)] += c[std::size_t(k)];
      }
      const std::size_t p = std::size_t(y) * w + x;
      for (int k = 0; k < component_count; ++k) {
        const double streamed = components[3 * (component_count * p + std::size_t(k)) + 1];
        worst = std::max(worst, std::abs(streamed - single[std::size_t(k)].y));
        largest = std::max(largest, std::abs(streamed));
      }
      const double total = single[0].y + single[1].y + single[2].y + single[3].y;
      worst = std::max(worst, std::abs(sums[3 * p + 1] - total));
    }
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(worst, 1e-5 * largest);
}
