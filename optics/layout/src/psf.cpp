#include "airr/layout/psf.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/path_polarization.hpp"
#include "psf_sample_blocks.hpp"

namespace airr {

double psf_samples::brightness() const {
  double sum = 0;
  for (double w : weight) sum += w;
  return launched ? sum / double(launched) : 0.0;
}

ideal_return follow_ideal_return(const part_frame& hm, const part_frame& rr, const part_frame& src,
                                 const glm::dvec3& origin, const glm::dvec3& dir, bool by_reflection) {
  ideal_return r;
  const auto p1 = hit_part(hm, origin, dir);
  if (!p1) return r.failed = ideal_return::step::half_mirror, r;
  r.towards_sheet = by_reflection ? reflect(dir, hm.n) : dir;
  const auto p2 = hit_part(rr, *p1, r.towards_sheet);
  if (!p2 || glm::dot(r.towards_sheet, rr.n) >= 0) return r.failed = ideal_return::step::sheet_front, r;
  r.sheet_point = *p2;
  // Either way the returning ray leaves the half mirror as the camera ray's mirror image: the
  // display is the aerial image's.
  r.towards_display = reflect(-dir, hm.n);
  const auto q1 = hit_part(hm, *p2, -r.towards_sheet);
  const auto q2 = q1 ? hit_part(src, *q1, r.towards_display, false) : std::nullopt;
  if (!q2) return r.failed = ideal_return::step::display_plane, r;
  r.landing = *q2;
  return r;
}

psf_chief_ray chief_ray_through(const scene& s, const glm::dvec3& aerial_point, std::size_t sheet) {
  psf_chief_ray c{half_mirror_frame(s), retroreflector_frame(s, sheet), source_frame(s)};
  c.sheet = sheet;
  c.by_reflection = sheet_seen_by_reflection(s, sheet);
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 d0 = glm::normalize(aerial_point - cam.position);
  const ideal_return r = follow_ideal_return(c.hm, c.rr, c.src, cam.position, d0, c.by_reflection);
  const std::string where = "psf: retroreflectors[" + std::to_string(sheet) + "]: ";
  switch (r.failed) {
    case ideal_return::step::half_mirror:
      throw input_error(where + "the camera ray through the aerial image misses the half mirror");
    case ideal_return::step::sheet_front:
      throw input_error(where + std::string("the camera ray ") + (c.by_reflection ? "mirrored by" : "through") +
                        " the half mirror misses the sheet's front");
    case ideal_return::step::display_plane:
      throw input_error(where + "the retroreflected chief ray misses the source plane");
    case ideal_return::step::none:
      break;
  }
  c.sheet_point = r.sheet_point;
  c.ideal = r.landing;
  c.camera_dir = d0;
  c.camera_right = cam.right;
  c.camera_up = cam.up;
  c.wi = -to_local(c.rr, r.towards_sheet);
  // Along the path: straight on through the half mirror, or folded at it.
  const glm::dvec3 fold = c.by_reflection ? *hit_part(c.hm, cam.position, d0) : aerial_point;
  c.rr_distance_mm = glm::length(r.sheet_point - fold) + glm::length(fold - aerial_point);
  return c;
}

std::optional<psf_landing> psf_landing_of(const psf_chief_ray& c, const retro_sample& rs) {
  const glm::dvec3 dir = to_world(c.rr, rs.wo);
  const glm::dvec3 origin = c.sheet_point + rs.shift_mm.x * c.rr.u + rs.shift_mm.y * c.rr.v;
  const auto at_hm = hit_part(c.hm, origin, dir);
  if (!at_hm) return std::nullopt;
  const glm::dvec3 towards_display = c.by_reflection ? dir : reflect(dir, c.hm.n);
  const auto at_source = hit_part(c.src, *at_hm, towards_display, false);
  if (!at_source) return std::nullopt;
  return psf_landing{*at_source - c.ideal, towards_display};
}

// The chief path's polarization from the observer to the sheet, the same for every sample.
static path_polarization chief_path_to_sheet(const scene& s, const psf_chief_ray& c) {
  path_polarization pol = path_polarization::at_observer(s, c.camera_right, c.camera_up, c.camera_dir);
  if (c.by_reflection) {
    pol.half_mirror_reflected(s.half_mirror, c.hm, reflect(c.camera_dir, c.hm.n));
  } else {
    pol.half_mirror_passed(s.half_mirror, c.hm);
  }
  return pol;
}

// What a sample's polarization along the chief path lets through of the display's white, per unit
// of its unpolarized weight (docs/polarization.md): the tracer's path for that sample. `pol`: the
// path to the sheet (chief_path_to_sheet).
static double chief_path_polarization(const scene& s, const psf_chief_ray& c, path_polarization pol,
                                      const retro_sample& rs) {
  const half_mirror_params& hm = s.half_mirror;
  const glm::dvec3 back = to_world(c.rr, rs.wo);
  pol.sheet(s.retroreflectors[c.sheet], c.rr, back, rs.polarization, c.wi, rs.wo);
  if (c.by_reflection) {
    pol.half_mirror_passed(hm, c.hm);
  } else {
    pol.half_mirror_reflected(hm, c.hm, reflect(back, c.hm.n));
  }
  return pol.emitted_white(s.source, c.src);
}

// Samples one sheet through its chief ray into `out` (which keeps what it holds); returns the
// sheet's brightness. Each sample carries the display's emission profile in the direction it left
// the display (`emission`, null when Lambertian), as the tracer weights its paths. `polarized`: the
// scene, when it polarizes.
static double add_sheet_samples(const psf_chief_ray& chief, const retro_model& model, const psf_params& p,
                                double hm_factor, const emission_profile* emission, psf_samples& out,
                                const scene* polarized) {
  const part_frame& src = chief.src;
  const glm::dvec3 wi = chief.wi;
  const std::optional<path_polarization> to_sheet =
      polarized ? std::optional(chief_path_to_sheet(*polarized, chief)) : std::nullopt;
  // The lobe and shift samples stratify each other across the PSF's samples (a rotated R6
  // sequence, as the tracer's pixels use); the rest comes from the per-sample generator.
  // Every sample meets the sheet at wi: the model prepares for it once.
  const std::unique_ptr<const retro_at_incidence> at_wi = polarized ? nullptr : model.at_incidence(wi);
  const std::vector<psf_samples> parts = sample_in_blocks<psf_samples>(
      p.samples, p.seed, 0, 0x5eedu, p.stratified,
      [&](const std::array<double, 6>&, const retro_samples& u, psf_samples& part) {
        const retro_sample rs = polarized ? model.sample_polarized(wi, u) : at_wi->sample(u);
        if (!(rs.weight > 0) || !rs.retroreflected) return;
        const auto landing = psf_landing_of(chief, rs);
        if (!landing) return;
        // The image of a point shows where rays land relative to the ideal point,
        // point-mirrored; source (u, v) map to aerial (x, y).
        part.offset_mm.emplace_back(-glm::dot(landing->offset, src.u), -glm::dot(landing->offset, src.v));
        part.weight.push_back(rs.weight * hm_factor * emission_at(emission, src, landing->towards_display) *
                              (polarized ? chief_path_polarization(*polarized, chief, *to_sheet, rs) : 1.0));
      });
  double sum = 0;
  for (const psf_samples& part : parts) {
    out.offset_mm.insert(out.offset_mm.end(), part.offset_mm.begin(), part.offset_mm.end());
    out.weight.insert(out.weight.end(), part.weight.begin(), part.weight.end());
    for (double w : part.weight) sum += w;
  }
  return p.samples ? sum / double(p.samples) : 0.0;
}

static psf_sheet_share share_of(const psf_chief_ray& c, double brightness) {
  return {.sheet = c.sheet,
          .brightness = brightness,
          .by_reflection = c.by_reflection,
          .rr_distance_mm = c.rr_distance_mm,
          .incidence_deg = polar_angle_deg(c.wi),
          .missed = {}};
}

psf_samples sample_sheet_psf(const scene& s, std::size_t sheet, const retro_model& model, const psf_params& p,
                             const glm::dvec3& aerial_point) {
  const psf_chief_ray chief = chief_ray_through(s, aerial_point, sheet);
  psf_samples out;
  out.launched = p.samples;
  out.rr_distance_mm = chief.rr_distance_mm;
  out.incidence_deg = polar_angle_deg(chief.wi);
  out.offset_mm.reserve(p.samples);
  out.weight.reserve(p.samples);
  const double brightness = add_sheet_samples(chief, model, p, s.half_mirror.reflectance * s.half_mirror.transmittance,
                                              scene_emission_profile(s).get(), out, scene_polarizes(s) ? &s : nullptr);
  out.sheets.push_back(share_of(chief, brightness));
  return out;
}

psf_samples sample_psf(const scene& s, const retro_model_list& models, const psf_params& p,
                       const glm::dvec3& aerial_point) {
  check_sheet_models(s, models, "psf");
  psf_samples out;
  out.launched = p.samples;
  std::string first_error;
  bool reached = false;
  const std::shared_ptr<const emission_profile> emission = scene_emission_profile(s);
  for (std::size_t i = 0; i < models.size(); ++i) {
    std::optional<psf_chief_ray> chief;
    try {
      chief = chief_ray_through(s, aerial_point, i);
    } catch (const input_error& e) {
      if (first_error.empty()) first_error = e.what();
      out.sheets.push_back({.sheet = i, .missed = e.what()});
      continue;
    }
    if (!reached) {
      out.rr_distance_mm = chief->rr_distance_mm;
      out.incidence_deg = polar_angle_deg(chief->wi);
      reached = true;
    }
    const double brightness =
        add_sheet_samples(*chief, *models[i], p, s.half_mirror.reflectance * s.half_mirror.transmittance,
                          emission.get(), out, scene_polarizes(s) ? &s : nullptr);
    out.sheets.push_back(share_of(*chief, brightness));
  }
  if (!reached) throw input_error(first_error);
  return out;
}

psf_samples sample_psf(const scene& s, const retro_model_list& models, const psf_params& p) {
  return sample_psf(s, models, p, aerial_image_center(s));
}

psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p, const glm::dvec3& aerial_point) {
  return sample_sheet_psf(s, 0, model, p, aerial_point);
}

psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p) {
  return sample_sheet_psf(s, 0, model, p, aerial_image_center(s));
}

double energy_radius(const psf_samples& psf, double fraction) { return energy_radii(psf, {fraction})[0]; }

std::vector<double> energy_radii(const psf_samples& psf, const std::vector<double>& fractions) {
  std::vector<std::pair<double, double>> rw(psf.offset_mm.size());
  double total = 0;
  for (std::size_t i = 0; i < rw.size(); ++i) {
    rw[i] = {glm::length(psf.offset_mm[i]), psf.weight[i]};
    total += psf.weight[i];
  }
  std::vector<double> radii(fractions.size(), 0.0);
  if (total <= 0) return radii;
  std::sort(rw.begin(), rw.end());
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    radii[k] = rw.back().first;
    double acc = 0;
    for (const auto& [r, w] : rw) {
      acc += w;
      if (acc >= fractions[k] * total) {
        radii[k] = r;
        break;
      }
    }
  }
  return radii;
}

}  // namespace airr
