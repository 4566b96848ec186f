#include "plate_walk.hpp"

#include "airr/core/geometry.hpp"
#include "airr/models/dielectric.hpp"

namespace airr {

namespace {
constexpr int max_events = 256;
}

prism_path walk_plate(const plate_optics& o, const follow_back& follow, const glm::dvec3& wi, const glm::dvec2& entry,
                      double u_front, pcg32& rng, plate_walk_record& record, polarized_walk* light) {
  prism_path out;
  if (!(wi.z > 0)) return out;
  const glm::dvec3 front_normal(0, 0, 1);
  if (u_front < fresnel_dielectric(wi.z, o.index)) {
    out.fate = prism_fate::front_reflection;
    out.wo = glm::dvec3(-wi.x, -wi.y, wi.z);
    out.weight = 1;
    if (light) light->reflect(front_normal, wi.z, o.index);
    return out;
  }
  glm::dvec3 d = *refract(-wi, front_normal, 1 / o.index);
  if (light) light->refract(front_normal, wi.z, o.index, d);
  record.inside = d;
  glm::dvec3 p(entry, 0.0);
  bool in_plate = true;
  double weight = 1;
  for (int event = 0; event < max_events; ++event) {
    out.events = event;
    if (in_plate && d.z > 0 && p.z >= -o.plate_mm - 1e-12 * o.length_mm) {
      // Up through the plate to the front surface.
      p += ((0 - p.z) / d.z) * d;
      if (rng.next_double() < fresnel_dielectric(d.z, 1 / o.index)) {
        if (light) light->reflect(front_normal, d.z, 1 / o.index);
        d.z = -d.z;
        ++out.front_reflections;
        continue;
      }
      out.wo = glm::normalize(*refract(d, -front_normal, o.index));
      if (light) light->refract(front_normal, d.z, 1 / o.index, out.wo);
      out.shift_mm = glm::dvec2(p) - entry;
      out.weight = weight;
      out.fate = glm::length(out.wo - wi) < o.retro_tolerance ? prism_fate::retroreflected : prism_fate::stray;
      return out;
    }
    if (in_plate && d.z < 0 && p.z > -o.plate_mm) p += ((-o.plate_mm - p.z) / d.z) * d;  // down to the top
    const stretch_end end = follow(p, d, in_plate);
    p = end.point;
    if (!end.face_normal) {
      if (in_plate && d.z > 0) continue;  // above the structure: on to the front surface
      if (in_plate) break;                // down through a hole in the structure: lost
      if (d.z < 0) {
        out.fate = prism_fate::transmitted;
        out.wo = d;
        out.shift_mm = glm::dvec2(p) - entry;
        out.weight = weight;
        return out;
      }
      break;  // no surface where one must be: numerically lost
    }
    const glm::dvec3 n = *end.face_normal;  // into the plate
    if (in_plate) {
      if (record.faces.empty()) record.faces.reserve(4);  // a cube corner's three, in one allocation
      record.faces.push_back(end);
      ++out.face_reflections;
      if (end.metal_reflectance) {
        weight *= *end.metal_reflectance;
        if (light) light->reflect(n, -glm::dot(d, n), metal_coat_index / o.index);
        d = reflect(d, n);
        continue;
      }
      if (rng.next_double() < fresnel_dielectric(-glm::dot(d, n), 1 / o.index)) {
        if (light) light->reflect(n, -glm::dot(d, n), 1 / o.index);
        d = reflect(d, n);
      } else {
        const glm::dvec3 out_of_plate = glm::normalize(*refract(d, n, o.index));
        if (light) light->refract(n, -glm::dot(d, n), 1 / o.index, out_of_plate);
        d = out_of_plate;
        in_plate = false;
        ++record.crossings;
      }
    } else {
      if (end.metal_reflectance) {  // the coat's back, from the air under the sheet
        weight *= *end.metal_reflectance;
        if (light) light->reflect(n, glm::dot(d, n), metal_coat_index);
        d = reflect(d, n);
        continue;
      }
      if (rng.next_double() < fresnel_dielectric(glm::dot(d, n), o.index)) {
        if (light) light->reflect(n, glm::dot(d, n), o.index);
        d = reflect(d, n);
      } else {
        const glm::dvec3 into_plate = glm::normalize(*refract(d, -n, 1 / o.index));
        if (light) light->refract(n, glm::dot(d, n), o.index, into_plate);
        d = into_plate;
        in_plate = true;
        ++record.crossings;
      }
    }
  }
  out.fate = prism_fate::lost;
  out.weight = 0;
  return out;
}

void diffract_exit(const aperture& used, diffracted_light light, double wavelength_nm, pcg32& rng, prism_path& path) {
  const drawn_light drawn = draw_light(light, wavelength_nm, rng);
  path.channels = drawn.channels;
  const auto spread = diffracted(path.wo, sample_far_field(used, rng), drawn.wavelength_nm * 1e-6);
  if (spread) {
    path.wo = *spread;
  } else {
    path.weight = 0;  // evanescent
  }
}

}  // namespace airr
