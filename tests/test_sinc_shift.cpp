// The sinc-shift model: its angular lobe against the density by chi-square, its energy, the blur
// it predicts (linear in distance, 1/a), and the shipped presets' trends.
#include <algorithm>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/core/table_search.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "airr/models/shift_table.hpp"
#include "airr/models/sinc_lobe.hpp"
#include "chi_square.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// Sinc-shift parameters at R = 300 mm: one a and mu for every angle, or a and mu over theta_deg.
sinc_shift_params lobe_params(std::vector<double> a_per_mm, std::vector<double> mu, double c_mm,
                              std::vector<double> theta_deg = {}) {
  sinc_shift_params p;
  p.theta_deg = std::move(theta_deg);
  p.a_per_mm = std::move(a_per_mm);
  p.mu = std::move(mu);
  p.c_mm = c_mm;
  p.reference_distance_mm = 300.0;
  return p;
}

// Integral of sinc^2 over [y0, y1] by composite Simpson: an independent reference.
double sinc2_integral(double y0, double y1) {
  const int n = 2000;
  const double h = (y1 - y0) / n;
  auto f = [](double y) {
    const double s = y == 0 ? 1.0 : std::sin(y) / y;
    return s * s;
  };
  double sum = f(y0) + f(y1);
  for (int i = 1; i < n; ++i) sum += f(y0 + i * h) * (i % 2 ? 4 : 2);
  return sum * h / 3;
}

scene sinc_scene(double a, double c, double distance_mm = 150) {
  scene s = test::uniform_source_scene(20.0);
  airr::set_floating_distance(s, distance_mm);
  s.sheet().model.type = "sinc_shift";
  airr::set_model_value(s.sheet().model, "a_per_mm", a);
  airr::set_model_value(s.sheet().model, "c_mm", c);
  return s;
}

scene preset_scene(const std::string& preset, double distance_mm, double tilt_deg) {
  scene s = test::uniform_source_scene(20.0);
  airr::set_floating_distance(s, distance_mm);
  s.sheet().pose.pitch_deg = tilt_deg;
  s.sheet().model.type = "sinc_shift";
  airr::set_model_value(s.sheet().model, "preset", preset);
  return s;
}

double blur_r50(const scene& s, std::uint64_t samples = 200000) {
  const auto model = make_sheet_model(s);
  return energy_radius(sample_psf(s, *model, {.samples = samples, .seed = 3}));
}

}  // namespace

class SincLobe : public ::testing::TestWithParam<double> {};

TEST_P(SincLobe, SamplingFollowsTheDensityByChiSquare) {
  const double a = GetParam(), k = a * 300.0;
  // Bins in y = k tan(delta), where the density is sinc^2(y) / (pi/2).
  std::vector<double> edges;
  for (double y = 0; y < 8.0; y += 0.25) edges.push_back(y);
  for (double y : {8.0, 12.0, 20.0, 50.0}) edges.push_back(y);
  std::vector<double> expected(edges.size()), observed(edges.size(), 0.0);
  const int n = 400000;
  double covered = 0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    expected[i] = sinc2_integral(edges[i], edges[i + 1]) / (std::numbers::pi / 2) * n;
    covered += expected[i];
  }
  expected.back() = n - covered;  // the tail beyond the last edge
  pcg32 rng(42, int(a * 1000));
  const sinc_lobe& lobe = sinc_lobe::instance();
  for (int i = 0; i < n; ++i) {
    const double y = k * lobe.sample_tan_delta(k, rng.next_double(), rng.next_double());
    const auto bin = std::upper_bound(edges.begin(), edges.end(), y) - edges.begin() - 1;
    observed[bin] += 1;
  }
  const auto r = test::chi_square(observed, expected);
  EXPECT_GT(r.p_value, 1e-3) << "a=" << a << " chi2=" << r.statistic << " dof=" << r.dof;
}

INSTANTIATE_TEST_SUITE_P(SeveralA, SincLobe, ::testing::Values(0.8, 1.17931, 2.0, 9.9302));

TEST(SincLobe, DensityIntegratesToOne) {
  for (double k : {1.0, 30.0, 300.0}) {
    // Integrate in y = k tan(delta) so the narrow peak is resolved: p(delta) d(delta) = sinc^2(y) dy / (pi/2).
    double sum = 0;
    const int n = 200000;
    const double y_max = 2000;
    for (int i = 0; i < n; ++i) {
      const double y = (i + 0.5) * y_max / n, delta = std::atan(y / k);
      sum += sinc_lobe::pdf(delta, k) * (k / (k * k + y * y)) * (y_max / n);  // d(delta)/dy = k / (k^2 + y^2)
    }
    EXPECT_NEAR(sum, 1.0, 2e-3) << "k=" << k;  // the tail beyond y_max holds 1/(pi y_max)
  }
}

TEST(SincShift, NeverReturnsMoreEnergyThanItReceives) {
  const sinc_shift_retro model(lobe_params({0.05}, {0.9}, 0.0), nullptr);
  for (double theta : {0.0, 30.0, 60.0, 85.0}) {
    const double t = theta * std::numbers::pi / 180;
    const glm::dvec3 wi(std::sin(t), 0, std::cos(t));
    pcg32 rng(7, 1);
    double sum = 0;
    const int n = 50000;
    for (int i = 0; i < n; ++i) {
      const retro_sample s = model.sample(wi, test::random_retro_samples(rng));
      EXPECT_LE(s.weight, 1.0);
      if (s.weight > 0) {
        EXPECT_GT(s.wo.z, 0.0);
      }
      sum += s.weight;
    }
    EXPECT_LE(sum / n, 0.9 + 1e-12) << theta;
    if (theta == 0.0) {
      EXPECT_NEAR(sum / n, 0.9, 0.01);  // a wide lobe still stays above the sheet
    }
  }
}

// The model prepared for one incidence (as the model image's angle bins use it) gives exactly
// the samples of the model itself, across the shift table's rows, with a per-angle a and mu, and
// for light from below the sheet; so does the default preparation of any other model.
TEST(SincShift, AtIncidenceSamplesAsTheModelDoes) {
  const sinc_shift_retro model(lobe_params({0.5, 0.3, 0.2}, {0.9, 0.8, 0.6}, 3.0, {0, 20, 40}),
                               cached_shift_table(default_shift_table_path()));
  const ideal_retro ideal(0.7);
  for (double theta : {0.0, 7.5, 33.0, 80.0, 120.0}) {
    const double t = theta * std::numbers::pi / 180;
    const glm::dvec3 wi(std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t));
    const auto prepared = model.at_incidence(wi);
    const auto prepared_ideal = ideal.at_incidence(wi);
    pcg32 rng(11, 3);
    for (int i = 0; i < 2000; ++i) {
      const retro_samples u = test::random_retro_samples(rng);
      const retro_sample a = model.sample(wi, u), b = prepared->sample(u);
      ASSERT_EQ(a.weight, b.weight) << theta;
      ASSERT_EQ(a.wo, b.wo) << theta;
      ASSERT_EQ(a.shift_mm, b.shift_mm) << theta;
      ASSERT_EQ(ideal.sample(wi, u).wo, prepared_ideal->sample(u).wo);
    }
  }
}

// Sampled together from the same numbers (as the model image's bins are), several incidences give
// each its own samples exactly: across the shift table's rows (the rows' shifts worked out once),
// for light from below the sheet, without a shift, and in a group that mixes models (each keeps
// its own; another model's incidences are sampled one by one).
TEST(SincShift, IncidencesSampledTogetherGiveEachItsOwnSamples) {
  const sinc_shift_retro model(lobe_params({0.5, 0.3, 0.2}, {0.9, 0.8, 0.6}, 3.0, {0, 20, 40}),
                               cached_shift_table(default_shift_table_path()));
  const sinc_shift_retro no_shift(lobe_params({0.4}, {0.7}, 0.0), nullptr);
  const ideal_retro ideal(0.7);
  auto wi_at = [](double theta_deg, double azimuth) {
    const double t = theta_deg * std::numbers::pi / 180;
    return glm::dvec3(std::sin(t) * std::cos(azimuth), std::sin(t) * std::sin(azimuth), std::cos(t));
  };
  std::vector<std::unique_ptr<const retro_at_incidence>> one_model, mixed;
  for (double theta : {0.0, 2.0, 4.5, 7.5, 12.0, 26.0, 33.0, 120.0})
    one_model.push_back(model.at_incidence(wi_at(theta, 0.3)));
  mixed.push_back(model.at_incidence(wi_at(3.0, 1.0)));
  mixed.push_back(no_shift.at_incidence(wi_at(3.0, 1.0)));
  mixed.push_back(ideal.at_incidence(wi_at(9.0, 2.0)));
  mixed.push_back(model.at_incidence(wi_at(17.0, 2.0)));
  for (const auto* group : {&one_model, &mixed}) {
    std::vector<const retro_at_incidence*> at;
    for (const auto& a : *group) at.push_back(a.get());
    std::vector<retro_sample> out(at.size());
    pcg32 rng(5, 9);
    for (int i = 0; i < 4000; ++i) {
      const retro_samples u = test::random_retro_samples(rng);
      sample_at_each(at, u, out);
      for (std::size_t k = 0; k < at.size(); ++k) {
        const retro_sample alone = at[k]->sample(u);
        ASSERT_EQ(out[k].weight, alone.weight) << k;
        ASSERT_EQ(out[k].wo, alone.wo) << k;
        ASSERT_EQ(out[k].shift_mm, alone.shift_mm) << k;
      }
    }
  }
}

// The model's own pdf against its sampler: directions binned by deviation and azimuth about wi
// (a basis built here), absorbed samples in a bin of their own, expected counts from integrating
// pdf over each bin. A grazing wi and a wide lobe put a good share below the sheet.
TEST(SincShift, SampledDirectionsFollowTheModelsPdfByChiSquare) {
  const sinc_shift_retro model(lobe_params({0.01}, {0.7}, 0.0), nullptr);
  const double theta = 60 * std::numbers::pi / 180;
  const glm::dvec3 wi(std::sin(theta), 0, std::cos(theta));
  const glm::dvec3 e1 = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), wi)), e2 = glm::cross(wi, e1);
  const int n_delta = 12, n_phi = 8;
  const double delta_max = std::numbers::pi / 2;
  auto delta_edge = [&](int i) { return delta_max * std::pow(double(i) / n_delta, 1.5); };
  auto direction = [&](double delta, double phi) {
    return std::cos(delta) * wi + std::sin(delta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
  };
  const int n = 300000;
  std::vector<double> expected(n_delta * n_phi + 1, 0.0), observed(n_delta * n_phi + 1, 0.0);
  double covered = 0;
  for (int i = 0; i < n_delta; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      const double d0 = delta_edge(i), d1 = delta_edge(i + 1);
      const double p0 = 2 * std::numbers::pi * j / n_phi, p1 = 2 * std::numbers::pi * (j + 1) / n_phi;
      const int m = 48;  // midpoint rule: the pdf diverges like 1 / sin(delta) on the axis
      double sum = 0;
      for (int a = 0; a < m; ++a) {
        for (int b = 0; b < m; ++b) {
          const double delta = d0 + (a + 0.5) * (d1 - d0) / m, phi = p0 + (b + 0.5) * (p1 - p0) / m;
          sum += model.pdf(wi, direction(delta, phi)).value() * std::sin(delta);
        }
      }
      expected[i * n_phi + j] = sum * (d1 - d0) / m * (p1 - p0) / m * n;
      covered += expected[i * n_phi + j];
    }
  }
  expected.back() = n - covered;
  EXPECT_GT(expected.back(), 0.05 * n);  // the absorbed share is substantial
  pcg32 rng(11, 5);
  for (int k = 0; k < n; ++k) {
    const retro_sample s = model.sample(wi, test::random_retro_samples(rng));
    if (!(s.weight > 0)) {
      observed.back() += 1;
      continue;
    }
    EXPECT_NEAR(*model.eval(wi, s.wo), 0.7 * *model.pdf(wi, s.wo), 1e-12 * *model.pdf(wi, s.wo));
    const double delta = std::acos(std::clamp(glm::dot(s.wo, wi), -1.0, 1.0));
    double phi = std::atan2(glm::dot(s.wo, e2), glm::dot(s.wo, e1));
    if (phi < 0) phi += 2 * std::numbers::pi;
    int i = 0;
    while (i + 1 < n_delta && delta >= delta_edge(i + 1)) ++i;
    const int j = std::min(n_phi - 1, int(phi / (2 * std::numbers::pi) * n_phi));
    observed[i * n_phi + j] += 1;
  }
  const auto r = test::chi_square(observed, expected);
  EXPECT_GT(r.p_value, 1e-3) << "chi2=" << r.statistic << " dof=" << r.dof;
  EXPECT_FALSE(ideal_retro(1.0).pdf(wi, wi).has_value());  // a delta has no density
}

TEST(SincShift, LobeBlurGrowsLinearlyWithDistanceAndAsOneOverA) {
  for (double a : {2.0, 4.0}) {
    std::vector<double> l, r;
    for (double d = 150; d <= 300; d += 25) {
      const scene s = sinc_scene(a, 0.0, d);
      const auto model = make_sheet_model(s);
      const psf_samples psf = sample_psf(s, *model, {.samples = 200000, .seed = 5});
      l.push_back(psf.rr_distance_mm);
      r.push_back(energy_radius(psf));
    }
    // Least-squares line and r^2.
    const double n = double(l.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (std::size_t i = 0; i < l.size(); ++i) {
      sx += l[i];
      sy += r[i];
      sxx += l[i] * l[i];
      sxy += l[i] * r[i];
      syy += r[i] * r[i];
    }
    const double cov = sxy - sx * sy / n, vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
    const double r2 = cov * cov / (vx * vy);
    EXPECT_GE(r2, 0.99) << "a=" << a;
    // Through the origin: r50 = L * y50 / (a R), y50 the median of sinc^2 on [0, inf).
    EXPECT_NEAR(r.front() / l.front(), r.back() / l.back(), 0.03 * r.back() / l.back());
  }
  const double r2 = blur_r50(sinc_scene(2.0, 0.0)), r4 = blur_r50(sinc_scene(4.0, 0.0));
  EXPECT_NEAR(r2 / r4, 2.0, 0.06);
}

TEST(Presets, LoadByNameAndPath) {
  const sheet_preset ay = load_preset("rf-ay");
  EXPECT_EQ(ay.name, "RF-Ay");
  ASSERT_EQ(ay.theta_deg.size(), 10u);
  EXPECT_DOUBLE_EQ(ay.a_per_mm[0], 9.93020);
  EXPECT_DOUBLE_EQ(ay.mu[9], 0.10973);
  EXPECT_DOUBLE_EQ(ay.c_mm, 0.94966);
  EXPECT_DOUBLE_EQ(ay.reference_distance_mm, 300);
  const sheet_preset an = load_preset(asset_dir() + "/presets/rf-an.json");
  EXPECT_DOUBLE_EQ(an.c_mm, 0.0015561);
  EXPECT_DOUBLE_EQ(interpolate_by_angle(an.theta_deg, an.a_per_mm, 2.5), (1.11525 + 1.21330) / 2);
  EXPECT_DOUBLE_EQ(interpolate_by_angle(an.theta_deg, an.mu, 60), 0.088765);
  test::temp_dir dir;
  save_preset(an, dir.file("copy.json"));
  EXPECT_EQ(preset_to_json(load_preset(dir.file("copy.json"))), preset_to_json(an));
}

TEST(Presets, SceneOverridesApplyAtEveryAngle) {
  retro_model_params m;
  m.type = "sinc_shift";
  set_model_value(m, "preset", "rf-ay");
  set_model_value(m, "mu", 0.5);
  const sinc_shift_params p = resolve_sinc_shift_params(m, {});
  EXPECT_EQ(p.mu, std::vector<double>{0.5});
  EXPECT_EQ(p.a_per_mm.size(), 10u);
  EXPECT_DOUBLE_EQ(p.c_mm, 0.94966);
}

TEST(Presets, BadPresetsGiveClearErrors) {
  test::temp_dir dir;
  auto expect_error = [&](const std::string& text, const std::string& needle) {
    const std::string path = dir.file("p.json");
    std::ofstream(path) << text;
    try {
      load_preset(path);
      ADD_FAILURE() << "no error for " << text;
    } catch (const input_error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const std::string head = R"({"format": "airr-preset", "version": 1, )";
  expect_error(head + R"("a_per_mm": [1, 2], "mu": 0.2, "c_mm": 0.1, "tilt_deg": [0, 5, 10]})",
               "a_per_mm: needs one value");
  expect_error(head + R"("a_per_mm": -1, "mu": 0.2, "c_mm": 0.1})", "a_per_mm: must be positive");
  expect_error(head + R"("a_per_mm": 1, "mu": 0.2})", "c_mm: missing");
  expect_error(head + R"("a_per_mm": 1, "mu": 0.2, "c_mm": 0.1, "colour": 1})", "colour: unknown key");
  expect_error(head + R"("a_per_mm": 1, "mu": 0.2, "c_mm": 0.1, "shift_index": 0.5})",
               "shift_index: must be in [1, 3]");
  expect_error("{", "malformed JSON");
  EXPECT_THROW(load_preset("no-such-sheet"), input_error);
}

// A preset's shift_index reads the shift table at the angle inside: at 30.87 deg outside an index
// of 1.5 gives 20 deg inside, where the shifts (in c) follow the table's 20 deg row by chi-square,
// and not its 30 deg row; the index round-trips through the preset file.
TEST(Presets, ShiftIndexReadsTheShiftTableAtTheAngleInside) {
  test::temp_dir dir;
  sheet_preset p;
  p.name = "in glass";
  p.a_per_mm = {1000};
  p.mu = {1};
  p.c_mm = 1;
  p.shift_index = 1.5;
  save_preset(p, dir.file("glass.json"));
  EXPECT_DOUBLE_EQ(load_preset(dir.file("glass.json")).shift_index, 1.5);
  EXPECT_DOUBLE_EQ(load_preset("rf-ay").shift_index, 1.0);

  retro_model_params m{.type = "sinc_shift", .values = {}};
  set_model_value(m, "preset", dir.file("glass.json"));
  const auto model = make_retro_model(m);
  const shift_table table = load_shift_table(default_shift_table_path());
  const double outside = degrees(std::asin(1.5 * std::sin(radians(20))));
  const glm::dvec3 wi = test::unit_direction(outside, 0);
  const int bins = table.bins(), n = 20000;
  std::vector<double> counts(std::size_t(bins), 0.0);
  pcg32 rng(3, 9);
  for (int i = 0; i < n; ++i) {
    const retro_sample r = model->sample(wi, test::random_retro_samples(rng));
    counts[std::size_t(std::min(bins - 1, int(glm::length(r.shift_mm) / table.s_max * bins)))] += 1;
  }
  auto p_value = [&](double theta) {
    const auto row =
        std::size_t(std::find(table.theta_deg.begin(), table.theta_deg.end(), theta) - table.theta_deg.begin());
    std::vector<double> expected;
    for (double pr : table.probability[row]) expected.push_back(pr * n);
    return test::chi_square(counts, expected).p_value;
  };
  std::printf("shifts at %.2f deg outside, index 1.5: p = %.3f against the 20 deg row, %.2g against 30 deg\n", outside,
              p_value(20), p_value(30));
  EXPECT_GT(p_value(20), 1e-3);
  EXPECT_LT(p_value(30), 1e-6);
}

TEST(Presets, BlurGrowsWithFloatingDistance) {
  for (const char* preset : {"rf-ay", "rf-an"}) {
    double previous = 0;
    for (double d = 150; d <= 300; d += 25) {
      const double r = blur_r50(preset_scene(preset, d, 0));
      EXPECT_GT(r, previous) << preset << " D=" << d;
      previous = r;
    }
  }
}

TEST(Presets, BlurAt45ExceedsBlurAt0) {
  for (const char* preset : {"rf-ay", "rf-an"}) {
    EXPECT_GT(blur_r50(preset_scene(preset, 150, 45)), blur_r50(preset_scene(preset, 150, 0))) << preset;
  }
}

TEST(Presets, RfAnBlursMoreThanRfAyAtEveryTilt) {
  for (double tilt = 0; tilt <= 45; tilt += 5) {
    const double ay = blur_r50(preset_scene("rf-ay", 150, tilt)), an = blur_r50(preset_scene("rf-an", 150, tilt));
    std::printf("tilt %4.0f deg: r50 RF-Ay %.4f mm, RF-AN %.4f mm\n", tilt, ay, an);
    EXPECT_GT(an, ay) << "tilt " << tilt;
  }
}

// The samplers' table search gives std::upper_bound's index: tables with repeated values, values
// below, between, on and above the entries, every length from 0 to 40.
TEST(TableSearch, FirstGreaterIsUpperBound) {
  pcg32 rng(3, 5);
  for (std::size_t n = 0; n <= 40; ++n) {
    std::vector<double> table(n);
    double v = 0;
    for (double& t : table) t = v += rng.next_double() < 0.3 ? 0.0 : rng.next_double();
    std::vector<double> xs = {-1.0, v + 1.0};
    for (double t : table) xs.insert(xs.end(), {t, t - 1e-12, t + 1e-12});
    for (int k = 0; k < 20; ++k) xs.push_back(rng.next_double() * (v + 0.5));
    for (double x : xs) {
      const auto expected = std::size_t(std::upper_bound(table.begin(), table.end(), x) - table.begin());
      EXPECT_EQ(first_greater(table.data(), n, x), expected) << "n " << n << ", x " << x;
    }
  }
}
