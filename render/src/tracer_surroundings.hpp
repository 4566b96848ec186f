#pragma once
// What a traced path meets besides the optical parts: the props it scatters at, where it samples
// the sun and the luminaires, and the ambient light it sees (private to tracer.cpp).
#include <limits>
#include <type_traits>

#include "airr/core/embree.hpp"
#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "tracer_path.hpp"

namespace airr::tracer_path {

// Ambient light L of source `source` (an ambient_* index) reaching the eye along `p`: its image
// component (and a luminaire's own, when kept), and the layers of `label` (p's, or p's with a
// sampled light's crossings) with the ambient event.
template <class Polarization, class Label>
void see_ambient(const path_state<Polarization, Label>& p, Label label, glm::vec3 L, image_component component,
                 std::uint16_t source, component_radiance& radiance, layer_sink* layers) {
  if constexpr (polarized<Polarization>) L *= p.pol.unpolarized_seen();  // ambient light is unpolarized
  radiance[component] += L;
  if (component == component_luminaires && radiance.each_luminaire)
    radiance.each_luminaire[source - ambient_first_luminaire] += L;
  if constexpr (!std::is_same_v<Label, no_label>) {
    label.push({path_event_kind::ambient, false, false, source});
    layers->add(label, L);
  }
}

// Whether the sun and the luminaires met along p's direction were sampled where it came from.
template <class Polarization, class Label>
bool light_sampled(const path_state<Polarization, Label>& p) {
  return glm::dot(p.dir, p.light_sampled_dir) > 1 - 1e-9;
}

// The luminaire p met (at its front, where it emits).
template <class Polarization, class Label>
void see_luminaire(const tracer_scene& ts, int which, const path_state<Polarization, Label>& p,
                   component_radiance& radiance, layer_sink* layers) {
  if (light_sampled(p)) return;
  see_ambient(p, p.label, p.throughput * ts.ambient.luminaires[std::size_t(which)].luminance, component_luminaires,
              std::uint16_t(ambient_first_luminaire + which), radiance, layers);
}

// How much of the light along a straight line gets through to `from` over [0, t_max), per channel:
// the half mirror passes its transmittance (with its films, and the state a polarizing one
// leaves, of which the diffuse prop at `from` takes the intensity), anything else stops it. A
// plate passes its transmission at the line's incidence, and the line goes on from where one of
// its transmitted paths (drawn by its share) leaves it, as the tracer's own paths do (the light's
// end, shifted as much, is taken as lying on the luminaire still). `label` gains the crossings as
// the tracer meets them going back.
template <class Polarization, class Label>
glm::vec3 transmittance_along(const tracer_scene& ts, glm::dvec3 from, const glm::dvec3& dir, double t_max, pcg32& rng,
                              std::uint64_t& rays, Label& label) {
  if (meet_luminaire(ts.ambient, from, dir, t_max).which >= 0) return glm::vec3(0.0f);
  const half_mirror_params& hm = ts.layout.half_mirror;
  const part_frame& f = ts.frames[part_half_mirror];
  // What reaches `from` of the unpolarized light of the source, written from the far end back.
  [[maybe_unused]] Polarization pol{};
  if constexpr (polarized<Polarization>) {
    const glm::dvec4 intensity{1, 0, 0, 0};
    pol = {{intensity, intensity, intensity}, polarization_frame::about(-dir)};
  }
  float passed = 1;
  for (int crossing = 0; crossing < 4; ++crossing) {
    RTCRayHit rh = make_ray_hit(from, dir, ray_epsilon_mm);
    rh.ray.tfar = float(std::min(t_max, double(std::numeric_limits<float>::max())));
    intersect(ts.embree->get(), rh);
    ++rays;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      if constexpr (polarized<Polarization>) return passed * pol.unpolarized_seen();
      return glm::vec3(passed);
    }
    if (rh.hit.instID[0] != part_half_mirror) return glm::vec3(0.0f);
    const glm::dvec3 hit = from + dir * double(rh.ray.tfar);
    t_max -= double(rh.ray.tfar);
    from = hit;
    const double cos_n = glm::dot(dir, f.n);
    if (hm.kind == half_mirror_kind::plate) {
      if (std::abs(cos_n) < 1e-9) return glm::vec3(0.0f);
      const plate_paths paths = plate_paths_at(hm.plate, std::abs(cos_n), cos_n < 0);
      if (!(paths.transmitted_total > 0)) return glm::vec3(0.0f);
      const std::size_t k = draw_plate_path(paths.transmitted, paths.transmitted_total, rng);
      from = cross_plate(hm.plate, f, hit, dir).leaving(paths.transmitted[k].advance, true);
      t_max -= glm::dot(from - hit, dir);
      passed *= float(paths.transmitted_total);
      push_half_mirror(label, hm.films, false, cos_n < 0, std::uint16_t(k));
      if constexpr (polarized<Polarization>) {
        const mueller m = path_polarization::plate_path_mueller(paths.transmitted[k]);
        pol.half_mirror_passed(hm, f, &m);
      }
    } else {
      passed *= float(hm.transmittance);
      push_half_mirror(label, hm.films, false, cos_n < 0, 0);
      if constexpr (polarized<Polarization>) pol.half_mirror_passed(hm, f);
    }
  }
  return glm::vec3(0.0f);
}

// At a Lambertian prop of albedo `albedo` at p.origin, facing n (towards where p came from):
// the light of the sun and of each luminaire it reflects towards the eye, each sampled once.
template <class Polarization, class Label>
void sample_lights(const tracer_scene& ts, const path_state<Polarization, Label>& p, const glm::dvec3& n,
                   const glm::vec3& albedo, pcg32& rng, component_radiance& radiance, layer_sink* layers,
                   std::uint64_t& rays) {
  const ambient_lights& a = ts.ambient;
  const glm::vec3 reflected = p.throughput * albedo * float(1 / pi);
  if (a.sun > 0) {
    const double u1 = rng.next_double(), u2 = rng.next_double();
    const glm::dvec3 w = sun_sample_direction(a, u1, u2);
    const double cos_here = glm::dot(n, w);
    if (cos_here > 0) {
      Label label = p.label;
      const glm::vec3 passed =
          transmittance_along<Polarization>(ts, p.origin, w, std::numeric_limits<double>::infinity(), rng, rays, label);
      // The disc's luminance times its solid angle is the illuminance it makes facing it.
      if (passed != glm::vec3(0.0f))
        see_ambient(p, std::move(label), reflected * float(a.sun_lux * cos_here) * passed, component_sun, ambient_sun,
                    radiance, layers);
    }
  }
  for (std::size_t k = 0; k < a.luminaires.size(); ++k) {
    const ambient_lights::luminaire& l = a.luminaires[k];
    const double u1 = rng.next_double(), u2 = rng.next_double();
    const glm::dvec3 to = luminaire_point(l, u1, u2) - p.origin;
    const double r2 = glm::dot(to, to);
    const glm::dvec3 w = to / std::sqrt(r2);
    const double cos_here = glm::dot(n, w), cos_there = -glm::dot(l.frame.n, w);
    if (cos_here <= 0 || cos_there <= 0 || !(l.luminance > 0)) continue;
    Label label = p.label;
    const glm::vec3 passed =
        transmittance_along<Polarization>(ts, p.origin, w, std::sqrt(r2) * (1 - 1e-6), rng, rays, label);
    if (passed != glm::vec3(0.0f)) {
      const double geometry = cos_here * cos_there * l.area_mm2 / r2;
      see_ambient(p, std::move(label), reflected * l.luminance * float(geometry) * passed, component_luminaires,
                  std::uint16_t(ambient_first_luminaire + k), radiance, layers);
    }
  }
}

// Scatters the path at a prop (a mirror reflection, or a Lambertian bounce drawn from the path's
// generator, where the sun and the luminaires are sampled first), both sides alike; false when the
// prop absorbs it.
template <class Polarization, class Label>
bool scatter_at_prop(const tracer_scene& ts, const tracer_scene::prop& prop, const RTCRayHit& rh,
                     path_state<Polarization, Label>& p, pcg32& rng, component_radiance& radiance, layer_sink* layers,
                     std::uint64_t& rays) {
  const surface_response s = prop_surface_of(prop.params, *prop.mesh, rh.hit.primID);
  if (s.kind == prop_surface::absorber) return false;
  p.label.push({path_event_kind::prop, false, false, prop.index});
  // Embree gives the normal in the mesh's frame; the prop's scale is uniform.
  glm::dvec3 n = glm::normalize(prop.rotation * glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  if (glm::dot(n, p.dir) > 0) n = -n;
  p.origin += p.dir * double(rh.ray.tfar);
  if (s.kind == prop_surface::mirror) {
    p.dir = reflect(p.dir, n);
    if constexpr (polarized<Polarization>) p.pol.mirror(-p.dir);
  } else {
    const bool sampled = ts.ambient.sun > 0 || !ts.ambient.luminaires.empty();
    if (sampled) sample_lights(ts, p, n, s.reflectance, rng, radiance, layers, rays);
    const double u1 = rng.next_double(), u2 = rng.next_double();
    p.dir = glm::normalize(make_basis(n).to_world(cosine_hemisphere({u1, u2})));
    if (sampled) p.light_sampled_dir = p.dir;
    if constexpr (polarized<Polarization>) p.pol.depolarize(-p.dir);
  }
  p.throughput *= s.reflectance;
  ++p.prop_scatterings;
  return true;
}

}  // namespace airr::tracer_path
