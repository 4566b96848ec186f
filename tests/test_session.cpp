// The progressive session: bit-identical results at any thread count, after cancellation, and
// snapshots that are always whole waves.
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/random.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/layout_model_image.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(Session, OneAndTwoThreadsAreBitIdentical) {
  scene s = test::uniform_source_scene(20.0, 64);
  s.sheet().pose.pitch_deg = 10;
  const render_snapshot one = test::render_to(s, 8, 1);
  const render_snapshot two = test::render_to(s, 8, 2);
  ASSERT_EQ(one.spp, 8u);
  ASSERT_EQ(two.spp, 8u);
  EXPECT_TRUE(*one.rgb == *two.rgb);
  // The seed matters: a different seed gives a different image.
  s.seed = 2;
  const render_snapshot other = test::render_to(s, 8, 2);
  EXPECT_FALSE(*one.rgb == *other.rgb);
}

TEST(Session, CancelMidWaveThenRestartMatchesAFreshRender) {
  scene a = test::uniform_source_scene(20.0, 64);
  scene b = a;
  b.sheet().pose.pitch_deg = 25;
  set_floating_distance(b, 200);
  const render_snapshot fresh = test::render_to(b, 12, 2);

  render_session session(a, {.threads = 2, .target_spp = 1 << 20, .max_wave_spp = 256});
  session.wait_for(0, 3);  // now in a long wave
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const std::uint64_t gen = session.edit(b);
  session.set_target_spp(12);
  const render_snapshot restarted = session.wait_for(gen, 12);
  ASSERT_EQ(restarted.generation, gen);
  ASSERT_EQ(restarted.spp, 12u);
  EXPECT_TRUE(*restarted.rgb == *fresh.rgb);
}

TEST(Session, ManyWavesKeepAddingSamples) {
  // 200 waves of one sample each: far more waves than the growth sequence has doublings.
  scene s = test::uniform_source_scene(20.0, 8);
  render_session session(s, {.threads = 1, .target_spp = 200, .max_wave_spp = 1});
  const render_snapshot snap = session.wait_for(0, 200);
  EXPECT_EQ(snap.spp, 200u);
}

TEST(Session, SnapshotsAreWholeWavesOfOneGeneration) {
  scene a = test::uniform_source_scene(20.0, 48);
  render_session session(a, {.threads = 2, .target_spp = 1 << 20, .max_wave_spp = 8});
  std::atomic<bool> done{false};
  std::atomic<int> bad{0}, seen{0};
  // A reader checks every snapshot while edits keep arriving: each one's spp is a wave boundary
  // (1, 3, 7, 15, then steps of 8) and its pixel buffer has the snapshot's size.
  std::thread reader([&] {
    while (!done) {
      const render_snapshot s = session.snapshot();
      if (!s.rgb) continue;
      ++seen;
      const bool boundary =
          (s.preview && s.spp == 0) || s.spp == 1 || s.spp == 3 || s.spp == 7 || (s.spp >= 15 && (s.spp - 15) % 8 == 0);
      if (!boundary || s.rgb->size() != std::size_t(s.width) * s.height * 3) ++bad;
    }
  });
  for (int i = 0; i < 60; ++i) {
    scene e = a;
    e.sheet().pose.pitch_deg = i % 30;
    session.edit(e);
    std::this_thread::sleep_for(std::chrono::milliseconds(i % 7));
  }
  done = true;
  reader.join();
  EXPECT_EQ(bad, 0);
  EXPECT_GT(seen, 0);
}

TEST(Session, EvenAndOddHalvesMakeUpTheWholeAndDiffer) {
  // 7 spp: samples 0, 2, 4, 6 are even, 1, 3, 5 odd; the halves recombine into the mean exactly
  // (to float rounding), and as independent estimates they differ.
  scene s = test::uniform_source_scene(20.0, 32);
  const render_snapshot one = test::render_to(s, 1);
  EXPECT_TRUE(one.even_rgb().empty());
  EXPECT_FALSE(one.odd_rgb);
  render_session session(s, {.target_spp = 7, .max_wave_spp = 2});
  const render_snapshot snap = session.wait_for(0, 7);
  ASSERT_EQ(snap.spp, 7u);
  const std::vector<float> even = snap.even_rgb();
  ASSERT_TRUE(!even.empty() && snap.odd_rgb);
  bool differ = false;
  for (std::size_t i = 0; i < snap.rgb->size(); ++i) {
    const double whole = (4.0 * even[i] + 3.0 * (*snap.odd_rgb)[i]) / 7.0;
    EXPECT_NEAR(whole, (*snap.rgb)[i], 1e-5 * (1 + std::abs(whole))) << i;
    differ = differ || even[i] != (*snap.odd_rgb)[i];
  }
  EXPECT_TRUE(differ);
}

namespace {
// Polls the session's snapshots until `ready` holds (or 20 s pass).
template <class Ready>
render_snapshot poll_until(const render_session& session, Ready ready) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  render_snapshot s = session.snapshot();
  while (!ready(s) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    s = session.snapshot();
  }
  return s;
}
// A snapshot with traced samples shows the best mix of them and `model` (model_image_weight),
// and says so.
void expect_best_mix(const render_snapshot& snap, const std::vector<float>& model) {
  ASSERT_TRUE(snap.rgb && snap.shown);
  const double w = model_image_weight(model, *snap.rgb, snap.odd_rgb.get(), snap.spp);
  EXPECT_EQ(snap.model_weight, w);
  EXPECT_EQ(snap.model_image, w > 0);
  const std::string traced = "tracer at " + std::to_string(snap.spp) + " spp";
  if (w == 0) {
    EXPECT_TRUE(*snap.shown == *snap.rgb);
    EXPECT_EQ(estimate_name(snap), traced);
  } else if (w == 1) {
    EXPECT_TRUE(*snap.shown == model);
  } else {
    for (std::size_t i = 0; i < model.size(); ++i) {
      ASSERT_EQ((*snap.shown)[i], float(w * model[i] + (1 - w) * (*snap.rgb)[i])) << i;
    }
    EXPECT_EQ(estimate_name(snap).rfind(traced + " with the model image", 0), 0u) << estimate_name(snap);
  }
}

}  // namespace

TEST(Session, TheModelImageAtViewQualityFollowsTheFirstLook) {
  scene a = test::uniform_source_scene(20.0, 64);
  scene b = a;
  b.sheet().pose.pitch_deg = 12;
  render_session session(a, {.threads = 2, .preview_stride = 1, .first_look = true});
  session.wait_for(0, 1);
  session.set_paused(true);
  const std::uint64_t gen = session.edit(b);
  const render_snapshot view = poll_until(
      session, [&](const render_snapshot& s) { return s.generation == gen && s.model_image && !s.first_look; });
  ASSERT_TRUE(view.model_image);
  EXPECT_FALSE(view.first_look);
  EXPECT_EQ(estimate_name(view), "model image");
  EXPECT_EQ(view.spp, 0u);
  const auto expected = compute_layout_model_image(b, make_sheet_models(b), nullptr, model_image_params::for_view());
  ASSERT_TRUE(expected);
  EXPECT_TRUE(*view.rgb == expected->image.rgb);
  // It is no first look: the first look differs from it.
  EXPECT_FALSE(*view.rgb == model_image_first_look(b, make_sheet_models(b), nullptr).rgb);
  // The first look never comes back over it.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(session.snapshot().first_look);
  // Traced samples come, and it is still shown at one sample, later mixed with them as much as
  // it helps.
  session.set_paused(false);
  const render_snapshot one = session.wait_for(gen, 1);
  EXPECT_GE(one.spp, 1u);
  ASSERT_TRUE(one.rgb && one.shown);
  if (one.spp == 1) {
    EXPECT_TRUE(one.model_image);
    EXPECT_TRUE(*one.shown == *view.rgb);
    EXPECT_FALSE(*one.rgb == *view.rgb);  // the traced mean is there beside it
  }
  expect_best_mix(session.wait_for(gen, 64), *view.rgb);
}

// While a part is dragged, an edit's first look is the last view-quality model image moved to the
// new placement; the opening layout's view image is made with the session, so even an edit at
// once is moved from it.
TEST(Session, ADragsFirstLookIsTheLastModelImageMoved) {
  const scene a = test::chart_scene("rf-ay", 96, 20);
  scene b = a;
  b.sheet().pose.pitch_deg += 0.5;
  render_session session(a, {.threads = 2, .preview_stride = 1, .first_look = true});
  const std::uint64_t gen = session.edit(b);
  const render_snapshot first =
      session.wait_until([&](const render_snapshot& snap) { return snap.generation == gen && snap.model_image; });
  ASSERT_TRUE(first.first_look) << "the view image came before the first look was seen";
  const auto display = cached_image_pixels(resolve_scene_path(a, a.source.image));
  const auto from = compute_layout_model_image(a, make_sheet_models(a), display.get(), model_image_params::for_view());
  ASSERT_TRUE(from);
  const image_rgb moved = remap_layout_model_image(*from, b, model_image_params::for_view());
  ASSERT_FALSE(moved.rgb.empty());
  EXPECT_TRUE(*first.shown == moved.rgb);
}

// The model image's share in what is shown: a model 2% off against a tracer whose mean has 5%
// noise counts for about 25 / (25 + 4), against 0.5% noise about 0.25 / (0.25 + 4); either way the
// mix is closer to the truth than the model image and than the traced mean.
TEST(Session, TheBestMixIsShown) {
  const std::size_t pixels = 3 * 4096;
  const std::uint64_t spp = 16;
  std::vector<float> truth(pixels), model(pixels);
  pcg32 rng = sample_rng(1, 2, 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    truth[i] = float(1 + rng.next_double());
    model[i] = truth[i] * (i % 2 ? 1.02f : 0.98f);
  }
  auto traced = [&](double sigma, std::vector<float>& odd) {
    std::vector<float> mean(pixels);
    odd.assign(pixels, 0.0f);
    for (std::size_t i = 0; i < pixels; ++i) {
      double all = 0, odds = 0;
      for (std::uint64_t k = 0; k < spp; ++k) {
        // Uniform noise of standard deviation sigma times the value.
        const double v = truth[i] * (1 + sigma * std::sqrt(12.0) * (rng.next_double() - 0.5));
        all += v;
        if (k & 1) odds += v;
      }
      mean[i] = float(all / spp);
      odd[i] = float(odds / (spp / 2));
    }
    return mean;
  };
  auto rms_error = [&](const std::vector<float>& v) {
    double e2 = 0;
    for (std::size_t i = 0; i < pixels; ++i) e2 += std::pow(double(v[i]) - truth[i], 2);
    return std::sqrt(e2 / double(pixels));
  };
  std::vector<float> odd;
  for (const double sigma : {0.05, 0.005}) {
    const std::vector<float> mean = traced(sigma * 4, odd);  // sigma: the noise in the mean of 16
    const double w = model_image_weight(model, mean, &odd, spp);
    const double expected = sigma * sigma / (sigma * sigma + 0.02 * 0.02);
    EXPECT_NEAR(w, expected, 0.1 * expected) << sigma;
    std::vector<float> mix(pixels);
    for (std::size_t i = 0; i < pixels; ++i) mix[i] = float(w * model[i] + (1 - w) * mean[i]);
    EXPECT_LT(rms_error(mix), rms_error(model)) << sigma;
    EXPECT_LT(rms_error(mix), rms_error(mean)) << sigma;
  }
  EXPECT_EQ(model_image_weight(model, odd, &odd, 1), 1.0);  // one sample says nothing of its noise
  EXPECT_EQ(model_image_weight(model, odd, nullptr, spp), 1.0);
  EXPECT_EQ(model_image_weight(odd, odd, &odd, spp), 1.0);  // the same images
}

TEST(Session, ModelImageFirstLookComesFirstThenTheTracer) {
  scene a = test::uniform_source_scene(20.0, 64);
  scene b = a;
  b.sheet().pose.pitch_deg = 12;
  render_session session(a, {.threads = 2, .preview_stride = 1, .first_look = true, .view_model_image = false});
  session.wait_for(0, 1);
  // Paused, the tracer takes the edit but traces nothing: what appears is the first look alone.
  session.set_paused(true);
  const std::uint64_t gen = session.edit(b);
  const render_snapshot first =
      poll_until(session, [&](const render_snapshot& s) { return s.generation == gen && s.model_image; });
  ASSERT_TRUE(first.model_image);
  EXPECT_TRUE(first.first_look);
  EXPECT_EQ(estimate_name(first), "model image (first look)");
  EXPECT_TRUE(first.preview);
  EXPECT_EQ(first.spp, 0u);
  EXPECT_GT(first.edit_seconds, 0.0);
  const image_rgb expected = model_image_first_look(b, make_sheet_models(b), nullptr);
  EXPECT_TRUE(*first.rgb == expected.rgb);
  // Resumed, traced samples join it, as much as it helps.
  session.set_paused(false);
  const render_snapshot traced = session.wait_for(gen, 64);
  expect_best_mix(traced, expected.rgb);

  // A refused edit shows no first look of the refused layout: the last traced image stays.
  session.set_paused(true);
  scene bad = b;
  bad.source.mesh = "no_such_mesh.glb";
  const std::uint64_t bad_gen = session.edit(bad);
  const render_snapshot refused =
      poll_until(session, [&](const render_snapshot& s) { return s.generation == bad_gen && !s.error.empty(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // room for a late first look
  const render_snapshot after = session.snapshot();
  EXPECT_FALSE(refused.error.empty());
  EXPECT_FALSE(after.preview);
  EXPECT_TRUE(*after.shown == *traced.shown || *after.shown == *after.rgb);  // the last good layout's
  EXPECT_FALSE(after.error.empty());
  ASSERT_TRUE(after.rgb);
  EXPECT_GE(after.spp, 1u);  // traced samples of the last good layout, not a first look (spp 0)
}

// After an edit, the traced preview (a sample every few pixels) is far worse than the last model
// image moved, which comes within milliseconds: it is never shown while a first look is coming,
// and shown when none comes. The opening shows its view-quality model image from the start.
TEST(Session, NoTracedPreviewWhileAFirstLookIsComing) {
  scene a = test::uniform_source_scene(20.0, 128);
  render_session session(a, {.threads = 2, .preview_stride = 4, .first_look = true});
  const render_snapshot opening = session.snapshot();
  EXPECT_EQ(opening.generation, 0u);
  EXPECT_TRUE(opening.model_image);
  EXPECT_EQ(estimate_name(opening), "model image");
  session.wait_for(0, 1);

  std::mutex mutex;
  std::vector<std::pair<std::uint64_t, std::string>> shown;  // every image shown after the opening
  std::atomic<bool> stop{false};
  std::thread recorder([&] {
    const void* last = nullptr;
    session.wait_until([&](const render_snapshot& snap) {
      if (snap.generation > 0 && snap.shown && snap.shown.get() != last) {
        last = snap.shown.get();
        const std::lock_guard lock(mutex);
        shown.emplace_back(snap.generation, estimate_name(snap));
      }
      return stop.load();
    });
  });
  scene b = a;
  std::uint64_t gen = 0;
  for (int k = 0; k < 12; ++k) {
    b.sheet().pose.pitch_deg += 0.5;
    gen = session.edit(b);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  session.wait_for(gen, 1);
  stop = true;
  session.stop();
  recorder.join();
  ASSERT_FALSE(shown.empty());
  for (const auto& [generation, what] : shown) EXPECT_NE(what, "tracer (preview)") << "edit " << generation;

  // An observer looking away from the device: no model image, and the preview is what there is.
  render_session away_session(a, {.threads = 2, .preview_stride = 4, .first_look = true});
  away_session.set_paused(true);
  scene away = a;
  away.observer.placement = observer_placement::look_at;
  away.observer.position_mm = {0, 0, 450};
  away.observer.look_at_mm = {0, 0, 900};
  const std::uint64_t away_gen = away_session.edit(away);
  const render_snapshot preview =
      poll_until(away_session, [&](const render_snapshot& s) { return s.generation == away_gen; });
  EXPECT_EQ(preview.generation, away_gen);
  EXPECT_EQ(estimate_name(preview), "tracer (preview)");
}
