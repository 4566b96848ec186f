// airr viewzone SCENE -o zone.csv [--png zone.png] [--sphere] [--distance MM] [--grid N]
//               [--x MIN MAX] [--y MIN MAX] [--rows N] [--set key=value ...]
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "airr/analysis/plot_png.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/files.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/scene_json.hpp"
#include "airr/optics/viewing_zone.hpp"
#include "commands.hpp"
#include "progress_bar.hpp"

namespace {

std::string zone_csv(const airr::scene& s, const airr::viewing_zone_map& m) {
  const bool sphere = m.grid.kind == airr::eye_grid::shape::sphere;
  std::string out = sphere ? "azimuth_deg,elevation_deg" : "x_mm,y_mm";
  out += ",eye_x_mm,eye_y_mm,eye_z_mm,visible_fraction\n";
  char row[256];
  for (int j = 0; j < m.grid.ny; ++j) {
    for (int i = 0; i < m.grid.nx; ++i) {
      const double x = m.grid.x_at(i), y = m.grid.y_at(j);
      const glm::dvec3 e = airr::eye_position(s, m.grid, x, y);
      std::snprintf(row, sizeof row, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", x, y, e.x, e.y, e.z,
                    m.visible[std::size_t(j) * m.grid.nx + i]);
      out += row;
    }
  }
  return out;
}

}  // namespace

void add_viewzone_command(CLI::App& app) {
  struct options {
    std::string scene_path, csv, png;
    bool sphere = false;
    double distance = 300;
    int grid = 21, rows = 128;
    std::vector<double> x_range, y_range;
    std::vector<std::string> sets;
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
  cmd->add_option("--rows", opt->rows, "Rows across the aerial image per eye (default 128)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. retroreflectors.0.pose.pitch_deg=10");
  cmd->callback([opt] {
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = airr::load_scene(opt->scene_path, overrides);
    airr::eye_grid g;
    g.kind = opt->sphere ? airr::eye_grid::shape::sphere : airr::eye_grid::shape::plane;
    g.distance_mm = opt->distance;
    g.nx = g.ny = opt->grid;
    const double reach = opt->sphere ? 60 : 200;
    g.x_min = opt->x_range.empty() ? -reach : opt->x_range[0];
    g.x_max = opt->x_range.empty() ? reach : opt->x_range[1];
    g.y_min = opt->y_range.empty() ? -reach : opt->y_range[0];
    g.y_max = opt->y_range.empty() ? reach : opt->y_range[1];
    airr::check_eye_grid(g);
    if (s.retroreflectors.empty()) throw airr::input_error(opt->scene_path + ": no retroreflector, no aerial image");

    progress_bar bar("viewzone");
    const airr::viewing_zone_map map = airr::geometric_viewing_zone(s, g, opt->rows, [&](int done, int total) {
      if (done < total) bar.update(double(done) / total);
    });
    bar.finish();
    airr::write_file_atomic(opt->csv, zone_csv(s, map));
    double best = 0, sum = 0;
    for (double v : map.visible) best = std::max(best, v), sum += v;
    std::printf("%d x %d eyes on a %s at %.6g mm: visible fraction up to %.4f, mean %.4f; %.3f s (%.2f ms per eye)\n",
                g.nx, g.ny, opt->sphere ? "sphere" : "plane", g.distance_mm, best, sum / double(map.visible.size()),
                map.seconds, 1e3 * map.seconds / double(map.visible.size()));
    std::printf("wrote %s\n", opt->csv.c_str());
    if (!opt->png.empty()) {
      airr::analysis::heatmap_params p;
      p.title = "visible fraction of the aerial image";
      p.x_title = opt->sphere ? "observer azimuth (deg)" : "eye x (mm, right)";
      p.y_title = opt->sphere ? "observer elevation (deg)" : "eye y (mm, up)";
      if (!opt->sphere) {
        char t[128];
        std::snprintf(t, sizeof t, "visible fraction of the aerial image, eyes %.6g mm in front of it", g.distance_mm);
        p.title = t;
      }
      p.value_title = "visible fraction";
      p.x_min = g.x_min;
      p.x_max = g.x_max;
      p.y_min = g.y_min;
      p.y_max = g.y_max;
      const glm::dvec2 at = airr::eye_grid_coordinates(s, g, airr::observer_position(s));
      p.marker = std::pair{at.x, at.y};
      p.marker_label = "observer";
      airr::analysis::write_heatmap_png(opt->png, map.visible, g.nx, g.ny, p);
      std::printf("wrote %s\n", opt->png.c_str());
    }
  });
}
