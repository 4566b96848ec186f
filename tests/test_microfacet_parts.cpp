// The microfacet retroreflector's parts: its Beckmann samplers against their densities
// (chi-square), and the ERA and Fresnel formulas against hand-computed values.
#include <gtest/gtest.h>

#include "microfacet_test_support.hpp"

using namespace airr;
using namespace airr::test;

TEST(Beckmann, DensityIntegratesToOne) {
  for (double alpha : {0.01, 0.05, 0.2, 0.5, 1.0}) {
    const double integral = integrate_patch([&](const glm::dvec3& m) { return beckmann_d(m, alpha) * m.z; }, alpha, 0,
                                            q_max, 0, 2 * pi, 4000, 8);
    EXPECT_NEAR(integral, 1, 1e-7) << "alpha " << alpha;
  }
}

TEST(Beckmann, VisibleDensityIntegratesToOne) {
  for (double alpha : {0.05, 0.2, 0.5}) {
    for (double theta : {0.0, 30.0, 60.0, 80.0, 89.0}) {
      const glm::dvec3 wi = direction(theta, 35);
      const double integral = integrate_patch([&](const glm::dvec3& m) { return beckmann_visible_d(wi, m, alpha); },
                                              alpha, 0, q_max, 0, 2 * pi, 2000, 720);
      EXPECT_NEAR(integral, 1, 1e-4) << "alpha " << alpha << " theta " << theta;
    }
  }
}

TEST(Beckmann, SamplingFollowsTheDensity) {
  for (double alpha : {0.05, 0.2, 0.5}) {
    const beckmann_bins bins(alpha);
    const auto prob = bins.probabilities([&](const glm::dvec3& m) { return beckmann_d(m, alpha) * m.z; });
    EXPECT_NEAR(total(prob), 1, 1e-6);
    pcg32 rng(7, 1);
    const double p = chi_square_p(bins, prob, 200000, [&] {
      const double u1 = rng.next_double();
      return sample_beckmann(alpha, u1, rng.next_double());
    });
    EXPECT_GT(p, 1e-3) << "alpha " << alpha;
    // The test has power: a roughness 5% off is rejected.
    const double p_wrong = chi_square_p(bins, prob, 200000, [&] {
      const double u1 = rng.next_double();
      return sample_beckmann(alpha * 1.05, u1, rng.next_double());
    });
    EXPECT_LT(p_wrong, 1e-6) << "alpha " << alpha;
  }
}

TEST(Beckmann, VisibleSamplingFollowsTheVisibleDensity) {
  for (double alpha : {0.05, 0.2, 0.5}) {
    const beckmann_bins bins(alpha);
    for (const auto& [theta, phi] : {std::pair{0.0, 0.0}, {30.0, 20.0}, {70.0, 200.0}, {88.0, 300.0}}) {
      const glm::dvec3 wi = direction(theta, phi);
      const auto prob = bins.probabilities([&](const glm::dvec3& m) { return beckmann_visible_d(wi, m, alpha); });
      EXPECT_NEAR(total(prob), 1, 1e-4);
      pcg32 rng(11, 3);
      const double p = chi_square_p(bins, prob, 200000, [&] {
        const double u1 = rng.next_double();
        return sample_beckmann_visible(wi, alpha, u1, rng.next_double());
      });
      EXPECT_GT(p, 1e-3) << "alpha " << alpha << " theta " << theta;
    }
  }
  // The test has power: at oblique incidence the visible normals are not the plain ones.
  const double alpha = 0.5;
  const beckmann_bins bins(alpha);
  const auto plain = bins.probabilities([&](const glm::dvec3& m) { return beckmann_d(m, alpha) * m.z; });
  pcg32 rng(5, 9);
  const glm::dvec3 wi = direction(70, 200);
  EXPECT_LT(chi_square_p(bins, plain, 200000,
                         [&] {
                           const double u1 = rng.next_double();
                           return sample_beckmann_visible(wi, alpha, u1, rng.next_double());
                         }),
            1e-6);
}

TEST(Era, MatchesHandComputedValues) {
  // U(x), L(x) evaluated separately for x = 0, 10, 20, 30, 40.
  const std::array<double, 5> x{0, 10, 20, 30, 40};
  const std::array<double, 5> upper{0.683356248, 0.613629456, 0.494063622, 0.313729998, 0.137477359};
  const std::array<double, 5> lower{0.678575082, 0.617530254, 0.494755694, 0.218412440, 0.0};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(era(x[i], 0), upper[i], 1e-8) << "x " << x[i];      // w = 1
    EXPECT_NEAR(era(x[i], 30), lower[i], 1e-8) << "x " << x[i];     // w = 0
    EXPECT_NEAR(era(x[i], 60), upper[i], 1e-8) << "x " << x[i];     // period 60
    EXPECT_NEAR(era(x[i], 15), 0.5 * (upper[i] + lower[i]), 1e-8);  // w = 1/2
    EXPECT_NEAR(era(x[i], -15), 0.5 * (upper[i] + lower[i]), 1e-8);
    EXPECT_NEAR(era(x[i], 200), upper[i] / 3 + 2 * lower[i] / 3, 1e-8);  // 200 mod 60 = 20: w = 1/3
  }
  EXPECT_EQ(era(40, 30), 0.0);  // L is clamped at 0 beyond about 35.4 deg
}

TEST(Fresnel, KnownValues) {
  for (double eta : {1.33, 1.5, 1.5046, 2.0}) {
    EXPECT_NEAR(fresnel_dielectric(1, eta), std::pow((eta - 1) / (eta + 1), 2), 1e-14);
    EXPECT_NEAR(fresnel_dielectric(1, 1 / eta), std::pow((eta - 1) / (eta + 1), 2), 1e-14);
    // At Brewster's angle the p component vanishes: F = ((eta^2 - 1) / (eta^2 + 1))^2 / 2.
    EXPECT_NEAR(fresnel_dielectric(std::cos(std::atan(eta)), eta), 0.5 * std::pow((eta * eta - 1) / (eta * eta + 1), 2),
                1e-14);
    EXPECT_NEAR(fresnel_dielectric(0, eta), 1, 1e-14);  // grazing
    // Reciprocity: the same interface seen from the other side.
    for (double c : {0.2, 0.5, 0.9}) {
      const double ct = std::sqrt(1 - (1 - c * c) / (eta * eta));
      EXPECT_NEAR(fresnel_dielectric(c, eta), fresnel_dielectric(ct, 1 / eta), 1e-14);
    }
    // Total internal reflection beyond the critical angle asin(1 / eta).
    const double critical = std::asin(1 / eta);
    EXPECT_EQ(fresnel_dielectric(std::cos(critical + 0.01), 1 / eta), 1.0);
    EXPECT_LT(fresnel_dielectric(std::cos(critical - 0.01), 1 / eta), 1.0);
  }
}
