// Corner-cube shift tables (spec section 3): the Embree generator against the point-inversion
// prediction, the shipped table, sampling, and strict loading.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/random.hpp"
#include "airr/models/corner_cube.hpp"
#include "airr/models/shift_table.hpp"
#include "airr/render/shift_table_tracer.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

constexpr double pi = 3.14159265358979323846;

const shift_table& shipped_table() {
  static const shift_table t = load_shift_table(default_shift_table_path());
  return t;
}

// The incidence direction of the spec, written out again so that the prediction shares no code
// with the generator: phi from the x edge projected on the aperture plane.
glm::dvec3 incidence(double theta_deg, double phi_deg) {
  const glm::dvec3 n = glm::dvec3(1, 1, 1) / std::sqrt(3.0);
  const glm::dvec3 t1 = glm::dvec3(2, -1, -1) / std::sqrt(6.0);
  const glm::dvec3 t2 = glm::cross(n, t1);
  const double th = theta_deg * pi / 180, ph = phi_deg * pi / 180;
  return -(std::cos(th) * n + std::sin(th) * (std::cos(ph) * t1 + std::sin(ph) * t2));
}

struct prediction {
  std::vector<double> probability;
  double retro_fraction = 0;
};

// Three reflections on planes through the apex compose to the point inversion, so a ray entering
// at p along d leaves at e = 2q - p, q = d / (d.x + d.y + d.z); it is retroreflected iff e is on
// the aperture. Entry points are uniform on the aperture, as a parallel ray grid makes them.
prediction predict_by_point_inversion(double theta_deg, const std::vector<double>& phi_deg, int samples_per_phi,
                                      int bins, double s_max) {
  prediction out;
  out.probability.assign(std::size_t(bins), 0.0);
  std::uint64_t kept = 0, total = 0;
  pcg32 rng(std::uint64_t(theta_deg * 1000) + 17, 3);
  const glm::dvec3 a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  for (double phi : phi_deg) {
    const glm::dvec3 d = incidence(theta_deg, phi);
    const glm::dvec3 q = d / (d.x + d.y + d.z);
    for (int i = 0; i < samples_per_phi; ++i) {
      double u = rng.next_double(), v = rng.next_double();
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const glm::dvec3 p = a + u * (b - a) + v * (c - a);
      const glm::dvec3 e = 2.0 * q - p;
      ++total;
      if (e.x < 0 || e.y < 0 || e.z < 0) continue;
      ++kept;
      const int bin = std::min(int(glm::length(e - p) / s_max * bins), bins - 1);
      out.probability[std::size_t(bin)] += 1;
    }
  }
  for (double& v : out.probability) v /= double(kept);
  out.retro_fraction = double(kept) / double(total);
  return out;
}

double total_variation(const std::vector<double>& p, const std::vector<double>& q) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += std::abs(p[i] - q[i]);
  return 0.5 * sum;
}

// Pearson chi-square of observed counts against expected probabilities, bins with fewer than 5
// expected counts merged into their neighbours; `dof` receives the degrees of freedom. Infinite
// when a bin of zero probability has samples.
double chi_square(const std::vector<std::uint64_t>& observed, const std::vector<double>& probability, int& dof) {
  std::uint64_t n = 0;
  for (auto o : observed) n += o;
  std::vector<double> obs(1, 0.0), exp(1, 0.0);
  for (std::size_t b = 0; b < observed.size(); ++b) {
    if (exp.back() >= 5) {
      obs.push_back(0);
      exp.push_back(0);
    }
    obs.back() += double(observed[b]);
    exp.back() += probability[b] * double(n);
    if (probability[b] == 0 && observed[b] > 0) return std::numeric_limits<double>::infinity();
  }
  if (exp.size() > 1 && exp.back() < 5) {  // a thin tail joins the group before it
    obs[obs.size() - 2] += obs.back();
    exp[exp.size() - 2] += exp.back();
    obs.pop_back();
    exp.pop_back();
  }
  double chi2 = 0;
  for (std::size_t g = 0; g < obs.size(); ++g) chi2 += (obs[g] - exp[g]) * (obs[g] - exp[g]) / exp[g];
  dof = int(obs.size()) - 1;
  return chi2;
}

// Histograms `count` draws of sample_shift at theta_deg over the table's bins.
std::vector<std::uint64_t> sample_histogram(const shift_table& t, double theta_deg, int count,
                                            std::vector<std::uint64_t>* in_bin_position = nullptr) {
  std::vector<std::uint64_t> hist(std::size_t(t.bins()), 0);
  pcg32 rng(std::uint64_t(theta_deg * 100) + 5, 11);
  const double width = t.s_max / t.bins();
  for (int i = 0; i < count; ++i) {
    const double u0 = rng.next_double(), u1 = rng.next_double(), u2 = rng.next_double();
    const double s = sample_shift(t, theta_deg, u0, u1, u2);
    const int bin = std::clamp(int(s / width), 0, t.bins() - 1);
    ++hist[std::size_t(bin)];
    if (in_bin_position) {
      const double frac = s / width - bin;
      ++(*in_bin_position)[std::min(std::size_t(frac * in_bin_position->size()), in_bin_position->size() - 1)];
    }
  }
  return hist;
}

// A chi-square this far above its mean would happen by chance far less than once in a million.
double chi_square_limit(int dof) { return dof + 6.0 * std::sqrt(2.0 * dof); }

std::size_t row_of(const shift_table& t, double theta_deg) {
  for (std::size_t i = 0; i < t.theta_deg.size(); ++i) {
    if (t.theta_deg[i] == theta_deg) return i;
  }
  ADD_FAILURE() << "no row for theta " << theta_deg;
  return 0;
}

}  // namespace

// ---------------------------------------------------------------- geometry and generator

TEST(CornerCube, ShippedModelIsTheCornerCube) {
  const triangle_mesh shipped = load_gltf_mesh(asset_dir() + "/models/corner_cube.gltf");
  const triangle_mesh made = make_corner_cube();
  EXPECT_EQ(shipped.positions, made.positions);
  EXPECT_EQ(shipped.indices, made.indices);
}

TEST(ShiftTableTracer, RetroFractionAtNormalIncidenceIsTwoThirds) {
  shift_table_params p;
  p.grid = 300;
  p.theta_deg = {0};
  const shift_table t = trace_shift_table(make_corner_cube(), p);
  ASSERT_EQ(t.retro_fraction.size(), 1u);
  std::printf("traced grid 300: retro fraction at theta 0 = %.5f\n", t.retro_fraction[0]);
  EXPECT_NEAR(t.retro_fraction[0], 2.0 / 3.0, 0.003);
}

TEST(ShiftTableTracer, ResultDoesNotDependOnThreadCount) {
  shift_table_params p;
  p.grid = 80;
  p.theta_deg = {0, 30};
  p.phi_deg = {0, 25, 70};
  shift_table one, two;
  tbb::task_arena(1).execute([&] { one = trace_shift_table(make_corner_cube(), p); });
  tbb::task_arena(2).execute([&] { two = trace_shift_table(make_corner_cube(), p); });
  EXPECT_EQ(one.probability, two.probability);
  EXPECT_EQ(one.retro_fraction, two.retro_fraction);
  EXPECT_EQ(one.provenance, two.provenance);
}

TEST(ShiftTableTracer, RejectsAMeshOffTheMirrorPlanes) {
  triangle_mesh m = make_corner_cube();
  m.positions[0] = {0.1f, 0.1f, 0.1f};  // the apex off every mirror plane
  EXPECT_THROW(trace_shift_table(m, shift_table_params{.grid = 10}), input_error);
}

// ---------------------------------------------------------------- the shipped table

TEST(ShippedShiftTable, RetroFractionAtNormalIncidenceIsTwoThirds) {
  const shift_table& t = shipped_table();
  EXPECT_NEAR(t.retro_fraction[row_of(t, 0)], 2.0 / 3.0, 0.003);
}

TEST(ShippedShiftTable, RecordsHowItWasMade) {
  const shift_table& t = shipped_table();
  EXPECT_EQ(t.theta_deg, (std::vector<double>{0, 5, 10, 15, 20, 25, 30, 35, 40, 45}));
  EXPECT_GE(t.bins(), 150);
  EXPECT_EQ(t.s_max, 1.5);
  for (const char* key : {"grid", "theta_deg", "phi_deg", "bins", "s_max", "generation_distance", "date", "command",
                          "model", "run_seconds", "threads", "rays_entering", "rays_kept"}) {
    EXPECT_TRUE(t.provenance.contains(key)) << key;
  }
  EXPECT_EQ(t.provenance.value("grid", 0), 1500);
}

TEST(ShippedShiftTable, MatchesPointInversionPrediction) {
  const shift_table& t = shipped_table();
  const std::vector<double> phi = t.provenance.at("phi_deg").get<std::vector<double>>();
  ASSERT_FALSE(phi.empty());
  for (std::size_t i = 0; i < t.theta_deg.size(); ++i) {
    // More samples where few are retroreflected, so that every row gets about as many.
    const int samples = int(std::clamp(60000 / std::max(t.retro_fraction[i], 0.01), 100000.0, 1000000.0));
    const prediction pred = predict_by_point_inversion(t.theta_deg[i], phi, samples, t.bins(), t.s_max);
    const double tv = total_variation(pred.probability, t.probability[i]);
    std::printf("theta %4.1f deg: TV distance %.4f, retro fraction table %.5f, predicted %.5f\n", t.theta_deg[i], tv,
                t.retro_fraction[i], pred.retro_fraction);
    EXPECT_LE(tv, 0.02) << "theta " << t.theta_deg[i];
    EXPECT_NEAR(t.retro_fraction[i], pred.retro_fraction, 0.005) << "theta " << t.theta_deg[i];
  }
}

// ---------------------------------------------------------------- sampling

TEST(SampleShift, TabulatedAngleFollowsItsRow) {
  const shift_table& t = shipped_table();
  for (double theta : {0.0, 20.0, 45.0}) {
    std::vector<std::uint64_t> in_bin(10, 0);
    const auto hist = sample_histogram(t, theta, 400000, &in_bin);
    int dof = 0;
    const double chi2 = chi_square(hist, t.probability[row_of(t, theta)], dof);
    EXPECT_LT(chi2, chi_square_limit(dof)) << "theta " << theta << ", " << dof << " degrees of freedom";
    // The position inside the bin is uniform.
    const double chi2_in_bin = chi_square(in_bin, std::vector<double>(10, 0.1), dof);
    EXPECT_LT(chi2_in_bin, chi_square_limit(dof)) << "theta " << theta;
  }
}

TEST(SampleShift, HalfwayAngleMixesTheNeighbouringRows) {
  const shift_table& t = shipped_table();
  const std::size_t lo = row_of(t, 10), hi = row_of(t, 15);
  std::vector<double> mix(std::size_t(t.bins()));
  for (std::size_t b = 0; b < mix.size(); ++b) mix[b] = 0.5 * (t.probability[lo][b] + t.probability[hi][b]);
  int dof = 0;
  const double chi2 = chi_square(sample_histogram(t, 12.5, 400000), mix, dof);
  EXPECT_LT(chi2, chi_square_limit(dof)) << dof << " degrees of freedom";
  // Against either row alone the samples do not fit.
  EXPECT_GT(chi_square(sample_histogram(t, 12.5, 400000), t.probability[lo], dof), chi_square_limit(dof));
}

TEST(SampleShift, ClampsOutsideTheTableAndSkipsEmptyBins) {
  shift_table t;
  t.theta_deg = {10, 20};
  t.s_max = 4;
  t.probability = {{0, 0.5, 0, 0.5}, {1, 0, 0, 0}};
  t.retro_fraction = {0.5, 0.5};
  finalize_shift_table(t);
  for (double u : {0.0, 0.2, 0.4999, 0.5, 0.9, 0.999999, 1.0}) {
    const double s = sample_shift(t, 0, 0.5, u, 0.5);  // below the table: the first row
    EXPECT_TRUE(s == 1.5 || s == 3.5) << "u " << u << " gave " << s;
    EXPECT_EQ(sample_shift(t, 90, 0.5, u, 0.25), 0.25);  // above: the last row
  }
  EXPECT_EQ(sample_shift(t, 15, 0.49, 0.9, 0.0), 0.0);  // u_pick < t = 0.5: the upper row
  EXPECT_EQ(sample_shift(t, 15, 0.51, 0.9, 0.0), 3.0);  // otherwise the lower one
}

// ---------------------------------------------------------------- files

TEST(ShiftTableFile, SaveLoadRoundTrip) {
  test::temp_dir dir;
  shift_table t;
  t.theta_deg = {0, 7.5};
  t.s_max = 1.25;
  t.probability = {{0.1, 0.2, 0.7}, {1.0 / 3, 1.0 / 3, 1.0 / 3}};
  t.retro_fraction = {2.0 / 3, 0.1};
  t.provenance = {{"grid", 12}, {"note", "made in a test"}};
  save_shift_table(t, dir.file("t.json"));
  const shift_table back = load_shift_table(dir.file("t.json"));
  EXPECT_EQ(back.theta_deg, t.theta_deg);
  EXPECT_EQ(back.s_max, t.s_max);
  EXPECT_EQ(back.probability, t.probability);
  EXPECT_EQ(back.retro_fraction, t.retro_fraction);
  EXPECT_EQ(back.provenance, t.provenance);
  EXPECT_EQ(back.cdf.size(), 2u);
}

TEST(ShiftTableFile, BadFilesGiveErrorsNamingTheFileAndField) {
  test::temp_dir dir;
  const nlohmann::json good = {{"format", "airr-shift-table"},
                               {"version", 1},
                               {"s_max", 1.5},
                               {"bins", 3},
                               {"theta_deg", {0, 5}},
                               {"probability", {{0.5, 0.5, 0}, {0.2, 0.3, 0.5}}},
                               {"retro_fraction", {0.6, 0.5}},
                               {"provenance", nlohmann::json::object()}};
  std::ofstream(dir.file("good.json")) << good.dump();
  EXPECT_NO_THROW(load_shift_table(dir.file("good.json")));

  struct bad_case {
    std::string name;
    std::function<void(nlohmann::json&)> edit;
    std::string field;
  };
  const std::vector<bad_case> cases = {
      {"format", [](nlohmann::json& j) { j["format"] = "something-else"; }, "format"},
      {"version", [](nlohmann::json& j) { j["version"] = 2; }, "version"},
      {"no_fractions", [](nlohmann::json& j) { j.erase("retro_fraction"); }, "retro_fraction"},
      {"fractions", [](nlohmann::json& j) { j["retro_fraction"] = {0.6}; }, "retro_fraction"},
      {"fraction_range", [](nlohmann::json& j) { j["retro_fraction"][1] = 1.5; }, "retro_fraction[1]"},
      {"rows", [](nlohmann::json& j) { j["probability"].erase(1); }, "probability"},
      {"row_length",
       [](nlohmann::json& j) {
         j["probability"][1] = {0.5, 0.5};
       },
       "probability[1]"},
      {"row_sum", [](nlohmann::json& j) { j["probability"][1][2] = 0.4; }, "probability[1]"},
      {"negative",
       [](nlohmann::json& j) {
         j["probability"][0] = {1.5, -0.5, 0};
       },
       "probability[0][1]"},
      {"not_number", [](nlohmann::json& j) { j["probability"][0][0] = "half"; }, "probability[0][0]"},
      {"theta_order",
       [](nlohmann::json& j) {
         j["theta_deg"] = {5, 0};
       },
       "theta_deg[1]"},
      {"s_max", [](nlohmann::json& j) { j["s_max"] = 0; }, "s_max"},
      {"unknown", [](nlohmann::json& j) { j["colour"] = "blue"; }, "colour"},
  };
  auto expect_error = [](const std::string& path, const std::string& field) {
    try {
      load_shift_table(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const input_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(": " + field), std::string::npos) << "missing field '" << field << "' in: " << what;
    }
  };
  for (const auto& c : cases) {
    nlohmann::json j = good;
    c.edit(j);
    const std::string path = dir.file(c.name + ".json");
    std::ofstream(path) << j.dump();
    expect_error(path, c.field);
  }

  const std::string malformed = dir.file("malformed.json");
  std::ofstream(malformed) << "{\"format\": \"airr-shift-table\", ";
  expect_error(malformed, "malformed JSON");
  expect_error(dir.file("missing.json"), "file not found");
}
