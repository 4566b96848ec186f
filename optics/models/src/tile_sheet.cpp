#include "airr/models/tile_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/geometry.hpp"
#include "plate_walk.hpp"

namespace airr {

namespace {

constexpr int max_steps = 100000;  // cells crossed by one straight stretch
// A tile's faces come in single precision, so after several faces light is reversed only to about
// 1e-6; within 1 mrad (0.3 mm at 300 mm) it counts as retroreflected.
constexpr double retro_tolerance = 1e-3;

// The tile frame: the sheet's turned by -azimuth about its normal, z shifted so that the tile's
// highest point lies plate_mm below the front surface.
struct tile_frame {
  double c = 1, s = 0, z_shift = 0;
  tile_frame(const tile_sheet_geometry& g, const tile_structure& t)
      : c(std::cos(radians(g.azimuth_deg))), s(std::sin(radians(g.azimuth_deg))), z_shift(g.plate_mm + t.top_mm()) {}
  glm::dvec3 direction_in(const glm::dvec3& d) const { return {c * d.x + s * d.y, -s * d.x + c * d.y, d.z}; }
  glm::dvec3 direction_out(const glm::dvec3& d) const { return {c * d.x - s * d.y, s * d.x + c * d.y, d.z}; }
  glm::dvec3 point_in(const glm::dvec3& p) const { return direction_in(p) + glm::dvec3(0, 0, z_shift); }
};

// A face where it lies: its index and the tile frame's origin of its cell.
struct placed_face {
  int face = -1;
  glm::dvec3 cell{0};
};

// `leaving`: the face the stretch starts on, if any; a flat face cannot be met again straight on.
stretch_end follow_tile(const tile_sheet_geometry& g, const tile_structure& t, const tile_frame& f,
                        const glm::dvec3& p0, const glm::dvec3& d0, bool in_plate, const placed_face& leaving) {
  const glm::dvec3 v = f.direction_in(d0);
  glm::dvec3 q = f.point_in(p0), p = p0;
  glm::dvec2 cell = glm::floor(glm::dvec2(q) / g.period_mm);
  const double eps = 1e-9 * std::min(g.period_mm.x, g.period_mm.y);
  // Past the face being left: beyond single precision's error in a hit's distance (a unit in the
  // last place of the cell's coordinates, not of the distance), growing when light leaves grazing.
  const float skip = float(1e-6 * std::min(g.period_mm.x, g.period_mm.y));
  for (int step = 0; step < max_steps; ++step) {
    const glm::dvec2 origin = cell * g.period_mm;
    const glm::dvec3 local = q - glm::dvec3(origin, 0);
    double t_cell = std::numeric_limits<double>::infinity();
    int axis = -1;
    for (int k = 0; k < 2; ++k) {
      double tk = INFINITY;
      if (v[k] > 0) tk = (g.period_mm[k] - local[k]) / v[k];
      if (v[k] < 0) tk = -local[k] / v[k];
      if (tk < t_cell) t_cell = std::max(tk, 0.0), axis = k;
    }
    double t_slab = INFINITY;
    if (in_plate && v.z > 0) t_slab = (t.top_mm() - q.z) / v.z;
    if (v.z < 0) t_slab = (t.bottom_mm() - q.z) / v.z;  // in the plate: through a hole in the tile
    const float t_far = float(std::min(t_cell, t_slab) + eps);
    RTCRayHit ray = make_ray_hit(local, v, float(eps));
    ray.ray.tfar = t_far;
    intersect(t.scene(), ray);
    glm::dvec2 shift(0);
    float step_past = skip;
    for (int again = 0; again < 4 && ray.hit.geomID != RTC_INVALID_GEOMETRY_ID; ++again, step_past *= 10) {
      shift = t.instance_offset(ray.hit.instID[0]) * g.period_mm;
      // Single precision puts the ray's start a little off the face it leaves: past it, if met.
      // Cells compare by index: one origin summed two ways can differ in its last bit.
      const bool same_cell =
          glm::round((origin + shift) / g.period_mm) == glm::round(glm::dvec2(leaving.cell) / g.period_mm);
      if (t.face_of(ray.hit.primID) != leaving.face || !same_cell) break;
      const float past = ray.ray.tfar;
      ray = make_ray_hit(local, v, past + step_past);
      ray.ray.tfar = t_far;
      intersect(t.scene(), ray);
    }
    if (ray.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      const int face = t.face_of(ray.hit.primID);
      const tile_structure::face& fc = t.faces()[std::size_t(face)];
      // The hit in double precision, on the face's plane.
      const double along = glm::dot(fc.normal, v);
      double th = ray.ray.tfar;
      if (std::abs(along) > 1e-12)
        th = (fc.offset + glm::dot(fc.normal, glm::dvec3(shift, 0)) - glm::dot(fc.normal, local)) / along;
      const glm::dvec3 n = (in_plate ? along < 0 : along > 0) ? fc.normal : -fc.normal;
      stretch_end end(p + th * d0, f.direction_out(n));
      end.metal_reflectance = fc.metal_reflectance;
      end.face = face;
      end.cell_origin = glm::dvec3(origin + shift, 0);
      return end;
    }
    if (t_slab <= t_cell) return {p + t_slab * d0, std::nullopt};
    q += t_cell * v;
    p += t_cell * d0;
    cell[axis] += v[axis] > 0 ? 1 : -1;
  }
  return {p, std::nullopt};  // along a cell's edge for ever: left to the event limit
}

}  // namespace

std::string default_tile_path() { return asset_dir() + "/models/corner_cube_tile.gltf"; }

polygon2 tile_path_aperture(const tile_sheet_geometry& g, const tile_structure& t, const glm::dvec3& inside,
                            const std::vector<std::pair<int, glm::dvec3>>& faces) {
  const tile_frame f(g, t);
  // The direction arriving at each face, and each face's plane where the walk met it.
  std::vector<glm::dvec3> arriving, normal;
  std::vector<double> offset;
  glm::dvec3 d = f.direction_in(inside);
  for (const auto& [face, cell] : faces) {
    const tile_structure::face& fc = t.faces().at(std::size_t(face));
    arriving.push_back(d);
    normal.push_back(fc.normal);
    offset.push_back(fc.offset + glm::dot(fc.normal, cell));
    d = reflect(d, fc.normal);
  }
  polygon2 result;
  for (std::size_t j = 0; j < faces.size(); ++j) {
    polygon2 traced;
    for (const glm::dvec3& corner : t.faces()[std::size_t(faces[j].first)].outline) {
      glm::dvec3 q = corner + faces[j].second;
      bool parallel = false;
      for (std::size_t i = j; i-- > 0;) {  // back along the stretch that arrived at face i + 1
        const double along = glm::dot(normal[i], arriving[i + 1]);
        if (std::abs(along) < 1e-12) parallel = true;
        q -= ((glm::dot(normal[i], q) - offset[i]) / along) * arriving[i + 1];
      }
      q -= ((q.z - f.z_shift) / arriving[0].z) * arriving[0];  // and up to the front surface
      if (parallel) return {};
      traced.push_back(glm::dvec2(f.direction_out(q)));
    }
    const polygon2 part = convex_hull(traced);
    result = j == 0 ? part : clip_convex_polygon(result, part);
    if (result.empty()) return {};
  }
  return result;
}

prism_path trace_tile_sheet(const tile_sheet_geometry& g, const tile_structure& t, const glm::dvec3& wi,
                            const glm::dvec2& entry, double u_front, pcg32& rng) {
  const tile_frame f(g, t);
  // One reference captured, so that the walk's std::function holds it without allocating.
  struct walk_state {
    const tile_sheet_geometry& g;
    const tile_structure& t;
    const tile_frame& f;
    placed_face last;  // where the previous stretch ended, when on a face
  } state{g, t, f, {}};
  const follow_back back = [&state](const glm::dvec3& p, const glm::dvec3& d, bool in_plate) {
    stretch_end end = follow_tile(state.g, state.t, state.f, p, d, in_plate, state.last);
    state.last = end.face_normal ? placed_face{end.face, end.cell_origin} : placed_face{};
    return end;
  };
  plate_walk_record record;
  const plate_optics optics{g.index, g.plate_mm, std::min(g.period_mm.x, g.period_mm.y), retro_tolerance};
  prism_path out = walk_plate(optics, back, wi, entry, u_front, rng, record);
  const bool out_of_front = out.fate == prism_fate::retroreflected || out.fate == prism_fate::stray;
  if (!out_of_front || record.faces.empty() || g.wavelength_nm <= 0) return out;
  std::vector<std::pair<int, glm::dvec3>> faces;
  for (const stretch_end& e : record.faces) faces.emplace_back(e.face, e.cell_origin);
  // Retroreflected light diffracts by the entry points that follow its faces; any other path's
  // beam is narrower than its first face seen from the front, which bounds its spread from below.
  aperture used;
  if (out.fate == prism_fate::retroreflected && out.front_reflections == 0 && record.crossings == 0)
    used.polygon = tile_path_aperture(g, t, record.inside, faces);
  if (polygon_area(used.polygon) <= 0) used.polygon = tile_path_aperture(g, t, record.inside, {faces.front()});
  if (polygon_area(used.polygon) <= 0) return out;  // a face seen edge on
  diffract_exit(used, g.light, g.wavelength_nm, rng, out);
  return out;
}

tile_sheet_retro::tile_sheet_retro(const tile_sheet_geometry& g) : g_(g) {
  check_model_numbers("tile_sheet", tile_sheet_retro_kind().fields,
                      {{"period_x_mm", g.period_mm.x},
                       {"period_y_mm", g.period_mm.y},
                       {"index", g.index},
                       {"plate_mm", g.plate_mm},
                       {"azimuth_deg", g.azimuth_deg},
                       {"wavelength_nm", g.wavelength_nm}});
  structure_ = std::make_unique<tile_structure>(g_);
}

retro_sample tile_sheet_retro::sample(const glm::dvec3& wi, retro_samples u) const {
  const tile_frame f(g_, *structure_);
  const glm::dvec2 entry(f.direction_out(glm::dvec3(u.lobe * g_.period_mm, 0)));
  const prism_path path = trace_tile_sheet(g_, *structure_, wi, entry, u.shift.x, u.more);
  return {path.wo, path.shift_mm, path.weight, path.fate == prism_fate::retroreflected, path.channels};
}

const retro_model_kind& tile_sheet_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "tile_sheet";
    k.help = "A sheet whose back repeats a designer's tile (a glTF mesh) behind a clear plate";
    k.fields = {
        text_field("tile", field_kind::path,
                   "glTF mesh of one tile of the back, in metres (empty: the shipped triangular cube corners at "
                   "0.1 mm pitch); metallic materials are a metal coat, other faces reflect by total internal "
                   "reflection"),
        number_field("period_x_mm", "mm", 1e-4, 10, 2 * 0.1 / std::sqrt(3.0), "The tile's repeat along its x", 1),
        number_field("period_y_mm", "mm", 1e-4, 10, 0.2, "The tile's repeat along its y", 1),
        number_field("index", "", 1, 3, 1.5, "Refractive index of the plate"),
        number_field("plate_mm", "mm", 0, 20, 0.1, "Plate thickness above the tile's highest point", 2),
        number_field("azimuth_deg", "deg", -360, 360, 0, "Rotation of the tile about the sheet normal"),
        number_field("wavelength_nm", "nm", 0, 20000, 550,
                     "Wavelength of the diffraction by the aperture each path used (0: none)", 1000),
        spectrum_field(),
    };
    k.make = [](const model_values& v, const model_setting& setting) -> std::unique_ptr<retro_model> {
      tile_sheet_geometry g;
      const std::string tile = v.text("tile");
      g.tile_file = tile.empty() ? default_tile_path() : resolve_path(tile, setting.base_dir);
      g.period_mm = {v.number("period_x_mm"), v.number("period_y_mm")};
      g.index = v.number("index");
      g.plate_mm = v.number("plate_mm");
      g.azimuth_deg = v.number("azimuth_deg");
      g.wavelength_nm = v.number("wavelength_nm");
      g.light = read_spectrum(v);
      try {
        g.tile = read_mesh_file(g.tile_file);
        return std::make_unique<tile_sheet_retro>(g);
      } catch (const input_error& e) {
        v.fail("tile", e.what());
      }
    };
    return k;
  }();
  return kind;
}

}  // namespace airr
