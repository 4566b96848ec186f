// The noise measurement behind `airr bench --noise`: the pair estimate recovers a known noise, and
// the noise law and time forecast are exact on points that follow a law.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "airr/core/error.hpp"
#include "airr/measure/noise_level.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(NoiseLevel, PairOfIndependentRendersGivesTheNoiseOfOne) {
  // Mean 2 with Gaussian noise of standard deviation 0.1 in every value: relative noise 0.05.
  std::mt19937 gen(11);
  std::normal_distribution<double> noise(0.0, 0.1);
  const int n = 256;
  image_rgb a{n, n, std::vector<float>(std::size_t(n) * n * 3)}, b = a;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    a.rgb[i] = float(2.0 + noise(gen));
    b.rgb[i] = float(2.0 + noise(gen));
  }
  // 196608 differences: the estimate's relative standard error is about 1 / sqrt(2 * 196608) = 0.16%.
  EXPECT_NEAR(pair_relative_noise(a, b), 0.05, 0.05 * 0.01);
  EXPECT_DOUBLE_EQ(pair_relative_noise(a, a), 0.0);
}

TEST(NoiseLevel, BadPairsAreNamed) {
  const image_rgb a{4, 4, std::vector<float>(48, 1.0f)}, b{4, 2, std::vector<float>(24, 1.0f)};
  EXPECT_EQ(test::error_of([&] { pair_relative_noise(a, b); }), "noise: the two renders differ in size (4x4 and 4x2)");
  const image_rgb black{4, 4, std::vector<float>(48, 0.0f)};
  EXPECT_EQ(test::error_of([&] { pair_relative_noise(black, black); }),
            "noise: the renders are black (no mean to relate the noise to)");
  EXPECT_NE(test::error_of([&] { fit_noise_law({{16, 1.0, 0.1}, {16, 1.1, 0.09}}); }), "");
}

TEST(NoiseLevel, LawAndForecastAreExactOnALaw) {
  // noise = 0.5 spp^-0.5, seconds = 1 + 0.1 spp.
  std::vector<noise_point> points;
  for (std::uint64_t spp : {16, 64, 256}) points.push_back({spp, 1 + 0.1 * double(spp), 0.5 / std::sqrt(double(spp))});
  const noise_law law = fit_noise_law(points);
  EXPECT_NEAR(law.amplitude, 0.5, 1e-12);
  EXPECT_NEAR(law.exponent, 0.5, 1e-12);
  EXPECT_NEAR(law.seconds_per_spp, 0.1, 1e-12);
  EXPECT_NEAR(law.startup_s, 1.0, 1e-9);
  const noise_target one = time_to_noise(law, points, 0.01);
  EXPECT_NEAR(one.spp, 2500, 1e-6);
  EXPECT_NEAR(one.seconds, 251, 1e-6);
  EXPECT_FALSE(one.within_measured);
  const noise_target inside = time_to_noise(law, points, 0.05);  // between 16 and 256 spp
  EXPECT_NEAR(inside.spp, 100, 1e-9);
  EXPECT_TRUE(inside.within_measured);
}

TEST(NoiseLevel, ForecastBeyondTheMeasuredPointsNeverConvergesFasterThanMonteCarlo) {
  // Measured noise = spp^-0.6 at 16 and 64 spp: beyond 64 the forecast uses the rate 1/2.
  const std::vector<noise_point> points{{16, 2.0, std::pow(16.0, -0.6)}, {64, 8.0, std::pow(64.0, -0.6)}};
  const noise_law law = fit_noise_law(points);
  EXPECT_NEAR(law.exponent, 0.6, 1e-12);
  const noise_target t = time_to_noise(law, points, 0.01);
  EXPECT_NEAR(t.spp, 64 * std::pow(std::pow(64.0, -0.6) / 0.01, 2), 1e-6);
  EXPECT_FALSE(t.within_measured);
}
