// The control variate's model image may arrive after the first samples are traced: adding its
// predictions of those samples then gives the estimate the control variate would have given from
// the start, to the bit, so nothing is lost and nothing biased.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// A render's sums, traced with the predictions apart (kept beside the sums, as the designer's
// session keeps them, or made at the end, as a render that publishes only at its target) or not.
struct accumulation {
  std::vector<float> sums, odd, components;
  prediction_sums predictions;
  explicit accumulation(const tracer_scene& ts, bool keep_predictions = true)
      : sums(std::size_t(ts.camera.width) * ts.camera.height * 3, 0.0f),
        odd(sums),
        components(component_count * sums.size(), 0.0f),
        predictions(keep_predictions ? prediction_sums{sums, sums} : prediction_sums{}) {}
  bool trace(const tracer_scene& ts, std::uint64_t first, std::uint64_t count, bool apart = true) {
    const std::atomic<bool> never{false};
    std::uint64_t rays = 0;
    return trace_rows(ts, 0, ts.camera.height, first, count, sums, never, rays, &odd, &components,
                      apart ? &predictions : nullptr);
  }
  // Each pixel's predictions of samples [0, spp): those kept, or made now.
  glm::dvec3 predicted(const tracer_scene& ts, std::size_t pixel, std::uint64_t spp) const {
    if (!predictions.all.empty()) {
      const float* p = predictions.all.data() + 3 * pixel;
      return {p[0], p[1], p[2]};
    }
    const int w = ts.camera.width;
    return predict_pixel(ts, int(pixel % std::size_t(w)), int(pixel / std::size_t(w)), 0, spp).all;
  }
  // Each pixel's estimate, as the session publishes it.
  std::vector<float> estimate(const tracer_scene& ts, std::uint64_t spp) const {
    std::vector<float> out(sums.size());
    const double inv = 1.0 / double(spp);
    for (std::size_t p = 0; p < sums.size() / 3; ++p) {
      const glm::dvec3 m = predicted(ts, p, spp);
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = 3 * p + std::size_t(c);
        out[i] = float((sums[i] - m[c]) * inv + (ts.model ? ts.model->image.rgb[i] : 0.0f));
      }
    }
    return out;
  }
};

// The image of `spp` samples traced at once with the control variate there from the start, its
// predictions kept beside the sums or made at the end.
std::vector<float> control_variate_estimate(const scene& s, std::uint64_t spp, bool keep_predictions = true) {
  embree_device device;
  tracer_scene ts;
  build_tracer_scene(ts, device, s);
  update_model_image(ts);
  EXPECT_TRUE(ts.model);
  accumulation acc(ts, keep_predictions);
  EXPECT_TRUE(acc.trace(ts, 0, spp));
  return acc.estimate(ts, spp);
}

// Largest |a - b| over the values, relative to the largest |a|.
double relative_max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(double(a[i]) - double(b[i])));
    scale = std::max(scale, std::abs(double(a[i])));
  }
  return diff / scale;
}

}  // namespace

TEST(LateControlVariate, PredictionsAddedLaterAreThoseOfTheControlVariate) {
  const scene s = test::chart_scene("rf-an", 48, 20);
  embree_device device;
  tracer_scene with_model, late;
  build_tracer_scene(with_model, device, s);
  build_tracer_scene(late, device, s);
  update_model_image(with_model);
  ASSERT_TRUE(with_model.model);
  ASSERT_FALSE(late.model);

  accumulation a(with_model), b(late), classic(with_model);
  ASSERT_TRUE(a.trace(with_model, 0, 6));
  ASSERT_TRUE(b.trace(late, 0, 3));  // plain samples: no predictions yet
  EXPECT_TRUE(std::all_of(b.predictions.all.begin(), b.predictions.all.end(), [](float v) { return v == 0; }));
  late.model = with_model.model;  // it arrives
  const std::atomic<bool> never{false};
  ASSERT_TRUE(add_predictions(late, 0, late.camera.height, 0, 3, b.predictions, never));
  ASSERT_TRUE(b.trace(late, 3, 3));

  EXPECT_TRUE(a.sums == b.sums);
  EXPECT_TRUE(a.odd == b.odd);
  EXPECT_TRUE(a.components == b.components);
  EXPECT_TRUE(a.predictions.all == b.predictions.all);
  EXPECT_TRUE(a.predictions.odd == b.predictions.odd);
  EXPECT_TRUE(a.estimate(with_model, 6) == b.estimate(late, 6));

  // The same estimate as the samples' differences from their predictions summed directly.
  ASSERT_TRUE(classic.trace(with_model, 0, 6, false));
  std::vector<float> apart(a.sums.size());
  for (std::size_t i = 0; i < apart.size(); ++i) apart[i] = a.sums[i] - a.predictions.all[i];
  const double difference = relative_max_difference(classic.sums, apart);
  std::printf("predictions apart against differences summed: %.2g (relative)\n", difference);
  EXPECT_LT(difference, 1e-5);
  EXPECT_GT(relative_max_difference(classic.sums, a.sums), 1e-2);  // the predictions matter

  // Predictions made at the end instead (none kept beside the samples): the same traced sums, and
  // the same estimate up to the kept predictions' single precision.
  accumulation at_end(with_model, false);
  ASSERT_TRUE(at_end.trace(with_model, 0, 6));
  EXPECT_TRUE(at_end.sums == a.sums);
  EXPECT_TRUE(at_end.odd == a.odd);
  const double made_later = relative_max_difference(a.estimate(with_model, 6), at_end.estimate(with_model, 6));
  std::printf("predictions made at the end against kept: %.2g (relative)\n", made_later);
  EXPECT_LT(made_later, 1e-5);

  // Cut short, it says so.
  const std::atomic<bool> cancelled{true};
  accumulation c(late);
  EXPECT_FALSE(add_predictions(late, 0, late.camera.height, 0, 1, c.predictions, cancelled));
}

// A session traces at once after an edit, before its control variate exists; the image at its
// target is the control variate's estimate all the same, to the bit.
TEST(LateControlVariate, SessionImageAtItsTargetIsTheControlVariates) {
  const scene a = test::chart_scene("rf-an", 48, 0), b = test::chart_scene("rf-an", 48, 20);
  const std::uint64_t spp = 8;
  render_session session(a, {.threads = 2, .target_spp = spp, .preview_stride = 1});
  session.wait_for(0, spp);
  const std::uint64_t gen = session.edit(b);
  const render_snapshot first = session.wait_for(gen, 1);
  const render_snapshot done = session.wait_for(gen, spp);
  ASSERT_EQ(done.spp, spp);

  EXPECT_TRUE(*done.rgb == control_variate_estimate(b, spp));
  embree_device device;

  // The first traced image came before the control variate (at 48 x 48 a wave takes about a
  // millisecond, the model image a hundred times that): the plain samples' mean.
  tracer_scene plain;
  build_tracer_scene(plain, device, b);
  accumulation p(plain);
  ASSERT_TRUE(p.trace(plain, 0, first.spp));
  EXPECT_TRUE(*first.rgb == p.estimate(plain, first.spp));
}

// Paused and resumed again and again while it traces: a cancelled wave keeps the rows it finished
// and the next one brings the others level (no copy of the sums undoes it), and the control
// variate's predictions, made once the target is reached (a pause that cuts them short has them
// made again on resume), follow each row's own samples, so the image at the target is the same to
// the bit. Images come only with the target's snapshot when the session is asked so.
TEST(LateControlVariate, PausesMidWaveChangeNothing) {
  const scene s = test::chart_scene("rf-an", 96, 20);
  const std::uint64_t spp = 12;
  render_session session(s, {.threads = 2, .target_spp = spp, .preview_stride = 1, .final_images_only = true});
  int pauses = 0;
  for (; pauses < 200; ++pauses) {
    const render_snapshot now = session.snapshot();
    if (now.spp >= spp) break;
    EXPECT_FALSE(now.rgb) << "an image before the target, at " << now.spp << " spp";
    std::this_thread::sleep_for(std::chrono::milliseconds(1 + pauses % 7));
    session.set_paused(true);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    session.set_paused(false);
  }
  const render_snapshot done = session.wait_for(0, spp);
  std::printf("paused %d times on the way to %llu spp\n", pauses, static_cast<unsigned long long>(spp));
  EXPECT_GT(pauses, 3);
  ASSERT_EQ(done.spp, spp);
  ASSERT_TRUE(done.rgb);

  EXPECT_TRUE(*done.rgb == control_variate_estimate(s, spp, false));
}
