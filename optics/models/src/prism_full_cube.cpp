#include <array>
#include <cmath>
#include <limits>

#include "airr/core/geometry.hpp"
#include "prism_structure.hpp"

namespace airr {

namespace {

constexpr int max_steps = 100000;  // cells crossed by one straight stretch

// The cube axes, 120 deg apart about the sheet normal, each at acos(1 / sqrt 3) from it.
std::array<glm::dvec3, 3> cube_axes(const prism_sheet_geometry& g) {
  std::array<glm::dvec3, 3> a;
  const double across = std::sqrt(2.0 / 3), up = 1 / std::sqrt(3.0);
  for (int k = 0; k < 3; ++k) {
    const double phi = radians(g.azimuth_deg + 90 + 120.0 * k);
    a[std::size_t(k)] = {across * std::cos(phi), across * std::sin(phi), up};
  }
  return a;
}

// An apex: the lattice point of index sum 0 below the origin.
glm::dvec3 apex_origin(const prism_sheet_geometry& g) { return {0, 0, -g.plate_mm - g.depth_mm()}; }

}  // namespace

stretch_end follow_full_cubes(const prism_sheet_geometry& g, const glm::dvec3& p, const glm::dvec3& d, bool in_plate) {
  const double edge = g.cube_edge_mm();
  const auto a = cube_axes(g);
  const glm::dvec3 rel = p - apex_origin(g);
  std::array<double, 3> c{}, dc{}, cell{};
  double c_sum = 0, dc_sum = 0;
  int sum = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    c[k] = glm::dot(rel, a[k]) / edge;
    dc[k] = glm::dot(d, a[k]) / edge;
    // On a cell boundary (after a face), the cell the ray goes into.
    const double nearest = std::round(c[k]);
    cell[k] = std::abs(c[k] - nearest) < 1e-9 ? (dc[k] < 0 ? nearest - 1 : nearest) : std::floor(c[k]);
    c_sum += c[k];
    dc_sum += dc[k];
    sum += int(cell[k]);
  }
  // The slab's ends: the ridges (sum 2) for glass going up, the apexes (sum 0) for air going down.
  const double inf = std::numeric_limits<double>::infinity();
  double t_leave = inf;
  if (in_plate && dc_sum > 0) t_leave = (2 - c_sum) / dc_sum;
  if (!in_plate && dc_sum < 0) t_leave = (0 - c_sum) / dc_sum;
  for (int step = 0; step < max_steps; ++step) {
    std::size_t k = 0;
    double t = inf;
    for (std::size_t j = 0; j < 3; ++j) {
      if (dc[j] == 0) continue;
      const double boundary = dc[j] > 0 ? cell[j] + 1 : cell[j];
      const double tj = (boundary - c[j]) / dc[j];
      if (tj < t) t = tj, k = j;
    }
    if (t_leave <= t) return {p + t_leave * d, std::nullopt};
    const int dir = dc[k] > 0 ? 1 : -1;
    const int next = sum + dir;
    // Glass into air or air into glass: a face of the cube whose axis k was crossed.
    if (in_plate && next < 0) return {p + t * d, -double(dir) * a[k]};
    if (!in_plate && next >= 0) return {p + t * d, double(dir) * a[k]};
    cell[k] += dir;
    sum = next;
  }
  return {p, std::nullopt};  // left to the event limit
}

polygon2 full_cube_hexagon(const prism_sheet_geometry& g, const glm::dvec3& d) {
  const double edge = g.cube_edge_mm();
  const auto a = cube_axes(g);
  polygon2 points;
  auto project = [&](const glm::dvec3& v) { points.push_back(glm::dvec2(v) - (v.z / d.z) * glm::dvec2(d)); };
  for (std::size_t k = 0; k < 3; ++k) {
    project(edge * a[k]);
    project(edge * (a[k] + a[(k + 1) % 3]));
  }
  return convex_hull(points);
}

corner_view full_cube_corner_view(const prism_sheet_geometry& g, const glm::dvec3& d) {
  const auto a = cube_axes(g);
  corner_view v;
  for (std::size_t k = 0; k < 3; ++k) {
    const glm::dvec3 end = g.cube_edge_mm() * a[k];
    v.edge_ends[k] = glm::dvec2(end) - (end.z / d.z) * glm::dvec2(d);
  }
  return v;
}

polygon2 full_cube_effective_aperture(const prism_sheet_geometry& g, const glm::dvec3& d) {
  for (const glm::dvec3& axis : cube_axes(g))
    if (glm::dot(d, axis) >= 0) return {};
  const polygon2 hexagon = full_cube_hexagon(g, d);
  polygon2 image;
  image.reserve(hexagon.size());
  for (const glm::dvec2& v : hexagon) image.push_back(-v);
  return clip_convex_polygon(image, hexagon);
}

glm::dvec2 full_cube_cell_point(const prism_sheet_geometry& g, const glm::dvec2& u) {
  const auto a = cube_axes(g);
  const double edge = g.cube_edge_mm();
  const glm::dvec2 b1 = edge * glm::dvec2(a[0] - a[1]), b2 = edge * glm::dvec2(a[1] - a[2]);
  return u.x * b1 + u.y * b2;
}

}  // namespace airr
