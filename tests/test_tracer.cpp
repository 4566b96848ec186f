// The tracer against analytic truths: where the aerial image forms, how sharp it is with an ideal
// retroreflector, and how much light arrives (R_hm x T_hm x mu of the source radiance).
#include <algorithm>

#include <gtest/gtest.h>

#include "airr/layout/layout.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// 10%-90% rise (pixels) of the square's left edge. A box-filtered step sampled at one phase
// looks wider than it is, so the edge spread function is assembled from renders with the source
// shifted by k/8 pixel, each profile averaged over the rows inside the square.
double left_edge_rise(scene s, std::uint64_t spp) {
  const double mm_per_px = make_camera(s).mm_per_pixel;
  // The observer stays where it is while the display moves.
  const glm::dvec3 eye = observer_position(s), target = observer_target(s);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {eye.x, eye.y, eye.z};
  s.observer.look_at_mm = {target.x, target.y, target.z};
  const double base_offset = s.source.pose.center_mm[0];
  std::vector<std::pair<double, double>> esf;
  double plateau = 0;
  int plateau_n = 0;
  for (int k = 0; k < 8; ++k) {
    s.source.pose.center_mm[0] = base_offset + k / 8.0 * mm_per_px;
    const render_snapshot snap = test::render_to(s, spp);
    const int w = snap.width, y_mid = snap.height / 2, half_rows = 3;
    for (int x = 0; x < w / 2; ++x) {
      double v = 0;
      for (int y = y_mid - half_rows; y <= y_mid + half_rows; ++y) v += (*snap.rgb)[3 * (std::size_t(y) * w + x)];
      v /= 2 * half_rows + 1;
      esf.emplace_back(x + 0.5 - k / 8.0, v);
      if (x >= w / 2 - 3) {
        plateau += v;
        ++plateau_n;
      }
    }
  }
  plateau /= plateau_n;
  std::sort(esf.begin(), esf.end());
  auto crossing = [&](double level) {
    for (std::size_t i = 1; i < esf.size(); ++i) {
      const double a = esf[i - 1].second / plateau, b = esf[i].second / plateau;
      if (a < level && b >= level) return esf[i - 1].first + (level - a) / (b - a) * (esf[i].first - esf[i - 1].first);
    }
    return -1e9;
  };
  return crossing(0.9) - crossing(0.1);
}

}  // namespace

class MirrorImage : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(MirrorImage, CentroidLandsOnTheProjectionOfZeroZeroD) {
  const auto [d, tilt] = GetParam();
  scene s = test::uniform_source_scene(8.0, 96);
  airr::set_floating_distance(s, d);
  s.sheet().pose.pitch_deg = tilt;
  const render_snapshot snap = test::render_to(s, 16);
  const test::centroid c = test::luminance_centroid(snap);
  const glm::dvec2 expected = camera_project(make_camera(s), {0, 0, d});
  EXPECT_GT(c.total, 0);
  EXPECT_NEAR(c.x, expected.x, 0.5) << "D=" << d << " tilt=" << tilt;
  EXPECT_NEAR(c.y, expected.y, 0.5) << "D=" << d << " tilt=" << tilt;
  const double rise = left_edge_rise(s, 16);
  EXPECT_GT(rise, 0.5);  // a box-filtered step rises over 0.8 px
  EXPECT_LE(rise, 1.5) << "D=" << d << " tilt=" << tilt;
}

INSTANTIATE_TEST_SUITE_P(DistancesAndTilts, MirrorImage,
                         ::testing::Combine(::testing::Values(150.0, 225.0, 300.0),
                                            ::testing::Values(0.0, 20.0, 40.0)));

TEST(MirrorImage, OffsetSourceMovesTheImageByItsMirror) {
  // A source moved +10 mm along z appears 10 mm lower (aerial y = -source z).
  scene s = test::uniform_source_scene(6.0, 96);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, 0, 450};
  s.observer.look_at_mm = {0, 0, 150};
  s.source.pose.center_mm = {5.0, -150.0, 10.0};
  const render_snapshot snap = test::render_to(s, 8);
  const test::centroid c = test::luminance_centroid(snap);
  const glm::dvec2 expected = camera_project(make_camera(s), {5.0, -10.0, 150.0});
  EXPECT_NEAR(c.x, expected.x, 0.5);
  EXPECT_NEAR(c.y, expected.y, 0.5);
}

struct energy_case {
  double r, t, mu;
};
class Energy : public ::testing::TestWithParam<energy_case> {};

TEST_P(Energy, MeanRadianceIsSourceTimesRTMu) {
  const energy_case e = GetParam();
  scene s = test::uniform_source_scene(40.0, 96);
  s.half_mirror.reflectance = e.r;
  s.half_mirror.transmittance = e.t;
  airr::set_model_value(s.sheet().model, "mu", e.mu);
  s.source.intensity = 7.0;
  const render_snapshot snap = test::render_to(s, 256);
  // The central 40 x 40 pixels lie well inside the 40 mm square's image (about 52 px wide at 0.77 mm per pixel).
  double sum = 0;
  int n = 0;
  for (int y = 28; y < 68; ++y) {
    for (int x = 28; x < 68; ++x) {
      sum += (*snap.rgb)[3 * (std::size_t(y) * snap.width + x) + 1];
      ++n;
    }
  }
  const double expected = 7.0 * e.r * e.t * e.mu;
  EXPECT_NEAR(sum / n, expected, 0.02 * expected) << "R=" << e.r << " T=" << e.t << " mu=" << e.mu;
}

INSTANTIATE_TEST_SUITE_P(ThreeSettings, Energy,
                         ::testing::Values(energy_case{0.5, 0.5, 1.0}, energy_case{0.3, 0.6, 0.8},
                                           energy_case{0.7, 0.2, 0.5}));

TEST(Tracer, NothingButTheAerialImageIsLit) {
  // Outside the square's image the layout shows black: no stray path reaches the source there.
  scene s = test::uniform_source_scene(10.0, 96);
  const render_snapshot snap = test::render_to(s, 4);
  double corner = 0;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) corner += (*snap.rgb)[3 * (std::size_t(y) * snap.width + x)];
  }
  EXPECT_EQ(corner, 0.0);
}
