// Fitting a, c and mu from measurements (airr fit): rendered measurements with known parameters
// fit back, the RF-Ay preset's synthetic measurements fit back to Table 2, and broken data
// directories fail with errors naming what is wrong.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/image_read.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/analysis/slanted_edge_mtf.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/test_charts.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/models/retro_sinc_shift.hpp"
#include "airr/render/render_metadata.hpp"
#include "test_helpers.hpp"

using namespace airr;
using nlohmann::json;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string two_digits(int v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", v);
  return buf;
}

// A render plus grey Gaussian noise (the same value on R, G and B, so luminance carries sigma).
image_rgb noisy(const render_snapshot& snap, double sigma, std::uint64_t seed) {
  image_rgb img = snap.image();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float n = float(noise(rng));
      for (int k = 0; k < 3; ++k) img.at(x, y)[k] += n;
    }
  }
  return img;
}

cv::Mat luminance_of(const render_snapshot& snap) {
  cv::Mat rgb(snap.height, snap.width, CV_32FC3, const_cast<float*>(snap.rgb->data()));
  return analysis::rec709_luminance(rgb);
}

void write_json(const std::string& path, const json& j) { std::ofstream(path) << j.dump(2); }

// Renders scene after scene in one session, so the chart texture and the meshes load once.
class sequential_renderer {
 public:
  explicit sequential_renderer(std::uint64_t spp) : spp_(spp) {}
  render_snapshot render(const scene& s) {
    std::uint64_t gen = 0;
    if (!session_)
      session_ = std::make_unique<render_session>(s, session_params{.target_spp = spp_});
    else
      gen = session_->edit(s);
    render_snapshot snap;
    while (!((snap = session_->wait_for(gen, spp_)).generation == gen && (snap.spp >= spp_ || !snap.error.empty()))) {
    }
    if (!snap.error.empty()) throw std::runtime_error(snap.error);
    return snap;
  }

 private:
  std::uint64_t spp_;
  std::unique_ptr<render_session> session_;
};

// ---- Round trip through the tracer ----

// Known parameters: a falls linearly from 6 to 2 over tilts 0..45, c = 0.5 mm, mu = 0.25.
sheet_preset round_trip_truth() {
  sheet_preset p;
  p.name = "round-trip truth";
  for (int t = 0; t <= 45; t += 5) {
    p.theta_deg.push_back(t);
    p.a_per_mm.push_back(6.0 - 4.0 * t / 45.0);
  }
  p.mu = {0.25};
  p.c_mm = 0.5;
  return p;
}

}  // namespace

// The edge route (what is fitted): the tracer renders the scene through the sinc-shift model with
// a(theta) per ray, the 2048-texel chart (0.024 mm texels, far below the 0.1 mm pixel), area
// sampling over each pixel, the PSF's variation over the 12.8 x 19.2 mm field, Monte Carlo
// noise, added noise at SNR 50, then slanted_edge_mtf with its LSF window. The PSF route (what the fit
// simulates): the model PSF at the aerial-image centre, projected on x, with the measurement's
// window and the 0.1 mm pixel's aperture.
TEST(SheetFit, RenderedMeasurementsFitBack) {
  const auto t_start = std::chrono::steady_clock::now();
  test::temp_dir dir;
  const sheet_preset truth = round_trip_truth();
  save_preset(truth, dir.file("truth.json"));
  const std::string chart = dir.file("edge.exr");
  write_image(chart, make_slanted_edge_chart(2048), {});

  // 0.1 mm pixels (Nyquist 5 lp/mm). The edges get 192 rows: the SNR-50 noise moves a single
  // tilt's a by about +-3% with 128 rows, +-2% with 192 (spread over noise seeds), while Monte
  // Carlo noise at 128 spp moves it by about 1% (and c by about 1%, which moves the small tilts' a by
  // several %), so the edges get 256 spp.
  const int size = 128, edge_rows = 192;
  const double pixel_mm = 0.1, square_mm = 10.0;
  const std::uint64_t edge_spp = 256, white_spp = 32;
  auto fov_for = [&](int rows) { return degrees(2.0 * std::atan(0.5 * rows * pixel_mm / 300.0)); };
  scene setup = test::uniform_source_scene(50.0, size);
  setup.observer.fov_deg = fov_for(size);
  save_scene(setup, dir.file("setup.json"));
  ASSERT_NEAR(make_camera(setup).mm_per_pixel, pixel_mm, 1e-9);

  scene truth_scene = setup;
  truth_scene.sheet().model.type = "sinc_shift";
  airr::set_model_value(truth_scene.sheet().model, "preset", dir.file("truth.json"));

  std::uint64_t noise_seed = 1000;
  sequential_renderer edges(edge_spp), whites(white_spp);
  auto render_edge = [&](double tilt, double d, const std::string& name) {
    scene s = truth_scene;
    s.source.image = chart;
    s.observer.height = edge_rows;
    s.observer.fov_deg = fov_for(edge_rows);
    s.sheet().pose.pitch_deg = tilt;
    airr::set_floating_distance(s, d);
    const render_snapshot snap = edges.render(s);
    const double contrast = analysis::slanted_edge_mtf(luminance_of(snap)).esf_contrast;
    write_image(dir.file(name), noisy(snap, contrast / 50.0, ++noise_seed), render_metadata(s, snap, 1.0));
  };
  json fit = {{"format", "airr-fit-data"},     {"version", 1},
              {"name", "round trip"},          {"scene", "setup.json"},
              {"tilt_series", json::array()},  {"distance_series", json::array()},
              {"white_squares", json::array()}};
  for (int t = 0; t <= 45; t += 5) {
    const std::string name = "tilt_" + two_digits(t) + ".exr";
    render_edge(t, 150, name);
    fit["tilt_series"].push_back({{"tilt_deg", t}, {"floating_distance_mm", 150}, {"edge_image", name}});

    // The white square: a 10 mm uniform source in a dark surround.
    scene s = truth_scene;
    s.source.width_mm = s.source.height_mm = square_mm;
    s.sheet().pose.pitch_deg = t;
    const render_snapshot snap = whites.render(s);
    const double white = s.source.intensity * 0.25 * 0.25;  // R T mu
    const std::string white_name = "white_" + two_digits(t) + ".exr";
    write_image(dir.file(white_name), noisy(snap, white / 50.0, ++noise_seed), render_metadata(s, snap, 1.0));
    fit["white_squares"].push_back({{"tilt_deg", t}, {"image", white_name}, {"square_mm", square_mm}});
  }
  fit["distance_series"].push_back({{"floating_distance_mm", 150}, {"edge_image", "tilt_00.exr"}});
  for (int d = 200; d <= 300; d += 50) {
    const std::string name = "distance_" + std::to_string(d) + ".exr";
    render_edge(0, d, name);
    fit["distance_series"].push_back({{"floating_distance_mm", d}, {"tilt_deg", 0}, {"edge_image", name}});
  }
  write_json(dir.file("fit.json"), fit);
  const double render_seconds = seconds_since(t_start);

  const auto t_fit = std::chrono::steady_clock::now();
  const analysis::fit_data data = analysis::load_fit_data(dir.path.string());
  analysis::fit_params p;
  const auto r = analysis::fit_sheet(data, p, {});
  const double fit_seconds = seconds_since(t_fit);

  std::printf(
      "round trip (edges %dx%d, white squares %dx%d, %.2f mm/pixel, %llu spp edges, %llu spp white squares, "
      "SNR 50):\n",
      size, edge_rows, size, size, pixel_mm, static_cast<unsigned long long>(edge_spp),
      static_cast<unsigned long long>(white_spp));
  std::printf("%8s %8s %8s %7s %8s %8s %7s\n", "tilt", "a_true", "a_fit", "a_err", "mu_true", "mu_fit", "mu_err");
  for (std::size_t i = 0; i < truth.theta_deg.size(); ++i) {
    const double a_true = truth.a_per_mm[i], a_fit = r.preset.a_per_mm[i], mu_fit = r.preset.mu[i];
    std::printf("%8g %8.4f %8.4f %+6.2f%% %8.4f %8.4f %+6.2f%%\n", truth.theta_deg[i], a_true, a_fit,
                100 * (a_fit / a_true - 1), 0.25, mu_fit, 100 * (mu_fit / 0.25 - 1));
    EXPECT_NEAR(a_fit, a_true, 0.05 * a_true) << "tilt " << truth.theta_deg[i];
    EXPECT_NEAR(mu_fit, 0.25, 0.05 * 0.25) << "tilt " << truth.theta_deg[i];
    EXPECT_TRUE(r.report.a[i].minimum_checked) << "tilt " << truth.theta_deg[i];
  }
  std::printf("c: true 0.5 mm, fitted %.4f mm (%+.2f%%)\n", r.preset.c_mm, 100 * (r.preset.c_mm / 0.5 - 1));
  std::printf("renders %.1f s, fit %.1f s (%llu PSF samples, %llu simulations)\n", render_seconds, fit_seconds,
              static_cast<unsigned long long>(p.psf_samples), static_cast<unsigned long long>(r.report.simulations));
  EXPECT_NEAR(r.preset.c_mm, 0.5, 0.05);
  EXPECT_TRUE(r.report.c.converged);

  // The written preset drives the sinc-shift model.
  save_preset(r.preset, dir.file("fitted.json"));
  retro_model_params m;
  m.type = "sinc_shift";
  set_model_value(m, "preset", dir.file("fitted.json"));
  const auto model = make_retro_model(m);
  const auto* sinc = dynamic_cast<const sinc_shift_retro*>(model.get());
  ASSERT_NE(sinc, nullptr);
  EXPECT_DOUBLE_EQ(sinc->a_at(45), r.preset.a_per_mm.back());
  EXPECT_DOUBLE_EQ(sinc->params().c_mm, r.preset.c_mm);
  const sheet_preset loaded = load_preset(dir.file("fitted.json"));
  EXPECT_EQ(loaded.provenance["source"], "airr fit");
  EXPECT_EQ(loaded.provenance["files"].size(), data.files().size());
  EXPECT_TRUE(loaded.provenance["fit"]["a"][0].contains("loss"));
}

// ---- RF-Ay: its own synthetic measurements fit back to Table 2 ----

// The measurements are synthesised by `airr fit --synthesise` with the model PSF from the preset
// (1,000,000 samples, seed 7; MTF with the 0.25 mm pixel's aperture; white squares as the square
// convolved with the PSF), and the fit runs through `airr fit` with its default settings.
TEST(SheetFit, RfAyFitsBackToTable2) {
  test::temp_dir dir;
  const auto synth = test::run_cli("fit --synthesise " + dir.file("data") + " --preset rf-ay");
  ASSERT_EQ(synth.exit_code, 0) << synth.out;
  const auto t0 = std::chrono::steady_clock::now();
  const auto fit = test::run_cli("fit --data " + dir.file("data") + " -o " + dir.file("rf-ay-fit.json"));
  const double seconds = seconds_since(t0);
  ASSERT_EQ(fit.exit_code, 0) << fit.out;
  std::printf("%s", fit.out.substr(fit.out.find("fit of ")).c_str());

  test::expect_preset_near_table(load_preset(dir.file("rf-ay-fit.json")), load_preset("rf-ay"), 0.05);
  std::printf("airr fit took %.1f s\n", seconds);
  EXPECT_NE(fit.out.find("run time"), std::string::npos);
}

// ---- The pieces the fit is built from ----

TEST(SheetFit, MeasuredLikeMtfWithoutWindowIsPsfMtf) {
  scene s = test::uniform_source_scene(50.0);
  s.sheet().model.type = "sinc_shift";
  airr::set_model_value(s.sheet().model, "preset", "rf-an");
  const auto model = make_sheet_model(s);
  const psf_samples psf = sample_psf(s, *model, {.samples = 5000, .seed = 3});
  const analysis::psf_mtf_params params{.max_lp_per_mm = 1.5, .points = 31, .pixel_mm = 0.2};
  const auto expected = analysis::psf_mtf(psf, params);
  const auto got = analysis::measured_like_mtf(psf, params, 0.0, false);
  ASSERT_EQ(got.mtf.size(), expected.mtf.size());
  for (std::size_t i = 0; i < got.mtf.size(); ++i) EXPECT_NEAR(got.mtf[i], expected.mtf[i], 1e-9) << i;
  // A window cuts the far tail, which lifts the MTF at low frequencies.
  const auto windowed = analysis::measured_like_mtf(psf, params, 2.0, false);
  EXPECT_GT(windowed.mtf[2], got.mtf[2] + 0.005);
}

TEST(SheetFit, WhiteSquareImageKeepsTheLight) {
  // An ideal retroreflector: the square's image is the square itself, R T mu x intensity bright.
  scene s = test::uniform_source_scene(50.0, 64);
  airr::set_model_value(s.sheet().model, "mu", 0.5);
  const auto model = make_sheet_model(s);
  const psf_samples psf = sample_psf(s, *model, {.samples = 1000, .seed = 1});
  const cv::Mat img = analysis::white_square_image(s, psf, 10.0, 10.0);
  const double mm = make_camera(s).mm_per_pixel, level = s.source.intensity * 0.25 * 0.5;
  EXPECT_NEAR(img.at<double>(32, 32), level, 1e-9);
  EXPECT_NEAR(img.at<double>(2, 2), 0.0, 1e-12);
  EXPECT_NEAR(cv::sum(img)[0], level * (10.0 / mm) * (10.0 / mm), 1e-6 * level * (10.0 / mm) * (10.0 / mm));
}

// ---- Broken data directories ----

namespace {

// A complete, valid data directory of CSV measurements (Gaussian MTF curves).
struct csv_data_dir {
  test::temp_dir dir;
  json fit;

  csv_data_dir() {
    scene setup = test::uniform_source_scene(50.0, 32);
    save_scene(setup, dir.file("setup.json"));
    fit = {{"format", "airr-fit-data"},
           {"version", 1},
           {"scene", "setup.json"},
           {"tilt_series", json::array()},
           {"distance_series", json::array()}};
    for (int t : {0, 20}) {
      write_curve("tilt_" + std::to_string(t) + ".csv", 0.8);
      fit["tilt_series"].push_back({{"tilt_deg", t}, {"mtf_csv", "tilt_" + std::to_string(t) + ".csv"}});
    }
    for (int d : {150, 300}) {
      write_curve("d_" + std::to_string(d) + ".csv", 150.0 / d);
      fit["distance_series"].push_back({{"floating_distance_mm", d}, {"mtf_csv", "d_" + std::to_string(d) + ".csv"}});
    }
    save();
  }
  void write_curve(const std::string& name, double width_lp) {
    std::ofstream out(dir.file(name));
    out << "cycles_per_pixel,lp_per_mm,mtf\n";
    for (int i = 0; i <= 40; ++i) {
      const double f = 0.05 * i;
      out << f * 0.1 << "," << f << "," << std::exp(-f * f / (2 * width_lp * width_lp)) << "\n";
    }
  }
  void save() const { write_json(dir.file("fit.json"), fit); }
};

void expect_error(const std::string& dir, const std::vector<std::string>& must_contain) {
  try {
    analysis::load_fit_data(dir);
    ADD_FAILURE() << "no error for " << dir;
  } catch (const input_error& e) {
    const std::string msg = e.what();
    for (const auto& m : must_contain) EXPECT_NE(msg.find(m), std::string::npos) << "missing '" << m << "' in: " << msg;
  }
}

}  // namespace

TEST(FitData, ValidDirectoryLoads) {
  csv_data_dir d;
  const auto data = analysis::load_fit_data(d.dir.path.string());
  ASSERT_EQ(data.tilt_series.size(), 2u);
  EXPECT_EQ(data.tilt_series[1].tilt_deg, 20);
  EXPECT_NEAR(data.tilt_series[0].pixel_mm, 0.1, 1e-12);  // from cycles_per_pixel / lp_per_mm
  EXPECT_EQ(data.distance_series.size(), 2u);
  EXPECT_TRUE(data.white_squares.empty());
}

TEST(FitData, NoFitJson) {
  test::temp_dir dir;
  expect_error(dir.path.string(), {"fit.json", "missing"});
}

TEST(FitData, MalformedJson) {
  csv_data_dir d;
  std::ofstream(d.dir.file("fit.json")) << "{\"format\": \"airr-fit-data\", ";
  expect_error(d.dir.path.string(), {"fit.json", "malformed JSON"});
}

TEST(FitData, MissingCsv) {
  csv_data_dir d;
  d.fit["tilt_series"][1]["mtf_csv"] = "gone.csv";
  d.save();
  expect_error(d.dir.path.string(), {"fit.json", "tilt_series[1].mtf_csv", "gone.csv", "not found"});
}

TEST(FitData, MissingImage) {
  csv_data_dir d;
  d.fit["white_squares"] = json::array({{{"tilt_deg", 0}, {"image", "white_00.exr"}}});
  d.save();
  expect_error(d.dir.path.string(), {"white_squares[0].image", "white_00.exr", "not found"});
}

TEST(FitData, NoTiltZero) {
  csv_data_dir d;
  d.fit["tilt_series"][0]["tilt_deg"] = 5;
  d.save();
  expect_error(d.dir.path.string(), {"tilt_series", "no measurement at tilt 0"});
}

TEST(FitData, OneDistance) {
  csv_data_dir d;
  d.fit["distance_series"][1]["floating_distance_mm"] = 150;
  d.save();
  expect_error(d.dir.path.string(), {"distance_series", "at least 2 different floating distances"});
}

TEST(FitData, CsvWithoutLpPerMm) {
  csv_data_dir d;
  std::ofstream(d.dir.file("tilt_20.csv")) << "cycles_per_pixel,mtf\n0,1\n0.05,0.9\n0.1,0.8\n";
  expect_error(d.dir.path.string(), {"tilt_series[1].mtf_csv", "tilt_20.csv", "no lp_per_mm column"});
}

TEST(FitData, NanInCsv) {
  csv_data_dir d;
  std::ofstream(d.dir.file("d_300.csv")) << "cycles_per_pixel,lp_per_mm,mtf\n0,0,1\n0.01,0.1,nan\n0.02,0.2,0.8\n";
  expect_error(d.dir.path.string(), {"d_300.csv", "line 3", "mtf", "not a finite number"});
}

TEST(FitData, NanInWhiteSquare) {
  csv_data_dir d;
  image_rgb img{32, 32, std::vector<float>(32 * 32 * 3, 0.5f)};
  img.at(7, 9)[1] = std::nanf("");
  write_image(d.dir.file("white_00.exr"), img, {});
  d.fit["white_squares"] = json::array({{{"tilt_deg", 0}, {"image", "white_00.exr"}}});
  d.save();
  expect_error(d.dir.path.string(), {"white_squares[0].image", "white_00.exr", "pixel (7, 9)", "NaN"});
}

TEST(FitData, WithoutWhiteSquaresMuIsTakenFromFitJson) {
  csv_data_dir d;
  d.fit["mu"] = 0.3;
  d.save();
  const auto data = analysis::load_fit_data(d.dir.path.string());
  analysis::fit_params p;
  p.psf_samples = 2000;
  int calls = 0;
  const auto r = analysis::fit_sheet(data, p, [&](const analysis::fit_progress& f) {
    EXPECT_GE(f.fraction, 0.0);
    EXPECT_LE(f.fraction, 1.0);
    ++calls;
    return true;
  });
  EXPECT_GT(calls, 10);
  EXPECT_EQ(r.preset.mu, std::vector<double>{0.3});
  EXPECT_NE(r.report.mu_note.value_or("").find("not fitted"), std::string::npos);
  EXPECT_EQ(r.preset.theta_deg, (std::vector<double>{0, 20}));
  EXPECT_EQ(r.report.a.size(), 2u);
}

TEST(FitData, FitCancels) {
  csv_data_dir d;
  const auto data = analysis::load_fit_data(d.dir.path.string());
  analysis::fit_params p;
  p.psf_samples = 2000;
  int calls = 0;
  EXPECT_THROW(analysis::fit_sheet(data, p, [&](const analysis::fit_progress&) { return ++calls < 5; }),
               analysis::fit_cancelled);
  EXPECT_EQ(calls, 5);
}

TEST(FitData, CliReportsOneLine) {
  csv_data_dir d;
  d.fit.erase("distance_series");
  d.save();
  const auto r = test::run_cli("fit --data " + d.dir.path.string() + " -o " + d.dir.file("p.json"));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_EQ(r.out.rfind("error: ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("distance_series: missing"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}
