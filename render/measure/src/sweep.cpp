#include "airr/measure/sweep.hpp"

#include "airr/analysis/mtf_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <tbb/parallel_for.h>

#include "airr/core/assets.hpp"
#include "airr/core/csv_table.hpp"
#include "airr/core/error.hpp"
#include "airr/core/number_range.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

namespace {

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string point_label(double d, double tilt) {
  return "sweep point floating_distance=" + number(d) + ", tilt=" + number(tilt);
}

std::string detail_of(const sweep_point& pt) {
  return "D " + number(pt.floating_distance_mm) + " mm, tilt " + number(pt.tilt_deg) + " deg";
}

// What an error at a point says, without the point's label its message may begin with.
std::string reason_of(const std::exception& e, const std::string& label) {
  std::string m = e.what();
  if (m.starts_with(label + ": ")) m.erase(0, label.size() + 2);
  return m;
}

// The point as no layout, for `reason`: no numbers.
void mark_invalid(sweep_point& pt, std::string reason) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  pt.mean_mtf = pt.r50_mm = pt.brightness = nan;
  pt.mtf50_lp_per_mm.reset();
  pt.sheet_brightness.clear();
  pt.reason = std::move(reason);
}

// The model PSF's numbers at one point (both routes report them); the PSF itself.
psf_samples measure_psf(const scene& s, const sweep_params& p, sweep_point& pt) {
  psf_samples psf = scene_psf(s, p.psf_samples);
  pt.r50_mm = energy_radius(psf);
  pt.brightness = psf.brightness();
  for (const psf_sheet_share& share : psf.sheets) pt.sheet_brightness.push_back(share.brightness);
  return psf;
}

// The edge route's MTF at one point: its edge chart rendered to p.spp by `session` (made on first
// use, edited after: an edit renders what a fresh session would) and measured.
mtf_summary edge_point_mtf(std::unique_ptr<render_session>& session, const scene& s, const sweep_params& p,
                           const std::string& label, const std::function<void(std::uint64_t)>& spp_done) {
  std::uint64_t gen = 0;
  if (!session) {
    // No coarse preview: only the finished image is measured.
    session = std::make_unique<render_session>(
        s, session_params{.threads = p.threads, .target_spp = p.spp, .preview_stride = 1});
  } else {
    gen = session->edit(s);
  }
  render_snapshot snap;
  while (true) {
    snap = session->snapshot();
    const bool current = snap.generation == gen;
    if (current && (!snap.error.empty() || snap.spp >= p.spp)) break;
    const std::uint64_t done = current ? snap.spp : 0;
    if (spp_done) spp_done(done);
    session->wait_for(gen, std::min<std::uint64_t>(p.spp, done + 1));
  }
  if (!snap.error.empty()) throw input_error(label + ": " + snap.error);
  try {
    return edge_route_mtf(s, snap, p.roi_fraction);
  } catch (const std::exception& e) {
    throw std::runtime_error(label + ": " + e.what());
  }
}

// Measures a point whose layout passed the checks; one that still is no layout (a camera ray
// missing a part) keeps its reason instead. `session`: the edge route's, made on first use.
void measure_point(const scene& s, const sweep_params& p, sweep_point& pt, std::unique_ptr<render_session>& session,
                   const std::function<void(std::uint64_t)>& spp_done) {
  const std::string label = point_label(pt.floating_distance_mm, pt.tilt_deg);
  try {
    const psf_samples psf = measure_psf(s, p, pt);
    const mtf_summary m =
        p.psf_route ? psf_route_mtf(psf, make_camera(s).mm_per_pixel) : edge_point_mtf(session, s, p, label, spp_done);
    pt.mean_mtf = m.mean_mtf;
    pt.mtf50_lp_per_mm = m.mtf50_lp_per_mm;
  } catch (const airr_error& e) {
    mark_invalid(pt, reason_of(e, label));
  }
}

// Throws input_error naming the first point and its reason when no point is a layout.
void check_some_point_valid(const sweep_result& r) {
  if (std::any_of(r.points.begin(), r.points.end(), [](const sweep_point& pt) { return pt.valid(); })) return;
  const sweep_point& first = r.points.front();
  throw input_error(point_label(first.floating_distance_mm, first.tilt_deg) + ": " + first.reason +
                    " (and no other point of the sweep is a layout)");
}

}  // namespace

sweep_axis parse_sweep_axis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw input_error("--vary " + text + ": expected key=start:end:step, e.g. floating_distance=150:300:25");
  sweep_axis a;
  a.key = text.substr(0, eq);
  if (a.key != "floating_distance" && a.key != "tilt")
    throw input_error("--vary " + text + ": unknown key '" + a.key + "' (use floating_distance or tilt)");
  a.range = parse_number_range(text.substr(eq + 1), "--vary " + text, max_sweep_points);
  return a;
}

std::vector<double> sweep_values(const sweep_axis& a) { return range_values(a.range); }

// Refuses, before anything is measured, a sweep whose points at once would not fit: the PSF route
// measures up to 8 points side by side (one a thread), the edge route one point's PSF and render.
static void check_sweep_memory(const sweep_result& r, const std::vector<scene>& scenes, const sweep_params& p) {
  const std::size_t threads =
      p.threads > 0 ? std::size_t(p.threads) : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t at_once = p.psf_route ? std::min<std::size_t>({scenes.size(), 8, threads}) : 1;
  std::uint64_t need = measuring_process_bytes + at_once * psf_memory_need(p.psf_samples);
  for (std::size_t i = 0; i < scenes.size() && !p.psf_route; ++i) {
    if (r.points[i].valid()) {
      need += render_memory_need(scenes[i], session_params{});
      break;
    }
  }
  check_memory_need("sweep: " + std::to_string(at_once) + (at_once == 1 ? " point" : " points") + " at once of " +
                        std::to_string(p.psf_samples) + " PSF samples" + (p.psf_route ? "" : " and an edge render"),
                    need);
}

sweep_result run_sweep(const scene& base, const sweep_params& p, const sweep_progress& progress,
                       const item_share& share) {
  if (p.axes.empty()) throw input_error("--vary: give floating_distance=start:end:step and/or tilt=start:end:step");
  std::vector<double> distances = {airr::floating_distance(base)}, tilts = {base.sheet().pose.pitch_deg};
  bool d_set = false, tilt_set = false;
  for (const auto& a : p.axes) {
    bool& seen = a.key == "floating_distance" ? d_set : tilt_set;
    if (seen) throw input_error("--vary " + a.key + ": given twice");
    seen = true;
    (a.key == "floating_distance" ? distances : tilts) = sweep_values(a);
  }
  if (distances.size() * tilts.size() > std::size_t(max_sweep_points))
    throw input_error("--vary: the grid has " + std::to_string(distances.size() * tilts.size()) +
                      " points, more than " + std::to_string(max_sweep_points));

  std::string chart = p.chart.empty() ? asset_dir() + "/charts/slanted_edge.png" : p.chart;
  chart = std::filesystem::absolute(chart).lexically_normal().string();

  // Every point's layout is checked before the first one is measured; one that is no layout
  // keeps its reason.
  sweep_result r;
  std::vector<scene> scenes;
  for (double tilt : tilts) {
    for (double d : distances) {
      sweep_point& pt = r.points.emplace_back();
      pt.floating_distance_mm = d;
      pt.tilt_deg = tilt;
      const std::string label = point_label(d, tilt);
      scene s = base;
      try {
        airr::set_floating_distance(s, d);
        s.sheet().pose.pitch_deg = tilt;
        if (!p.psf_route) s = with_edge_chart(s, chart);
        check_scene(s, label);
      } catch (const airr_error& e) {
        mark_invalid(pt, reason_of(e, label));
      }
      scenes.push_back(std::move(s));
    }
  }

  check_some_point_valid(r);  // before anything is measured, when the checks already tell
  check_sweep_memory(r, scenes, p);
  r.mm_per_pixel = make_camera(base).mm_per_pixel;
  const double n = double(scenes.size());
  std::unique_ptr<render_session> session;
  if (share) {
    // Each point as a shared item (an MPI job's ranks): its numbers travel, the edge route's
    // render on a session of its own.
    const std::size_t width = 5 + base.retroreflectors.size();
    std::mutex mutex;
    int done = 0;
    // A point that is no layout travels as a count of -1 sheets: its reason is found again where
    // it is read (a point's measurement is the same on every process).
    const std::vector<double> values = share(scenes.size(), width, [&](std::size_t i, double* o) {
      sweep_point pt = r.points[i];
      if (pt.valid()) {
        std::unique_ptr<render_session> own;
        measure_point(scenes[i], p, pt, own, {});
        if (own) own->stop();
      }
      o[0] = pt.mean_mtf;
      o[1] = pt.mtf50_lp_per_mm.value_or(std::numeric_limits<double>::quiet_NaN());
      o[2] = pt.r50_mm;
      o[3] = pt.brightness;
      o[4] = pt.valid() ? double(std::min(pt.sheet_brightness.size(), width - 5)) : -1.0;
      for (std::size_t k = 0; k < pt.sheet_brightness.size() && k < width - 5; ++k) o[5 + k] = pt.sheet_brightness[k];
      std::lock_guard lock(mutex);
      if (progress) progress(double(++done) / n, detail_of(pt));
    });
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const double* v = values.data() + i * width;
      sweep_point& pt = r.points[i];
      if (v[4] < 0) {
        if (pt.valid()) {
          std::unique_ptr<render_session> own;
          measure_point(scenes[i], p, pt, own, {});
          if (own) own->stop();
        }
        continue;
      }
      pt.mean_mtf = v[0];
      if (!std::isnan(v[1])) pt.mtf50_lp_per_mm = v[1];
      pt.r50_mm = v[2];
      pt.brightness = v[3];
      pt.sheet_brightness.assign(v + 5, v + 5 + std::size_t(v[4]));
    }
  } else if (p.psf_route) {
    // Points in parallel, a batch at a time so that progress is reported between batches; each
    // point's result depends on its layout and seed alone.
    const std::size_t batch = 8;
    for (std::size_t first = 0; first < scenes.size(); first += batch) {
      const std::size_t last = std::min(scenes.size(), first + batch);
      if (progress) progress(double(first) / n, detail_of(r.points[first]));
      tbb::parallel_for(first, last, [&](std::size_t i) {
        if (r.points[i].valid()) measure_point(scenes[i], p, r.points[i], session, {});
      });
    }
  } else {
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      sweep_point& pt = r.points[i];
      const std::string detail = detail_of(pt);
      if (progress) progress(double(i) / n, detail);
      if (!pt.valid()) continue;
      measure_point(scenes[i], p, pt, session, [&](std::uint64_t spp) {
        if (progress)
          progress((double(i) + double(spp) / double(p.spp)) / n, detail + ", " + std::to_string(spp) + " spp");
      });
    }
  }
  if (session) session->stop();
  if (progress) progress(1.0, std::to_string(scenes.size()) + " points");

  check_some_point_valid(r);
  if (distances.size() > 1) {
    // Each tilt's slope over its valid points (two at least).
    for (std::size_t t = 0; t < tilts.size(); ++t) {
      std::vector<double> x, y;
      for (std::size_t k = 0; k < distances.size(); ++k) {
        const sweep_point& pt = r.points[t * distances.size() + k];
        if (!pt.valid()) continue;
        x.push_back(distances[k]);
        y.push_back(pt.mean_mtf);
      }
      if (x.size() >= 2) r.slopes.push_back({tilts[t], analysis::least_squares_slope(x, y)});
    }
  }
  return r;
}

std::string sweep_csv(const sweep_result& r) {
  std::size_t sheets = 0;
  bool reasons = false;
  for (const auto& pt : r.points) {
    sheets = std::max(sheets, pt.sheet_brightness.size());
    reasons |= !pt.valid();
  }
  std::string out = "floating_distance_mm,tilt_deg,mean_mtf_0_1,mtf50_lp_per_mm,r50_mm,brightness";
  for (std::size_t i = 0; i < sheets; ++i) out += ",brightness_sheet_" + std::to_string(i);
  out += reasons ? ",reason\n" : "\n";
  for (const auto& pt : r.points) {
    out += number(pt.floating_distance_mm) + "," + number(pt.tilt_deg);
    if (pt.valid()) {
      out += "," + number(pt.mean_mtf) + "," + (pt.mtf50_lp_per_mm ? number(*pt.mtf50_lp_per_mm) : "") + "," +
             number(pt.r50_mm) + "," + number(pt.brightness);
      for (std::size_t i = 0; i < sheets; ++i) out += "," + number(pt.sheet_brightness.at(i));
      out += reasons ? ",\n" : "\n";
    } else {
      out += std::string(4 + sheets, ',') + "," + csv_quoted(pt.reason) + "\n";
    }
  }
  return out;
}

}  // namespace airr
