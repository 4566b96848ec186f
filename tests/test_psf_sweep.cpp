// The model PSF and a rendered slanted edge measure the same MTF (model spec, section 4);
// `airr sweep` and `airr psf` on the command line.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <ostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/csv_table.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/sweep.hpp"
#include "airr/measure/test_charts.hpp"
#include "airr/models/preset.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// 2048 texels over the 50 mm source (0.024 mm): the chart's own blur (an antialiased edge looked
// up bilinearly) stays far below the 0.25 mm pixel's; the shipped 512-texel chart would not.
const std::string& fine_edge_chart() {
  static const test::temp_dir dir;
  static const std::string path = [] {
    const std::string p = dir.file("slanted_edge_2048.exr");
    write_image(p, make_slanted_edge_chart(2048), {});
    return p;
  }();
  return path;
}

struct two_route_case {
  const char* preset;  // nullptr: the ideal retroreflector
  double floating_distance_mm;
  std::uint64_t spp;
};

std::string case_name(const two_route_case& c) {
  std::string name = c.preset ? c.preset : "ideal";
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name + "_D" + std::to_string(int(c.floating_distance_mm));
}

void PrintTo(const two_route_case& c, std::ostream* os) { *os << case_name(c); }

// The default layout seen by a 160 x 64 camera of 0.25 mm pixels (Nyquist 2 lp/mm), framing the
// centre 40 x 16 mm of the source: wide enough for the edge analysis's window on the widest blur,
// short enough that incidence angles along the edge stay within 1.5 degrees of the chief ray's.
scene two_route_scene(const two_route_case& c) {
  constexpr double pixel_mm = 0.25;
  scene s = test::uniform_source_scene(50.0);
  s.source.image = fine_edge_chart();
  s.observer.width = 160;
  s.observer.height = 64;
  s.observer.fov_deg =
      2.0 * std::atan(0.5 * s.observer.height * pixel_mm / s.observer.distance_mm) * 180.0 / std::numbers::pi;
  airr::set_floating_distance(s, c.floating_distance_mm);
  if (c.preset) {
    s.sheet().model.type = "sinc_shift";
    airr::set_model_value(s.sheet().model, "preset", c.preset);
    // mu only scales brightness, but RF-Ay's falls 12% from 0 to 5 degrees: across the frame that
    // is a brightness gradient the edge analysis reads as a broad part of the line spread (+0.008
    // in mean MTF). Holding mu at its 0-degree value leaves blur as the only difference.
    airr::set_model_value(s.sheet().model, "mu", load_preset(c.preset).mu.front());
  }
  return s;
}

class TwoRoutes : public ::testing::TestWithParam<two_route_case> {};

// PSF route: sample_psf through the chief ray at the aerial-image centre; MTF = |FT| of the
// offsets along x (the whole sinc^2 tail counted) times the 0.25 mm pixel's sinc.
// Edge route: the tracer renders the 2048-texel edge chart (pixel jitter = the pixel's box, plus
// the chart's texels, plus Monte Carlo noise); e-SFR on its luminance over the whole frame. Its
// Hamming window (about 19 mm half-width for RF-AN) leaves out the far sinc^2 tail that the PSF
// route counts, so for RF-AN the edge route reads about 0.01 higher; at 256 spp its noise is
// about +-0.007 in mean MTF (RF-Ay +-0.002, ideal none).
TEST_P(TwoRoutes, MeanMtfOverZeroToOneLpPerMmAgrees) {
  const two_route_case c = GetParam();
  const scene s = two_route_scene(c);
  const mtf_summary psf = psf_route_mtf(scene_psf(s, 100000), make_camera(s).mm_per_pixel);
  const render_snapshot snap = test::render_to(s, c.spp);
  const mtf_summary edge = edge_route_mtf(s, snap, 1.0);
  ASSERT_DOUBLE_EQ(psf.mm_per_pixel, edge.mm_per_pixel);
  std::printf(
      "two routes: %-8s D %3.0f mm: PSF %.4f, edge render %.4f (%llu spp), difference %+.4f; "
      "MTF50 %.3f / %.3f lp/mm\n",
      c.preset ? c.preset : "ideal", c.floating_distance_mm, psf.mean_mtf, edge.mean_mtf,
      static_cast<unsigned long long>(snap.spp), edge.mean_mtf - psf.mean_mtf, psf.mtf50_lp_per_mm.value_or(0.0),
      edge.mtf50_lp_per_mm.value_or(0.0));
  EXPECT_NEAR(edge.mean_mtf, psf.mean_mtf, 0.03);
  // With the ideal retroreflector only the pixel's aperture blurs, which both routes include (it
  // alone takes 0.034 off the mean): nothing but the chart's texels separates them.
  if (!c.preset) {
    EXPECT_NEAR(edge.mean_mtf, psf.mean_mtf, 0.005);
  }
}

INSTANTIATE_TEST_SUITE_P(IdealAndPresets, TwoRoutes,
                         ::testing::Values(two_route_case{nullptr, 150, 32}, two_route_case{nullptr, 300, 32},
                                           two_route_case{"rf-ay", 150, 128}, two_route_case{"rf-ay", 300, 128},
                                           two_route_case{"rf-an", 150, 256}, two_route_case{"rf-an", 300, 256}),
                         [](const auto& info) { return case_name(info.param); });

// ---------------------------------------------------------------- airr sweep

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string preset_sets(const char* preset) {
  return std::string(" --set retroreflectors.0.model.type=sinc_shift --set retroreflectors.0.model.preset=") + preset;
}

TEST(Sweep, SlopeIsNegativeForThePresetsAndTheCsvHasOneRowPerPoint) {
  test::temp_dir dir;
  for (const char* preset : {"rf-ay", "rf-an"}) {
    const std::string csv = dir.file(std::string(preset) + ".csv"), png = dir.file(std::string(preset) + ".png");
    const auto r = test::run_cli("sweep " + default_scene_path() +
                                 " --vary floating_distance=150:300:75 --psf --samples 40000 -o " + csv + " --plot " +
                                 png + preset_sets(preset));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(slope d of mean MTF against D at tilt 0 deg: (\S+) per mm)")))
        << r.out;
    const double slope = std::stod(m[1]);
    std::printf("sweep %s (PSF route, D 150..300): slope d = %.6g per mm\n", preset, slope);
    EXPECT_LT(slope, 0.0) << preset;

    const auto rows = lines_of(read_file(csv));
    ASSERT_EQ(rows.size(), 4u) << read_file(csv);
    EXPECT_EQ(rows[0],
              "floating_distance_mm,tilt_deg,mean_mtf_0_1,mtf50_lp_per_mm,r50_mm,brightness,brightness_sheet_0");
    double previous_r50 = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      double d = 0, tilt = 0, mean = 0, m50 = 0, r50 = 0;
      ASSERT_EQ(std::sscanf(rows[i].c_str(), "%lf,%lf,%lf,%lf,%lf", &d, &tilt, &mean, &m50, &r50), 5) << rows[i];
      EXPECT_DOUBLE_EQ(d, 150.0 + 75.0 * double(i - 1));
      EXPECT_DOUBLE_EQ(tilt, 0.0);
      EXPECT_GT(mean, 0.0);
      EXPECT_LT(mean, 1.0);
      EXPECT_GT(r50, previous_r50) << "the 50%-energy radius grows with D";
      previous_r50 = r50;
    }
    EXPECT_TRUE(std::filesystem::is_regular_file(png));
  }
}

TEST(Sweep, GridOfDistanceAndTiltHasEveryPoint) {
  test::temp_dir dir;
  const std::string csv = dir.file("grid.csv");
  const auto r = test::run_cli("sweep " + default_scene_path() +
                               " --vary floating_distance=150:300:150 --vary tilt=0:10:5 --psf --samples 2000 -o " +
                               csv + preset_sets("rf-an"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto rows = lines_of(read_file(csv));
  ASSERT_EQ(rows.size(), 7u) << read_file(csv);
  EXPECT_EQ(rows[1].rfind("150,0,", 0), 0u) << rows[1];
  EXPECT_EQ(rows[2].rfind("300,0,", 0), 0u) << rows[2];
  EXPECT_EQ(rows[6].rfind("300,10,", 0), 0u) << rows[6];
  // One slope per tilt.
  EXPECT_EQ(std::regex_search(r.out, std::regex("at tilt 5 deg")), true) << r.out;
}

// The edge route renders the chart at each point; blur grows with D, so mean MTF falls.
TEST(Sweep, EdgeRouteMeanMtfFallsWithDistance) {
  scene s = test::uniform_source_scene(50.0);
  s.observer.width = 160;
  s.observer.height = 64;
  s.observer.fov_deg = 2.0 * std::atan(0.5 * 64 * 0.25 / s.observer.distance_mm) * 180.0 / std::numbers::pi;
  s.sheet().model.type = "sinc_shift";
  airr::set_model_value(s.sheet().model, "preset", "rf-an");
  sweep_params p;
  p.axes = {parse_sweep_axis("floating_distance=150:300:150")};
  p.spp = 64;
  p.roi_fraction = 1.0;
  p.psf_samples = 20000;
  double last_fraction = -1;
  bool monotone = true;
  const sweep_result r = run_sweep(s, p, [&](double f, const std::string&) {
    monotone = monotone && f >= last_fraction;
    last_fraction = f;
  });
  ASSERT_EQ(r.points.size(), 2u);
  ASSERT_EQ(r.slopes.size(), 1u);
  std::printf("edge-route sweep rf-an: mean MTF %.4f at D 150, %.4f at D 300, slope %.6g per mm\n",
              r.points[0].mean_mtf, r.points[1].mean_mtf, r.slopes[0].per_mm);
  EXPECT_LT(r.slopes[0].per_mm, 0.0);
  EXPECT_TRUE(monotone);
  EXPECT_DOUBLE_EQ(last_fraction, 1.0);
  EXPECT_DOUBLE_EQ(r.mm_per_pixel, make_camera(s).mm_per_pixel);
}

int line_count(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Sweep, BadVaryIsAOneLineError) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"zoom=1:2:1", "unknown key 'zoom'"},
      {"floating_distance=300:150:25", "start is above end"},
      {"tilt=0:45:0", "step must be positive"},
      {"tilt=0:45:-5", "step must be positive"},
      {"floating_distance=150:300:0.5", "more than 200 points"},
      {"floating_distance=150:abc:25", "end 'abc' is not a number"},
      {"floating_distance=150:300", "expected start:end:step"},
  };
  for (const auto& [vary, message] : cases) {
    const auto r = test::run_cli("sweep " + default_scene_path() + " --psf --vary " + vary);
    EXPECT_NE(r.exit_code, 0) << vary << ": " << r.out;
    EXPECT_EQ(line_count(r.out), 1) << vary << ": " << r.out;
    EXPECT_EQ(r.out.rfind("error: --vary " + vary + ": ", 0), 0u) << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << "missing '" << message << "' in: " << r.out;
  }
  // A sweep none of whose points is a layout names the first point and its reason.
  const auto r = test::run_cli("sweep " + default_scene_path() + " --psf --vary floating_distance=-100:-50:50");
  EXPECT_NE(r.exit_code, 0) << r.out;
  EXPECT_EQ(line_count(r.out), 1) << r.out;
  EXPECT_EQ(r.out.rfind("error: sweep point floating_distance=-100, tilt=0: ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("no other point of the sweep is a layout"), std::string::npos) << r.out;
}

// A sweep goes on past the layouts that are no layout: on the shipped kiosk, the camera ray
// through the aerial image misses the half mirror from D = 270 mm on, while D up to 240 mm works.
// Each such point is a row of the CSV with its reason and no numbers; the others are measured as a
// sweep of the valid range alone measures them.
TEST(Sweep, PointsThatAreNoLayoutAreRowsWithTheirReason) {
  test::temp_dir dir;
  const std::string kiosk = asset_dir() + "/scenes/two_sheet_kiosk.json";
  const std::string csv = dir.file("kiosk.csv"), plot = dir.file("kiosk.png");
  const auto r = test::run_cli("sweep " + kiosk + " --psf --samples 20000 --vary floating_distance=120:300:30 -o " +
                               csv + " --plot " + plot);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("no layout: "), std::string::npos) << r.out;
  const auto rows = lines_of(read_file(csv));
  ASSERT_EQ(rows.size(), 8u) << read_file(csv);
  const auto header = split_csv_line(rows[0]);
  ASSERT_EQ(header.back(), "reason") << rows[0];
  int valid = 0, invalid = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto fields = split_csv_line(rows[i]);
    ASSERT_EQ(fields.size(), header.size()) << rows[i];
    const double d = std::stod(fields[0]);
    EXPECT_DOUBLE_EQ(d, 120.0 + 30.0 * double(i - 1));
    if (fields.back().empty()) {
      ++valid;
      EXPECT_LE(d, 240.0);
      EXPECT_GT(std::stod(fields[2]), 0.0) << rows[i];
      EXPECT_GT(std::stod(fields[4]), 0.0) << rows[i];
    } else {
      ++invalid;
      EXPECT_GE(d, 270.0);
      EXPECT_NE(fields.back().find("misses the half mirror"), std::string::npos) << rows[i];
      for (std::size_t c = 2; c + 1 < fields.size(); ++c) EXPECT_EQ(fields[c], "") << rows[i];
    }
  }
  std::printf("kiosk sweep D 120..300: %d points measured, %d no layout\n", valid, invalid);
  EXPECT_EQ(valid, 5);
  EXPECT_EQ(invalid, 2);
  EXPECT_TRUE(std::filesystem::is_regular_file(plot));

  const std::string valid_csv = dir.file("valid.csv");
  ASSERT_EQ(
      test::run_cli("sweep " + kiosk + " --psf --samples 20000 --vary floating_distance=120:240:30 -o " + valid_csv)
          .exit_code,
      0);
  const auto valid_rows = lines_of(read_file(valid_csv));
  ASSERT_EQ(valid_rows.size(), 6u);
  for (std::size_t i = 1; i < valid_rows.size(); ++i) EXPECT_EQ(rows[i], valid_rows[i] + ",");

  // A sweep whose every point misses names the first point and its reason.
  const auto none = test::run_cli("sweep " + kiosk + " --psf --samples 2000 --vary floating_distance=270:330:30");
  EXPECT_NE(none.exit_code, 0) << none.out;
  EXPECT_NE(none.out.find("error: sweep point floating_distance=270, tilt=10: psf: retroreflectors[0]: the camera "
                          "ray through the aerial image misses the half mirror (and no other point"),
            std::string::npos)
      << none.out;
}

// ---------------------------------------------------------------- airr psf

double printed_value(const std::string& out, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(pattern))) return std::nan("");
  return std::stod(m[1]);
}

// On the ideal bench: its ideal sheet, then each preset in its place.
TEST(PsfCommand, CsvStartsAtOneAndFallsAndTheIdealRadiusIsZero) {
  test::temp_dir dir;
  for (const char* preset : {static_cast<const char*>(nullptr), "rf-ay", "rf-an"}) {
    const std::string csv = dir.file("psf.csv"), png = dir.file("psf.png");
    const auto r = test::run_cli("psf " + ideal_bench_scene_path() + " -o " + csv + " --plot " + png +
                                 " --samples 20000" + (preset ? preset_sets(preset) : std::string()));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto rows = lines_of(read_file(csv));
    ASSERT_EQ(rows.size(), 102u);
    EXPECT_EQ(rows[0], "lp_per_mm,mtf");
    std::vector<double> f, mtf;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      double a = 0, b = 0;
      ASSERT_EQ(std::sscanf(rows[i].c_str(), "%lf,%lf", &a, &b), 2) << rows[i];
      f.push_back(a);
      mtf.push_back(b);
    }
    EXPECT_DOUBLE_EQ(f.front(), 0.0);
    EXPECT_DOUBLE_EQ(mtf.front(), 1.0);
    // Non-increasing on average: a negative least-squares slope, and no value above the first.
    EXPECT_LT(analysis::least_squares_slope(f, mtf), 0.0);
    for (double v : mtf) EXPECT_LE(v, 1.0 + 1e-12);

    const double r50 = printed_value(r.out, R"(50%-energy radius: (\S+) mm)");
    const double mean = printed_value(r.out, R"(mean MTF over \(0, 1\] lp/mm: (\S+))");
    const double brightness = printed_value(r.out, R"(brightness: (\S+) )");
    EXPECT_NE(r.out.find("samples: 20000 launched"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("time: "), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::is_regular_file(png));
    if (!preset) {
      EXPECT_EQ(r50, 0.0) << r.out;
      EXPECT_NEAR(brightness, 0.25, 1e-12) << "R x T x mu = 0.5 x 0.5 x 1";
    } else {
      EXPECT_GT(r50, 0.1) << r.out;
      EXPECT_LT(brightness, 0.25 * 0.34) << r.out;
    }
    EXPECT_GT(mean, 0.0);
    EXPECT_LT(mean, 1.0);
  }
}

TEST(PsfCommand, NoPixelRaisesTheIdealMeanMtfToOne) {
  test::temp_dir dir;
  const auto with = test::run_cli("psf " + ideal_bench_scene_path() + " -o " + dir.file("a.csv") + " --samples 1000");
  const auto without =
      test::run_cli("psf " + ideal_bench_scene_path() + " -o " + dir.file("b.csv") + " --samples 1000 --no-pixel");
  ASSERT_EQ(with.exit_code, 0) << with.out;
  ASSERT_EQ(without.exit_code, 0) << without.out;
  const std::string pattern = R"(mean MTF over \(0, 1\] lp/mm: (\S+))";
  EXPECT_NEAR(printed_value(without.out, pattern), 1.0, 1e-9) << without.out;
  // The default camera's pixel alone: the mean of sinc(pi f p) over (0, 1] lp/mm.
  const double p = make_camera(load_scene(ideal_bench_scene_path())).mm_per_pixel;
  double sum = 0;
  for (int i = 1; i <= 200; ++i) {
    const double x = std::numbers::pi * (i / 200.0) * p;
    sum += std::sin(x) / x;
  }
  EXPECT_NEAR(printed_value(with.out, pattern), sum / 200, 1e-4) << with.out;
  EXPECT_LT(sum / 200, 0.96);
}

}  // namespace
