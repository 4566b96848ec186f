// Tolerance analysis (issue 34): for a metric linear in one tolerance (the device's depth against
// the sheet's position along z) the Monte Carlo's spread is the sensitivity times the tolerance;
// a limit at the metric's median passes half the layouts; bad tolerances are named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "airr/core/assets.hpp"
#include "airr/design/metrics.hpp"
#include "airr/design/tolerance.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/formats/scene_json.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

design_spec tolerance_spec(const test::temp_dir& dir, const std::string& members) {
  std::ofstream(dir.file("spec.json")) << R"({"format": "airr-design", "version": 1, "scene": ")" +
                                              default_scene_path() +
                                              R"(", "objectives": [{"metric": "size_z_mm", "goal": "minimise"}], )" +
                                              members + "}";
  return load_design_spec(dir.file("spec.json"));
}

}  // namespace

TEST(DesignTolerance, LinearMetricSpreadsBySensitivityTimesTolerance) {
  test::temp_dir dir;
  const double nominal = device_size_mm(load_scene(default_scene_path())).z;
  for (const char* distribution : {"normal", "uniform"}) {
    const bool uniform = std::string(distribution) == "uniform";
    const std::string size = uniform ? R"("half_width": 3)" : R"("sd": 2)";
    const design_spec spec = tolerance_spec(
        dir, R"("constraints": [{"metric": "size_z_mm", "max": )" + std::to_string(nominal) +
                 R"(}], "tolerances": [{"key": "retroreflectors.0.pose.center_mm.2", "distribution": ")" +
                 distribution + "\", " + size + R"(}], "tolerance": {"samples": 2000, "seed": 3})");
    const tolerance_result r = run_tolerance(spec, spec.base);
    ASSERT_EQ(r.metrics.size(), 2u);
    const metric_distribution& m = r.metrics[0];
    const double input_sd = uniform ? 3 / std::sqrt(3.0) : 2.0;
    const double per_size = r.sensitivity[0][0];  // change per 3 mm (uniform) or per 2 mm (normal)
    const double expected_sd = std::abs(per_size) / (uniform ? 3.0 : 2.0) * input_sd;
    std::printf(
        "%s: size_z mean %.3f sd %.4f (sensitivity %.4f per size: sd %.4f expected); yield %.4f at the "
        "median %.3f, %d invalid\n",
        distribution, m.mean, m.sd, per_size, expected_sd, r.yield, nominal, r.invalid);
    EXPECT_EQ(r.invalid, 0);
    EXPECT_NEAR(std::abs(per_size), uniform ? 3.0 : 2.0, 1e-6);  // the depth moves with the sheet
    EXPECT_NEAR(m.sd / expected_sd, 1.0, 0.05);
    EXPECT_NEAR(m.p50, nominal, 0.1);
    EXPECT_NEAR(r.yield, 0.5, 0.03);
  }
}

// Every layout keeps what was drawn for it: set into the nominal scene, the drawn values give the
// metrics recorded for it, and the worst layouts are those that broke the constraint, deepest first.
TEST(DesignTolerance, EachLayoutKeepsItsDrawnValuesAndTheWorstComeFirst) {
  test::temp_dir dir;
  const double nominal = device_size_mm(load_scene(default_scene_path())).z;
  const design_spec spec =
      tolerance_spec(dir, R"("constraints": [{"metric": "size_z_mm", "max": )" + std::to_string(nominal) +
                              R"(}], "tolerances": [{"key": "retroreflectors.0.pose.center_mm.2", "sd": 2},
               {"key": "tilt_deg", "sd": 0.5}], "tolerance": {"samples": 40, "seed": 5})");
  const tolerance_result r = run_tolerance(spec, spec.base);
  ASSERT_EQ(r.layouts.size(), 40u);
  for (std::size_t i = 0; i < r.layouts.size(); i += 7) {
    const tolerance_layout& l = r.layouts[i];
    ASSERT_TRUE(l.valid);
    ASSERT_EQ(l.values.size(), 2u);
    const scene drawn = with_overrides(
        spec.base,
        {design_override("retroreflectors.0.pose.center_mm.2", l.values[0]), design_override("tilt_deg", l.values[1])},
        "test");
    const design_evaluation e = evaluate_design(spec, drawn);
    EXPECT_NEAR(e.objective_values[0], l.metrics[0], 1e-9) << i;
    EXPECT_EQ(e.broken.empty(), l.broken.empty()) << i;
  }
  const std::vector<std::size_t> worst = worst_layouts(r, 5);
  ASSERT_EQ(worst.size(), 5u);
  for (std::size_t k = 0; k + 1 < worst.size(); ++k) {
    const tolerance_layout &a = r.layouts[worst[k]], &b = r.layouts[worst[k + 1]];
    EXPECT_GE(a.broken.size(), b.broken.size());
    if (a.broken.size() == b.broken.size()) {
      EXPECT_LE(a.score, b.score);
    }
  }
  EXPECT_FALSE(r.layouts[worst[0]].broken.empty());  // about half the layouts are deeper than nominal
}

TEST(DesignTolerance, BadTolerancesAreNamed) {
  test::temp_dir dir;
  auto error_for = [&](const std::string& members) { return test::error_of([&] { tolerance_spec(dir, members); }); };
  const std::string bad_key = error_for(R"("tolerances": [{"key": "half_mirror.pose.twist", "sd": 1}])");
  EXPECT_NE(bad_key.find("tolerances[0].key"), std::string::npos) << bad_key;
  const std::string bad_sd = error_for(R"("tolerances": [{"key": "tilt_deg", "sd": 0}])");
  EXPECT_NE(bad_sd.find("tolerances[0].sd"), std::string::npos) << bad_sd;
  const std::string bad_kind = error_for(R"("tolerances": [{"key": "tilt_deg", "distribution": "cauchy", "sd": 1}])");
  EXPECT_NE(bad_kind.find("tolerances[0].distribution"), std::string::npos) << bad_kind;
  const std::string unset =
      error_for(R"("tolerances": [{"key": "retroreflectors.0.model.a_per_mm", "sd": 1, "percent": true}])");
  EXPECT_NE(unset.find("not a number"), std::string::npos) << unset;
}
