// The microfacet retroreflector (spec 2.3) as a whole: its energy and retro spread against analytic
// values and an independent linearised propagation.
#include <gtest/gtest.h>

#include "microfacet_test_support.hpp"

using namespace airr;
using namespace airr::test;

namespace {

microfacet_params smooth_params(double alpha_internal) {
  microfacet_params p;
  p.alpha_surface = 0;
  p.alpha_internal = alpha_internal;
  return p;
}

struct branch_energy {
  double surface = 0, retro = 0, diffuse = 0, total = 0;
  double surface_sq = 0, total_sq = 0;
  int n = 0;
};

branch_energy measure(const microfacet_retro& model, const glm::dvec3& wi, int n, std::uint64_t seed) {
  pcg32 rng(seed, 17);
  branch_energy e;
  for (int i = 0; i < n; ++i) {
    const microfacet_trace t = model.trace(wi, next_randoms(rng));
    const double w = t.sample.weight;
    if (t.branch == microfacet_branch::surface) e.surface += w, e.surface_sq += w * w;
    if (t.branch == microfacet_branch::retro) e.retro += w;
    if (t.branch == microfacet_branch::diffuse) e.diffuse += w;
    e.total += w;
    e.total_sq += w * w;
  }
  e.n = n;
  for (double* v : {&e.surface, &e.retro, &e.diffuse, &e.total, &e.surface_sq, &e.total_sq}) *v /= n;
  return e;
}

double standard_error(double mean, double mean_sq, int n) {
  return std::sqrt(std::max(0.0, mean_sq - mean * mean) / n);
}

// The expected energies of a smooth sheet whose internal path loses nothing to geometry (internal
// angle below 35.26 deg, where every cube face faces the ray): surface F, retro
// (1 - F) p R_int^3 (1 - F), diffuse (1 - F) (1 - p), with p = ERA at the refracted angle. Spec 2.3:
// each of the three coated faces reflects R_int, and what the coating does not reflect is absorbed,
// so only the 1 - ERA share reaches the diffuse lobe.
branch_energy analytic_smooth(const glm::dvec3& wi, double eta, double internal_reflectance) {
  const double f = fresnel_dielectric(wi.z, eta);
  const double sin_x = std::sqrt(1 - wi.z * wi.z) / eta;
  const double x_deg = std::asin(sin_x) / rad;
  const double phi_deg = std::atan2(wi.y, wi.x) / rad;
  const double p = era(x_deg, phi_deg);
  const double coating = std::pow(internal_reflectance, 3);
  branch_energy e;
  e.surface = f;
  e.retro = (1 - f) * p * coating * (1 - f);
  e.diffuse = (1 - f) * (1 - p);
  e.total = e.surface + e.retro + e.diffuse;
  return e;
}

}  // namespace

TEST(MicrofacetRetro, EveryWeightIsAtMostOneAndTheMeanAtMostOne) {
  for (double alpha_surface : {0.0, 0.3}) {
    for (double alpha_internal : {0.0005, 0.3}) {
      microfacet_params params = smooth_params(alpha_internal);
      params.alpha_surface = alpha_surface;
      const microfacet_retro model(params);
      pcg32 rng(3, 5);
      for (double theta = 0; theta < 90; theta += 5) {
        for (double phi = 0; phi < 360; phi += 30) {
          const glm::dvec3 wi = direction(theta, phi);
          double sum = 0;
          const int n = 1000;
          for (int i = 0; i < n; ++i) {
            const retro_sample s = model.sample(wi, next_randoms(rng));
            ASSERT_GE(s.weight, 0);
            ASSERT_LE(s.weight, 1);
            if (s.weight > 0) {
              ASSERT_NEAR(glm::length(s.wo), 1, 1e-9);
              ASSERT_GT(s.wo.z, 0);
            }
            EXPECT_EQ(s.shift_mm, glm::dvec2(0, 0));
            sum += s.weight;
          }
          EXPECT_LE(sum / n, 1.0);
          EXPECT_GT(sum / n, 0.0) << theta << " " << phi;
        }
      }
    }
  }
  EXPECT_EQ(microfacet_retro(smooth_params(0.0005)).sample({0.6, 0, -0.8}, {}).weight, 0.0);  // from below
}

TEST(MicrofacetRetro, MuScalesTheWeight) {
  microfacet_params params = smooth_params(0.0005);
  params.mu = 0.25;
  const microfacet_retro scaled(params);
  const microfacet_retro plain(smooth_params(0.0005));
  pcg32 rng(1, 2);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 wi = direction(60 * rng.next_double(), 360 * rng.next_double());
    const retro_samples r = next_randoms(rng);
    const retro_sample a = scaled.sample(wi, r), b = plain.sample(wi, r);
    EXPECT_NEAR(a.weight, 0.25 * b.weight, 1e-15);
    EXPECT_EQ(a.wo, b.wo);
  }
}

TEST(MicrofacetRetro, RetroreflectedDirectionsStayCloseToWi) {
  const microfacet_retro model(smooth_params(0.0005));
  for (const auto& [theta, phi] : {std::pair{0.0, 0.0}, {15.0, 10.0}, {30.0, 45.0}, {45.0, 200.0}, {55.0, 290.0}}) {
    const glm::dvec3 wi = direction(theta, phi);
    pcg32 rng(21, 4);
    double angle_sum = 0, max_angle = 0;
    int kept = 0, lost = 0;
    for (int i = 0; i < 50000; ++i) {
      const microfacet_trace t = model.trace(wi, next_randoms(rng));
      if (t.branch != microfacet_branch::retro) continue;
      if (t.sample.weight == 0) {
        ++lost;
        continue;
      }
      const double a = std::acos(std::clamp(glm::dot(t.sample.wo, wi), -1.0, 1.0)) / rad;
      angle_sum += a;
      max_angle = std::max(max_angle, a);
      ++kept;
    }
    ASSERT_GT(kept, 5000);
    EXPECT_EQ(lost, 0) << "theta " << theta;  // internal angle below 35.26 deg: every face faces the ray
    EXPECT_LT(angle_sum / kept, 0.5) << "theta " << theta;
    EXPECT_LT(max_angle, 1.0) << "theta " << theta;
  }
}

TEST(MicrofacetRetro, SmoothSurfaceReflectsTheFresnelFraction) {
  const microfacet_retro model(smooth_params(0.0005));
  const int n = 200000;
  for (double theta : {15.0, 30.0, 45.0, 60.0, 75.0, 85.0}) {
    const glm::dvec3 wi = direction(theta, 70);
    const glm::dvec3 mirror{-wi.x, -wi.y, wi.z};
    pcg32 rng(31, 6);
    double energy = 0;
    for (int i = 0; i < n; ++i) {
      const retro_sample s = model.sample(wi, next_randoms(rng));
      if (glm::length(s.wo - mirror) < 1e-12) energy += s.weight;
    }
    energy /= n;
    const double f = fresnel_dielectric(std::cos(theta * rad), 1.5046);
    EXPECT_NEAR(energy, f, 4 * std::sqrt(f * (1 - f) / n) + 1e-12) << "theta " << theta;
  }
}

TEST(MicrofacetRetro, RoughSurfaceReflectionMatchesQuadrature) {
  const double alpha = 0.2, eta = 1.5046;
  microfacet_params params = smooth_params(0.0005);
  params.alpha_surface = alpha;
  const microfacet_retro model(params);
  for (double theta : {0.0, 30.0, 60.0, 80.0}) {
    const glm::dvec3 wi = direction(theta, 125);
    // Expected surface energy: Fresnel at the visible facet, lost when the mirror goes below.
    const double expected = integrate_patch(
        [&](const glm::dvec3& m) {
          const glm::dvec3 wo = 2 * glm::dot(wi, m) * m - wi;
          return wo.z > 0 ? beckmann_visible_d(wi, m, alpha) * fresnel_dielectric(glm::dot(wi, m), eta) : 0.0;
        },
        alpha, 0, q_max, 0, 2 * pi, 2000, 720);
    const branch_energy e = measure(model, wi, 200000, 41);
    EXPECT_NEAR(e.surface, expected, 4 * standard_error(e.surface, e.surface_sq, e.n)) << "theta " << theta;
  }
}

TEST(MicrofacetRetro, BranchEnergiesMatchTheAnalyticValues) {
  const microfacet_params params = smooth_params(0.0005);
  const microfacet_retro model(params);
  const int n = 400000;
  std::printf("microfacet retroreflector, alpha_surface 0, alpha_internal 0.0005, eta %.4f, R_int %.2f, %d samples\n",
              params.eta, params.internal_reflectance, n);
  std::printf("theta  phi | surface  retro    diffuse  total   | analytic: surface  retro    diffuse  total\n");
  for (double phi : {0.0, 30.0}) {
    for (double theta : {0.0, 15.0, 30.0, 45.0}) {
      const glm::dvec3 wi = direction(theta, phi);
      const branch_energy e = measure(model, wi, n, 51);
      const branch_energy a = analytic_smooth(wi, params.eta, params.internal_reflectance);
      std::printf("%5.0f %4.0f | %.5f  %.5f  %.5f  %.5f |           %.5f  %.5f  %.5f  %.5f\n", theta, phi, e.surface,
                  e.retro, e.diffuse, e.total, a.surface, a.retro, a.diffuse, a.total);
      const double tol = 4 * std::sqrt(0.25 / n);  // each branch is a Bernoulli share of weights <= 1
      EXPECT_NEAR(e.surface, a.surface, tol) << theta << " " << phi;
      EXPECT_NEAR(e.retro, a.retro, tol) << theta << " " << phi;
      EXPECT_NEAR(e.diffuse, a.diffuse, tol) << theta << " " << phi;
      EXPECT_NEAR(e.total, a.total, 4 * standard_error(e.total, e.total_sq, e.n)) << theta << " " << phi;
      EXPECT_LE(e.total, 1.0);
    }
  }
}

TEST(MicrofacetRetro, NormalIncidenceRetroFractionIsUOfZero) {
  const microfacet_params params = smooth_params(0.0005);
  const microfacet_retro model(params);
  pcg32 rng(61, 8);
  int retro = 0, refracted = 0;
  double diffuse_cos = 0;
  for (int i = 0; i < 200000; ++i) {
    const microfacet_trace t = model.trace({0, 0, 1}, next_randoms(rng));
    if (t.branch == microfacet_branch::retro) ++retro, ++refracted;
    if (t.branch == microfacet_branch::diffuse) ++refracted, diffuse_cos += t.sample.wo.z;
  }
  // The retroreflective path's share is ERA alone (spec 2.3): the coating reflectance weights the
  // path, it does not decide it.
  const double p = 0.683356248;  // U(0)
  EXPECT_NEAR(double(retro) / refracted, p, 4 * std::sqrt(p * (1 - p) / refracted));
  // The diffuse lobe is cosine-weighted: mean cos = 2/3, standard deviation sqrt(1/18).
  const int diffuse = refracted - retro;
  EXPECT_NEAR(diffuse_cos / diffuse, 2.0 / 3, 4 * std::sqrt(1.0 / 18 / diffuse));
}

// Spec 2.3 at normal incidence on a smooth sheet with nearly ideal cube faces: each coated face
// reflects R_int, so the retroreflected energy is (1 - F_in) ERA R_int^3 (1 - F_out); the coating
// absorbs (1 - F_in) ERA (1 - R_int^3), none of which reaches the diffuse lobe, whose energy stays
// (1 - F_in) (1 - ERA). Expected values are written out here from the spec's formulas.
TEST(MicrofacetRetro, NormalIncidenceCoatingReflectsAtEachFaceAndAbsorbsTheRest) {
  const double eta = 1.5046;
  const double f = std::pow((eta - 1) / (eta + 1), 2);  // Fresnel at normal incidence, entry and exit
  // ERA at x = 0: the straight-down refracted ray has azimuth 0, where w = 1 and ERA = U(0).
  const double era0 = std::max(0.0, -0.353394 * std::atan(0.055244 * 0 - 1.632606) + 0.322462);
  EXPECT_NEAR(era(0, 0), era0, 1e-12);
  const glm::dvec3 wi{0, 0, 1};
  const int n = 500000;
  std::printf("normal incidence, alpha_surface 0, alpha_internal 1e-6, eta %.4f, F %.6f, ERA %.6f, %d samples\n", eta,
              f, era0, n);
  for (double r_int : {0.83, 1.0}) {
    microfacet_params params = smooth_params(1e-6);
    params.eta = eta;
    params.internal_reflectance = r_int;
    const microfacet_retro model(params);
    pcg32 rng(91, 5);
    double retro = 0, retro_sq = 0, diffuse = 0, diffuse_sq = 0, coating = 0, coating_sq = 0;
    for (int i = 0; i < n; ++i) {
      const microfacet_trace t = model.trace(wi, next_randoms(rng));
      const double w = t.sample.weight;
      const double r = t.branch == microfacet_branch::retro ? w : 0;
      const double d = t.branch == microfacet_branch::diffuse ? w : 0;
      // The sample absorbs 1 - w (mu = 1). Of a retroreflected sample's light, w / (1 - F) reached
      // the exit surface, which reflected F of it back in (absorbed); the rest of the loss is the
      // coating's.
      const double c = 1 - w - r * f / (1 - f);
      retro += r, retro_sq += r * r;
      diffuse += d, diffuse_sq += d * d;
      coating += c, coating_sq += c * c;
    }
    retro /= n, retro_sq /= n, diffuse /= n, diffuse_sq /= n, coating /= n, coating_sq /= n;
    const double retro_se = standard_error(retro, retro_sq, n);
    const double diffuse_se = standard_error(diffuse, diffuse_sq, n);
    const double coating_se = standard_error(coating, coating_sq, n);
    const double r3 = r_int * r_int * r_int;
    const double expected_retro = (1 - f) * era0 * r3 * (1 - f);
    const double expected_coating = (1 - f) * era0 * (1 - r3);
    const double expected_diffuse = (1 - f) * (1 - era0);
    std::printf(
        "R_int %.2f: retro %.5f +- %.5f (expected %.5f, %+.3f%%), absorbed by the coating %.5f +- %.5f "
        "(expected %.5f), diffuse %.5f +- %.5f (expected %.5f)\n",
        r_int, retro, retro_se, expected_retro, 100 * (retro / expected_retro - 1), coating, coating_se,
        expected_coating, diffuse, diffuse_se, expected_diffuse);
    // The 1% band is wide against the Monte Carlo noise, so a pass is not luck and a 1% bias shows.
    ASSERT_LT(4 * retro_se, 0.005 * expected_retro);
    EXPECT_NEAR(retro, expected_retro, 0.01 * expected_retro) << "R_int " << r_int;
    EXPECT_NEAR(diffuse, expected_diffuse, 4 * diffuse_se) << "R_int " << r_int;
    if (expected_coating > 0) {
      ASSERT_LT(4 * coating_se, 0.005 * expected_coating);
      EXPECT_NEAR(coating, expected_coating, 0.01 * expected_coating) << "R_int " << r_int;
    } else {
      EXPECT_NEAR(coating, 0, 1e-9) << "R_int " << r_int;  // perfect mirrors: only the exit reflection is lost
    }
  }
}

// The coating reflectance changes nothing but the retroreflected weight, at any incidence: the same
// random numbers take the same branch and direction, and the retro weight scales by R_int^3.
TEST(MicrofacetRetro, CoatingLossScalesOnlyTheRetroWeight) {
  microfacet_params params = smooth_params(0.01);
  params.alpha_surface = 0.1;
  params.internal_reflectance = 1.0;
  const microfacet_retro mirror(params);
  params.internal_reflectance = 0.83;
  const microfacet_retro coated(params);
  pcg32 rng(101, 9);
  int retro = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 wi = direction(80 * rng.next_double(), 360 * rng.next_double());
    const retro_samples r = next_randoms(rng);
    const microfacet_trace a = coated.trace(wi, r), b = mirror.trace(wi, r);
    ASSERT_EQ(a.branch, b.branch);
    EXPECT_EQ(a.sample.wo, b.sample.wo);
    const double scale = a.branch == microfacet_branch::retro ? 0.83 * 0.83 * 0.83 : 1.0;
    EXPECT_NEAR(a.sample.weight, scale * b.sample.weight, 1e-15);
    retro += a.branch == microfacet_branch::retro && b.sample.weight > 0;
  }
  EXPECT_GT(retro, 2000);
}

namespace {

// Independent small-roughness prediction of E[1 - cos(wo, wi)] for the retroreflected path of a
// smooth sheet: each facet normal is the face normal plus a tangent offset with covariance
// alpha^2 / 2 per axis (the Beckmann slope variance), propagated to first order through the
// three reflections and the exit refraction. To first order the result is the same for every face
// order and prism orientation (checked here), so the face-order rule does not enter it.
double linearised_retro_spread(const glm::dvec3& wi, double eta, double alpha) {
  const auto snell = [](const glm::dvec3& d, const glm::dvec3& n, double ratio) {  // n faces against d
    const double c = -glm::dot(d, n);
    return ratio * d + (ratio * c - std::sqrt(1 - ratio * ratio * (1 - c * c))) * n;
  };
  const glm::dvec3 t0 = snell(-wi, {0, 0, 1}, 1 / eta);
  const auto exit = [&](const glm::dvec3& d) { return snell(glm::normalize(d), {0, 0, -1}, eta); };
  std::vector<double> spreads;
  for (double s : {1.0, -1.0}) {
    std::array<glm::dvec3, 3> n;
    for (int k = 0; k < 3; ++k) {
      const double a = 2 * pi * k / 3;
      n[k] = {s * 2 / std::sqrt(6.0) * std::cos(a), s * 2 / std::sqrt(6.0) * std::sin(a), 1 / std::sqrt(3.0)};
    }
    std::array<int, 3> order{0, 1, 2};
    do {
      glm::dmat3 cov(0.0);
      glm::dvec3 d = t0;
      for (int k : order) {
        const glm::dmat3 reflect = glm::dmat3(1.0) - 2.0 * glm::outerProduct(n[k], n[k]);
        const glm::dmat3 tangent = glm::dmat3(1.0) - glm::outerProduct(n[k], n[k]);
        // d' = d - 2 (d.m) m with m = n + delta: the first-order change is B delta.
        const glm::dmat3 b = -2.0 * (glm::outerProduct(n[k], d) + glm::dot(d, n[k]) * glm::dmat3(1.0));
        cov = reflect * cov * glm::transpose(reflect) + (alpha * alpha / 2) * b * tangent * glm::transpose(b);
        d = reflect * d;
      }
      glm::dmat3 jac;
      const double h = 1e-6;
      for (int i = 0; i < 3; ++i) {
        glm::dvec3 e(0.0);
        e[i] = h;
        jac[i] = (exit(d + e) - exit(d - e)) / (2 * h);
      }
      const glm::dmat3 out = jac * cov * glm::transpose(jac);
      spreads.push_back((out[0][0] + out[1][1] + out[2][2]) / 2);
    } while (std::next_permutation(order.begin(), order.end()));
  }
  for (double v : spreads) EXPECT_NEAR(v, spreads[0], 1e-6 * spreads[0]);
  return spreads[0];
}

}  // namespace

TEST(MicrofacetRetro, RetroSpreadMatchesLinearisedPropagation) {
  const double alpha = 0.01;
  const microfacet_params params = smooth_params(alpha);
  const microfacet_retro model(params);
  for (const auto& [theta, phi] : {std::pair{0.0, 0.0}, {20.0, 10.0}, {35.0, 100.0}, {45.0, 250.0}}) {
    const glm::dvec3 wi = direction(theta, phi);
    pcg32 rng(71, 2);
    double sum = 0, sum_sq = 0;
    int kept = 0;
    for (int i = 0; i < 400000; ++i) {
      const microfacet_trace t = model.trace(wi, next_randoms(rng));
      if (t.branch != microfacet_branch::retro || t.sample.weight == 0) continue;
      const double v = 1 - glm::dot(t.sample.wo, wi);
      sum += v;
      sum_sq += v * v;
      ++kept;
    }
    const double mean = sum / kept;
    const double predicted = linearised_retro_spread(wi, params.eta, alpha);
    std::printf("theta %4.0f phi %4.0f: mean 1 - cos %.4e, linearised %.4e (%d samples)\n", theta, phi, mean, predicted,
                kept);
    EXPECT_NEAR(mean, predicted, 0.02 * predicted + 4 * standard_error(mean, sum_sq / kept, kept)) << theta;
  }
}

TEST(MicrofacetRetro, SteepIncidenceLosesThePrismOrientationThatFacesAway) {
  // Beyond an internal angle of 35.26 deg a cube face can turn away from the refracted ray; a prism
  // orientation with such a face cannot retroreflect, so the retro branch keeps (orientations with
  // all three faces towards the ray) / 2 of its samples.
  const microfacet_params params = smooth_params(0.0005);
  const microfacet_retro model(params);
  // Away from 30 mod 60 deg (ERA 0 there) and from the angles where a face is grazing.
  for (const auto& [theta, phi] :
       {std::pair{40.0, 0.0}, {62.0, 20.0}, {62.0, 100.0}, {70.0, 0.0}, {75.0, 10.0}, {80.0, 180.0}, {85.0, 250.0}}) {
    const glm::dvec3 wi = direction(theta, phi);
    const double sin_x = std::sin(theta * rad) / params.eta;
    const glm::dvec3 t{-sin_x * std::cos(phi * rad), -sin_x * std::sin(phi * rad), -std::sqrt(1 - sin_x * sin_x)};
    int facing = 0;
    for (double s : {1.0, -1.0}) {
      bool all = true;
      for (int k = 0; k < 3; ++k) {
        const double a = 2 * pi * k / 3;
        const glm::dvec3 n{s * 2 / std::sqrt(6.0) * std::cos(a), s * 2 / std::sqrt(6.0) * std::sin(a),
                           1 / std::sqrt(3.0)};
        ASSERT_GT(std::abs(glm::dot(t, n)), 0.005) << theta << " " << phi << ": too close to grazing";
        all = all && glm::dot(t, n) < 0;
      }
      facing += all;
    }
    pcg32 rng(81, 3);
    int retro = 0, kept = 0;
    double angle_sum = 0;
    for (int i = 0; i < 100000; ++i) {
      const microfacet_trace tr = model.trace(wi, next_randoms(rng));
      if (tr.branch != microfacet_branch::retro) continue;
      ++retro;
      if (tr.sample.weight > 0) {
        ++kept;
        angle_sum += std::acos(std::min(1.0, glm::dot(tr.sample.wo, wi))) / rad;
      }
    }
    ASSERT_GT(retro, 1000) << theta << " " << phi;
    // Near grazing the exit refraction magnifies the internal spread (about 13 times at 85 deg).
    if (kept > 0) {
      EXPECT_LT(angle_sum / kept, 1.0) << theta << " " << phi;
    }
    const double expected = facing / 2.0;
    EXPECT_NEAR(double(kept) / retro, expected, 4 * std::sqrt(0.25 / retro) + 1e-12)
        << "theta " << theta << " phi " << phi << " facing orientations " << facing;
  }
}
