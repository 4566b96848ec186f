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

// The white square's image (camera_pixels square, row by row) as the bench's EXR.
void write_white_square(const std::string& path, const double* luminance, double mm_per_pixel) {
  image_rgb rgb{camera_pixels, camera_pixels, std::vector<float>(std::size_t(camera_pixels * camera_pixels) * 3)};
  for (int y = 0; y < camera_pixels; ++y)
    for (int x = 0; x < camera_pixels; ++x)
      for (int k = 0; k < 3; ++k) rgb.at(x, y)[k] = float(luminance[y * camera_pixels + x]);
  char mm[64];
  std::snprintf(mm, sizeof mm, "%.17g", mm_per_pixel);
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
                         const synthesis_params& p, const fit_progress_callback& progress, const item_share& share) {
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

  // The measurements as items: per tilt (0 to 45 deg) its MTF curve and white square, per D (150 to
  // 300 mm) its curve.
  struct measurement {
    double tilt, d;
    bool white;
  };
  std::vector<measurement> ms;
  for (int t = 0; t <= 45; t += 5) ms.push_back({double(t), 150, true});
  for (int d = 150; d <= 300; d += 25) ms.push_back({0, double(d), false});
  if (progress && !progress({.stage = "tilt 00 deg", .fraction = 0})) throw fit_cancelled();
  const std::size_t points = 101, pixels = std::size_t(camera_pixels * camera_pixels), width = 2 * points + pixels;
  const std::vector<double> values = run_items(
      share, ms.size(), width,
      [&](std::size_t i, double* out) {
        const scene s = measurement_layout(setup, ms[i].tilt, ms[i].d);
        const psf_samples psf = sample_psf(s, make_sheet_models(s), {.samples = p.samples, .seed = p.seed});
        const auto c = measured_like_mtf(psf, {.max_lp_per_mm = 2.0, .points = int(points), .pixel_mm = pixel_mm},
                                         p.lsf_window_mm, false);
        std::copy(c.lp_per_mm.begin(), c.lp_per_mm.end(), out);
        std::copy(c.mtf.begin(), c.mtf.end(), out + points);
        if (!ms[i].white) return;
        const cv::Mat img = white_square_image(s, psf, square_mm, square_mm);
        if (img.rows != camera_pixels || img.cols != camera_pixels)
          throw std::logic_error("the bench's camera is not " + std::to_string(camera_pixels) + " pixels square");
        for (std::size_t k = 0; k < pixels; ++k)
          out[2 * points + k] = img.at<double>(int(k / camera_pixels), int(k % camera_pixels));
      },
      [&](std::size_t i) {
        const std::string stage =
            ms[i].white ? "tilt " + two_digits(ms[i].tilt) + " deg" : "D " + std::to_string(int(ms[i].d)) + " mm";
        if (progress && !progress({.stage = stage, .fraction = double(i + 1) / double(ms.size())}))
          throw fit_cancelled();
      });

  auto write_csv = [&](const double* item, const std::string& name) {
    mtf_curve curve;
    for (std::size_t k = 0; k < points; ++k) curve.cycles_per_pixel.push_back(item[k] * pixel_mm);
    curve.mtf.assign(item + points, item + 2 * points);
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
  if (!truth.shift_table.empty()) {
    copy_file_atomic(truth.shift_table, (dir / "shift_table.json").string());
    fit["shift_table"] = "shift_table.json";
  }
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double* item = values.data() + i * width;
    const int t = int(ms[i].tilt), d = int(ms[i].d);
    if (ms[i].white) {
      const std::string csv = "tilt_" + two_digits(t) + ".csv", white = "white_" + two_digits(t) + ".exr";
      write_csv(item, csv);
      fit["tilt_series"].push_back(curve_entry({{"tilt_deg", t}, {"floating_distance_mm", 150}, {"mtf_csv", csv}}));
      write_white_square((dir / white).string(), item + 2 * points,
                         make_camera(measurement_layout(setup, t, d)).mm_per_pixel);
      fit["white_squares"].push_back({{"tilt_deg", t}, {"image", white}, {"square_mm", square_mm}});
    } else {
      const std::string csv = "distance_" + std::to_string(d) + ".csv";
      write_csv(item, csv);
      fit["distance_series"].push_back(curve_entry({{"floating_distance_mm", d}, {"tilt_deg", 0}, {"mtf_csv", csv}}));
    }
  }
  write_file_atomic((dir / "fit.json").string(), fit.dump(2) + "\n");
}

}  // namespace airr::analysis
