#include "airr/render/tracer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "airr/core/error.hpp"
#include "airr/core/low_discrepancy.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/path_polarization.hpp"
#include "display_radiance.hpp"
#include "tracer_path.hpp"
#include "tracer_surroundings.hpp"

namespace airr {

// Camera rays of this many neighbouring pixels are intersected together.
static constexpr int camera_stream = 64;

void build_tracer_scene(tracer_scene& ts, const embree_device& device, const scene& s, retro_model_list models) {
  // Everything that can fail is built first, so a bad edit leaves the previous state intact.
  std::vector<std::string> part_meshes = {resolve_scene_path(s, s.source.mesh),
                                          resolve_scene_path(s, s.half_mirror.mesh)};
  for (const auto& r : s.retroreflectors) part_meshes.push_back(resolve_scene_path(s, r.mesh));
  std::vector<tracer_scene::prop> props;
  for (std::size_t i = 0; i < s.props.size(); ++i) {
    const prop_params& p = s.props[i];
    if (!p.visible) continue;
    props.push_back({p, prop_mesh(s, p), pose_rotation(p.pose), std::uint16_t(i)});
  }
  // A prototype's key names its file, and for props the loaded mesh (a changed file is a new one).
  std::vector<std::string> keys;
  for (const auto& path : part_meshes) keys.push_back("part:" + path);
  for (const auto& p : props) keys.push_back(prop_mesh_key(p.params, p.mesh.get()));
  std::unique_ptr<embree_instanced_scene> embree;
  if (!ts.embree || ts.embree->keys() != keys) {
    std::vector<instance_mesh> meshes;
    std::map<std::string, std::shared_ptr<const triangle_mesh>> parts;
    for (std::size_t i = 0; i < part_meshes.size(); ++i) {
      auto& m = parts[part_meshes[i]];
      if (!m)
        m = std::make_shared<const triangle_mesh>(part_meshes[i].empty() ? make_unit_panel()
                                                                         : load_gltf_mesh(part_meshes[i]));
      meshes.push_back({keys[i], m});
    }
    for (std::size_t k = 0; k < props.size(); ++k) meshes.push_back({keys[part_meshes.size() + k], props[k].mesh});
    embree = std::make_unique<embree_instanced_scene>(device, meshes);
  }
  const std::string tex = resolve_scene_path(s, s.source.image);
  std::shared_ptr<const image_rgb> texture = tex.empty() ? nullptr : cached_image_pixels(tex);
  std::shared_ptr<const emission_profile> emission = scene_emission_profile(s);
  if (models.size() != s.retroreflectors.size()) models = make_sheet_models(s);

  if (embree) ts.embree = std::move(embree);
  ts.texture = std::move(texture);
  ts.emission = std::move(emission);
  ts.retro = std::move(models);
  ts.layout = s;
  ts.ambient = make_ambient_lights(s.environment);
  derive_half_mirror_light(ts.layout.half_mirror);
  ts.polarized = scene_polarizes(s) || ts.force_polarized || ts.stokes >= 0;
  if (ts.stokes >= 0) ts.use_model_image = false;  // it predicts what the eye sees, not S1 to S3
  ts.frames = {source_panel_frame(s), half_mirror_frame(s)};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) ts.frames.push_back(retroreflector_frame(s, i));
  ts.props = std::move(props);
  ts.first_prop = unsigned(ts.frames.size());
  ts.source_area = source_frame(s);
  ts.camera = make_camera(s);
  if (ts.layers) ts.layers = std::make_shared<const path_layers>(ts.layers->bound(s));
  ts.model.reset();  // it no longer matches the layout
  std::vector<glm::dmat4> transforms;
  for (const auto& f : ts.frames) transforms.push_back(part_transform(f));
  for (const auto& p : ts.props) transforms.push_back(prop_transform(p.params));
  ts.embree->set_transforms(transforms);
}

static glm::vec3 source_radiance(const tracer_scene& ts, const glm::dvec2& local) {
  return display_radiance(ts.source_area, ts.texture.get(), float(white_radiance(ts.layout.source)), local);
}

using tracer_path::component_of;
using tracer_path::light_sampled;
using tracer_path::meet_plate;
using tracer_path::meet_thin_half_mirror;
using tracer_path::no_label;
using tracer_path::no_polarization;
using tracer_path::path_stack;
using tracer_path::path_state;
using tracer_path::path_trail;
using tracer_path::polarized;
using tracer_path::push_display;
using tracer_path::push_half_mirror;
using tracer_path::push_sheet;
using tracer_path::scatter_at_prop;
using tracer_path::see_ambient;
using tracer_path::see_luminaire;

std::array<double, 6> pixel_sequence_rotation(const tracer_scene& ts, int px, int py) {
  pcg32 pixel_rng = sample_rng(std::uint64_t(py) * ts.camera.width + px, 0, ts.layout.seed ^ 0x5eedu);
  std::array<double, 6> rotation;
  for (double& r : rotation) r = pixel_rng.next_double();
  return rotation;
}

// The random numbers of one camera sample, drawn before it is traced: the pixel jitter and the
// first retroreflection's lobe and shift samples come from the pixel's rotated R6 point; its
// further numbers and the lens from the sample's generators.
struct sample_numbers {
  glm::dvec2 jitter{0.5};
  glm::dvec2 lens{0.5};
  retro_samples first_retro;
  pcg32 rng{0, 0};  // everything later along the path
};

static sample_numbers draw_sample_numbers(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                                          const std::array<double, 6>& rotation) {
  const std::array<double, 6> q = r6_point(sample_index, rotation);
  const std::uint64_t pixel = std::uint64_t(py) * ts.camera.width + px;
  sample_numbers n;
  n.rng = sample_rng(pixel, sample_index, ts.layout.seed);
  n.jitter = {q[0], q[1]};
  if (ts.camera.aperture_mm > 0) n.lens = {n.rng.next_double(), n.rng.next_double()};
  n.first_retro.lobe = {q[2], q[3]};
  n.first_retro.shift = {q[4], q[5]};
  n.first_retro.more = sample_rng(pixel, sample_index, ts.layout.seed ^ 0x6d6f7265u);
  return n;
}

static camera_ray first_ray(const tracer_scene& ts, int px, int py, const sample_numbers& n);

// `first`: the camera ray; `first_hit`: its hit when it was traced already (in a stream), else null.
// `layers`, when given, gets the radiance of each of ts.layers' layers; `each_luminaire` each
// luminaire's share of the luminaires' component.
static component_radiance trace_path(const tracer_scene& ts, sample_numbers n, const camera_ray& first,
                                     const RTCRayHit* first_hit, std::uint64_t& rays, layer_sink* layers = nullptr,
                                     glm::vec3* each_luminaire = nullptr);

static glm::vec3 total(const component_radiance& c) {
  glm::vec3 sum(0.0f);
  for (const glm::vec3& v : c) sum += v;
  return sum;
}

glm::vec3 trace_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index, std::uint64_t& rays) {
  return trace_sample(ts, px, py, sample_index, pixel_sequence_rotation(ts, px, py), rays);
}

glm::vec3 trace_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                       const std::array<double, 6>& rotation, std::uint64_t& rays) {
  const sample_numbers n = draw_sample_numbers(ts, px, py, sample_index, rotation);
  return total(trace_path(ts, n, first_ray(ts, px, py, n), nullptr, rays));
}

// With `layers`, the prediction is taken from the layers `variate_layers` too.
static component_radiance estimate_from(const tracer_scene& ts, int px, int py, const sample_numbers& n,
                                        const camera_ray& first, const RTCRayHit* first_hit, std::uint64_t& rays,
                                        layer_sink* layers = nullptr, std::uint64_t variate_layers = 0,
                                        glm::vec3* each_luminaire = nullptr) {
  component_radiance c = trace_path(ts, n, first, first_hit, rays, layers, each_luminaire);
  if (ts.model) {
    const glm::vec3 g = model_prediction(*ts.model, px, py, n.jitter, n.first_retro);
    c[component_aerial] -= g;
    for (std::size_t k = 0; layers && k < ts.layers->count(); ++k)
      if (variate_layers >> k & 1) layers->radiance[k] -= g;
  }
  return c;
}

component_radiance estimate_components(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                                       const std::array<double, 6>& rotation, std::uint64_t& rays) {
  const sample_numbers n = draw_sample_numbers(ts, px, py, sample_index, rotation);
  return estimate_from(ts, px, py, n, first_ray(ts, px, py, n), nullptr, rays);
}

glm::vec3 estimate_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                          const std::array<double, 6>& rotation, std::uint64_t& rays) {
  return total(estimate_components(ts, px, py, sample_index, rotation, rays));
}

glm::vec3 model_value(const tracer_scene& ts, int px, int py) {
  if (!ts.model) return glm::vec3(0.0f);
  const float* p = ts.model->image.at(px, py);
  return {p[0], p[1], p[2]};
}

static camera_ray first_ray(const tracer_scene& ts, int px, int py, const sample_numbers& n) {
  return make_camera_ray(ts.camera, px + n.jitter.x, py + n.jitter.y, n.lens);
}

template <class Polarization, class Label>
static component_radiance trace_path_as(const tracer_scene& ts, sample_numbers n, const camera_ray& first,
                                        const RTCRayHit* first_hit, std::uint64_t& rays, layer_sink* layers,
                                        glm::vec3* each_luminaire) {
  constexpr bool with_polarization = polarized<Polarization>;
  pcg32& rng = n.rng;
  const auto& hm = ts.layout.half_mirror;
  const ambient_lights& ambient = ts.ambient;

  path_stack<Polarization, Label> stack;
  stack.paths[stack.pending++] = {first.origin, first.dir, glm::vec3(1.0f), 0};
  stack.paths[0].label.push({path_event_kind::eye});
  if constexpr (with_polarization)
    stack.paths[0].pol = path_polarization::at_observer(ts.layout, ts.camera.right, ts.camera.up, first.dir, ts.stokes);
  component_radiance radiance{};
  radiance.each_luminaire = each_luminaire;

  while (stack.pending > 0) {
    path_state<Polarization, Label> p = stack.paths[--stack.pending];
    for (; p.depth < ts.layout.render.max_depth; ++p.depth) {
      RTCRayHit rh;
      if (p.depth == 0 && first_hit) {
        rh = *first_hit;  // only the camera ray starts at depth 0
      } else {
        rh = make_ray_hit(p.origin, p.dir, p.depth == 0 ? 0.0f : ray_epsilon_mm);
        intersect(ts.embree->get(), rh);
        ++rays;
      }
      const bool missed = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID;
      if (!ambient.luminaires.empty()) {
        const double t_max = missed ? std::numeric_limits<double>::infinity() : double(rh.ray.tfar);
        const luminaire_hit lh = meet_luminaire(ambient, p.origin, p.dir, t_max);
        if (lh.which >= 0) {
          if (lh.front) see_luminaire(ts, lh.which, p, radiance, layers);
          break;  // a luminaire's back is black
        }
      }
      if (missed) {
        if (ambient.room > 0)
          see_ambient(p, p.label, p.throughput * ambient.room, component_room, ambient_room, radiance, layers);
        if (sees_sun(ambient, p.dir) && !light_sampled(p))
          see_ambient(p, p.label, p.throughput * ambient.sun, component_sun, ambient_sun, radiance, layers);
        break;
      }
      if constexpr (std::is_same_v<Label, path_trail>) p.label.add_segment(p.origin, p.dir, rh.ray.tfar, p.throughput);

      const unsigned part = rh.hit.instID[0];
      if (part >= ts.first_prop) {
        if (!scatter_at_prop(ts, ts.props[part - ts.first_prop], rh, p, rng, radiance, layers, rays)) break;
        continue;
      }
      const part_frame& f = ts.frames[part];
      const glm::dvec3 hit = p.origin + p.dir * double(rh.ray.tfar);
      const double cos_n = glm::dot(p.dir, f.n);

      if (part == part_source) {
        if (cos_n < 0) {
          const float profile = float(emission_at(ts.emission.get(), f, p.dir));
          glm::vec3 L;
          if constexpr (with_polarization) {
            L = p.throughput * profile * source_radiance(ts, part_local(f, hit)) * p.pol.emitted(ts.layout.source, f);
          } else {
            L = p.throughput * profile * source_radiance(ts, part_local(f, hit));
          }
          radiance[component_of(p)] += L;
          if constexpr (!std::is_same_v<Label, no_label>) {
            push_display(p.label, ts.layout.source.films);
            layers->add(p.label, L);
          }
        }
        break;  // the display absorbs what it does not emit; its back emits nothing
      }
      if (part == part_half_mirror) {
        const bool goes_on = hm.kind == half_mirror_kind::plate ? meet_plate(hm, f, hit, p, stack, rng)
                                                                : meet_thin_half_mirror(hm, f, hit, p, stack, rng);
        if (!goes_on) break;
        continue;
      }
      // Retroreflector: only its front face retroreflects.
      if (cos_n >= 0) break;
      const glm::dvec3 wi = -to_local(f, p.dir);
      retro_samples u = n.first_retro;
      if (!p.first_retro_used) {
        p.first_retro_used = true;
      } else {
        u.lobe = {rng.next_double(), rng.next_double()};
        u.shift = {rng.next_double(), rng.next_double()};
        u.more = rng.split();
      }
      const retro_model& sheet = *ts.retro[part - part_first_sheet];
      const retro_sample rs = with_polarization ? sheet.sample_polarized(wi, u) : sheet.sample(wi, u);
      if (!(rs.weight > 0)) break;
      p.dir = glm::normalize(to_world(f, rs.wo));
      if constexpr (with_polarization) {
        p.pol.sheet(ts.layout.retroreflectors[part - part_first_sheet], f, p.dir, rs.polarization, wi, rs.wo);
      }
      p.origin = hit + rs.shift_mm.x * f.u + rs.shift_mm.y * f.v;
      p.throughput *= glm::vec3(rs.channels) * float(rs.weight);
      const auto k = std::uint16_t(part - part_first_sheet);
      push_sheet(p.label, ts.layout.retroreflectors[k].films, rs.retroreflected, k);
      if (rs.retroreflected) {
        ++p.retroreflections;
      } else {
        ++p.sheet_scatterings;
      }
    }
  }
  return radiance;
}

static component_radiance trace_path(const tracer_scene& ts, sample_numbers n, const camera_ray& first,
                                     const RTCRayHit* first_hit, std::uint64_t& rays, layer_sink* layers,
                                     glm::vec3* each_luminaire) {
  glm::vec3* e = each_luminaire;
  if (layers && !layers->records.empty()) {
    return ts.polarized ? trace_path_as<path_polarization, path_trail>(ts, n, first, first_hit, rays, layers, e)
                        : trace_path_as<no_polarization, path_trail>(ts, n, first, first_hit, rays, layers, e);
  }
  if (layers) {
    return ts.polarized ? trace_path_as<path_polarization, path_label>(ts, n, first, first_hit, rays, layers, e)
                        : trace_path_as<no_polarization, path_label>(ts, n, first, first_hit, rays, layers, e);
  }
  return ts.polarized ? trace_path_as<path_polarization, no_label>(ts, n, first, first_hit, rays, nullptr, e)
                      : trace_path_as<no_polarization, no_label>(ts, n, first, first_hit, rays, nullptr, e);
}

std::uint64_t model_layers(const tracer_scene& ts) {
  if (!ts.layers || !ts.model) return 0;
  std::uint64_t mask = ~std::uint64_t(0);
  for (const auto& sheet : ts.model->sheets) {
    if (sheet->bins.empty()) continue;
    const psf_chief_ray& c = sheet->bins.front().chief;
    // The modelled path, traced from the eye: to the half mirror along the camera's ray, to the
    // sheet, back to the half mirror and on to the display.
    const bool eye_side_front = glm::dot(c.camera_dir, c.hm.n) < 0;
    // The sheet sends the light straight back the way the camera's ray came to it.
    const glm::dvec3 to_sheet = c.by_reflection ? reflect(c.camera_dir, c.hm.n) : c.camera_dir;
    const bool display_side_front = glm::dot(-to_sheet, c.hm.n) < 0;
    const auto& films = ts.layout.half_mirror.films;
    path_label l;
    l.push({path_event_kind::eye});
    push_half_mirror(l, films, c.by_reflection, eye_side_front, 0);
    push_sheet(l, ts.layout.retroreflectors[std::size_t(c.sheet)].films, true, std::uint16_t(c.sheet));
    push_half_mirror(l, films, !c.by_reflection, display_side_front, 0);
    push_display(l, ts.layout.source.films);
    mask &= ts.layers->select(l);
  }
  const std::uint64_t unmatched = std::uint64_t(1) << ts.layers->layers.size();
  return mask == ~std::uint64_t(0) || mask == 0 ? unmatched : mask;
}

static void add_prediction(const tracer_scene& ts, int x, int y, std::uint64_t i, const sample_numbers& n,
                           prediction_sums& predictions);

bool trace_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                std::vector<float>& sums, const std::atomic<bool>& cancel, std::uint64_t& rays,
                std::vector<float>* odd_sums, std::vector<float>* component_sums, prediction_sums* predictions,
                std::vector<float>* layer_sums, const component_slots& slots) {
  const int w = ts.camera.width;
  if (!ts.layers) layer_sums = nullptr;
  const std::size_t layer_count = layer_sums ? ts.layers->count() : 0;
  const std::uint64_t variate_layers = predictions ? 0 : model_layers(ts);
  const bool keep_predictions = predictions && ts.model && !predictions->all.empty();
  std::array<glm::vec3, max_path_layers + 1> layer_radiance;
  std::array<glm::vec3, max_luminaires> luminaire_radiance;
  const int luminaires = component_sums ? slots.luminaires : 0;
  std::optional<layer_sink> sink;
  if (layer_sums) sink.emplace(*ts.layers, layer_radiance.data());
  std::vector<std::array<double, 6>> rotations(std::size_t(w), std::array<double, 6>{});
  std::array<sample_numbers, camera_stream> numbers;
  std::array<camera_ray, camera_stream> camera_rays;
  std::array<RTCRayHit, camera_stream> hits;
  for (int y = y0; y < y1; ++y) {
    if (cancel.load(std::memory_order_relaxed)) return false;
    for (int x = 0; x < w; ++x) rotations[std::size_t(x)] = pixel_sequence_rotation(ts, x, y);
    // Each sample index across a run of the row's pixels: their camera rays go out as one
    // coherent stream. A pixel still gets its samples in order.
    for (std::uint64_t i = first; i < first + count; ++i) {
      for (int x0 = 0; x0 < w; x0 += camera_stream) {
        const int n = std::min(camera_stream, w - x0);
        for (int k = 0; k < n; ++k) {
          numbers[std::size_t(k)] = draw_sample_numbers(ts, x0 + k, y, i, rotations[std::size_t(x0 + k)]);
          const camera_ray& r = camera_rays[std::size_t(k)] = first_ray(ts, x0 + k, y, numbers[std::size_t(k)]);
          hits[std::size_t(k)] = make_ray_hit(r.origin, r.dir);
        }
        intersect_coherent(ts.embree->get(), hits.data(), unsigned(n));
        rays += std::uint64_t(n);
        for (int k = 0; k < n; ++k) {
          const int x = x0 + k;
          float* acc = sums.data() + 3 * (std::size_t(y) * w + x);
          float* odd = odd_sums ? odd_sums->data() + 3 * (std::size_t(y) * w + x) : nullptr;
          const sample_numbers& numbers_k = numbers[std::size_t(k)];
          const camera_ray& ray_k = camera_rays[std::size_t(k)];
          layer_sink* layers_out = sink ? &*sink : nullptr;
          if (layers_out) std::fill_n(layer_radiance.data(), layer_count, glm::vec3(0.0f));
          std::fill_n(luminaire_radiance.data(), luminaires, glm::vec3(0.0f));
          glm::vec3* each_luminaire = luminaires ? luminaire_radiance.data() : nullptr;
          const component_radiance c =
              predictions ? trace_path(ts, numbers_k, ray_k, &hits[std::size_t(k)], rays, layers_out, each_luminaire)
                          : estimate_from(ts, x, y, numbers_k, ray_k, &hits[std::size_t(k)], rays, layers_out,
                                          variate_layers, each_luminaire);
          if (keep_predictions) add_prediction(ts, x, y, i, numbers_k, *predictions);
          const glm::vec3 L = total(c);
          if (component_sums) {
            float* comp = component_sums->data() + 3 * std::size_t(slots.count) * (std::size_t(y) * w + x);
            for (int j = 0; j < component_count; ++j) {
              const int at = slots.slot[std::size_t(j)];
              if (at < 0) continue;
              comp[3 * at] += c[std::size_t(j)].x;
              comp[3 * at + 1] += c[std::size_t(j)].y;
              comp[3 * at + 2] += c[std::size_t(j)].z;
            }
            for (int j = 0; j < luminaires; ++j) {
              float* one = comp + 3 * (slots.first_luminaire + j);
              one[0] += luminaire_radiance[std::size_t(j)].x;
              one[1] += luminaire_radiance[std::size_t(j)].y;
              one[2] += luminaire_radiance[std::size_t(j)].z;
            }
          }
          if (layer_sums) {
            float* lay = layer_sums->data() + 3 * layer_count * (std::size_t(y) * w + x);
            for (std::size_t j = 0; j < layer_count; ++j) {
              lay[3 * j] += layer_radiance[j].x;
              lay[3 * j + 1] += layer_radiance[j].y;
              lay[3 * j + 2] += layer_radiance[j].z;
            }
          }
          acc[0] += L.x;
          acc[1] += L.y;
          acc[2] += L.z;
          if (odd && (i & 1)) {
            odd[0] += L.x;
            odd[1] += L.y;
            odd[2] += L.z;
          }
        }
      }
    }
  }
  return true;
}

void tracer_path::label_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                             layer_sink& sink, const std::atomic<bool>& cancel, std::uint64_t& rays) {
  for (int y = y0; y < y1 && !cancel.load(std::memory_order_relaxed); ++y) {
    for (int x = 0; x < ts.camera.width; ++x) {
      const std::array<double, 6> rotation = pixel_sequence_rotation(ts, x, y);
      for (std::uint64_t i = first; i < first + count; ++i) {
        const sample_numbers n = draw_sample_numbers(ts, x, y, i, rotation);
        sink.x = std::uint32_t(x);
        sink.y = std::uint32_t(y);
        sink.sample = i;
        trace_path(ts, n, first_ray(ts, x, y, n), nullptr, rays, &sink);
      }
    }
  }
}

static void add_prediction(const tracer_scene& ts, int x, int y, std::uint64_t i, const sample_numbers& n,
                           prediction_sums& predictions) {
  const glm::vec3 m = model_prediction(*ts.model, x, y, n.jitter, n.first_retro);
  const std::size_t p = 3 * (std::size_t(y) * ts.camera.width + x);
  for (int c = 0; c < 3; ++c) {
    predictions.all[p + std::size_t(c)] += m[c];
    if (i & 1) predictions.odd[p + std::size_t(c)] += m[c];
  }
}

bool add_predictions(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                     prediction_sums& predictions, const std::atomic<bool>& cancel) {
  if (!ts.model || predictions.all.empty()) return true;
  for (int y = y0; y < y1; ++y) {
    if (cancel.load(std::memory_order_relaxed)) return false;
    for (int x = 0; x < ts.camera.width; ++x) {
      const std::array<double, 6> rotation = pixel_sequence_rotation(ts, x, y);
      for (std::uint64_t i = first; i < first + count; ++i) {
        add_prediction(ts, x, y, i, draw_sample_numbers(ts, x, y, i, rotation), predictions);
      }
    }
  }
  return true;
}

pixel_predictions predict_pixel(const tracer_scene& ts, int px, int py, std::uint64_t first, std::uint64_t count) {
  pixel_predictions out;
  if (!ts.model) return out;
  const std::array<double, 6> rotation = pixel_sequence_rotation(ts, px, py);
  const std::vector<model_pixel> pixels = model_pixels_at(*ts.model, px, py);
  for (std::uint64_t i = first; i < first + count; ++i) {
    const sample_numbers n = draw_sample_numbers(ts, px, py, i, rotation);
    const glm::dvec3 m = model_prediction(*ts.model, pixels, n.jitter, n.first_retro);
    out.all += m;
    if (i & 1) out.odd += m;
  }
  return out;
}

}  // namespace airr
