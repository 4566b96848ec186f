#include "airr/analysis/fit_synthesis.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/fit_simulation.hpp"
#include "airr/analysis/mtf_csv.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/files.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"

namespace airr::analysis {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int camera_pixels = 40;
constexpr double camera_mm = 0.4, pixel_mm = 0.25, square_mm = 10.0;

std::string two_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02.0f", v);
  return buf;
}

void write_white_square(const std::string& path, const scene& s, const psf_samples& psf) {
  const cv::Mat img = white_square_image(s, psf, square_mm, square_mm);
  image_rgb rgb{img.cols, img.rows, std::vector<float>(std::size_t(img.total()) * 3)};
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      for (int k = 0; k < 3; ++k) rgb.at(x, y)[k] = float(img.at<double>(y, x));
  char mm[64];
  std::snprintf(mm, sizeof mm, "%.17g", make_camera(s).mm_per_pixel);
  write_image(path, rgb, {{"airr:mm_per_pixel", mm}, {"airr:generator", "airr fit synthesis"}});
}

}  // namespace

scene synthesis_bench(scene setup) {
  setup.props.clear();  // the model PSF does not see them
  setup.source.emission_profile.clear();
  setup.source.image.clear();
  const std::string panel = (fs::path(asset_dir()) / "models/panel.gltf").string();
  setup.source.mesh = setup.half_mirror.mesh = panel;
  for (auto& sheet : setup.retroreflectors) sheet.mesh = panel;
  setup.observer.width = setup.observer.height = camera_pixels;
  setup.observer.fov_deg = degrees(2.0 * std::atan(0.5 * camera_pixels * camera_mm / setup.observer.distance_mm));
  return setup;
}

scene synthesis_bench_file(const std::string& setup_path) {
  if (setup_path.empty()) return synthesis_bench(scene{});
  const scene setup = load_scene(setup_path);
  check_fit_sheets(setup, setup_path);
  return synthesis_bench(setup);
}

void synthesise_fit_data(const std::string& dir_name, const scene& bench, const synthesis_truth& truth,
                         const synthesis_params& p, const fit_progress_callback& progress) {
  const fs::path dir = fs::absolute(dir_name);
  fs::create_directories(dir);
  retro_model_params model = truth.model;
  rebase_model_paths(model, truth.base_dir, dir.string());
  scene setup = rebase_scene_paths(bench, dir.string());
  // The panels relative to the data, so that a copied tree (data and assets) still loads.
  const std::string panel = fs::relative(fs::path(asset_dir()) / "models/panel.gltf", dir).string();
  setup.source.mesh = setup.half_mirror.mesh = panel;
  for (auto& sheet : setup.retroreflectors) sheet.mesh = panel, sheet.model = model;
  save_scene(setup, (dir / "setup.json").string());
  setup = load_scene((dir / "setup.json").string());  // checks the model builds

  const int steps = 10 + 7 + 10;
  int done = 0;
  auto step = [&](const std::string& stage) {
    if (progress && !progress({.stage = stage, .fraction = double(done) / steps})) throw fit_cancelled();
    ++done;
  };
  scene s;
  auto truth_psf = [&](double tilt, double d) {
    s = measurement_layout(setup, tilt, d);
    return sample_psf(s, make_sheet_models(s), {.samples = p.samples, .seed = p.seed});
  };
  auto write_csv = [&](const psf_samples& psf, const std::string& name) {
    const auto c =
        measured_like_mtf(psf, {.max_lp_per_mm = 2.0, .points = 101, .pixel_mm = pixel_mm}, p.lsf_window_mm, false);
    mtf_curve curve;
    for (std::size_t i = 0; i < c.mtf.size(); ++i) curve.cycles_per_pixel.push_back(c.lp_per_mm[i] * pixel_mm);
    curve.mtf = c.mtf;
    write_file_atomic((dir / name).string(), format_mtf_csv(curve, pixel_mm));
  };
  auto curve_entry = [&](json e) {
    if (p.lsf_window_mm > 0) e["lsf_window_mm"] = p.lsf_window_mm;
    return e;
  };

  json fit = {{"format", fit_data_format},
              {"version", fit_data_version},
              {"name", truth.name},
              {"note", truth.note + " (model PSF, " + std::to_string(p.samples) + " samples, seed " +
                           std::to_string(p.seed) + "; MTF curves include a 0.25 mm pixel's aperture)"},
              {"scene", "setup.json"},
              {"tilt_series", json::array()},
              {"distance_series", json::array()},
              {"white_squares", json::array()}};
  for (int t = 0; t <= 45; t += 5) {
    step("tilt " + std::to_string(t) + " deg");
    const auto psf = truth_psf(t, 150);
    const std::string csv = "tilt_" + two_digits(t) + ".csv", white = "white_" + two_digits(t) + ".exr";
    write_csv(psf, csv);
    fit["tilt_series"].push_back(curve_entry({{"tilt_deg", t}, {"floating_distance_mm", 150}, {"mtf_csv", csv}}));
    step("white square at tilt " + std::to_string(t) + " deg");
    write_white_square((dir / white).string(), s, psf);
    fit["white_squares"].push_back({{"tilt_deg", t}, {"image", white}, {"square_mm", square_mm}});
  }
  for (int d = 150; d <= 300; d += 25) {
    step("D " + std::to_string(d) + " mm");
    const std::string csv = "distance_" + std::to_string(d) + ".csv";
    write_csv(truth_psf(0, d), csv);
    fit["distance_series"].push_back(curve_entry({{"floating_distance_mm", d}, {"tilt_deg", 0}, {"mtf_csv", csv}}));
  }
  write_file_atomic((dir / "fit.json").string(), fit.dump(2) + "\n");
}

}  // namespace airr::analysis
