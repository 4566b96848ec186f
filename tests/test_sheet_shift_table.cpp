// A sheet's own shift distributions traced from its explicit model (sheet_shift_table.hpp), and
// presets that carry them: the hollow prism sheet's cube corners are the shipped corner cube, so at
// normal incidence its traced row matches the shipped table (traced from the glTF cube by another
// tracer) and two thirds of its aperture retroreflects; a preset's table travels beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "airr/analysis/fit_synthesis.hpp"
#include "airr/analysis/sheet_shift_table.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/measure/polarization_gain.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

double mean_shift(const shift_table& t, std::size_t row) {
  double m = 0;
  for (int b = 0; b < t.bins(); ++b) m += t.probability[row][std::size_t(b)] * (b + 0.5) * t.s_max / t.bins();
  return m;
}

}  // namespace

TEST(SheetShiftTable, AHollowPrismSheetMatchesTheShippedCornerCubeAtSmallTilts) {
  const sheet_description sheet = load_sheet(asset_dir() + "/sheets/prism-rf-ay-like.json");
  const auto unit = analysis::sheet_shift_unit_mm(sheet.model, sheet.base_dir);
  ASSERT_TRUE(unit);
  EXPECT_NEAR(*unit, 2 * 1.16 / std::sqrt(6.0), 1e-9);  // the cube edge
  const shift_table traced =
      analysis::trace_sheet_shift_table(sheet.model, sheet.base_dir, analysis::synthesis_bench(scene{}), *unit,
                                        {.step_deg = 10, .max_deg = 20, .samples = 200000})
          .shifts;
  const shift_table shipped = load_shift_table(default_shift_table_path());
  ASSERT_EQ(traced.theta_deg, (std::vector<double>{0, 10, 20}));
  ASSERT_EQ(traced.bins(), shipped.bins());
  for (std::size_t row = 0; row < 3; ++row) {
    const std::size_t at = std::size_t(2 * row);  // the shipped rows are 5 deg apart
    ASSERT_EQ(shipped.theta_deg[at], traced.theta_deg[row]);
    double worst = 0;
    for (int b = 0; b < traced.bins(); ++b)
      worst = std::max(worst, std::abs(traced.cdf[row][std::size_t(b)] - shipped.cdf[at][std::size_t(b)]));
    std::printf("tilt %g: mean shift %.4f (shipped %.4f), largest CDF difference %.4f\n", traced.theta_deg[row],
                mean_shift(traced, row), mean_shift(shipped, at), worst);
    EXPECT_LT(worst, 0.02) << "tilt " << traced.theta_deg[row];
    EXPECT_NEAR(mean_shift(traced, row), mean_shift(shipped, at), 0.02 * mean_shift(shipped, at));
  }
  // Retroreflected light per entering ray: the aperture's two thirds times three metal faces.
  EXPECT_NEAR(traced.retro_fraction[0], 2.0 / 3.0 * std::pow(0.83, 3), 0.005);
  // A sheet that names no cube edge keeps the shipped table.
  EXPECT_FALSE(analysis::sheet_shift_unit_mm({.type = "bead_sheet", .values = {}}, ""));
}

// The sheet's Mueller matrices carry its polarization into the sinc-shift and microfacet models:
// in the p-AIRR scene with the RF-Ay-like sheet pitched 25 deg (where its paths mix S2 and S3 by a
// third), the sheet and a preset with its traced matrices give the same gain; the models without
// them (the field kept as by a mirror) are far off.
TEST(SheetShiftTable, ASheetsMuellerMatricesCarryItsPAirrGain) {
  const sheet_description sheet = load_sheet(asset_dir() + "/sheets/prism-rf-ay-like.json");
  const analysis::traced_sheet traced =
      analysis::trace_sheet_shift_table(sheet.model, sheet.base_dir, analysis::synthesis_bench(scene{}), 1.0,
                                        {.step_deg = 5, .max_deg = 45, .samples = 20000});
  test::temp_dir dir;
  sheet_preset with = load_preset("rf-ay"), without = with;
  ASSERT_EQ(with.theta_deg, traced.shifts.theta_deg);
  with.polarization = traced.polarization;
  save_preset(with, dir.file("with.json"));
  save_preset(without, dir.file("without.json"));
  auto gain_with = [&](const retro_model_params& model) {
    scene s = load_scene(asset_dir() + "/scenes/p_airr.json", {parse_override("retroreflectors.0.pose.pitch_deg=25")});
    s.sheet().model = model;
    return measure_polarization_gain(s, 2).gain();
  };
  auto preset_model = [&](const std::string& file) {
    retro_model_params m{.type = "sinc_shift", .values = {}};
    set_model_value(m, "preset", dir.file(file));
    return m;
  };
  // The microfacet model takes the same matrices from the preset (its own blur, the sheet's light).
  retro_model_params microfacet{.type = "microfacet", .values = {}};
  const double microfacet_mirror = gain_with(microfacet);
  set_model_value(microfacet, "polarization_preset", dir.file("with.json"));
  const double explicit_gain = gain_with(sheet.model), fitted = gain_with(preset_model("with.json")),
               mirror = gain_with(preset_model("without.json")), microfacet_fitted = gain_with(microfacet);
  std::printf(
      "p-AIRR gain at 25 deg: the sheet %.4f, a preset with its matrices %.4f, without %.4f; the microfacet "
      "model with them %.4f, without %.4f\n",
      explicit_gain, fitted, mirror, microfacet_fitted, microfacet_mirror);
  EXPECT_NEAR(fitted / explicit_gain, 1.0, 0.03);
  EXPECT_GT(std::abs(mirror / explicit_gain - 1.0), 0.1);
  EXPECT_NEAR(microfacet_fitted / explicit_gain, 1.0, 0.03);
  EXPECT_GT(std::abs(microfacet_mirror / explicit_gain - 1.0), 0.1);
  // A preset without matrices is refused, naming the field.
  set_model_value(microfacet, "polarization_preset", dir.file("without.json"));
  const std::string e = test::error_of([&] { make_retro_model(microfacet, {}); });
  EXPECT_NE(e.find("polarization_preset"), std::string::npos) << e;
  EXPECT_NE(e.find("no Mueller matrices"), std::string::npos) << e;
}

TEST(SheetShiftTable, APresetsTableTravelsBesideItAndIsRead) {
  test::temp_dir dir;
  std::filesystem::create_directories(dir.file("a"));
  std::filesystem::create_directories(dir.file("b"));
  const shift_table shipped = load_shift_table(default_shift_table_path());
  save_shift_table(shipped, dir.file("a/table.json"));
  sheet_preset p = load_preset("rf-ay");
  p.shift_table = dir.file("a/table.json");
  save_preset(p, dir.file("b/mine.json"));
  EXPECT_TRUE(std::filesystem::exists(dir.file("b/mine_shifts.json")));
  const sheet_preset back = load_preset(dir.file("b/mine.json"));
  EXPECT_EQ(std::filesystem::path(back.shift_table), std::filesystem::path(dir.file("b/mine_shifts.json")));
  EXPECT_EQ(load_shift_table(back.shift_table).probability, shipped.probability);

  // The sinc-shift model reads the preset's table; the scene's own table wins over it.
  retro_model_params m{.type = "sinc_shift", .values = {}};
  set_model_value(m, "preset", dir.file("b/mine.json"));
  EXPECT_EQ(resolve_sinc_shift_params(m, {}).shift_table, back.shift_table);
  set_model_value(m, "shift_table", dir.file("a/table.json"));
  EXPECT_EQ(resolve_sinc_shift_params(m, {}).shift_table, dir.file("a/table.json"));

  // Without its table the preset names the field and the file it looked for.
  std::filesystem::remove(dir.file("b/mine_shifts.json"));
  const std::string e =
      test::error_of([&] { preset_from_json(read_json_file(dir.file("b/mine.json")), dir.file("b/mine.json")); });
  EXPECT_NE(e.find("mine.json"), std::string::npos) << e;
  EXPECT_NE(e.find("shift_table"), std::string::npos) << e;
  EXPECT_NE(e.find("mine_shifts.json"), std::string::npos) << e;
}

// A preset's Mueller matrices round-trip, interpolate element by element between tilts, and bad
// ones are named.
TEST(SheetShiftTable, APresetsPolarizationRoundTripsAndBadMatricesAreNamed) {
  test::temp_dir dir;
  sheet_preset p = load_preset("rf-ay");
  ASSERT_GE(p.theta_deg.size(), 2u);
  p.polarization.assign(p.theta_deg.size(), mueller::identity());
  p.polarization[1] = linear_retarder(0.3, 1.0);
  save_preset(p, dir.file("p.json"));
  const sheet_preset back = load_preset(dir.file("p.json"));
  ASSERT_EQ(back.polarization.size(), p.theta_deg.size());
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(back.polarization[1].m[i][k], p.polarization[1].m[i][k]);
  const double mid = 0.5 * (p.theta_deg[0] + p.theta_deg[1]);
  const mueller half = interpolate_by_angle(back.theta_deg, back.polarization, mid);
  EXPECT_NEAR(half.m[2][3], 0.5 * p.polarization[1].m[2][3], 1e-12);

  auto error_for = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = preset_to_json(p);
    edit(j);
    return test::error_of([&] { preset_from_json(j, dir.file("bad.json")); });
  };
  const std::string count = error_for([](nlohmann::json& j) { j["polarization"].erase(0); });
  EXPECT_NE(count.find("polarization"), std::string::npos) << count;
  EXPECT_NE(count.find("bad.json"), std::string::npos) << count;
  const std::string large = error_for([](nlohmann::json& j) { j["polarization"][2][1][2] = 1.5; });
  EXPECT_NE(large.find("polarization[2]"), std::string::npos) << large;
  const std::string shape = error_for([](nlohmann::json& j) { j["polarization"] = {1, 2, 3}; });
  EXPECT_NE(shape.find("4 rows of 4"), std::string::npos) << shape;
}
