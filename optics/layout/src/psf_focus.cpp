#include "airr/layout/psf_focus.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/core/number_range.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "psf_sample_blocks.hpp"

namespace airr {

namespace {

struct bundle_part {
  std::vector<glm::dvec3> origin, dir;
  std::vector<double> weight;
};

// What one sheet's rays share: the parts, the display point and the way to and from the sheet.
struct sheet_path {
  part_frame hm, rr, src;
  glm::dvec3 display_point{0}, aerial_point{0};
  bool by_reflection = false;
  double hm_factor = 1;
  std::shared_ptr<const emission_profile> emission;
};

// One ray from the display point to sheet point q and back past the half mirror; its weight is
// the power it carries per unit source radiance and display area, per unit sheet-sample density.
void trace_one(const sheet_path& sp, const retro_model& model, const glm::dvec3& q, const retro_samples& u,
               bundle_part& out) {
  // The light reaches q straight from the display point (through the half mirror), or mirrored
  // by it: then it arrives along the line from the display point's mirror image, the aerial point.
  const glm::dvec3 from = sp.by_reflection ? sp.display_point : sp.aerial_point;
  const glm::dvec3 to_q = q - from;
  const double dist = glm::length(to_q);
  if (!(dist > 0)) return;
  const glm::dvec3 d_in = to_q / dist;
  const auto at_hm = hit_part(sp.hm, from, d_in);
  if (!at_hm || glm::length(*at_hm - from) >= dist) return;
  const double cos_sheet = -glm::dot(d_in, sp.rr.n);
  if (cos_sheet <= 0) return;
  // Leaving the display: towards the half mirror point, mirrored back when the path folds there.
  const glm::dvec3 emitted = sp.by_reflection ? d_in : reflect(d_in, sp.hm.n);
  const double cos_display = glm::dot(emitted, sp.src.n);
  if (cos_display <= 0) return;
  const double profile = emission_at(sp.emission.get(), sp.src, -emitted);

  const retro_sample rs = model.sample(-to_local(sp.rr, d_in), u);
  if (!(rs.weight > 0) || !rs.retroreflected) return;
  const glm::dvec3 back = to_world(sp.rr, rs.wo);
  const glm::dvec3 start = q + rs.shift_mm.x * sp.rr.u + rs.shift_mm.y * sp.rr.v;
  const auto again = hit_part(sp.hm, start, back);
  if (!again) return;
  out.origin.push_back(*again);
  out.dir.push_back(sp.by_reflection ? reflect(back, sp.hm.n) : back);
  out.weight.push_back(profile * cos_display * cos_sheet / (dist * dist) * sp.rr.width * sp.rr.height * sp.hm_factor *
                       rs.weight);
}

// Samples sheet i's bundle into `b`; returns its power, or why it has none.
std::optional<double> add_sheet_bundle(const scene& s, std::size_t sheet, const retro_model& model,
                                       const focus_params& p, focus_bundle& b, std::string& why) {
  sheet_path sp;
  sp.hm = half_mirror_frame(s);
  sp.rr = retroreflector_frame(s, sheet);
  sp.src = source_frame(s);
  sp.aerial_point = b.aerial_point;
  sp.display_point = b.aerial_point - 2.0 * glm::dot(b.aerial_point - sp.hm.center, sp.hm.n) * sp.hm.n;
  sp.by_reflection = sheet_seen_by_reflection(s, sheet);
  sp.hm_factor = s.half_mirror.reflectance * s.half_mirror.transmittance;
  sp.emission = scene_emission_profile(s);
  if (!inside_part(sp.src, part_local(sp.src, sp.display_point))) {
    why = "the aerial point's display point is off the display";
    return std::nullopt;
  }

  // The sheet point, the lobe and the shift stratify each other.
  const std::vector<bundle_part> parts = sample_in_blocks<bundle_part>(
      p.samples, p.seed, 1, 0xf0c5u, p.stratified,
      [&](const std::array<double, 6>& r, const retro_samples& u, bundle_part& part) {
        const glm::dvec3 q = part_point(sp.rr, (r[0] - 0.5) * sp.rr.width, (r[1] - 0.5) * sp.rr.height);
        trace_one(sp, model, q, u, part);
      });
  double power = 0;
  for (const bundle_part& part : parts) {
    b.origin.insert(b.origin.end(), part.origin.begin(), part.origin.end());
    b.dir.insert(b.dir.end(), part.dir.begin(), part.dir.end());
    b.weight.insert(b.weight.end(), part.weight.begin(), part.weight.end());
    for (double w : part.weight) power += w;
  }
  if (power <= 0) {
    why = "no ray from the display point returns past the half mirror";
    return std::nullopt;
  }
  return p.samples ? power / double(p.samples) : 0.0;
}

}  // namespace

focus_bundle sample_focus_bundle(const scene& s, const retro_model_list& models, const focus_params& p,
                                 const glm::dvec3& aerial_point) {
  check_sheet_models(s, models, "through focus");
  focus_bundle b;
  b.aerial_point = aerial_point;
  b.launched = p.samples;
  const pinhole_camera cam = make_camera(s);
  b.axis = glm::normalize(cam.position - aerial_point);
  b.x_axis = glm::normalize(cam.right - glm::dot(cam.right, b.axis) * b.axis);
  b.y_axis = glm::cross(b.axis, b.x_axis);
  std::string first_error;
  for (std::size_t i = 0; i < models.size(); ++i) {
    std::string why;
    const auto power = add_sheet_bundle(s, i, *models[i], p, b, why);
    const std::string where = "through focus: retroreflectors[" + std::to_string(i) + "]: ";
    if (!power && first_error.empty()) first_error = where + why;
    b.sheets.push_back({.sheet = i,
                        .brightness = power.value_or(0.0),
                        .by_reflection = sheet_seen_by_reflection(s, i),
                        .missed = power ? std::string() : where + why});
  }
  if (b.weight.empty()) throw input_error(first_error);
  return b;
}

psf_samples cut_focus_bundle(const focus_bundle& b, double offset_mm) {
  psf_samples out;
  out.launched = b.weight.size();
  out.sheets = b.sheets;
  double total = 0;
  for (double w : b.weight) total += w;
  const glm::dvec3 centre = b.aerial_point + offset_mm * b.axis;
  for (std::size_t i = 0; i < b.weight.size(); ++i) {
    const double along = glm::dot(b.dir[i], b.axis);
    if (std::abs(along) < 1e-12) continue;
    const glm::dvec3 x = b.origin[i] + (glm::dot(centre - b.origin[i], b.axis) / along) * b.dir[i] - centre;
    out.offset_mm.emplace_back(glm::dot(x, b.x_axis), glm::dot(x, b.y_axis));
    out.weight.push_back(b.weight[i] / total * double(out.launched));
  }
  return out;
}

std::vector<double> parse_focus_offsets(const std::string& text) {
  return range_values(parse_number_range(text, "--focus " + text, 201));
}

}  // namespace airr
