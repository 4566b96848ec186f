// airr viewzone SCENE -o zone.csv [--png zone.png] [--sphere] [--distance MM] [--grid N]
//               [--x MIN MAX] [--y MIN MAX] [--rows N] [--full [--spp N]] [--set key=value ...]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/prop_hits.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/item_shards.hpp"
#include "cluster/mpi_job.hpp"

namespace {

// One quantity per eye, ny rows of nx.
struct zone_column {
  std::string name;    // CSV column
  std::string title;   // heatmap title and colour bar
  std::string suffix;  // heatmap file: the --png stem plus this
  const std::vector<double>* values;
  double lo, hi;
  const std::vector<double>* heat = nullptr;  // the heatmap's values, when not `values`
};

std::string zone_csv(const airr::scene& s, const airr::eye_grid& g, const std::vector<zone_column>& columns) {
  const bool sphere = g.kind == airr::eye_grid::shape::sphere;
  std::string out = sphere ? "azimuth_deg,elevation_deg" : "x_mm,y_mm";
  out += ",eye_x_mm,eye_y_mm,eye_z_mm";
  for (const zone_column& c : columns) out += "," + c.name;
  out += "\n";
  char cell[160];
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x_at(i), y = g.y_at(j);
      const glm::dvec3 e = airr::eye_position(s, g, x, y);
      std::snprintf(cell, sizeof cell, "%.10g,%.10g,%.10g,%.10g,%.10g", x, y, e.x, e.y, e.z);
      out += cell;
      for (const zone_column& c : columns) {
        const double v = (*c.values)[std::size_t(j) * g.nx + i];
        if (std::isfinite(v)) {
          std::snprintf(cell, sizeof cell, ",%.10g", v);
          out += cell;
        } else {
          out += std::isinf(v) ? ",inf" : ",";  // a contrast against a dark background; nothing seen from here
        }
      }
      out += "\n";
    }
  }
  return out;
}

// The aerial image's luminance, its contrast and, per threshold, the share of it reaching that
// contrast; `shown` keeps the contrast heatmap's values.
void add_legibility_columns(const airr::scene& s, const airr::full_zone_map& map, std::vector<zone_column>& columns,
                            std::vector<double>& shown) {
  double luminance_hi = 0, contrast_hi = 1;
  for (double v : map.luminance) luminance_hi = std::max(luminance_hi, v);
  shown = airr::contrast_shown(map, contrast_hi);
  columns.push_back({"luminance", std::string("aerial image's mean luminance (") + airr::image_units(s.source) + ")",
                     "_luminance", &map.luminance, 0, luminance_hi > 0 ? luminance_hi : 1});
  columns.push_back(
      {"contrast", "contrast (aerial + background) / background", "_contrast", &map.contrast, 1, contrast_hi, &shown});
  for (std::size_t k = 0; k < map.thresholds.size(); ++k) {
    char name[64], title[96];
    std::snprintf(name, sizeof name, "share_contrast_%g", map.thresholds[k]);
    std::snprintf(title, sizeof title, "share of the aerial image at contrast >= %g", map.thresholds[k]);
    columns.push_back({name, title, std::string("_") + name, &map.contrast_share[k], 0, 1});
  }
  // The character maps' heatmaps span their finite values (infinite: nothing legible there).
  const auto add_finite = [&](const char* name, const char* title, const char* suffix, const std::vector<double>& v) {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (double x : v)
      if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
    if (!(hi > lo)) lo = 0, hi = std::max(hi, 1.0);
    columns.push_back({name, title, suffix, &v, lo, hi});
  };
  add_finite("char_height_mm", "smallest legible character (mm on the aerial image)", "_char_height",
             map.char_height_mm);
  add_finite("char_height_arcmin", "smallest legible character (arcmin)", "_char_arcmin", map.char_arcmin);
}

void print_legibility(const airr::scene& s, const airr::full_zone_map& map) {
  double best = 0;
  for (double v : map.luminance) best = std::max(best, v);
  std::printf("aerial image's mean luminance up to %.6g %s\n", best, airr::image_units(s.source));
  for (std::size_t k = 0; k < map.thresholds.size(); ++k) {
    std::printf("legible share of the zone at contrast %g: %.4f (eyes seeing %.0f%% of the image at that contrast)\n",
                map.thresholds[k], airr::legible_share(map, k), 100 * airr::legible_image_share);
  }
  double smallest = std::numeric_limits<double>::infinity();
  std::size_t at = 0;
  for (std::size_t e = 0; e < map.char_height_mm.size(); ++e)
    if (map.char_height_mm[e] < smallest) smallest = map.char_height_mm[e], at = e;
  if (std::isfinite(smallest))
    std::printf("smallest legible character: %.4g mm (%.3g arcmin) at the best eye\n", smallest, map.char_arcmin[at]);
}

}  // namespace

void add_viewzone_command(CLI::App& app) {
  struct options {
    std::string scene_path, csv, png;
    bool sphere = false;
    double distance = 300;
    int grid = 21, rows = 64;
    std::vector<double> x_range, y_range;
    std::vector<std::string> sets;
    bool full = false;
    std::uint64_t spp = 16;
    std::vector<double> contrast = airr::default_contrast_thresholds;
    shard_options shards;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand(
      "viewzone", "Where the aerial image can be seen: its visible fraction over a grid of eye positions (geometric)");
  cmd->add_option("scene", opt->scene_path, "Scene JSON file")->required();
  cmd->add_option("-o,--output", opt->csv, "CSV file to write (grid coordinates, eye position, visible fraction)")
      ->required();
  cmd->add_option("--png", opt->png, "Also write the map as a PNG heatmap (the current observer marked)");
  cmd->add_flag("--sphere", opt->sphere,
                "Eyes on the sphere around the aerial image (azimuth, elevation in degrees) instead of a plane in "
                "front of it (x, y in mm)");
  cmd->add_option("--distance", opt->distance, "Distance of the plane or the sphere's radius, mm (default 300)")
      ->check(CLI::Range(1.0, 1e6));
  cmd->add_option("--grid", opt->grid, "Eye positions per side (default 21)")->check(CLI::Range(1, 1001));
  cmd->add_option("--x", opt->x_range, "First and last x (mm) or azimuth (deg); default -200 200 mm or -60 60 deg")
      ->expected(2);
  cmd->add_option("--y", opt->y_range, "First and last y (mm) or elevation (deg); default -200 200 mm or -60 60 deg")
      ->expected(2);
  cmd->add_option("--rows", opt->rows, "Slabs across the aerial image per eye (default 64)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--full", opt->full,
                "Also the full model per eye: mean brightness (relative to the best eye), mean MTF over (0, 1] lp/mm "
                "of the model PSF, stray-light ratio, the aerial image's luminance and contrast, and the share of it "
                "reaching each --contrast (from a small render split into components); PNGs for each");
  cmd->add_option("--spp", opt->spp, "Samples per pixel of each eye's render with --full (default 16)")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--contrast", opt->contrast,
                  "Contrast thresholds for --full's legibility (default 1.5 3 25: just visible, usable, best)")
      ->check(CLI::Range(1.0, 1e6));
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. retroreflectors.0.pose.pitch_deg=10");
  add_shard_options(cmd, opt->shards);
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);
    const airr::eye_grid g =
        airr::requested_eye_grid(opt->sphere, opt->distance, opt->grid, opt->x_range, opt->y_range);
    if (s.retroreflectors.empty()) throw airr::input_error(opt->scene_path + ": no retroreflector, no aerial image");

    // Under mpirun or srun the full pass's eyes are shared among the ranks (eye i on rank i mod N),
    // rank 0 showing its share's progress and writing; the geometric pass is rank 0's alone.
    const mpi_job& job = this_job();
    if (!opt->shards.shard.empty() && !opt->full) throw airr::input_error("--shard: only with --full");
    if (!job.root() && !opt->full) return;
    std::optional<progress_bar> bar;
    if (job.root())
      bar.emplace(opt->full
                      ? job.size > 1 ? "viewzone (full, " + std::to_string(job.size) + " ranks)" : "viewzone (full)"
                      : "viewzone");
    // This process's eyes (alone, or a shard's), or in an MPI job the whole job's, counted by rank 0.
    auto report = [&](int done, int total) {
      if (bar && done < total)
        bar->update(double(done) / total, std::to_string(done) + " of " + std::to_string(total) + " eyes");
    };
    auto local_report = [&](int done, int total) {
      if (job.size == 1) report(done, total);
    };
    airr::full_zone_map map;
    if (opt->full) {
      map = airr::full_viewing_zone(
          s, g, {.rows_per_eye = opt->rows, .render_spp = opt->spp, .contrast_thresholds = opt->contrast}, local_report,
          nullptr,
          command_item_share(opt->shards, [&](std::size_t done, std::size_t n) { report(int(done), int(n)); }));
      if (!job.root() || write_shard_part(opt->shards)) return;
    } else {
      const airr::viewing_zone_map geometric =
          airr::geometric_viewing_zone(s, g, airr::scene_prop_hits(s), opt->rows, report);
      map.grid = geometric.grid;
      map.visible = geometric.visible;
      map.seconds = geometric.seconds;
    }
    bar->finish();
    std::vector<double> contrast_shown;  // the contrast map's heatmap, infinite values at its top
    std::vector<zone_column> columns = {
        {"visible_fraction", "visible fraction of the aerial image", "", &map.visible, 0, 1}};
    if (opt->full) {
      double mtf_hi = 0;
      for (double v : map.mean_mtf) mtf_hi = std::isfinite(v) ? std::max(mtf_hi, v) : mtf_hi;
      columns.push_back(
          {"brightness", "mean brightness, relative to the best eye", "_brightness", &map.brightness, 0, 1});
      columns.push_back(
          {"mean_mtf", "mean MTF over (0, 1] lp/mm (model PSF)", "_mtf", &map.mean_mtf, 0, mtf_hi > 0 ? mtf_hi : 1});
      double stray_hi = 0;
      for (double v : map.stray_ratio) stray_hi = std::isfinite(v) ? std::max(stray_hi, v) : stray_hi;
      columns.push_back({"stray_ratio", "stray light / aerial image, inside its outline", "_stray", &map.stray_ratio, 0,
                         stray_hi > 0 ? stray_hi : 1});
      double direct_hi = 0;
      for (double v : map.direct) direct_hi = std::isfinite(v) ? std::max(direct_hi, v) : direct_hi;
      columns.push_back({"direct", "display seen directly inside the aerial outline / its own luminance", "_direct",
                         &map.direct, 0, direct_hi > 0 ? direct_hi : 1});
      add_legibility_columns(s, map, columns, contrast_shown);
    }
    airr::write_file_atomic(opt->csv, zone_csv(s, g, columns));
    if (opt->full) print_legibility(s, map);
    double best = 0, sum = 0;
    for (double v : map.visible) best = std::max(best, v), sum += v;
    std::printf("%d x %d eyes on a %s at %.6g mm: visible fraction up to %.4f, mean %.4f; %.3f s (%.2f ms per eye)%s\n",
                g.nx, g.ny, opt->sphere ? "sphere" : "plane", g.distance_mm, best, sum / double(map.visible.size()),
                map.seconds, 1e3 * map.seconds / double(map.visible.size()), opt->full ? ", full model" : "");
    std::printf("wrote %s\n", opt->csv.c_str());
    if (!opt->png.empty()) {
      const std::filesystem::path png(opt->png);
      const glm::dvec2 at = airr::eye_grid_coordinates(s, g, airr::observer_position(s));
      for (const zone_column& c : columns) {
        airr::analysis::heatmap_params p;
        char title[160];
        if (opt->sphere) {
          std::snprintf(title, sizeof title, "%s", c.title.c_str());
        } else {
          std::snprintf(title, sizeof title, "%s, eyes %.6g mm in front", c.title.c_str(), g.distance_mm);
        }
        p.title = title;
        p.x_title = opt->sphere ? "observer azimuth (deg)" : "eye x (mm, right)";
        p.y_title = opt->sphere ? "observer elevation (deg)" : "eye y (mm, up)";
        p.value_title = c.name;
        p.x_min = g.x_min;
        p.x_max = g.x_max;
        p.y_min = g.y_min;
        p.y_max = g.y_max;
        p.value_min = c.lo;
        p.value_max = c.hi;
        p.marker = std::pair{at.x, at.y};
        p.marker_label = "observer";
        const std::string path =
            (png.parent_path() / (png.stem().string() + c.suffix + png.extension().string())).string();
        airr::analysis::write_heatmap_png(path, c.heat ? *c.heat : *c.values, g.nx, g.ny, p);
        std::printf("wrote %s\n", path.c_str());
      }
    }
  });
}
