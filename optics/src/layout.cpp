#include "airr/optics/layout.hpp"

#include <cmath>

#include "airr/optics/error.hpp"

namespace airr {

glm::dmat4 part_transform(const part_frame& f) {
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(f.u * f.width, 0);
  m[1] = glm::dvec4(f.v * f.height, 0);
  m[2] = glm::dvec4(f.n, 0);
  m[3] = glm::dvec4(f.center, 1);
  return m;
}

part_frame source_frame(const scene& s) {
  part_frame f;
  const auto& o = s.source.offset_mm;
  f.center = glm::dvec3(o[0], -s.floating_distance_mm + o[1], o[2]);
  f.n = {0, 1, 0};
  f.u = {1, 0, 0};
  f.v = glm::cross(f.n, f.u);  // (0, 0, -1): the image's top lies towards -z
  f.width = s.source.width_mm;
  f.height = s.source.height_mm;
  return f;
}

part_frame half_mirror_frame(const scene& s) {
  part_frame f;
  f.n = glm::normalize(glm::dvec3(0, 1, 1));
  f.u = {1, 0, 0};
  f.v = glm::cross(f.n, f.u);
  f.width = s.half_mirror.width_mm;
  f.height = s.half_mirror.height_mm;
  return f;
}

part_frame retroreflector_frame(const scene& s) {
  const double t = radians(s.retroreflector.tilt_deg);
  part_frame f;
  f.center = {0, 0, -s.retroreflector.distance_mm};
  f.n = {0, std::sin(t), std::cos(t)};
  f.u = {1, 0, 0};
  f.v = glm::cross(f.n, f.u);
  f.width = s.retroreflector.width_mm;
  f.height = s.retroreflector.height_mm;
  return f;
}

glm::dvec3 aerial_image_center(const scene& s) {
  const part_frame hm = half_mirror_frame(s);
  return mirror_point(source_frame(s).center, hm.center, hm.n);
}

// ---------------------------------------------------------------- intersection

static glm::dvec3 corner(const part_frame& f, double su, double sv) {
  return part_point(f, su * 0.5 * f.width, sv * 0.5 * f.height);
}

// Whether segment p-q meets the rectangle f.
static bool segment_hits(const part_frame& f, const glm::dvec3& p, const glm::dvec3& q) {
  const double dp = glm::dot(p - f.center, f.n);
  const double dq = glm::dot(q - f.center, f.n);
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0)) return false;
  if (dp == dq) return false;  // parallel in the plane: caught by the other part's edges
  const glm::dvec3 x = p + (q - p) * (dp / (dp - dq));
  return inside_part(f, part_local(f, x));
}

static bool edges_hit(const part_frame& a, const part_frame& b) {
  const glm::dvec3 c[4] = {corner(a, -1, -1), corner(a, 1, -1), corner(a, 1, 1), corner(a, -1, 1)};
  for (int i = 0; i < 4; ++i) {
    if (segment_hits(b, c[i], c[(i + 1) % 4])) return true;
  }
  return false;
}

bool parts_intersect(const part_frame& a, const part_frame& b) { return edges_hit(a, b) || edges_hit(b, a); }

void check_layout(const scene& s, const std::string& origin) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s), rr = retroreflector_frame(s);
  auto fail = [&](const char* what) { throw input_error(origin + ": layout: " + std::string(what) + " intersect"); };
  if (parts_intersect(src, hm)) fail("source and half mirror");
  if (parts_intersect(rr, hm)) fail("retroreflector and half mirror");
  if (parts_intersect(src, rr)) fail("source and retroreflector");
  const glm::dvec3 cam = make_camera(s).position;
  if (glm::dot(cam - hm.center, hm.n) <= 0) {
    throw input_error(origin + ": layout: camera must be in front of the half mirror");
  }
}

// ---------------------------------------------------------------- camera

pinhole_camera make_camera(const scene& s) {
  pinhole_camera c;
  // Framed on the canonical aerial-image centre, so a source offset shows as a moved image.
  const glm::dvec3 target(0, 0, s.floating_distance_mm);
  c.position = target + glm::dvec3(0, 0, s.camera.distance_mm);
  c.tan_half_fov = std::tan(radians(0.5 * s.camera.fov_deg));
  c.width = s.camera.width;
  c.height = s.camera.height;
  c.mm_per_pixel = 2.0 * s.camera.distance_mm * c.tan_half_fov / c.height;
  return c;
}

glm::dvec3 camera_direction(const pinhole_camera& c, double px, double py) {
  const double half_h = c.tan_half_fov;
  const double x = (2.0 * px / c.height - double(c.width) / c.height) * half_h;
  const double y = (1.0 - 2.0 * py / c.height) * half_h;
  return glm::normalize(c.forward + x * c.right + y * c.up);
}

glm::dvec2 camera_project(const pinhole_camera& c, const glm::dvec3& p) {
  const glm::dvec3 d = p - c.position;
  const double depth = glm::dot(d, c.forward);
  const double x = glm::dot(d, c.right) / depth / c.tan_half_fov;  // in units of half height
  const double y = glm::dot(d, c.up) / depth / c.tan_half_fov;
  return {(x + double(c.width) / c.height) * 0.5 * c.height, (1.0 - y) * 0.5 * c.height};
}

}  // namespace airr
