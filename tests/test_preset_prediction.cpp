// Presets predicted from a sheet's geometry (issue 33, item 4): sheet files load strictly and
// round-trip; `airr predict-preset` measures the explicit prism sheet on the simulated bench and
// fits the sinc-shift model to it, and the predicted preset agrees with the explicit sheet (mean
// MTF, brightness, corner size). The shipped RF-Ay preset, fitted to the real sheet, does not
// agree with the explicit model that closely: the check can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "airr/analysis/preset_prediction.hpp"
#include "airr/core/assets.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

std::string sheet_path(const std::string& name) { return asset_dir() + "/sheets/" + name + ".json"; }

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Mean MTF of the explicit sheet and of each preset at `tilts`, with the bench's own measurement.
std::vector<std::vector<analysis::prediction_agreement>> agreement(const sheet_description& sheet,
                                                                   const std::vector<sheet_preset>& presets,
                                                                   const std::vector<double>& tilts = {0, 10, 20, 30}) {
  const analysis::synthesis_params bench_settings = analysis::prediction_params{}.synthesis;
  return analysis::compare_predictions(sheet, presets, analysis::synthesis_bench(scene{}), tilts, bench_settings);
}

}  // namespace

TEST(SheetFile, RoundTripsAndRefusesBadInput) {
  test::temp_dir dir;
  sheet_description s = load_sheet(sheet_path("prism-rf-an-like"));
  EXPECT_EQ(s.model.type, "prism_sheet");
  EXPECT_FALSE(s.note.empty());
  save_sheet(s, dir.file("copy.json"));
  const sheet_description back = load_sheet(dir.file("copy.json"));
  EXPECT_EQ(back.name, s.name);
  EXPECT_EQ(back.note, s.note);
  EXPECT_EQ(back.model.type, s.model.type);
  EXPECT_EQ(back.model.values, s.model.values);

  auto error_for = [&](const std::string& text) {
    write_text(dir.file("bad.json"), text);
    return test::error_of([&] { load_sheet(dir.file("bad.json")); });
  };
  const std::string head = R"({"format": "airr-sheet", "version": 1, "name": "x", )";
  EXPECT_NE(error_for("{").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_for(R"({"format": "airr-preset", "version": 1})").find("format"), std::string::npos);
  EXPECT_NE(error_for(head + R"("note": ""})").find("model: missing"), std::string::npos);
  EXPECT_NE(error_for(head + R"("model": {"type": "prism"}})").find("unknown model 'prism'"), std::string::npos);
  const std::string range = error_for(head + R"("model": {"type": "prism_sheet", "pitch_mm": -1}})");
  EXPECT_NE(range.find("pitch_mm"), std::string::npos) << range;
  EXPECT_NE(range.find("bad.json"), std::string::npos) << range;
  EXPECT_NE(error_for(head + R"("model": {"type": "prism_sheet"}, "colour": 1})").find("colour"), std::string::npos);
  EXPECT_NE(test::error_of([&] { load_sheet(dir.file("absent.json")); }).find("absent.json"), std::string::npos);
}

// Every shipped sheet loads and builds its model (the tile sheet's tile found beside it); a tile
// sheet whose tile is missing names the tile's file.
TEST(SheetFile, EveryShippedSheetBuildsItsModel) {
  int sheets = 0;
  for (const auto& entry : std::filesystem::directory_iterator(asset_dir() + "/sheets")) {
    const sheet_description s = load_sheet(entry.path().string());
    EXPECT_NO_THROW(make_retro_model(s.model, {.base_dir = s.base_dir}, "model")) << entry.path();
    ++sheets;
  }
  EXPECT_GE(sheets, 4);
  test::temp_dir dir;
  write_text(
      dir.file("tile.json"),
      R"({"format": "airr-sheet", "version": 1, "name": "x", "model": {"type": "tile_sheet", "tile": "cad.glb"}})");
  const std::string missing = test::error_of([&] { load_sheet(dir.file("tile.json")); });
  EXPECT_NE(missing.find("cad.glb"), std::string::npos) << missing;
  EXPECT_NE(missing.find("tile"), std::string::npos) << missing;
}

TEST(PresetPrediction, BadSheetIsAOneLineError) {
  test::temp_dir dir;
  write_text(dir.file("sheet.json"), R"({"format": "airr-sheet", "version": 1, "name": "x",
    "model": {"type": "prism_sheet", "index": 7}})");
  test::expect_one_line_error(
      test::run_cli("predict-preset --sheet " + dir.file("sheet.json") + " -o " + dir.file("p.json")),
      {"sheet.json", "index"});
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.json")));
}

// The prediction with fewer samples than the command's default (1,000,000 per measurement,
// 200,000 per fit simulation) to keep the suite short; the agreement is measured with the
// default bench settings. For the sheet like each shipped preset (RF-Ay: hollow metal cube
// corners of 1.16 mm, shift-dominated; RF-AN: metal-coated 0.16 mm prisms behind a plate,
// diffraction-dominated) the predicted preset's mean MTF is the explicit sheet's within 0.01 at
// tilts 0, 10, 20 and 30 deg, and its mu gives the explicit sheet's brightness within 6%; the
// shipped preset, fitted to the real sheet, does not agree with the explicit model that closely.
void expect_prediction_agrees(const std::string& sheet_name, const std::string& shipped_name, sheet_preset& predicted,
                              const test::temp_dir& dir) {
  const auto r =
      test::run_cli("predict-preset --sheet " + sheet_path(sheet_name) + " -o " + dir.file("predicted.json") +
                    " --data " + dir.file("bench") + " --samples 400000 --fit-samples 100000");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::printf("%s", r.out.substr(r.out.find("preset predicted")).c_str());
  EXPECT_TRUE(std::filesystem::exists(dir.file("bench/fit.json")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("bench/tilt_30.csv")));

  const sheet_description sheet = load_sheet(sheet_path(sheet_name));
  predicted = load_preset(dir.file("predicted.json"));
  EXPECT_EQ(predicted.name, sheet.name);
  EXPECT_EQ(predicted.provenance["source"], "airr predict-preset");
  EXPECT_EQ(predicted.provenance["sheet"]["model"]["type"], "prism_sheet");
  EXPECT_EQ(predicted.provenance["fit"]["settings"]["a_matches"], "mean_mtf");

  const sheet_preset shipped = load_preset(shipped_name);
  const auto both = agreement(sheet, {predicted, shipped});
  const auto &ours = both[0], &theirs = both[1];
  double worst_shipped = 0;
  std::printf("%8s %13s %13s %13s %17s\n", "tilt_deg", "explicit", "predicted", ("shipped " + shipped_name).c_str(),
              "brightness ratio");
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const auto& g = ours[i];
    std::printf("%8g %13.4f %13.4f %13.4f %17.4f\n", g.tilt_deg, g.explicit_mean_mtf, g.predicted_mean_mtf,
                theirs[i].predicted_mean_mtf, g.predicted_brightness / g.explicit_brightness);
    EXPECT_NEAR(g.predicted_mean_mtf, g.explicit_mean_mtf, 0.01) << sheet_name << ", tilt " << g.tilt_deg;
    EXPECT_NEAR(g.predicted_brightness / g.explicit_brightness, 1.0, 0.06) << sheet_name << ", tilt " << g.tilt_deg;
    worst_shipped = std::max(worst_shipped, std::abs(theirs[i].predicted_mean_mtf - theirs[i].explicit_mean_mtf));
  }
  EXPECT_GT(worst_shipped, 0.01) << "the check could not tell the shipped preset from the prediction";
}

// Between its tilts the preset interpolates a and mu and its table's rows; the hollow sheet's mean
// MTF rises by 0.14 from 30 to 35 deg as its corners stop shifting the light, which the shipped
// table puts 5 deg later (a then ran 3.2, 16.5, 3.9 per mm at 30, 35, 40 deg and the preset was off
// by 0.056 at 32.5 deg). With the sheet's own table the preset holds within 0.015 between its tilts
// too, where the change is steepest (31 to 34 deg) included, and no a stands out from its neighbours.
TEST(PresetPrediction, PredictedPresetAgreesWithTheExplicitSheet) {
  sheet_preset predicted;
  const test::temp_dir dir;  // holds the preset's shift table
  expect_prediction_agrees("prism-rf-ay-like", "rf-ay", predicted, dir);
  // The corner size comes out at the cube edge, 2 pitch / sqrt 6, within 5%.
  const sheet_description sheet = load_sheet(sheet_path("prism-rf-ay-like"));
  const double edge = 2 * read_model_values(sheet.model).number("pitch_mm") / std::sqrt(6.0);
  EXPECT_NEAR(predicted.c_mm, edge, 0.05 * edge);
  EXPECT_FALSE(predicted.shift_table.empty());

  const auto between = agreement(sheet, {predicted}, {2.5, 17.5, 27.5, 32.5, 33.5, 37.5, 42.5});
  for (const auto& g : between[0]) {
    std::printf("between tilts: %5g deg explicit %.4f predicted %.4f\n", g.tilt_deg, g.explicit_mean_mtf,
                g.predicted_mean_mtf);
    EXPECT_NEAR(g.predicted_mean_mtf, g.explicit_mean_mtf, 0.015) << "tilt " << g.tilt_deg;
  }
  const auto& a = predicted.a_per_mm;
  ASSERT_EQ(a.size(), 10u);
  for (std::size_t i = 1; i + 1 < a.size(); ++i) {
    const double against_neighbours = a[i] / std::sqrt(a[i - 1] * a[i + 1]);
    EXPECT_GT(against_neighbours, 0.5) << "a at " << predicted.theta_deg[i] << " deg";
    EXPECT_LT(against_neighbours, 2.0) << "a at " << predicted.theta_deg[i] << " deg";
  }

  // The preset carries the sheet's Mueller matrix at each tilt (its effect: SheetShiftTable.*).
  EXPECT_EQ(predicted.polarization.size(), 10u);
}

TEST(PresetPrediction, PredictedPresetAgreesWithADiffractionDominatedSheet) {
  sheet_preset predicted;
  const test::temp_dir dir;
  expect_prediction_agrees("prism-rf-an-like", "rf-an", predicted, dir);
}
