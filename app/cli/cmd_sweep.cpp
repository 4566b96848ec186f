// airr sweep SCENE --vary floating_distance=150:300:25 [--vary tilt=0:45:5] [--psf] [--spp N]
//                  [-o sweep.csv] [--plot sweep.png] [--png map.png --map r50|mean_mtf|mtf50]
//                  [--set key=value ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/sweep.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"
#include "cluster/item_shards.hpp"
#include "cluster/mpi_job.hpp"

namespace {

void write_sweep_plot(const std::string& path, const airr::sweep_result& r, const airr::sweep_params& p) {
  bool d_varies = false;  // more than one floating distance
  for (const auto& pt : r.points) d_varies |= pt.floating_distance_mm != r.points.front().floating_distance_mm;
  std::map<double, airr::analysis::plot_series> by_group;  // one curve per tilt when D varies
  for (const auto& pt : r.points) {
    auto& s = by_group[d_varies ? pt.tilt_deg : 0.0];
    s.x.push_back(d_varies ? pt.floating_distance_mm : pt.tilt_deg);
    s.y.push_back(pt.mean_mtf);
  }
  std::vector<airr::analysis::plot_series> series;
  const std::string route = p.psf_route ? "model PSF" : "edge render, " + std::to_string(p.spp) + " spp";
  for (auto& [tilt, s] : by_group) {
    char label[128];
    if (d_varies) {
      double slope = 0;
      for (const auto& sl : r.slopes)
        if (sl.tilt_deg == tilt) slope = sl.per_mm;
      std::snprintf(label, sizeof label, "%s, tilt %g deg (slope %.3g per 100 mm)", route.c_str(), tilt, 100 * slope);
    } else {
      std::snprintf(label, sizeof label, "%s, D %g mm", route.c_str(), r.points.front().floating_distance_mm);
    }
    s.label = label;
    series.push_back(std::move(s));
  }
  airr::analysis::plot_params pp;
  pp.title = d_varies ? "mean MTF over (0, 1] lp/mm against floating distance"
                      : "mean MTF over (0, 1] lp/mm against retroreflector tilt";
  pp.x_title = d_varies ? "floating distance D (mm)" : "retroreflector tilt (deg)";
  pp.y_title = "mean MTF over (0, 1] lp/mm (unitless)";
  pp.y_min = 0.0;
  pp.y_max = 1.0;
  airr::analysis::write_plot_png(path, series, pp);
}

// The blur over a floating-distance x tilt grid as a heat map, the scene's own layout marked.
void write_sweep_map(const std::string& path, const airr::sweep_result& r, const std::string& metric,
                     const airr::scene& s, const airr::sweep_params& p) {
  std::vector<double> distances, tilts, values;
  for (const auto& pt : r.points) {
    if (std::find(distances.begin(), distances.end(), pt.floating_distance_mm) == distances.end())
      distances.push_back(pt.floating_distance_mm);
    if (std::find(tilts.begin(), tilts.end(), pt.tilt_deg) == tilts.end()) tilts.push_back(pt.tilt_deg);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    values.push_back(metric == "r50"        ? pt.r50_mm
                     : metric == "mean_mtf" ? pt.mean_mtf
                                            : pt.mtf50_lp_per_mm.value_or(nan));
  }
  if (distances.size() < 2 || tilts.size() < 2)
    throw airr::input_error("sweep: --png draws a floating distance x tilt map: vary both, each over 2 or more values");
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo))
    hi = lo + (std::isfinite(lo) ? std::max(1e-9, std::abs(lo) * 0.01) : 1.0), lo = std::isfinite(lo) ? lo : 0.0;
  airr::analysis::heatmap_params hp;
  const std::string route = p.psf_route ? "model PSF" : "edge render, " + std::to_string(p.spp) + " spp";
  hp.title = (metric == "r50"        ? "r50 (50% energy radius)"
              : metric == "mean_mtf" ? "mean MTF over (0, 1] lp/mm"
                                     : "MTF50") +
             std::string(" over floating distance and tilt (") + route + ")";
  hp.x_title = "floating distance D (mm)";
  hp.y_title = "retroreflector tilt (deg)";
  hp.value_title = metric == "r50" ? "r50 (mm)" : metric == "mean_mtf" ? "mean MTF (unitless)" : "MTF50 (lp/mm)";
  hp.x_min = distances.front();
  hp.x_max = distances.back();
  hp.y_min = tilts.front();
  hp.y_max = tilts.back();
  hp.value_min = lo;
  hp.value_max = hi;
  hp.marker = std::make_pair(airr::floating_distance(s), s.sheet().pose.pitch_deg);
  hp.marker_label = "design";
  airr::analysis::write_heatmap_png(path, values, int(distances.size()), int(tilts.size()), hp);
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  struct options {
    std::string scene_path, csv, plot, chart, map_png, map_metric = "r50";
    std::vector<std::string> vary, sets;
    bool psf = false;
    std::uint64_t spp = 64;
    std::uint64_t samples = 100000;
    int threads = 0;
    shard_options shards;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("sweep", "Mean MTF, MTF50 and PSF radius over floating distance and/or tilt");
  cmd->add_option("scene", opt->scene_path, "Scene JSON file")->required();
  cmd->add_option("--vary", opt->vary,
                  "floating_distance=start:end:step (mm) or tilt=start:end:step (deg); both: a grid")
      ->required();
  cmd->add_flag("--psf", opt->psf, "Use the model PSF instead of rendering an edge chart");
  cmd->add_option("--spp", opt->spp, "Edge route: samples per pixel (default 64)")->check(CLI::Range(1, 1 << 24));
  cmd->add_option("--chart", opt->chart, "Edge route: chart image (default assets/charts/slanted_edge.png)");
  cmd->add_option("--samples", opt->samples, "PSF samples per point (default 100000)")
      ->check(CLI::Range(100, 100000000));
  cmd->add_option("-o,--output", opt->csv, "CSV file to write");
  cmd->add_option("--plot", opt->plot, "PNG plot of mean MTF against the varied parameter");
  cmd->add_option("--png", opt->map_png,
                  "PNG map over floating distance x tilt (vary both) of --map, the scene's layout marked");
  cmd->add_option("--map", opt->map_metric, "What --png maps: r50 (default), mean_mtf or mtf50")
      ->check(CLI::IsMember({"r50", "mean_mtf", "mtf50"}));
  cmd->add_option("--set", opt->sets, "Override a scene value, e.g. retroreflectors.0.model.preset=rf-ay");
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")->check(CLI::Range(0, 1024));
  add_shard_options(cmd, opt->shards);
  cmd->callback([opt] {
    airr::sweep_params p;
    for (const auto& v : opt->vary) p.axes.push_back(airr::parse_sweep_axis(v));
    p.psf_route = opt->psf;
    p.spp = opt->spp;
    p.chart = opt->chart;
    p.psf_samples = opt->samples;
    p.threads = opt->threads;
    std::vector<airr::scene_override> overrides;
    for (const auto& s : opt->sets) overrides.push_back(airr::parse_override(s));
    const airr::scene s = load_scene_noting(opt->scene_path, overrides);

    if (!opt->map_png.empty() && opt->vary.size() != 2)
      throw airr::input_error("sweep: --png draws a floating distance x tilt map: give --vary for both");
    // Under mpirun or srun the points are shared among the ranks (point i on rank i mod N); rank 0
    // shows the job's progress and writes.
    const mpi_job& job = this_job();
    std::optional<progress_bar> bar;
    bool finished = false;
    if (job.root()) bar.emplace(job.size > 1 ? "sweep (" + std::to_string(job.size) + " ranks)" : "sweep");
    auto show = [&](double f, const std::string& detail) {
      if (!bar || finished) return;
      if (f < 1.0) {
        bar->update(f, detail);
      } else {
        bar->finish(detail);
        finished = true;
      }
    };
    const auto r = airr::run_sweep(
        s, p,
        [&](double f, const std::string& detail) {
          if (job.size == 1) show(f, detail);
        },
        command_item_share(opt->shards, [&](std::size_t done, std::size_t n) {
          show(double(done) / double(n), std::to_string(done) + " of " + std::to_string(n) + " points");
        }));
    if (!job.root() || write_shard_part(opt->shards)) return;

    std::printf("route: %s; pixel %.6g mm on the aerial-image plane (its aperture is included)\n",
                p.psf_route ? "model PSF" : ("slanted-edge render, " + std::to_string(p.spp) + " spp").c_str(),
                r.mm_per_pixel);
    std::printf("%8s %8s %12s %12s %10s %11s  %s\n", "D_mm", "tilt_deg", "mean_mtf_0_1", "mtf50_lp/mm", "r50_mm",
                "brightness", "by sheet");
    for (const auto& pt : r.points) {
      if (!pt.valid()) {
        std::printf("%8g %8g  no layout: %s\n", pt.floating_distance_mm, pt.tilt_deg, pt.reason.c_str());
        continue;
      }
      char m50[32] = "not reached";
      if (pt.mtf50_lp_per_mm) std::snprintf(m50, sizeof m50, "%.4f", *pt.mtf50_lp_per_mm);
      std::string shares;
      for (double b : pt.sheet_brightness) shares += (shares.empty() ? "" : " + ") + std::to_string(b);
      std::printf("%8g %8g %12.5f %12s %10.4f %11.6f  %s\n", pt.floating_distance_mm, pt.tilt_deg, pt.mean_mtf, m50,
                  pt.r50_mm, pt.brightness, shares.c_str());
    }
    if (airr::in_cd_m2(s.source)) {
      std::printf("brightness is per unit display luminance: the aerial image's luminance is it x %.6g cd/m2\n",
                  s.source.luminance_cd_m2);
    }
    for (const auto& sl : r.slopes)
      std::printf("slope d of mean MTF against D at tilt %g deg: %.6g per mm (%.4g per 100 mm)\n", sl.tilt_deg,
                  sl.per_mm, 100 * sl.per_mm);
    if (!opt->csv.empty()) {
      airr::write_file_atomic(opt->csv, airr::sweep_csv(r));
      std::printf("wrote %s\n", opt->csv.c_str());
    }
    if (!opt->plot.empty()) {
      write_sweep_plot(opt->plot, r, p);
      std::printf("wrote %s\n", opt->plot.c_str());
    }
    if (!opt->map_png.empty()) {
      write_sweep_map(opt->map_png, r, opt->map_metric, s, p);
      std::printf("wrote %s\n", opt->map_png.c_str());
    }
  });
}
