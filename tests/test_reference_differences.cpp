// The sinc-shift model's known differences from the authors' reference code (docs/models.md),
// each emulated by a small wrapper around our model and measured on the model PSF of the paper's
// bench: mean MTF over (0, 1] lp/mm, the optics alone. Every wrapper is first checked against a
// closed form, so the figures it prints measure what they say.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "airr/analysis/psf_mtf.hpp"
#include "airr/core/geometry.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

enum class variant {
  cone,             // a constant 4.89e-4 rad added to every deviation
  coupled_azimuth,  // the deviation's azimuth equal to the shift's direction
  slipped_azimuth,  // the same, the shift's direction in degrees read as radians
  dropped_cos2,     // the deviation density without its 1 / cos^2 factor
};

constexpr double cone_rad = 4.89e-4;

// Our model's sample, changed as the variant would have it.
class reference_variant final : public retro_model {
 public:
  reference_variant(std::shared_ptr<const retro_model> base, variant v) : base_(std::move(base)), v_(v) {}

  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override {
    retro_sample s = base_->sample(wi, u);  // the same numbers as our model's own sample
    pcg32 copy = u.more;
    pcg32 own = copy.split();  // the variant's numbers, a stream apart from the model's
    if (!(s.weight > 0)) return s;
    const double cos_d = std::clamp(glm::dot(s.wo, wi), -1.0, 1.0);
    const double delta = std::acos(cos_d);
    glm::dvec3 axis = s.wo - cos_d * wi;  // the deviation's direction, across wi
    const double len = glm::length(axis);
    if (len > 1e-15) {
      axis /= len;
    } else {
      const double phi = 2 * pi * own.next_double();
      const basis b = make_basis(wi);
      axis = b.to_world({std::cos(phi), std::sin(phi), 0});
    }
    double new_delta = delta;
    switch (v_) {
      case variant::cone:
        new_delta = delta + cone_rad;
        break;
      case variant::coupled_azimuth:
      case variant::slipped_azimuth: {
        if (s.shift_mm == glm::dvec2(0)) break;
        double psi = std::atan2(s.shift_mm.y, s.shift_mm.x);
        if (v_ == variant::slipped_azimuth) psi = degrees(psi);
        const glm::dvec3 along{std::cos(psi), std::sin(psi), 0};
        const glm::dvec3 across = along - glm::dot(along, wi) * wi;
        if (glm::length(across) > 1e-12) axis = glm::normalize(across);
        break;
      }
      case variant::dropped_cos2:
        // Density times cos^2: rejection keeps the shape; the mean MTF is normalised at zero
        // frequency, so the lost weight does not matter.
        if (own.next_double() >= cos_d * cos_d) s.weight = 0;
        break;
    }
    s.wo = std::cos(new_delta) * wi + std::sin(new_delta) * axis;
    if (s.wo.z <= 0) s.weight = 0;
    return s;
  }

 private:
  std::shared_ptr<const retro_model> base_;
  variant v_;
};

scene bench(const std::string& preset, double tilt_deg, double d_mm) {
  scene s = test::uniform_source_scene(50);
  retro_model_params& m = s.sheet().model;
  m = with_model_type(m, preset.empty() ? "ideal" : "sinc_shift");
  if (!preset.empty()) set_model_value(m, "preset", preset);
  s.sheet().pose.pitch_deg = tilt_deg;
  set_floating_distance(s, d_mm);
  return s;
}

constexpr std::uint64_t samples = 100000;

double mean_mtf(const scene& s, const retro_model& model) {
  return analysis::psf_mean_mtf(sample_psf(s, model, {.samples = samples, .seed = 3}), 1.0);
}

}  // namespace

TEST(ReferenceDifferences, ConeVariantOnAnIdealSheetIsARing) {
  // All deviation is the cone: a ring of radius rr_distance * tan(cone) on the aerial-image
  // plane, whose MTF along x is J0(2 pi f r).
  const scene s = bench("", 0, 150);
  const auto cone = std::make_shared<reference_variant>(make_sheet_model(s), variant::cone);
  const psf_samples psf = sample_psf(s, *cone, {.samples = samples, .seed = 3});
  const double r = psf.rr_distance_mm * std::tan(cone_rad);
  const auto curve = analysis::psf_mtf(psf, {.max_lp_per_mm = 4.0, .points = 9});
  for (std::size_t i = 0; i < curve.lp_per_mm.size(); ++i) {
    const double expected = std::abs(std::cyl_bessel_j(0.0, 2 * pi * curve.lp_per_mm[i] * r));
    EXPECT_NEAR(curve.mtf[i], expected, 0.005) << curve.lp_per_mm[i] << " lp/mm";
  }
}

TEST(ReferenceDifferences, DroppedCosineKeepsTheFractionTheDensitiesPredict) {
  // The rejection keeps cos^2(delta) of the lobe: its mean under our density
  // sinc^2(k tan d) / cos^2 d, which is integral sinc^2(k x) / (1 + x^2) dx over integral
  // sinc^2(k x) dx = pi / (2k) with x = tan d (quadrature, independent of the sampler).
  const double k = 300 * 1.11525;  // RF-AN at tilt 0
  double num = 0;
  const int n = 2000000;
  const double x_max = 2000.0 / k, dx = x_max / n;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * dx, u = k * x;
    num += std::pow(std::sin(u) / u, 2) / (1 + x * x) * dx;
  }
  const double expected = num / (pi / (2 * k));

  scene s = bench("rf-an", 0, 150);
  set_model_value(s.sheet().model, "c_mm", 0.0);  // no shift: the weight is mu alone
  const auto base = make_sheet_model(s);
  const reference_variant dropped(std::shared_ptr<const retro_model>(make_sheet_model(s)), variant::dropped_cos2);
  pcg32 rng(5, 7);
  double kept = 0, launched = 0;
  for (int i = 0; i < 400000; ++i) {
    const retro_samples u = test::random_retro_samples(rng);
    const double w0 = base->sample({0, 0, 1}, u).weight;
    if (!(w0 > 0)) continue;
    launched += 1;
    kept += dropped.sample({0, 0, 1}, u).weight / w0;
  }
  std::printf("kept fraction %.5f, quadrature %.5f\n", kept / launched, expected);
  EXPECT_NEAR(kept / launched, expected, 4 * std::sqrt(expected * (1 - expected) / launched));
}

TEST(ReferenceDifferences, MeasuredEffectsOnMeanMtf) {
  std::printf("mean MTF over (0, 1] lp/mm, model PSF, optics alone, %llu samples\n",
              static_cast<unsigned long long>(samples));
  std::printf("preset  tilt   D  | ours     | cone           | coupled azimuth | slipped azimuth | no 1/cos^2\n");
  for (const char* preset : {"rf-ay", "rf-an"}) {
    for (double tilt : {0.0, 20.0}) {
      for (double d : {150.0, 300.0}) {
        const scene s = bench(preset, tilt, d);
        const std::shared_ptr<const retro_model> base = make_sheet_model(s);
        const double ours = mean_mtf(s, *base);
        double effect[4];
        for (int v = 0; v < 4; ++v) effect[v] = mean_mtf(s, reference_variant(base, variant(v))) - ours;
        std::printf("%-6s %5.0f %4.0f | %.5f  | %+.5f       | %+.5f        | %+.5f        | %+.5f\n", preset, tilt, d,
                    ours, effect[0], effect[1], effect[2], effect[3]);
        // A cone widens every deviation, so it can only blur.
        EXPECT_LT(effect[0], 0) << preset << " tilt " << tilt << " D " << d;
      }
    }
  }
}
