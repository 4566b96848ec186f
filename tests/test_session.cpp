// The progressive session: bit-identical results at any thread count, after cancellation, and
// snapshots that are always whole waves.
#include <thread>

#include <gtest/gtest.h>

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
