#pragma once
// The small geometry every layer shares: angle conversions, reflection, mirror images, orthonormal
// bases, part frames with their local coordinates, and ray-rectangle hits.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <glm/glm.hpp>

namespace airr {

inline constexpr double pi = std::numbers::pi;
inline constexpr double radians(double degrees) { return degrees * (pi / 180.0); }
inline constexpr double degrees(double radians) { return radians * (180.0 / pi); }

// Direction d mirrored about a plane with unit normal n (either side of it).
inline glm::dvec3 reflect(const glm::dvec3& d, const glm::dvec3& n) { return d - 2.0 * glm::dot(d, n) * n; }

// Point p mirrored in the plane through c with unit normal n.
inline glm::dvec3 mirror_point(const glm::dvec3& p, const glm::dvec3& c, const glm::dvec3& n) {
  return p - 2.0 * glm::dot(p - c, n) * n;
}

// Angle in degrees between unit w and the +z axis of its frame (an incidence angle).
inline double polar_angle_deg(const glm::dvec3& w) { return degrees(std::acos(std::clamp(w.z, -1.0, 1.0))); }

// A direction about +z with density cos(theta) / pi (a Lambertian surface's), from u in [0, 1)^2.
inline glm::dvec3 cosine_hemisphere(const glm::dvec2& u) {
  const double s = std::sqrt(u.x);
  const double phi = 2 * pi * u.y;
  return {s * std::cos(phi), s * std::sin(phi), std::sqrt(std::max(0.0, 1 - u.x))};
}

// A point uniformly distributed over the unit disc, from u in [0, 1)^2.
inline glm::dvec2 uniform_disc(const glm::dvec2& u) {
  const double r = std::sqrt(u.x);
  const double phi = 2 * pi * u.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}

// An orthonormal basis (t, b, n) around a unit vector n, continuous except at n.z = -1
// (Duff et al., "Building an orthonormal basis, revisited").
struct basis {
  glm::dvec3 t, b, n;
  glm::dvec3 to_local(const glm::dvec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::dvec3 to_world(const glm::dvec3& v) const { return v.x * t + v.y * b + v.z * n; }
};
inline basis make_basis(const glm::dvec3& n) {
  const double s = std::copysign(1.0, n.z);
  const double a = -1.0 / (s + n.z);
  const double c = n.x * n.y * a;
  return {{1 + s * n.x * n.x * a, s * c, -s * n.x}, {c, s + n.y * n.y * a, -n.y}, n};
}

// A rectangular part: centre, in-plane unit axes u and v, unit normal n = u x v, full sizes (mm).
struct part_frame {
  glm::dvec3 center{0};
  glm::dvec3 u{1, 0, 0};
  glm::dvec3 v{0, 1, 0};
  glm::dvec3 n{0, 0, 1};
  double width = 1;
  double height = 1;
};

// Maps the unit panel (local x, y in [-0.5, 0.5], normal +z) onto the part.
glm::dmat4 part_transform(const part_frame& f);

// A world direction in the part's frame (x along u, y along v, z along n), and back.
inline glm::dvec3 to_local(const part_frame& f, const glm::dvec3& w) {
  return {glm::dot(w, f.u), glm::dot(w, f.v), glm::dot(w, f.n)};
}
inline glm::dvec3 to_world(const part_frame& f, const glm::dvec3& l) { return l.x * f.u + l.y * f.v + l.z * f.n; }

// In-plane coordinates (mm from the centre along u and v) of a world point.
inline glm::dvec2 part_local(const part_frame& f, const glm::dvec3& p) {
  const glm::dvec3 d = p - f.center;
  return {glm::dot(d, f.u), glm::dot(d, f.v)};
}

// The world point at in-plane coordinates (mm from the centre along u and v).
inline glm::dvec3 part_point(const part_frame& f, double x, double y) { return f.center + x * f.u + y * f.v; }

// Whether in-plane coordinates lie on the rectangle (edges included), or within `margin` (mm along
// x and y) of it.
inline bool inside_part(const part_frame& f, const glm::dvec2& l, const glm::dvec2& margin = glm::dvec2(0.0)) {
  return std::abs(l.x) <= 0.5 * f.width + margin.x && std::abs(l.y) <= 0.5 * f.height + margin.y;
}

// Where the ray o + t d (t > 1e-9) meets the part's plane; with `bounded`, only on the rectangle.
inline std::optional<glm::dvec3> hit_part(const part_frame& f, const glm::dvec3& o, const glm::dvec3& d,
                                          bool bounded = true) {
  const double denom = glm::dot(d, f.n);
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = glm::dot(f.center - o, f.n) / denom;
  if (t <= 1e-9) return std::nullopt;
  const glm::dvec3 p = o + t * d;
  if (bounded && !inside_part(f, part_local(f, p))) return std::nullopt;
  return p;
}

}  // namespace airr
