#pragma once
// What a traced path meets besides the optical parts: the props it scatters at and the room it
// sees when it leaves the scene (private to tracer.cpp).
#include <type_traits>

#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "tracer_path.hpp"

namespace airr::tracer_path {

// Scatters the path at a prop (a mirror reflection, or a Lambertian bounce drawn from the path's
// generator), both sides alike; false when the prop absorbs it.
template <class Polarization, class Label>
bool scatter_at_prop(const tracer_scene::prop& prop, const RTCRayHit& rh, path_state<Polarization, Label>& p,
                     pcg32& rng) {
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
    const double u1 = rng.next_double(), u2 = rng.next_double();
    p.dir = glm::normalize(make_basis(n).to_world(cosine_hemisphere({u1, u2})));
    if constexpr (polarized<Polarization>) p.pol.depolarize(-p.dir);
  }
  p.throughput *= s.reflectance;
  ++p.prop_scatterings;
  return true;
}

// A path that left the scene: the room's uniform, unpolarized surround (neutral white).
template <class Polarization, class Label>
void see_room(float room_luminance, path_state<Polarization, Label>& p, component_radiance& radiance,
              layer_sink* layers) {
  glm::vec3 L = p.throughput * room_luminance;
  if constexpr (polarized<Polarization>) L *= p.pol.unpolarized_seen();
  radiance[component_room] += L;
  if constexpr (!std::is_same_v<Label, no_label>) {
    p.label.push({path_event_kind::ambient, false, false, ambient_room});
    layers->add(p.label, L);
  }
}

}  // namespace airr::tracer_path
