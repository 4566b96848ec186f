// `airr bench --noise` end to end on a small image: pairs rendered through `airr render`, the law,
// the forecast, and a side-by-side comparison (here with the same build, so the ratio is near 1);
// --memory and --model-image likewise.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_helpers.hpp"

using namespace airr;

TEST(BenchNoise, MeasuresPairsAndComparesBuildsSideBySide) {
  const test::command_result r =
      test::run_cli(std::string("bench --noise --size 32 --noise-spp 2 8 --presets rf-an ") + "--compare " + AIRR_CLI);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* expected : {"rf-an", "this build", "other build", "2 spp:", "8 spp:", "law: noise =", "1%:",
                               "speed-up (other build's time / this build's):"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
  }
  // The same binary twice: the same seeds give the same noise figures.
  const auto first = r.out.find("8 spp: "), second = r.out.find("8 spp: ", first + 1);
  ASSERT_NE(second, std::string::npos) << r.out;
  EXPECT_EQ(r.out.substr(first, 14), r.out.substr(second, 14)) << r.out;
}

TEST(BenchNoise, BadComparisonBuildIsNamed) {
  const test::command_result r = test::run_cli("bench --noise --size 16 --compare /nonexistent/airr");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("/nonexistent/airr: not an executable airr"), std::string::npos) << r.out;
}

// `airr bench --memory` on small images: four renders of this build, each with its peak, and the
// bytes a pixel with and without components.
TEST(BenchMemory, ReportsPeaksAndBytesAPixel) {
  const test::command_result r = test::run_cli("bench --memory --size 128");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  int rows = 0;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream row(line);
    std::string build, size, components;
    double peak = 0, seconds = 0;
    if (!(row >> build >> size >> size >> components >> peak >> seconds) || build != "this") continue;
    ++rows;
    EXPECT_TRUE(size == "64^2" || size == "128^2") << line;
    EXPECT_TRUE(components == "yes" || components == "no") << line;
    EXPECT_GT(peak, 10.0) << line;  // megabytes: the libraries alone take more
  }
  EXPECT_EQ(rows, 4) << r.out;
  EXPECT_NE(r.out.find("bytes a pixel"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("with components"), std::string::npos) << r.out;
}

// `airr bench --model-image` on a small image: one line per preset, tilt and quality, whose parts
// (measured one after another) add up to no more than the total, and one for the view image moved.
TEST(BenchModelImage, ReportsWhereTheTimeGoes) {
  const test::command_result r = test::run_cli("bench --model-image --size 48 --runs 1 --presets rf-an --tilts 0 30");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  int lines = 0, moved = 0;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream moved_row(line);
    double moved_tilt = 0, moved_ms = 0;
    std::string word;
    if (moved_row >> moved_tilt >> word >> moved_ms && word == "moved") {
      ++moved;  // the view image moved by a drag's step
      EXPECT_GT(moved_ms, 0) << line;
    }
    std::istringstream row(line);
    std::string preset, quality;
    double tilt = 0, total = 0, paths = 0, bins = 0, spectra = 0, samples = 0, loop = 0;
    if (!(row >> preset >> tilt >> quality >> total >> paths >> bins >> spectra >> samples >> loop) ||
        preset != "rf-an")
      continue;
    ++lines;
    EXPECT_TRUE(quality == "view" || quality == "quick" || quality == "full") << line;
    EXPECT_LE(paths + bins + spectra + samples + loop, total + 2.5) << line;  // rounded to whole ms each
  }
  EXPECT_EQ(lines, 6) << r.out;
  EXPECT_EQ(moved, 2) << r.out;
}

// --qualities measures the qualities named alone; a name not among them is refused.
TEST(BenchModelImage, MeasuresTheQualitiesNamed) {
  const test::command_result r =
      test::run_cli("bench --model-image --size 48 --runs 1 --presets rf-an --tilts 0 30 --qualities view");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  int view = 0, other = 0;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream row(line);
    std::string preset, quality;
    double tilt = 0;
    if (!(row >> preset >> tilt >> quality) || preset != "rf-an") continue;
    ++(quality == "view" ? view : other);
  }
  EXPECT_EQ(view, 2) << r.out;
  EXPECT_EQ(other, 0) << r.out;
  EXPECT_NE(r.out.find("median over the cases: view "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("quick"), std::string::npos) << r.out;

  const test::command_result bad = test::run_cli("bench --model-image --size 48 --qualities fast");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("fast"), std::string::npos) << bad.out;
  const test::command_result no_view =
      test::run_cli("bench --model-image --size 48 --qualities full --compare " AIRR_CLI);
  EXPECT_NE(no_view.exit_code, 0);
  EXPECT_NE(no_view.out.find("view quality"), std::string::npos) << no_view.out;
}

// --compare runs the other build's --model-error and reads its model image's time per case (here
// the other build is this one).
TEST(BenchModelImage, ComparesWithAnotherBuild) {
  const test::command_result r = test::run_cli(
      "bench --model-image --size 48 --runs 1 --presets rf-an --tilts 0 30 "
      "--compare " AIRR_CLI);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::size_t at = r.out.find("full quality, one run per case: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream row(r.out.substr(at + 32));
  double a = 0, b = 0;
  ASSERT_TRUE(row >> a >> b) << r.out;
  EXPECT_GT(a, 0);
  EXPECT_GT(b, 0);
  EXPECT_NE(r.out.find("this build's view-quality one: "), std::string::npos) << r.out;

  const test::command_result bad =
      test::run_cli("bench --model-image --size 48 --runs 1 --presets rf-an --tilts 0 --compare /nonexistent/airr");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("/nonexistent/airr: not an executable airr"), std::string::npos) << bad.out;
}

// --model-error --compare reads the other build's row (tracer noise, model image, view image, first
// look, then both with the noise taken out): against itself, its model image and its model image
// with the noise taken out are this build's own.
TEST(BenchModelError, ComparesWithAnotherBuild) {
  const test::command_result r =
      test::run_cli("bench --model-error --size 32 --spp 16 --presets rf-ay --tilts 10 --compare " AIRR_CLI);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::size_t other = r.out.find("other build (");
  ASSERT_NE(other, std::string::npos) << r.out;
  auto row_after = [&](std::size_t from) {
    std::istringstream lines(r.out.substr(from));
    std::vector<double> numbers;
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      std::string preset;
      if (!(words >> preset) || preset != "rf-ay") continue;
      for (std::string word; words >> word;) numbers.push_back(std::stod(word));
      break;
    }
    return numbers;
  };
  const std::vector<double> own = row_after(0), its = row_after(other);
  ASSERT_EQ(own.size(), 9u) << r.out;  // tilt, six percentages, two times
  ASSERT_EQ(its.size(), 6u) << r.out;  // tilt, its noise, model, model with the noise out, this view, this view out
  EXPECT_EQ(its[1], own[1]) << r.out;
  EXPECT_EQ(its[2], own[2]) << r.out;
  EXPECT_EQ(its[3], own[5]) << r.out;
  EXPECT_EQ(its[4], own[3]) << r.out;
}

// `airr bench --drag` on a small image: a line per edit, the worst frame, both after-drag figures,
// and a CSV row per 60 Hz frame of the drag (3 edits at 10 per second: about 18 frames).
TEST(BenchDrag, ReportsEveryFrameOfTheDrag) {
  test::temp_dir dir;
  const std::string csv = dir.file("frames.csv");
  const test::command_result r = test::run_cli("bench --drag --size 32 --edits 3 --rest 1 --drag-csv " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("worst frame during the drag: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("after the drag: within 2%"), std::string::npos) << r.out;
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_EQ(line, "time_s,edit,shown_edit,estimate,latency_ms,relative_rms");
  while (std::getline(in, line)) {
    ++rows;
    std::istringstream row(line);
    double t = 0, rms = -1;
    int edit = 0;
    char comma = 0;
    ASSERT_TRUE(row >> t >> comma >> edit) << line;
    EXPECT_GE(edit, 1);
    EXPECT_LE(edit, 3);
    rms = std::stod(line.substr(line.rfind(',') + 1));
    EXPECT_GE(rms, 0.0) << line;
  }
  EXPECT_GE(rows, 12);
  EXPECT_LE(rows, 18);
}

// `airr bench --sheets` on a small image: the three models each with its median time and the
// median of the rounds' ratios to the sinc-shift model, which lies within the rounds' range (the
// sinc-shift model's own exactly 1).
TEST(BenchSheets, TakesTheModelsInTurns) {
  const test::command_result r = test::run_cli("bench --sheets --size 32 --spp 1 --runs 3");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("median of 3 runs taken in turns"), std::string::npos) << r.out;
  std::vector<std::string> models;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream row(line);
    std::string model, s, per_s, x_the;
    double seconds = 0, rate = 0, ratio = 0, lo = 0, hi = 0;
    if (!(row >> model >> seconds >> s >> rate >> per_s) || s != "s") continue;
    const auto at = line.find("x the sinc-shift"), rounds = line.find("(rounds: ");
    ASSERT_NE(at, std::string::npos) << line;
    ASSERT_NE(rounds, std::string::npos) << line;
    ratio = std::stod(line.substr(line.rfind(' ', at - 1) + 1));
    ASSERT_EQ(std::sscanf(line.c_str() + rounds, "(rounds: %lf to %lf)", &lo, &hi), 2) << line;
    models.push_back(model);
    EXPECT_GT(seconds, 0) << line;
    EXPECT_GT(rate, 0) << line;
    EXPECT_LE(lo, ratio + 0.005) << line;
    EXPECT_LE(ratio, hi + 0.005) << line;
    if (model == "sinc_shift") {
      EXPECT_EQ(ratio, 1.0) << line;
      EXPECT_EQ(lo, 1.0) << line;
      EXPECT_EQ(hi, 1.0) << line;
    }
  }
  EXPECT_EQ(models, (std::vector<std::string>{"sinc_shift", "prism_sheet", "bead_sheet"})) << r.out;
}
