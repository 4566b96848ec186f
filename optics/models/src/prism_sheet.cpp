#include "airr/models/prism_sheet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/models/diffraction.hpp"
#include "prism_structure.hpp"

namespace airr {

double prism_sheet_geometry::triangle_side_mm() const { return 2 * pitch_mm / std::sqrt(3.0); }
double prism_sheet_geometry::cube_edge_mm() const {
  return full_cubes ? pitch_mm / std::sqrt(2.0) : triangle_side_mm() / std::sqrt(2.0);
}
double prism_sheet_geometry::depth_mm() const {
  return full_cubes ? 2 * cube_edge_mm() / std::sqrt(3.0) : std::sqrt(2.0) * pitch_mm / 3;
}

namespace {

constexpr int max_steps = 100000;  // triangles crossed by one straight stretch

// The three groove families' in-plane unit normals, 120 deg apart (they sum to zero): family k's
// ridges are the lines e_k . x = j pitch for every integer j, all three meeting at the array's
// vertices.
// A walk asks for them several times and the azimuth seldom changes: kept per thread.
const std::array<glm::dvec2, 3>& groove_normals(const prism_sheet_geometry& g) {
  thread_local double azimuth = std::numeric_limits<double>::quiet_NaN();
  thread_local std::array<glm::dvec2, 3> e;
  if (g.azimuth_deg != azimuth) {
    for (int k = 0; k < 3; ++k) {
      const double a = radians(g.azimuth_deg + 90 + 120.0 * k);
      e[std::size_t(k)] = {std::cos(a), std::sin(a)};
    }
    azimuth = g.azimuth_deg;
  }
  return e;
}

// Follows the ray from p along d through the aperture triangles until it meets the grooved
// surface or leaves the slab between the ridges and the apexes. In one triangle, with f_k the
// ray's position across family k's strip (0 at one ridge, 1 at the next), the surface is the
// highest of three planes: face k at depth sqrt(2) pitch f_k (a triangle whose f's sum to 1) or
// sqrt(2) pitch (1 - f_k) (sum 2). g_k = z - plane_k is linear along the ray; the surface is
// min_k g_k = 0, positive inside the plate.
stretch_end follow(const prism_sheet_geometry& g, const std::array<glm::dvec2, 3>& e, glm::dvec3 p, const glm::dvec3& d,
                   bool in_plate) {
  const double h = g.pitch_mm, top = -g.plate_mm, bottom = top - g.depth_mm(), s2 = std::sqrt(2.0);
  const double eps = 1e-12 * h;
  std::array<double, 3> f{}, i{}, a{};
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double u = glm::dot(e[std::size_t(k)], glm::dvec2(p)) / h;
    i[std::size_t(k)] = std::floor(u);
    f[std::size_t(k)] = u - i[std::size_t(k)];
    a[std::size_t(k)] = glm::dot(e[std::size_t(k)], glm::dvec2(d)) / h;  // df_k per unit of ray length
    sum += f[std::size_t(k)];
  }
  bool low = sum < 1.5;  // the triangle whose f's sum to 1: its edges at f_k = 0
  for (int step = 0; step < max_steps; ++step) {
    // Leaving the triangle across an edge, or the slab.
    double t_exit = std::numeric_limits<double>::infinity();
    int k_exit = -1;
    for (int k = 0; k < 3; ++k) {
      const double ak = a[std::size_t(k)];
      const double t =
          low ? (ak < 0 ? -f[std::size_t(k)] / ak : INFINITY) : (ak > 0 ? (1 - f[std::size_t(k)]) / ak : INFINITY);
      if (t < t_exit) t_exit = t, k_exit = k;
    }
    double t_slab = INFINITY;
    if (in_plate && d.z > 0) t_slab = (top - p.z) / d.z;
    if (!in_plate && d.z < 0) t_slab = (bottom - p.z) / d.z;
    // The faces: g_k(t) = g0 + t slope.
    double t_hit = INFINITY;
    int k_hit = -1;
    std::array<double, 3> g0{}, slope{};
    for (int k = 0; k < 3; ++k) {
      const double across = low ? f[std::size_t(k)] : 1 - f[std::size_t(k)];
      g0[std::size_t(k)] = p.z - top + s2 * h * across;
      slope[std::size_t(k)] = d.z + s2 * h * (low ? a[std::size_t(k)] : -a[std::size_t(k)]);
    }
    if (in_plate) {
      // The first face the ray comes down to.
      for (int k = 0; k < 3; ++k) {
        if (slope[std::size_t(k)] >= 0) continue;
        const double t = -g0[std::size_t(k)] / slope[std::size_t(k)];
        if (t > eps && t < t_hit) t_hit = t, k_hit = k;
      }
    } else {
      // From below, the surface is reached when the last face still above the ray comes down to it,
      // unless by then the ray has gone under a face it was above.
      double t_last = 0;
      bool reachable = true;
      for (int k = 0; k < 3; ++k) {
        if (g0[std::size_t(k)] >= 0) continue;
        if (slope[std::size_t(k)] <= 0) {
          reachable = false;
          break;
        }
        const double t = -g0[std::size_t(k)] / slope[std::size_t(k)];
        if (t >= t_last) t_last = t, k_hit = k;
      }
      for (int k = 0; k < 3 && reachable; ++k)
        if (g0[std::size_t(k)] >= 0 && g0[std::size_t(k)] + slope[std::size_t(k)] * t_last < -eps) reachable = false;
      if (reachable && k_hit >= 0 && t_last > eps) t_hit = t_last;
      if (!reachable) k_hit = -1;
    }
    if (k_hit >= 0 && t_hit <= t_exit && t_hit <= t_slab) {
      const glm::dvec2 ek = e[std::size_t(k_hit)] * (low ? s2 : -s2);
      return {p + t_hit * d, glm::dvec3(ek, 1.0) / std::sqrt(3.0), low ? 1 : -1};
    }
    if (t_slab <= t_exit) return {p + t_slab * d, std::nullopt};
    // Into the neighbouring triangle: across family k_exit's ridge.
    p += t_exit * d;
    for (int k = 0; k < 3; ++k) f[std::size_t(k)] += t_exit * a[std::size_t(k)];
    const std::size_t k = std::size_t(k_exit);
    if (low) {
      i[k] -= 1;
      f[k] = 1;
    } else {
      i[k] += 1;
      f[k] = 0;
    }
    low = !low;
  }
  return {p, std::nullopt};  // a ray running along the grooves for ever: left to the event limit
}

}  // namespace

namespace {

// In a triangle whose f's sum to 1 the vertex opposite edge k lies along +e_k, 2/3 of the height
// from the centroid (the apex is under the centroid).
glm::dvec2 triangle_vertex(const prism_sheet_geometry& g, int pointing, std::size_t k) {
  return double(pointing) * 2 * g.pitch_mm / 3 * groove_normals(g)[k];
}

}  // namespace

polygon2 aperture_triangle(const prism_sheet_geometry& g, int pointing) {
  return {triangle_vertex(g, pointing, 0), triangle_vertex(g, pointing, 1), triangle_vertex(g, pointing, 2)};
}

namespace {

// An angle's stand-in, increasing with it over [0, 4) counter-clockwise from +x (no arc tangent).
double pseudo_angle(const glm::dvec2& v) {
  const double p = v.x / (std::abs(v.x) + std::abs(v.y));
  return v.y >= 0 ? 1 - p : 3 + p;
}

}  // namespace

polygon2 face_order_aperture(const polygon2& effective, const corner_view& view, const glm::dvec2& entry) {
  // The six half-lines from the apex along the edges and against them; the entry's direction lies
  // between two neighbours, the first met turning clockwise from it (or on it) and the first met
  // turning counter-clockwise, whose wedge (under 180 deg) holds its part. Angles are measured
  // from the entry's direction, in its frame.
  const glm::dvec2 w = entry != view.apex ? entry - view.apex : glm::dvec2(1, 0);
  auto turned = [&](const glm::dvec2& r) { return glm::dvec2(w.x * r.x + w.y * r.y, w.x * r.y - w.y * r.x); };
  glm::dvec2 lo{0}, hi{0};
  double lo_angle = 5, hi_angle = 5;
  for (std::size_t k = 0; k < 6; ++k) {
    const glm::dvec2 r = (k % 2 ? -1.0 : 1.0) * (view.edge_ends[k / 2] - view.apex);
    const glm::dvec2 t = turned(r);
    const double clockwise = pseudo_angle({t.x, -t.y}), counter = pseudo_angle(t);
    if (clockwise < lo_angle) lo_angle = clockwise, lo = r;
    if (counter > 0 && counter < hi_angle) hi_angle = counter, hi = r;
  }
  double reach = 0;
  for (const glm::dvec2& p : effective) reach = std::max(reach, 4 * glm::length(p - view.apex));
  const polygon2 wedge = {view.apex, view.apex + reach / glm::length(lo) * lo,
                          view.apex + reach / glm::length(hi) * hi};
  return clip_convex_polygon(effective, wedge);
}

// The face order's part of an effective aperture already worked out for d (non-empty).
static polygon2 face_order_part(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing,
                                const polygon2& effective, const glm::dvec2& shift_mm) {
  const corner_view view = g.full_cubes ? full_cube_corner_view(g, d) : triangular_corner_view(g, d, pointing);
  // Entry and exit are mirror images through the apex line: the entry is half the shift back.
  return face_order_aperture(effective, view, view.apex - 0.5 * shift_mm);
}

polygon2 face_order_aperture(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing,
                             const glm::dvec2& shift_mm) {
  const polygon2 effective = g.full_cubes ? full_cube_effective_aperture(g, d) : effective_aperture(g, d, pointing);
  if (effective.empty()) return {};
  return face_order_part(g, d, pointing, effective, shift_mm);
}

corner_view triangular_corner_view(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing) {
  return {glm::dvec2(d) * (g.depth_mm() / d.z),
          {triangle_vertex(g, pointing, 0), triangle_vertex(g, pointing, 1), triangle_vertex(g, pointing, 2)}};
}

polygon2 effective_aperture(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing) {
  const polygon2 triangle = aperture_triangle(g, pointing);
  polygon2 image;
  image.reserve(3);
  const glm::dvec2 q = glm::dvec2(d) * (g.depth_mm() / d.z);  // apex (0, 0, -depth) + s d at the ridges
  for (const glm::dvec2& v : triangle) image.push_back(2.0 * q - v);
  return clip_convex_polygon(image, triangle);
}

glm::dvec2 prism_cell_point(const prism_sheet_geometry& g, const glm::dvec2& u) {
  if (g.full_cubes) return full_cube_cell_point(g, u);
  // The cell's sides run along two ridge families (perpendicular to their normals), one
  // triangle side long.
  const auto e = groove_normals(g);
  const double side = g.triangle_side_mm();
  const glm::dvec2 v1 = side * glm::dvec2(-e[0].y, e[0].x), v2 = side * glm::dvec2(-e[1].y, e[1].x);
  return u.x * v1 + u.y * v2;
}

prism_path trace_prism_sheet(const prism_sheet_geometry& g, const glm::dvec3& wi, const glm::dvec2& entry,
                             double u_front, pcg32& rng, std::optional<mueller>* polarized) {
  const auto e = groove_normals(g);
  const follow_back back = [&](const glm::dvec3& p, const glm::dvec3& d, bool in_plate) {
    stretch_end end = g.full_cubes ? follow_full_cubes(g, p, d, in_plate) : follow(g, e, p, d, in_plate);
    if (g.metallised) end.metal_reflectance = g.face_reflectance;
    return end;
  };
  plate_walk_record record;
  std::optional<polarized_walk> light;
  if (polarized) light = polarized_walk::arriving(wi);
  prism_path out =
      walk_plate({g.index, g.plate_mm, g.pitch_mm}, back, wi, entry, u_front, rng, record, light ? &*light : nullptr);
  if (light) *polarized = light->leaving(out.wo);
  const bool out_of_front = out.fate == prism_fate::retroreflected || out.fate == prism_fate::stray;
  if (!out_of_front || out.face_reflections == 0 || g.wavelength_nm <= 0) return out;
  // One cube corner's three faces: the beam leaves through the part of its aperture that
  // retroreflects, and spreads by its far field. Any other path's beam is narrower than the
  // aperture triangle of the first cube corner it met: that triangle bounds its spread from below.
  const glm::dvec3 inside = record.inside;
  const int first_pointing = record.faces.front().pointing;
  aperture used;
  if (out.fate == prism_fate::retroreflected && out.face_reflections == 3 && out.front_reflections == 0) {
    used.polygon =
        g.full_cubes ? full_cube_effective_aperture(g, inside) : effective_aperture(g, inside, first_pointing);
    // Total internal reflection shifts the phase by polarisation differently for each face
    // order: the six orders' parts diffract apart (a metal coat keeps the whole coherent).
    if (!g.metallised && !used.polygon.empty())
      used.polygon = face_order_part(g, inside, first_pointing, used.polygon, out.shift_mm);
  }
  if (used.polygon.empty())
    used.polygon = g.full_cubes ? full_cube_hexagon(g, inside) : aperture_triangle(g, first_pointing);
  diffract_exit(used, g.light, g.wavelength_nm, rng, out);
  return out;
}

prism_sheet_retro::prism_sheet_retro(const prism_sheet_geometry& g) : g_(g) {
  check_model_numbers("prism_sheet", prism_sheet_retro_kind().fields,
                      {{"pitch_mm", g.pitch_mm},
                       {"index", g.index},
                       {"plate_mm", g.plate_mm},
                       {"face_reflectance", g.face_reflectance},
                       {"azimuth_deg", g.azimuth_deg},
                       {"wavelength_nm", g.wavelength_nm}});
}

retro_sample prism_sheet_retro::sample(const glm::dvec3& wi, retro_samples u) const {
  const prism_path path = trace_prism_sheet(g_, wi, prism_cell_point(g_, u.lobe), u.shift.x, u.more);
  return {path.wo, path.shift_mm, path.weight, path.fate == prism_fate::retroreflected, path.channels};
}

retro_sample prism_sheet_retro::sample_polarized(const glm::dvec3& wi, retro_samples u) const {
  std::optional<mueller> m;
  const prism_path path = trace_prism_sheet(g_, wi, prism_cell_point(g_, u.lobe), u.shift.x, u.more, &m);
  // The walk went the sample's way, from the observer's side: the light goes the other.
  if (m) m = reversed_path(*m);
  return {path.wo, path.shift_mm, path.weight, path.fate == prism_fate::retroreflected, path.channels, m};
}

const retro_model_kind& prism_sheet_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "prism_sheet";
    k.help = "Prism sheet traced as geometry: triangular cube corners behind a clear plate";
    k.fields = {
        number_field("pitch_mm", "mm", 1e-4, 10, 0.1,
                     "Spacing of parallel grooves (height of the aperture triangles); full cubes: the hexagonal "
                     "apertures' width across flats",
                     1),
        choice_field("prisms", {"triangular", "full_cube"},
                     "Triangular cube corners cut by three groove families, or full cubes (hexagonal apertures "
                     "of three square faces)"),
        number_field("index", "", 1, 3, 1.5, "Refractive index of the plate"),
        number_field("plate_mm", "mm", 0, 20, 0.1, "Plate thickness above the grooves' ridges", 2),
        choice_field("coating", {"tir", "metal"},
                     "Faces reflect by total internal reflection (Fresnel loss where it fails) or by a metal coat"),
        number_field("face_reflectance", "", 0, 1, 0.85, "Reflectance of the metal coat, per face"),
        number_field("azimuth_deg", "deg", -360, 360, 0, "Rotation of the grooves about the sheet normal"),
        number_field("wavelength_nm", "nm", 0, 20000, 550,
                     "Wavelength of the diffraction by each cube corner's aperture (0: none)", 1000),
        spectrum_field(),
    };
    k.make = [](const model_values& v, const model_setting&) -> std::unique_ptr<retro_model> {
      prism_sheet_geometry g;
      g.pitch_mm = v.number("pitch_mm");
      g.full_cubes = v.text("prisms") == "full_cube";
      g.index = v.number("index");
      g.plate_mm = v.number("plate_mm");
      g.metallised = v.text("coating") == "metal";
      g.face_reflectance = v.number("face_reflectance");
      g.azimuth_deg = v.number("azimuth_deg");
      g.wavelength_nm = v.number("wavelength_nm");
      g.light = read_spectrum(v);
      return std::make_unique<prism_sheet_retro>(g);
    };
    return k;
  }();
  return kind;
}

}  // namespace airr
