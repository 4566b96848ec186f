#include "airr/layout/layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "airr/core/error.hpp"

namespace airr {

glm::dmat4 part_transform(const part_frame& f) {
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(f.u * f.width, 0);
  m[1] = glm::dvec4(f.v * f.height, 0);
  m[2] = glm::dvec4(f.n, 0);
  m[3] = glm::dvec4(f.center, 1);
  return m;
}

// ---------------------------------------------------------------- poses

// Sine and cosine of an angle in degrees, exact at multiples of 90 (so that the canonical layout's
// axes are exactly the world's).
static glm::dvec2 sin_cos_deg(double deg) {
  const double quarter = deg / 90.0;
  if (quarter == std::round(quarter)) {
    static constexpr double s[4] = {0, 1, 0, -1}, c[4] = {1, 0, -1, 0};
    const int k = int(((long long)quarter % 4 + 4) % 4);
    return {s[k], c[k]};
  }
  const double r = radians(deg);
  return {std::sin(r), std::cos(r)};
}

glm::dmat3 pose_rotation(const pose& p) {
  const glm::dvec2 y = sin_cos_deg(p.yaw_deg), x = sin_cos_deg(-p.pitch_deg), z = sin_cos_deg(p.roll_deg);
  // glm matrices are column-major: each glm::dvec3 below is a column.
  const glm::dmat3 ry(glm::dvec3(y[1], 0, -y[0]), glm::dvec3(0, 1, 0), glm::dvec3(y[0], 0, y[1]));
  const glm::dmat3 rx(glm::dvec3(1, 0, 0), glm::dvec3(0, x[1], x[0]), glm::dvec3(0, -x[0], x[1]));
  const glm::dmat3 rz(glm::dvec3(z[1], z[0], 0), glm::dvec3(-z[0], z[1], 0), glm::dvec3(0, 0, 1));
  return ry * rx * rz;
}

pose pose_from_rotation(const glm::dmat3& r, const glm::dvec3& center) {
  const glm::dvec3 n = r[2];
  pose p;
  p.center_mm = {center.x, center.y, center.z};
  p.pitch_deg = degrees(std::asin(std::clamp(n.y, -1.0, 1.0)));
  p.yaw_deg = std::hypot(n.x, n.z) > 1e-12 ? degrees(std::atan2(n.x, n.z)) : 0.0;
  // What is left after yaw and pitch is the roll about the normal.
  const glm::dvec3 u = glm::transpose(pose_rotation(p)) * r[0];
  p.roll_deg = degrees(std::atan2(u.y, u.x));
  return p;
}

glm::dmat4 prop_transform(const prop_params& p) {
  const glm::dmat3 r = pose_rotation(p.pose) * p.scale;
  glm::dmat4 m(r);
  m[3] = glm::dvec4(p.pose.center_mm[0], p.pose.center_mm[1], p.pose.center_mm[2], 1.0);
  return m;
}

part_frame pose_frame(const pose& p, double width_mm, double height_mm) {
  const glm::dmat3 r = pose_rotation(p);
  part_frame f;
  f.center = {p.center_mm[0], p.center_mm[1], p.center_mm[2]};
  f.u = r[0];
  f.v = r[1];
  f.n = r[2];
  f.width = width_mm;
  f.height = height_mm;
  return f;
}

std::shared_ptr<const emission_profile> scene_emission_profile(const scene& s) {
  if (s.source.emission_profile.empty()) return nullptr;
  return load_emission_profile(resolve_scene_path(s, s.source.emission_profile));
}

double emission_at(const emission_profile* profile, const part_frame& display, const glm::dvec3& towards_display) {
  if (!profile) return 1.0;
  return profile->at(degrees(std::acos(std::clamp(-glm::dot(towards_display, display.n), -1.0, 1.0))));
}

glm::dvec3 sun_direction(const sun_params& s) {
  const glm::dvec2 az = sin_cos_deg(s.azimuth_deg), el = sin_cos_deg(s.elevation_deg);
  return {az[0] * el[1], el[0], az[1] * el[1]};
}

part_frame luminaire_frame(const luminaire_params& l) {
  return pose_frame(l.pose, l.width_mm, l.shape == luminaire_shape::disc ? l.width_mm : l.height_mm);
}

std::vector<glm::dvec3> luminaire_outline(const luminaire_params& l, int sides) {
  const part_frame f = luminaire_frame(l);
  if (l.shape == luminaire_shape::rectangle) {
    const auto k = corners(f);
    return {k.begin(), k.end()};
  }
  std::vector<glm::dvec3> out;
  for (int j = 0; j < sides; ++j) {
    const double a = 2 * pi * j / sides;
    out.push_back(f.center + f.width / 2 * (std::cos(a) * f.u + std::sin(a) * f.v));
  }
  return out;
}

part_frame source_frame(const scene& s) { return pose_frame(s.source.pose, s.source.width_mm, s.source.height_mm); }

part_frame source_panel_frame(const scene& s) {
  const double b = 2 * s.source.bezel_mm;
  return pose_frame(s.source.pose, s.source.width_mm + b, s.source.height_mm + b);
}

part_frame half_mirror_frame(const scene& s) {
  return pose_frame(s.half_mirror.pose, s.half_mirror.width_mm, s.half_mirror.height_mm);
}

part_frame retroreflector_frame(const scene& s, std::size_t sheet) {
  const retroreflector_params& r = s.retroreflectors.at(sheet);
  return pose_frame(r.pose, r.width_mm, r.height_mm);
}

part_frame aerial_image_frame(const scene& s) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s);
  part_frame f = src;
  f.center = mirror_point(src.center, hm.center, hm.n);
  f.u = reflect(src.u, hm.n);
  f.v = reflect(src.v, hm.n);
  f.n = glm::cross(f.u, f.v);  // the side the converged light leaves towards
  return f;
}

glm::dvec3 aerial_image_center(const scene& s) { return aerial_image_frame(s).center; }

pose mirrored_in_half_mirror(const scene& s, const part_frame& f) {
  const part_frame hm = half_mirror_frame(s);
  const glm::dvec3 n = reflect(f.n, hm.n), v = reflect(f.v, hm.n);
  return pose_from_rotation(glm::dmat3(glm::cross(v, n), v, n), mirror_point(f.center, hm.center, hm.n));
}

bool sheet_seen_by_reflection(const scene& s, std::size_t sheet) {
  const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s, sheet);
  const glm::dvec3 display = source_frame(s).center;
  return glm::dot(rr.center - hm.center, hm.n) * glm::dot(display - hm.center, hm.n) <= 0;
}

double sheet_chief_incidence_deg(const scene& s, std::size_t sheet) {
  const part_frame rr = retroreflector_frame(s, sheet);
  const glm::dvec3 from = sheet_seen_by_reflection(s, sheet) ? source_frame(s).center : aerial_image_center(s);
  return polar_angle_deg(to_local(rr, glm::normalize(from - rr.center)));
}

double floating_distance(const scene& s) { return glm::length(aerial_image_center(s) - half_mirror_frame(s).center); }

void set_floating_distance(scene& s, double d_mm) {
  if (!(d_mm > 0) || !std::isfinite(d_mm)) {
    throw input_error("floating_distance_mm: must be a positive finite number (is " + std::to_string(d_mm) + ")");
  }
  const glm::dvec3 c = half_mirror_frame(s).center;
  const glm::dvec3 src = source_frame(s).center;
  const double now = glm::length(src - c);  // the mirror keeps distances from its centre
  if (now < 1e-9) throw input_error("floating_distance_mm: the display is centred on the half mirror's centre");
  const glm::dvec3 moved = c + (src - c) * (d_mm / now);
  s.source.pose.center_mm = {moved.x, moved.y, moved.z};
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

// Whether a's corners or centre lie on b, for two rectangles in one plane.
static bool overlaps_in_plane(const part_frame& a, const part_frame& b) {
  if (inside_part(b, part_local(b, a.center))) return true;
  for (double su : {-1.0, 1.0}) {
    for (double sv : {-1.0, 1.0}) {
      if (inside_part(b, part_local(b, corner(a, su, sv)))) return true;
    }
  }
  return false;
}

bool parts_intersect(const part_frame& a, const part_frame& b) {
  const bool coplanar =
      std::abs(std::abs(glm::dot(a.n, b.n)) - 1) < 1e-12 && std::abs(glm::dot(a.center - b.center, b.n)) < 1e-9;
  if (coplanar) return overlaps_in_plane(a, b) || overlaps_in_plane(b, a);
  return edges_hit(a, b) || edges_hit(b, a);
}

// Where a convex polygon crosses the plane through `c` with normal `n`, as the interval of its
// crossing points' positions along `d`; empty (lo > hi) unless it has corners strictly on both
// sides.
template <std::size_t N>
static glm::dvec2 plane_crossing(const std::array<glm::dvec3, N>& poly, const glm::dvec3& c, const glm::dvec3& n,
                                 const glm::dvec3& d) {
  constexpr double eps = 1e-9;  // mm: a corner this close to the plane lies on it
  std::array<double, N> s;
  bool below = false, above = false;
  for (std::size_t i = 0; i < N; ++i) {
    s[i] = glm::dot(poly[i] - c, n);
    below |= s[i] < -eps;
    above |= s[i] > eps;
  }
  glm::dvec2 t(std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity());
  if (!below || !above) return t;
  auto add = [&](const glm::dvec3& p) { t = {std::min(t[0], glm::dot(p, d)), std::max(t[1], glm::dot(p, d))}; };
  for (std::size_t i = 0; i < N; ++i) {
    const std::size_t j = (i + 1) % N;
    if (std::abs(s[i]) <= eps) add(poly[i]);
    if ((s[i] < -eps && s[j] > eps) || (s[i] > eps && s[j] < -eps))
      add(poly[i] + (poly[j] - poly[i]) * (s[i] / (s[i] - s[j])));
  }
  return t;
}

double part_cut_length(const part_frame& f, const std::array<glm::dvec3, 3>& triangle) {
  const glm::dvec3 tn = glm::cross(triangle[1] - triangle[0], triangle[2] - triangle[0]);
  const glm::dvec3 d = glm::cross(f.n, tn);
  if (glm::length(d) < 1e-12 * glm::length(tn) || glm::length(tn) == 0) return 0;  // parallel planes, or no triangle
  const glm::dvec3 dir = glm::normalize(d);
  // Both polygons meet the line where their planes cross in an interval; the cut is their overlap.
  const glm::dvec2 a = plane_crossing(corners(f), triangle[0], glm::normalize(tn), dir);
  const glm::dvec2 b = plane_crossing(triangle, f.center, f.n, dir);
  return std::max(0.0, std::min(a[1], b[1]) - std::max(a[0], b[0]));
}

namespace {
struct named_part {
  std::string field;  // as in the scene file
  std::string name;   // as in a sentence
  part_frame frame;
};
}  // namespace

static std::vector<named_part> layout_parts(const scene& s) {
  std::vector<named_part> parts = {{"source", "the display", source_panel_frame(s)},
                                   {"half_mirror", "the half mirror", half_mirror_frame(s)}};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    const std::string n = std::to_string(i);
    parts.push_back({"retroreflectors[" + n + "]", s.retroreflectors.size() == 1 ? "the retroreflector" : "sheet " + n,
                     retroreflector_frame(s, i)});
  }
  return parts;
}

// Within this distance of a panel's plane (and over it), a point counts as inside the part.
static constexpr double part_thickness_mm = 1.0;

void check_layout(const scene& s, const std::string& origin) {
  const std::vector<named_part> parts = layout_parts(s);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    for (std::size_t j = i + 1; j < parts.size(); ++j) {
      if (parts_intersect(parts[i].frame, parts[j].frame)) {
        throw input_error(origin + ": " + parts[j].field + ": layout: " + parts[i].name + " and " + parts[j].name +
                          " intersect");
      }
    }
  }
  const part_frame hm = half_mirror_frame(s);
  const glm::dvec3 eye = observer_position(s);
  for (const auto& p : parts) {
    if (std::abs(glm::dot(eye - p.frame.center, p.frame.n)) <= part_thickness_mm &&
        inside_part(p.frame, part_local(p.frame, eye))) {
      throw input_error(origin + ": observer: the observer is inside " + p.name);
    }
  }
  const double eye_side = glm::dot(eye - hm.center, hm.n);
  const double image_side = glm::dot(aerial_image_center(s) - hm.center, hm.n);
  if (eye_side * image_side <= 0) {
    throw input_error(origin +
                      ": observer: behind the half mirror (on the display's side), where no aerial image can be seen");
  }
}

// ---------------------------------------------------------------- observer

static glm::dvec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

glm::dvec3 observer_target(const scene& s) {
  return s.observer.placement == observer_placement::orbit ? aerial_image_center(s) : to_vec(s.observer.look_at_mm);
}

glm::dvec3 observer_position(const scene& s) {
  const observer_params& o = s.observer;
  if (o.placement == observer_placement::look_at) return to_vec(o.position_mm);
  const glm::dvec2 az = sin_cos_deg(o.azimuth_deg), el = sin_cos_deg(o.elevation_deg);
  return aerial_image_center(s) + o.distance_mm * glm::dvec3(az[0] * el[1], el[0], az[1] * el[1]);
}

pinhole_camera make_camera(const scene& s) {
  const observer_params& o = s.observer;
  pinhole_camera c;
  c.position = observer_position(s);
  const glm::dvec3 to_target = observer_target(s) - c.position;
  c.target_distance = glm::length(to_target);
  c.forward = to_target / c.target_distance;
  // Level horizon: right stays horizontal; looking straight up or down, +x is right.
  const glm::dvec3 side = glm::cross(c.forward, glm::dvec3(0, 1, 0));
  c.right = glm::length(side) > 1e-9 ? glm::normalize(side) : glm::dvec3(1, 0, 0);
  c.up = glm::cross(c.right, c.forward);
  c.tan_half_fov = std::tan(radians(0.5 * o.fov_deg));
  c.width = o.width;
  c.height = o.height;
  c.mm_per_pixel = 2.0 * c.target_distance * c.tan_half_fov / c.height;
  if (o.lens == observer_lens::thin_lens) {
    c.aperture_mm = o.focal_length_mm / o.f_number;
    c.focus_distance = o.focus_distance_mm.value_or(c.target_distance);
  }
  return c;
}

glm::dvec3 camera_direction(const pinhole_camera& c, double px, double py) {
  const double half_h = c.tan_half_fov;
  const double x = (2.0 * px / c.height - double(c.width) / c.height) * half_h;
  const double y = (1.0 - 2.0 * py / c.height) * half_h;
  return glm::normalize(c.forward + x * c.right + y * c.up);
}

camera_ray make_camera_ray(const pinhole_camera& c, double px, double py, const glm::dvec2& lens) {
  const glm::dvec3 d = camera_direction(c, px, py);
  if (c.aperture_mm <= 0) return {c.position, d};
  // Uniform point on the aperture disc (polar mapping), aimed at d's point on the focus plane.
  const double r = 0.5 * c.aperture_mm * std::sqrt(lens.x), phi = 2 * pi * lens.y;
  const glm::dvec3 origin = c.position + r * std::cos(phi) * c.right + r * std::sin(phi) * c.up;
  const glm::dvec3 focus = c.position + d * (c.focus_distance / glm::dot(d, c.forward));
  return {origin, glm::normalize(focus - origin)};
}

glm::dvec2 camera_project(const pinhole_camera& c, const glm::dvec3& p) {
  const glm::dvec3 d = p - c.position;
  const double depth = glm::dot(d, c.forward);
  const double x = glm::dot(d, c.right) / depth / c.tan_half_fov;  // in units of half height
  const double y = glm::dot(d, c.up) / depth / c.tan_half_fov;
  return {(x + double(c.width) / c.height) * 0.5 * c.height, (1.0 - y) * 0.5 * c.height};
}

void apply_observer_preset(scene& s, observer_preset preset) {
  observer_params& o = s.observer;
  o.lens = observer_lens::thin_lens;
  o.focus_distance_mm.reset();
  if (preset == observer_preset::paper_camera) {
    o.placement = observer_placement::orbit;
    o.azimuth_deg = o.elevation_deg = 0;
    o.distance_mm = 300;
    o.focal_length_mm = 50;
    o.f_number = 4;
  } else {
    o.focal_length_mm = 17;   // the reduced eye's focal length
    o.f_number = 17.0 / 4.0;  // a 4 mm pupil
  }
}

// The field of view that holds every point (in the camera's frame) with 10% to spare.
static double fov_to_hold(const pinhole_camera& c, const std::vector<glm::dvec3>& points) {
  const double aspect = double(c.width) / c.height;
  double t = 0;
  for (const auto& p : points) {
    const glm::dvec3 d = p - c.position;
    const double depth = glm::dot(d, c.forward);
    if (depth <= 1e-6) return 170;
    t = std::max({t, std::abs(glm::dot(d, c.up)) / depth, std::abs(glm::dot(d, c.right)) / depth / aspect});
  }
  return std::min(170.0, degrees(2 * std::atan(1.1 * t)));
}

static void add_corners(std::vector<glm::dvec3>& out, const part_frame& f) {
  for (double su : {-1.0, 1.0}) {
    for (double sv : {-1.0, 1.0}) out.push_back(corner(f, su, sv));
  }
}

double fov_for_aerial_image(const scene& s) {
  std::vector<glm::dvec3> pts;
  part_frame f = aerial_image_frame(s);
  f.width *= 1.35;  // the canonical 14 deg at 300 mm frames a 50 mm image like this
  f.height *= 1.35;
  add_corners(pts, f);
  return fov_to_hold(make_camera(s), pts);
}

double fov_for_whole_device(const scene& s) {
  std::vector<glm::dvec3> pts;
  for (const auto& p : layout_parts(s)) add_corners(pts, p.frame);
  add_corners(pts, aerial_image_frame(s));
  return fov_to_hold(make_camera(s), pts);
}

}  // namespace airr

namespace airr {

std::vector<glm::dvec3> ideal_light_path(const scene& s, const glm::dvec3& aerial_point) {
  const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s), src = source_frame(s);
  const glm::dvec3 eye = observer_position(s);
  std::vector<glm::dvec3> path{eye};
  const glm::dvec3 d = glm::normalize(aerial_point - eye);
  const auto p1 = hit_part(hm, eye, d, false);
  if (!p1) return path;
  const auto p2 = hit_part(rr, *p1, d, false);
  if (!p2) return path;
  const auto p3 = hit_part(src, *p1, reflect(-d, hm.n), false);
  path.insert(path.end(), {*p1, *p2, *p1});
  if (p3) path.push_back(*p3);
  return path;
}

std::array<glm::dvec3, 4> corners(const part_frame& f) {
  return {part_point(f, -0.5 * f.width, -0.5 * f.height), part_point(f, 0.5 * f.width, -0.5 * f.height),
          part_point(f, 0.5 * f.width, 0.5 * f.height), part_point(f, -0.5 * f.width, 0.5 * f.height)};
}

}  // namespace airr
