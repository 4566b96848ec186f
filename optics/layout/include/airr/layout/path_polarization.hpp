#pragma once
// A traced path's polarization (docs/polarization.md), followed from the observer back to the
// display: for each channel, the row that turns the Stokes vector of the light on the path's
// current segment (written in `frame`, its k the light's direction there) into what the observer
// sees (S0, after its polarizer). Each call applies one part as the light meets it, in the order
// the tracer meets them going back. Private to the tracer.
#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/polarization.hpp"

namespace airr {

// A part's local frame (part_frame axes) in the world.
inline polarization_frame world_frame(const part_frame& f, const polarization_frame& local) {
  return {to_world(f, local.x), to_world(f, local.y), to_world(f, local.k)};
}

struct path_polarization {
  std::array<glm::dvec4, 3> rows;
  polarization_frame frame;

  // At the observer (its camera's right and up): light arriving against the camera ray `dir`,
  // through its polarizer if any; or with `stokes` 0 to 3, the Stokes parameter S_stokes of the
  // light arriving, before the polarizer, in the frame of the image's right and up.
  static path_polarization at_observer(const scene& s, const glm::dvec3& right, const glm::dvec3& up,
                                       const glm::dvec3& dir, int stokes = -1);

  // The half mirror with its films, for a path (traced back) it reflected into `reflected` (the
  // path's direction back after it), or passed. A plate's `taken`: the Mueller matrix of the path
  // the tracer chose (plate_path_mueller); none: its main image's, the reflection at the near face
  // or every transmitted path, divided by the half mirror's reflectance or transmittance.
  void half_mirror_reflected(const half_mirror_params& hm, const part_frame& f, const glm::dvec3& reflected,
                             const mueller* taken = nullptr);
  void half_mirror_passed(const half_mirror_params& hm, const part_frame& f, const mueller* taken = nullptr);
  // A plate's path in the s/p frames of the light in and out, divided by its own weight.
  static mueller plate_path_mueller(const plate_path& path);
  // A sheet with its films, for a path (traced back) it sent back along `back` (world); `sheet`:
  // the model's Mueller matrix of the light's path between `local` frames (retro_model.hpp), or
  // none: the sheet keeps the field as a perfect mirror does.
  void sheet(const retroreflector_params& r, const part_frame& f, const glm::dvec3& back,
             const std::optional<mueller>& sheet, const glm::dvec3& wi, const glm::dvec3& wo);
  // The display's light seen by the observer, the mean of the channels (the model PSF's white).
  double emitted_white(const source_params& display, const part_frame& f) const;

  // A part's films on one face crossed by the current segment's light, as the light leaves that
  // face (`leaving`: outermost last) or arrives at it (outermost first).
  void films(const std::vector<film_params>& films, part_face face, const part_frame& f, bool leaving);
  // The half mirror (a plain one or a reflective polarizer), its Mueller matrix divided by the
  // scalar reflectance or transmittance the tracer weighs the branch with. `k_in`: the light's
  // direction before it (reflection), the current segment's after.
  void half_mirror_reflection(const half_mirror_params& hm, const part_frame& f, const glm::dvec3& k_in,
                              const mueller* taken);
  void half_mirror_transmission(const half_mirror_params& hm, const part_frame& f, const mueller* taken);
  // A mirror (or a sheet, which keeps the field as a perfect mirror facing the light does, default
  // of every sheet model) sending light that came along k_in along the current segment.
  void mirror(const glm::dvec3& k_in);
  // A diffuse surface: what leaves it is unpolarized.
  void depolarize(const glm::dvec3& k_in);
  // What the observer sees of the display's light per channel (1 for unpolarized light and no
  // analyzer): the display's state through its front films.
  glm::vec3 emitted(const source_params& display, const part_frame& f) const;
  // What the observer sees of unpolarized light on the current segment, per channel.
  glm::vec3 unpolarized_seen() const;

 private:
  void apply(const mueller& m, const polarization_frame& in, const polarization_frame& out);
  // apply(interface_mueller(-1, 1), in, out), a mirror's, on the rows without forming matrices.
  void apply_mirror(const polarization_frame& in, const polarization_frame& out);
};

}  // namespace airr
