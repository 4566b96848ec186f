#pragma once
// A path's state in the tracer and the half mirror it meets (private to tracer.cpp).
#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <string>
#include <type_traits>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/layout/path_polarization.hpp"
#include "airr/render/path_label.hpp"
#include "airr/render/ray_file.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

// Surfaces are infinitely thin; new rays start this far along to skip the surface they leave.
inline constexpr float ray_epsilon_mm = 1e-3f;

// Paths split into both half-mirror branches this many times (weights R and T, no noise);
// after that one branch is chosen at random with weight R + T.
inline constexpr int max_half_mirror_splits = 3;

namespace tracer_path {

struct no_polarization {};
// The label of a path that is not asked for its events.
struct no_label {
  void push(const path_event&) {}
};
// The label of a path kept for the ray file, with the segments it traced (eye first), each with
// the path's throughput along it.
struct path_trail : path_label {
  struct segment {
    glm::vec3 origin, dir;
    float length;
    glm::vec3 throughput;
  };
  std::array<segment, max_path_interactions> segments;
  int segment_count = 0;
  void add_segment(const glm::dvec3& origin, const glm::dvec3& dir, float length, const glm::vec3& throughput) {
    if (segment_count < max_path_interactions)
      segments[std::size_t(segment_count++)] = {glm::vec3(origin), glm::vec3(dir), length, throughput};
  }
};

// The films on `face` of a part (`whose`: films_on_display ...) as one event, when it has any.
template <class Label>
void push_films(Label& label, const std::vector<film_params>& films, part_face face, std::uint16_t whose) {
  if constexpr (!std::is_same_v<Label, no_label>) {
    if (std::any_of(films.begin(), films.end(), [&](const film_params& f) { return f.face == face; }))
      label.push({path_event_kind::film, false, face == part_face::front, whose});
  }
}

// A half mirror's reflection or transmission (`order`: the plate path's), with its films, as the
// tracer meets them going back: the films of the face the light leaves by (the traced ray's side,
// the front when `traced_from_front`), the half mirror, the films of the face the light arrived on.
template <class Label>
void push_half_mirror(Label& label, const std::vector<film_params>& films, bool reflected, bool traced_from_front,
                      std::uint16_t order) {
  const part_face eye_side = traced_from_front ? part_face::front : part_face::back;
  const part_face other_side = traced_from_front ? part_face::back : part_face::front;
  const part_face arrived_on = reflected ? eye_side : other_side;
  push_films(label, films, eye_side, films_on_half_mirror);
  label.push({path_event_kind::half_mirror, reflected, arrived_on == part_face::front, order});
  push_films(label, films, arrived_on, films_on_half_mirror);
}

// Sheet k sending the light back through the films on its front, in and out.
template <class Label>
void push_sheet(Label& label, const std::vector<film_params>& films, bool retroreflected, std::uint16_t k) {
  const auto whose = std::uint16_t(films_on_first_sheet + k);
  push_films(label, films, part_face::front, whose);
  label.push({path_event_kind::sheet, retroreflected, false, k});
  push_films(label, films, part_face::front, whose);
}

// The display's emission through the films on its front.
template <class Label>
void push_display(Label& label, const std::vector<film_params>& films) {
  push_films(label, films, part_face::front, films_on_display);
  label.push({path_event_kind::display});
}

// `Polarization`: path_polarization when the scene polarizes, else nothing (the path as it was).
// `Label`: path_label when layers are asked for, path_trail for the ray file, else nothing.
template <class Polarization, class Label>
struct path_state {
  glm::dvec3 origin;
  glm::dvec3 dir;
  glm::vec3 throughput;
  int depth;
  int retroreflections = 0;
  int mirror_reflections = 0;
  int prop_scatterings = 0;
  int sheet_scatterings = 0;  // a sheet sent the light back without retroreflecting it
  // Each branch split off before any retroreflection takes the sample's first-retroreflection
  // numbers at its first sheet, as the control variate predicts every sheet with them.
  bool first_retro_used = false;
  // The direction a Lambertian prop sent the path on, having sampled the sun and the luminaires
  // from there (light_sampled): met along it, they are counted already.
  glm::dvec3 light_sampled_dir{0.0};
  [[no_unique_address]] Polarization pol{};
  [[no_unique_address]] Label label{};
};

template <class Polarization>
inline constexpr bool polarized = std::is_same_v<Polarization, path_polarization>;

// The component of the display's light along `p` (ambient light has its own).
template <class Polarization, class Label>
image_component component_of(const path_state<Polarization, Label>& p) {
  if (p.retroreflections > 0) return component_aerial;
  if (p.prop_scatterings > 0 || p.sheet_scatterings > 0) return component_rest;
  if (p.mirror_reflections == 0) return component_direct;
  return p.mirror_reflections == 1 ? component_reflection : component_rest;
}

// The paths split off and still to trace.
template <class Polarization, class Label>
struct path_stack {
  path_state<Polarization, Label> paths[max_half_mirror_splits + 1];
  int pending = 0, splits_left = max_half_mirror_splits;
};

// The thin half mirror (a plain one or a reflective polarizer) met at `hit`: `p` goes on through
// it, its reflection split off onto the stack while splits are left; after that one branch is
// chosen. False when nothing goes on.
template <class Polarization, class Label>
bool meet_thin_half_mirror(const half_mirror_params& hm, const part_frame& f, const glm::dvec3& hit,
                           path_state<Polarization, Label>& p, path_stack<Polarization, Label>& stack, pcg32& rng) {
  constexpr bool with_polarization = polarized<Polarization>;
  const double hm_total = hm.reflectance + hm.transmittance;
  if (hm_total <= 0) return false;
  const glm::dvec3 reflected = reflect(p.dir, f.n);
  // The traced ray comes from the front (the normal's side): reflected light arrived there.
  const bool from_front = glm::dot(p.dir, f.n) < 0;
  p.origin = hit;
  if (stack.splits_left > 0) {
    --stack.splits_left;
    path_state<Polarization, Label> r = p;
    push_half_mirror(r.label, hm.films, true, from_front, 0);
    r.dir = reflected;
    r.throughput *= float(hm.reflectance);
    ++r.depth;
    ++r.mirror_reflections;
    if constexpr (with_polarization) r.pol.half_mirror_reflected(hm, f, reflected);
    stack.paths[stack.pending++] = r;
    p.throughput *= float(hm.transmittance);
    push_half_mirror(p.label, hm.films, false, from_front, 0);
    if constexpr (with_polarization) p.pol.half_mirror_passed(hm, f);
  } else {
    const bool reflect_it = rng.next_double() * hm_total < hm.reflectance;
    push_half_mirror(p.label, hm.films, reflect_it, from_front, 0);
    if (reflect_it) {
      p.dir = reflected;
      ++p.mirror_reflections;
      if constexpr (with_polarization) p.pol.half_mirror_reflected(hm, f, reflected);
    } else if constexpr (with_polarization) {
      p.pol.half_mirror_passed(hm, f);
    }
    p.throughput *= float(hm_total);
  }
  return true;
}

// A ray (traced back along `dir`) crossing the plate whose mid-plane it meets at `hit`: where it
// enters the near face, the way along the faces its paths advance inside, and the step from the
// near face to the far one; a path of `advance` plate thicknesses leaves at `leaving`.
struct plate_crossing {
  glm::dvec3 entry, along, across;
  double thickness_mm;
  glm::dvec3 leaving(double advance, bool transmitted) const {
    return entry + advance * thickness_mm * along + (transmitted ? across : glm::dvec3(0));
  }
};
inline plate_crossing cross_plate(const plate_params& plate, const part_frame& f, const glm::dvec3& hit,
                                  const glm::dvec3& dir) {
  const double cos_n = glm::dot(dir, f.n), t = plate.thickness_mm;
  const glm::dvec3 tangent = dir - cos_n * f.n;
  const double tangent_length = glm::length(tangent);
  return {hit - dir * (0.5 * t / std::abs(cos_n)), tangent_length > 1e-12 ? tangent / tangent_length : glm::dvec3(0),
          (cos_n < 0 ? -t : t) * f.n, t};
}

// One of a family of plate paths (`total` their weights' sum) drawn by its share.
inline std::size_t draw_plate_path(const std::array<plate_path, plate_orders>& family, double total, pcg32& rng) {
  double u = rng.next_double() * total;
  std::size_t k = 0;
  while (k + 1 < family.size() && u >= family[k].weight) u -= family[k++].weight;
  return k;
}

// The plate met at `hit` on its mid-plane: as the thin half mirror, the reflected and the
// transmitted families split or chosen by their totals, and within a family one path chosen by
// its share (so its Mueller matrix is divided by its own weight, the family's scalar weight
// applied); the light leaves the plate's face where that path leaves it.
template <class Polarization, class Label>
bool meet_plate(const half_mirror_params& hm, const part_frame& f, const glm::dvec3& hit,
                path_state<Polarization, Label>& p, path_stack<Polarization, Label>& stack, pcg32& rng) {
  const double cos_n = glm::dot(p.dir, f.n);
  const double cos_i = std::abs(cos_n);
  if (cos_i < 1e-9) return false;  // along the plate: it meets an edge
  const plate_paths paths = plate_paths_at(hm.plate, cos_i, cos_n < 0);
  const plate_crossing crossing = cross_plate(hm.plate, f, hit, p.dir);

  const auto take = [&](path_state<Polarization, Label>& q, bool reflected, double weight) {
    const auto& family = reflected ? paths.reflected : paths.transmitted;
    const double total = reflected ? paths.reflected_total : paths.transmitted_total;
    const std::size_t k = draw_plate_path(family, total, rng);
    q.origin = crossing.leaving(family[k].advance, !reflected);
    push_half_mirror(q.label, hm.films, reflected, cos_n < 0, std::uint16_t(k));
    if (reflected) {
      q.dir = reflect(q.dir, f.n);
      ++q.mirror_reflections;
    }
    q.throughput *= float(weight);
    if constexpr (polarized<Polarization>) {
      const mueller m = path_polarization::plate_path_mueller(family[k]);
      if (reflected) {
        q.pol.half_mirror_reflected(hm, f, q.dir, &m);
      } else {
        q.pol.half_mirror_passed(hm, f, &m);
      }
    }
  };
  const double all = paths.reflected_total + paths.transmitted_total;
  if (!(all > 0)) return false;
  if (stack.splits_left > 0) {
    --stack.splits_left;
    path_state<Polarization, Label> r = p;
    ++r.depth;
    if (paths.reflected_total > 0) {
      take(r, true, paths.reflected_total);
      stack.paths[stack.pending++] = r;
    }
    if (!(paths.transmitted_total > 0)) return false;
    take(p, false, paths.transmitted_total);
  } else {
    take(p, rng.next_double() * all < paths.reflected_total, all);
  }
  return true;
}

}  // namespace tracer_path

// Where a labelled path's light goes: to each of ts.layers' layers that selects its label, and
// to the census and the ray record when kept. A label's selection is remembered, as a render
// meets few distinct labels and matching every expression again is most of what layers cost.
struct layer_sink {
  layer_sink(const path_layers& l, glm::vec3* r) : layers(l), radiance(r) {}
  const path_layers& layers;
  glm::vec3* radiance;  // layers.count() of them
  struct remembered {
    path_label label;
    std::uint64_t selected = 0;
  };
  std::array<remembered, 64> seen{};
  std::map<std::string, census_class>* census = nullptr;  // every label's light, when kept
  // When kept: the paths each layer selects, each record up to its segment limit (the first
  // records.size() layers); the pixel and the sample being traced.
  std::span<ray_record> records;
  std::span<const std::uint64_t> segment_limits;
  std::uint32_t x = 0, y = 0;
  std::uint64_t sample = 0;

  // The layers selecting `l`, as path_layers::select.
  std::uint64_t add(const path_label& l, const glm::vec3& L) {
    if (census) {
      const auto [c, first] = census->try_emplace(label_text(l));
      if (first) c->second.label = l;
      c->second.light += glm::dvec3(L);
    }
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the events
    for (int i = 0; i < l.count; ++i) {
      const path_event& e = l.events[std::size_t(i)];
      h = (h ^ (std::uint64_t(e.kind) | std::uint64_t(e.taken) << 8 | std::uint64_t(e.front) << 9 |
                std::uint64_t(e.index) << 10)) *
          1099511628211ull;
    }
    remembered& r = seen[h % seen.size()];
    if (r.selected == 0 || r.label.count != l.count ||
        !std::equal(l.events.begin(), l.events.begin() + l.count, r.label.events.begin())) {
      r.label = l;
      r.selected = layers.select(l);
    }
    for (std::size_t k = 0; k < layers.count(); ++k)
      if (r.selected >> k & 1) radiance[k] += L;
    return r.selected;
  }

  void add(const tracer_path::path_trail& t, const glm::vec3& L) {
    const std::uint64_t kept = add(static_cast<const path_label&>(t), L) & ((std::uint64_t(1) << records.size()) - 1);
    if (kept == 0) return;
    // The events segments leave, eye first: the films a segment crosses are not where it ends.
    std::array<path_event, max_path_interactions> ends;
    int end_count = 0;
    for (int i = 0; i < t.count && end_count < max_path_interactions; ++i)
      if (t.events[std::size_t(i)].kind != path_event_kind::film)
        ends[std::size_t(end_count++)] = t.events[std::size_t(i)];
    // The light's order: the trail's last segment first, each turned around. A segment carries
    // what reaches the eye divided by the throughput from the eye to it.
    std::vector<ray_segment> out;
    out.reserve(std::size_t(t.segment_count));
    for (int j = t.segment_count - 1; j >= 0; --j) {
      const auto& g = t.segments[std::size_t(j)];
      ray_segment r;
      r.start = g.origin + g.dir * g.length;
      r.direction = -g.dir;
      r.length = g.length;
      for (int c = 0; c < 3; ++c) r.radiance[c] = g.throughput[c] > 0 ? L[c] / g.throughput[c] : 0.0f;
      r.event = ends[std::size_t(j + 1)];  // the one at the segment's far end
      out.push_back(r);
    }
    for (std::size_t k = 0; k < records.size(); ++k)
      if (kept >> k & 1) add_to_record(records[k], {x, y, sample, 0, 0, L}, out, segment_limits[k]);
  }
};

namespace tracer_path {
// Traces samples [first, first + count) of rows [y0, y1) with labels into `sink` (the trails when
// sink.records are given), as a render traces them, without the control variate.
void label_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count, layer_sink& sink,
                const std::atomic<bool>& cancel, std::uint64_t& rays);
}  // namespace tracer_path

}  // namespace airr
