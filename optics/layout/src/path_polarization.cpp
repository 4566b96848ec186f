#include "airr/layout/path_polarization.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "airr/layout/layout.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

namespace {

// The index a film's light is refracted into (its retardance grows with the path in it).
constexpr double film_index = 1.5;

glm::dvec4 row_times(const glm::dvec4& r, const mueller& m) {
  glm::dvec4 out;
  for (int c = 0; c < 4; ++c) out[c] = r[0] * m.m[0][c] + r[1] * m.m[1][c] + r[2] * m.m[2][c] + r[3] * m.m[3][c];
  return out;
}

// A part's axis at angle_deg from its u towards its v. A path meets the same few films and
// polarizers at every sample: their cosines and sines are kept per thread.
glm::dvec3 axis_on(const part_frame& f, double angle_deg) {
  struct seen_angle {
    double angle_deg = std::numeric_limits<double>::quiet_NaN(), cos = 1, sin = 0;
  };
  thread_local std::array<seen_angle, 4> seen;
  thread_local std::size_t next = 0;
  for (const seen_angle& a : seen)
    if (a.angle_deg == angle_deg) return a.cos * f.u + a.sin * f.v;
  seen_angle& a = seen[next++ % seen.size()];
  a = {angle_deg, std::cos(radians(angle_deg)), std::sin(radians(angle_deg))};
  return a.cos * f.u + a.sin * f.v;
}

}  // namespace

path_polarization path_polarization::at_observer(const scene& s, const glm::dvec3& right, const glm::dvec3& up,
                                                 const glm::dvec3& dir, int stokes) {
  path_polarization p;
  p.frame = polarization_frame::with_x(-dir, right);
  glm::dvec4 row{1, 0, 0, 0};
  if (stokes >= 0) {
    row = glm::dvec4(0);
    row[stokes] = 1;
  } else if (s.observer.analyzer_deg) {
    const double a = radians(*s.observer.analyzer_deg);
    const glm::dvec3 axis = std::cos(a) * right + std::sin(a) * up;
    row = row_times(row, linear_polarizer(p.frame, axis));
  }
  p.rows = {row, row, row};
  return p;
}

void path_polarization::apply(const mueller& m, const polarization_frame& in, const polarization_frame& out) {
  const mueller turned = reframed(out, frame, m);
  for (glm::dvec4& r : rows) r = row_times(r, turned);
  frame = in;
}

void path_polarization::apply_mirror(const polarization_frame& in, const polarization_frame& out) {
  // Each row times the rotator from `out` into the current frame, then the mirror's diag(1, 1, -1, -1).
  const double_angle t(out, frame.x);
  for (glm::dvec4& r : rows) r = {r[0], r[1] * t.c - r[2] * t.s, -(r[1] * t.s + r[2] * t.c), -r[3]};
  frame = in;
}

void path_polarization::films(const std::vector<film_params>& films, part_face face, const part_frame& f,
                              bool leaving) {
  if (films.empty()) return;
  const double cos_i = std::min(1.0, std::abs(glm::dot(frame.k, f.n)));
  const double sin_t = std::sqrt(1 - cos_i * cos_i) / film_index;
  const double path = 1 / std::sqrt(1 - sin_t * sin_t);  // the film's thickness crossed at an angle
  const auto one = [&](const film_params& film) {
    if (film.face != face) return;
    const double_angle axis(frame, axis_on(f, film.axis_deg));
    if (film.kind == film_kind::polarizer) {
      const double along = std::sqrt(film.pass_transmittance), across = std::sqrt(film.block_transmittance);
      for (glm::dvec4& row : rows) row = row_through_axial_part(row, axis, along, across);
      return;
    }
    for (std::size_t c = 0; c < 3; ++c) {
      const double retardance = 2 * pi * film.retardance_waves * path * film.wavelength_nm / display_primaries_nm[c];
      rows[c] = row_through_axial_part(rows[c], axis, 1.0, std::polar(1.0, retardance));
    }
  };
  // Going back, light leaving a face meets its outermost film first.
  if (leaving) {
    for (auto it = films.rbegin(); it != films.rend(); ++it) one(*it);
  } else {
    for (const film_params& film : films) one(film);
  }
}

mueller path_polarization::plate_path_mueller(const plate_path& path) {
  if (!(path.weight > 0)) return mueller::scale(0);
  const double a = 1 / std::sqrt(path.weight);
  return interface_mueller(a * path.as, a * path.ap);
}

void path_polarization::half_mirror_reflection(const half_mirror_params& hm, const part_frame& f,
                                               const glm::dvec3& k_in, const mueller* taken) {
  // Every kind written in the light's s/p frames.
  const polarization_frame in = polarization_frame::at_surface(k_in, f.n);
  const polarization_frame out = polarization_frame::with_unit_x(reflect(k_in, f.n), in.x);
  if (hm.kind == half_mirror_kind::plate) {
    const double cos_n = glm::dot(k_in, f.n);
    if (taken) return apply(*taken, in, out);
    const plate_path main = plate_paths_at(hm.plate, std::abs(cos_n), cos_n < 0).reflected[0];
    const double a = hm.reflectance > 0 ? 1 / std::sqrt(hm.reflectance) : 0;
    return apply(interface_mueller(a * main.as, a * main.ap), in, out);
  }
  apply_mirror(in, out);
  if (hm.kind == half_mirror_kind::half_mirror) return;
  // The mirror after the polarizer (in the light's order): the rows meet the polarizer next.
  const reflective_polarizer_params& p = hm.polarizer;
  const double_angle pass(in, axis_on(f, p.axis_deg));
  // The branch's scalar weight (the reflectance) divided out of the polarizer's.
  const double per = hm.reflectance > 0 ? 1 / hm.reflectance : 0;
  const double along = std::sqrt(per * p.pass_reflectance), across = std::sqrt(per * p.block_reflectance);
  for (glm::dvec4& row : rows) row = row_through_axial_part(row, pass, along, across);
}

void path_polarization::half_mirror_transmission(const half_mirror_params& hm, const part_frame& f,
                                                 const mueller* taken) {
  if (hm.kind == half_mirror_kind::half_mirror) return;
  if (hm.kind == half_mirror_kind::plate) {
    const polarization_frame sp = polarization_frame::at_surface(frame.k, f.n);
    if (taken) return apply(*taken, sp, sp);
    const double cos_n = glm::dot(frame.k, f.n);
    mueller all = mueller::scale(0);
    for (const plate_path& path : plate_paths_at(hm.plate, std::abs(cos_n), cos_n < 0).transmitted)
      all = all + interface_mueller(path.as, path.ap);
    return apply(mueller::scale(hm.transmittance > 0 ? 1 / hm.transmittance : 0) * all, sp, sp);
  }
  const reflective_polarizer_params& p = hm.polarizer;
  const double per = hm.transmittance > 0 ? 1 / hm.transmittance : 0;
  const double_angle axis(frame, axis_on(f, p.axis_deg));
  const double along = std::sqrt(per * p.pass_transmittance), across = std::sqrt(per * p.block_transmittance);
  for (glm::dvec4& row : rows) row = row_through_axial_part(row, axis, along, across);
}

void path_polarization::mirror(const glm::dvec3& k_in) {
  const glm::dvec3 bisector = frame.k - k_in;
  if (glm::dot(bisector, bisector) < 1e-24) return;  // light passing straight on is not reflected
  // Written from the light's s/p frame, the mirror needs no turn into it; it leaves along frame.k.
  const polarization_frame in = polarization_frame::at_surface(k_in, glm::normalize(bisector));
  apply_mirror(in, polarization_frame::with_unit_x(frame.k, in.x));
}

void path_polarization::depolarize(const glm::dvec3& k_in) {
  for (glm::dvec4& r : rows) r = {r[0], 0, 0, 0};
  frame = polarization_frame::about(k_in);
}

glm::vec3 path_polarization::emitted(const source_params& display, const part_frame& f) const {
  path_polarization p = *this;
  p.films(display.films, part_face::front, f, true);
  stokes light = unpolarized();
  const source_polarization& state = display.polarization;
  if (state.state == light_state::linear) {
    const glm::dvec3 axis = axis_on(f, state.angle_deg);
    const glm::dvec3 across = axis - glm::dot(axis, p.frame.k) * p.frame.k;
    // Seen edge-on along its axis, linear light has no direction across k: none reaches here.
    if (glm::dot(across, across) < 1e-18) return glm::vec3(0.0f);
    light = linear_light(angle_in(p.frame, axis));
  } else if (state.state != light_state::unpolarized) {
    light = circular_light(state.state == light_state::circular_positive);
  }
  return {float(glm::dot(p.rows[0], light)), float(glm::dot(p.rows[1], light)), float(glm::dot(p.rows[2], light))};
}

void path_polarization::half_mirror_reflected(const half_mirror_params& hm, const part_frame& f,
                                              const glm::dvec3& reflected, const mueller* taken) {
  // The light leaves the mirror on the side its current segment lies, and came from that side.
  const part_face side = glm::dot(frame.k, f.n) > 0 ? part_face::front : part_face::back;
  films(hm.films, side, f, true);
  half_mirror_reflection(hm, f, -reflected, taken);
  films(hm.films, side, f, false);
}

void path_polarization::half_mirror_passed(const half_mirror_params& hm, const part_frame& f, const mueller* taken) {
  const bool to_front = glm::dot(frame.k, f.n) > 0;
  films(hm.films, to_front ? part_face::front : part_face::back, f, true);
  half_mirror_transmission(hm, f, taken);
  films(hm.films, to_front ? part_face::back : part_face::front, f, false);
}

void path_polarization::sheet(const retroreflector_params& r, const part_frame& f, const glm::dvec3& back,
                              const std::optional<mueller>& sheet, const glm::dvec3& wi, const glm::dvec3& wo) {
  // Out through the sheet's films, off the sheet, and in through them (tracing back).
  films(r.films, part_face::front, f, true);
  if (sheet) {
    const sheet_light_frames local = light_frames_of(wi, wo);
    apply(*sheet, world_frame(f, local.in), world_frame(f, local.out));
  } else {
    mirror(-back);
  }
  films(r.films, part_face::front, f, false);
}

glm::vec3 path_polarization::unpolarized_seen() const {
  const stokes light = unpolarized();
  return {float(glm::dot(rows[0], light)), float(glm::dot(rows[1], light)), float(glm::dot(rows[2], light))};
}

double path_polarization::emitted_white(const source_params& display, const part_frame& f) const {
  const glm::vec3 c = emitted(display, f);
  return (double(c.x) + double(c.y) + double(c.z)) / 3;
}

}  // namespace airr
