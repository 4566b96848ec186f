#include "airr/layout/viewing_zone.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "airr/core/cancel.hpp"
#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

viewing_parts::viewing_parts(const scene& s, prop_hit_function prop_hits)
    : half_mirror(half_mirror_frame(s)),
      display(source_frame(s)),
      panel(source_panel_frame(s)),
      aerial(aerial_image_frame(s)),
      props(std::move(prop_hits)) {
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) sheets.push_back(retroreflector_frame(s, i));
  const bool any_visible = std::any_of(s.props.begin(), s.props.end(), [](const prop_params& p) { return p.visible; });
  if (any_visible && !props) throw std::invalid_argument("viewing_parts: the scene has props but no prop_hit_function");
}

namespace {

// Parameter t of the ray o + t d on the part's rectangle; infinity when it misses.
double hit_distance(const part_frame& f, const glm::dvec3& o, const glm::dvec3& d) {
  const double denom = glm::dot(d, f.n);
  if (std::abs(denom) < 1e-15) return std::numeric_limits<double>::infinity();
  const double t = glm::dot(f.center - o, f.n) / denom;
  if (!(t > 1e-6) || !inside_part(f, part_local(f, o + t * d))) return std::numeric_limits<double>::infinity();
  return t;
}

// The first opaque part (the display's panel: -1; sheet i: i; a prop: -3) along the ray before `t_max`.
struct first_hit {
  int part = -2;  // -2: none
  double t = std::numeric_limits<double>::infinity();
};
first_hit first_opaque(const viewing_parts& parts, const glm::dvec3& o, const glm::dvec3& d, double t_max) {
  first_hit h;
  const double tp = hit_distance(parts.panel, o, d);
  if (tp < t_max) h = {-1, tp};
  for (std::size_t i = 0; i < parts.sheets.size(); ++i) {
    const double t = hit_distance(parts.sheets[i], o, d);
    if (t < std::min(h.t, t_max)) h = {int(i), t};
  }
  if (parts.props) {
    const double t = parts.props(o, d, std::min(h.t, t_max));
    if (t < std::min(h.t, t_max)) h = {-3, t};
  }
  return h;
}

}  // namespace

bool aerial_point_visible(const viewing_parts& parts, const glm::dvec3& eye, const glm::dvec3& p) {
  const glm::dvec3 to_p = p - eye;
  const double t_p = glm::length(to_p);
  if (!(t_p > 0)) return false;
  const glm::dvec3 d = to_p / t_p;
  const double t_h = hit_distance(parts.half_mirror, eye, d);
  if (!(t_h > t_p) || std::isinf(t_h)) return false;  // the light comes from the half mirror through p
  if (first_opaque(parts, eye, d, t_h).part != -2) return false;
  const glm::dvec3 h = eye + t_h * d;
  const glm::dvec3 mirrored = reflect(d, parts.half_mirror.n);
  // Transmitted to a sheet and mirrored back to the display, or the other way round.
  for (const auto& [out, back] : {std::pair{d, reflect(-d, parts.half_mirror.n)}, std::pair{mirrored, -d}}) {
    const first_hit sheet = first_opaque(parts, h, out, std::numeric_limits<double>::infinity());
    if (sheet.part < 0 || glm::dot(out, parts.sheets[std::size_t(sheet.part)].n) >= 0) continue;
    const first_hit display = first_opaque(parts, h, back, std::numeric_limits<double>::infinity());
    if (display.part != -1 || glm::dot(back, parts.display.n) >= 0) continue;
    if (inside_part(parts.display, part_local(parts.display, h + display.t * back))) return true;
  }
  return false;
}

namespace {

// The visible length of the aerial image's row at height y: points stepped from edge to edge
// (nudged inside), each step counted whole or cut where visibility changes (found by bisection).
double visible_width(const viewing_parts& parts, const glm::dvec3& eye, double y) {
  const part_frame& a = parts.aerial;
  const int steps = 64;
  const double w = a.width;
  auto visible_at = [&](double x) { return aerial_point_visible(parts, eye, part_point(a, x, y)); };
  auto x_at = [&](int k) { return std::clamp((double(k) / steps - 0.5) * w, -0.5 * w + 1e-9, 0.5 * w - 1e-9); };
  double total = 0;
  bool prev = visible_at(x_at(0));
  for (int k = 1; k <= steps; ++k) {
    const double x0 = x_at(k - 1), x1 = x_at(k);
    const bool cur = visible_at(x1);
    if (prev && cur) {
      total += x1 - x0;
    } else if (prev != cur) {
      double lo = x0, hi = x1;  // visibility at lo is prev's
      while (hi - lo > 1e-6 * w) {
        const double mid = 0.5 * (lo + hi);
        (visible_at(mid) == prev ? lo : hi) = mid;
      }
      total += prev ? lo - x0 : x1 - hi;
    }
    prev = cur;
  }
  return total;
}

// The visible area between rows y0 and y1 of widths w0 and w1. The maps between flat parts are
// projective, so the width is linear in y between the visible region's corners: a slab whose middle
// row is on the line is a trapezoid; one with a corner inside is halved until it is, or thin.
double slab_area(const viewing_parts& parts, const glm::dvec3& eye, double y0, double y1, double w0, double w1,
                 int depth) {
  const double ym = 0.5 * (y0 + y1);
  const double wm = visible_width(parts, eye, ym);
  if (depth == 0 || std::abs(wm - 0.5 * (w0 + w1)) <= 1e-5 * parts.aerial.width) {
    return 0.25 * (y1 - y0) * (w0 + 2 * wm + w1);
  }
  return slab_area(parts, eye, y0, ym, w0, wm, depth - 1) + slab_area(parts, eye, ym, y1, wm, w1, depth - 1);
}

}  // namespace

double visible_fraction(const viewing_parts& parts, const glm::dvec3& eye, int rows, bool refine) {
  const part_frame& a = parts.aerial;
  double total = 0;
  if (!refine) {
    for (int j = 0; j < rows; ++j) total += visible_width(parts, eye, ((j + 0.5) / rows - 0.5) * a.height);
    return total / (rows * a.width);
  }
  auto y_at = [&](int j) {
    return std::clamp((double(j) / rows - 0.5) * a.height, -0.5 * a.height + 1e-9, 0.5 * a.height - 1e-9);
  };
  double w0 = visible_width(parts, eye, y_at(0));
  for (int j = 0; j < rows; ++j) {
    const double w1 = visible_width(parts, eye, y_at(j + 1));
    total += slab_area(parts, eye, y_at(j), y_at(j + 1), w0, w1, 12);
    w0 = w1;
  }
  return total / (a.height * a.width);
}

glm::dvec3 eye_position(const scene& s, const eye_grid& g, double x, double y) {
  if (g.kind == eye_grid::shape::plane) return aerial_image_center(s) + glm::dvec3(x, y, g.distance_mm);
  scene orbit = s;
  orbit.observer.placement = observer_placement::orbit;
  orbit.observer.azimuth_deg = x;
  orbit.observer.elevation_deg = y;
  orbit.observer.distance_mm = g.distance_mm;
  return observer_position(orbit);
}

glm::dvec2 eye_grid_coordinates(const scene& s, const eye_grid& g, const glm::dvec3& eye) {
  const glm::dvec3 r = eye - aerial_image_center(s);
  if (g.kind == eye_grid::shape::plane) return {r.x, r.y};
  const double len = glm::length(r);
  if (!(len > 0)) return {0, 0};
  return {degrees(std::atan2(r.x, r.z)), degrees(std::asin(std::clamp(r.y / len, -1.0, 1.0)))};
}

void place_observer(scene& s, const eye_grid& g, double x, double y) {
  if (g.kind == eye_grid::shape::sphere) {
    s.observer.placement = observer_placement::orbit;
    s.observer.azimuth_deg = x;
    s.observer.elevation_deg = y;
    s.observer.distance_mm = g.distance_mm;
    return;
  }
  const glm::dvec3 eye = eye_position(s, g, x, y), target = aerial_image_center(s);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {eye.x, eye.y, eye.z};
  s.observer.look_at_mm = {target.x, target.y, target.z};
}

void check_eye_grid(const eye_grid& g) {
  auto fail = [](const std::string& what) { throw input_error("viewing zone: " + what); };
  if (g.nx < 1 || g.nx > 1001 || g.ny < 1 || g.ny > 1001) fail("grid size must be 1 to 1001 per side");
  for (double v : {g.x_min, g.x_max, g.y_min, g.y_max}) {
    if (!std::isfinite(v)) fail("grid bounds must be finite");
  }
  if (!(g.x_min <= g.x_max) || !(g.y_min <= g.y_max)) fail("grid bounds must be given low to high");
  if (!(g.distance_mm > 0) || !std::isfinite(g.distance_mm)) fail("distance must be a positive number of mm");
  if (g.kind == eye_grid::shape::sphere && (g.y_min < -89 || g.y_max > 89)) {
    fail("elevations must stay within -89 to 89 degrees");
  }
}

eye_grid requested_eye_grid(bool sphere, double distance_mm, int per_side, const std::vector<double>& x,
                            const std::vector<double>& y) {
  if (!(x.empty() || x.size() == 2) || !(y.empty() || y.size() == 2))
    throw input_error("viewing zone: x and y are (first, last)");
  eye_grid g;
  g.kind = sphere ? eye_grid::shape::sphere : eye_grid::shape::plane;
  g.distance_mm = distance_mm;
  g.nx = g.ny = per_side;
  const double reach = sphere ? 60 : 200;
  g.x_min = x.empty() ? -reach : x[0];
  g.x_max = x.empty() ? reach : x[1];
  g.y_min = y.empty() ? -reach : y[0];
  g.y_max = y.empty() ? reach : y[1];
  check_eye_grid(g);
  return g;
}

viewing_zone_map geometric_viewing_zone(const scene& s, const eye_grid& g, const prop_hit_function& prop_hits,
                                        int rows_per_eye, const std::function<void(int, int)>& progress,
                                        const std::atomic<bool>* cancel, bool refine) {
  check_eye_grid(g);
  if (rows_per_eye < 1 || rows_per_eye > 100000) throw input_error("viewing zone: rows per eye must be 1 to 100000");
  const auto t0 = std::chrono::steady_clock::now();
  viewing_zone_map map;
  map.grid = g;
  map.visible.assign(std::size_t(g.nx) * g.ny, 0.0);
  if (s.retroreflectors.empty()) return map;
  const viewing_parts parts(s, prop_hits);
  std::atomic<int> done{0};
  std::mutex report;
  tbb::parallel_for(0, g.ny, [&](int j) {
    if (cancel_requested(cancel)) return;
    for (int i = 0; i < g.nx; ++i) {
      map.visible[std::size_t(j) * g.nx + i] =
          visible_fraction(parts, eye_position(s, g, g.x_at(i), g.y_at(j)), rows_per_eye, refine);
    }
    const int n = ++done;
    if (progress) {
      const std::lock_guard lock(report);
      progress(n, g.ny);
    }
  });
  if (cancel_requested(cancel)) map.visible.clear();
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return map;
}

}  // namespace airr
