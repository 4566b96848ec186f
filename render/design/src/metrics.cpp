#include "airr/design/metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "airr/core/error.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/mtf_routes.hpp"
#include "airr/measure/viewing_zone_full.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/render/prop_hits.hpp"

namespace airr {

namespace {

// The eye metrics of one layout at one eye, each worked out once when first asked for; the
// stray-light ratio and every ghost metric from one small render.
class eye_metrics {
 public:
  // `parts`: the layout's viewing parts, when a visible fraction is asked for; `expressions`: the
  // ghost metrics' (each once).
  eye_metrics(const design_spec& spec, const scene& s, const glm::dvec3& eye, const viewing_parts* parts,
              std::vector<std::string> expressions)
      : spec_(spec), s_(observer_at(s, eye)), eye_(eye), parts_(parts), expressions_(std::move(expressions)) {}

  double value(design_metric m, const std::string& expression) {
    if (m == design_metric::visible_fraction) return visible_fraction(*parts_, eye_);
    const double inf = std::numeric_limits<double>::infinity();
    if (metric_takes_expression(m)) {
      const auto at = std::find(expressions_.begin(), expressions_.end(), expression);
      if (at == expressions_.end()) throw std::logic_error("eye_metrics: an expression it was not given");
      const ghost_seen& g = view().ghosts[std::size_t(at - expressions_.begin())];
      // Unseen: no aerial image to spoil (the ratio's worst), or no ghost to be near it (the
      // separation's best).
      if (m == design_metric::ghost_ratio) return std::isnan(g.ratio) ? inf : g.ratio;
      return std::isnan(g.separation_arcmin) ? inf : g.separation_arcmin;
    }
    if (m == design_metric::stray_light) {
      const double r = view().stray_ratio;
      return std::isnan(r) ? inf : r;  // none of the aerial image seen
    }
    if (m == design_metric::contrast) return view().seen.contrast;
    if (m == design_metric::legible_share) return view().seen.share_above.front();
    if (m == design_metric::char_height_mm)
      return psf_legible_character(s_, psf(), view().seen.contrast, spec_.legibility).height_mm;
    const psf_samples& p = psf();
    switch (m) {
      case design_metric::mean_mtf:
        return mtf().mean_mtf;
      case design_metric::mtf50_lp_per_mm:
        return mtf().mtf50_lp_per_mm.value_or(4.0);  // above 0.5 as far as searched
      case design_metric::r50_mm:
        return p.offset_mm.empty() ? std::numeric_limits<double>::infinity() : energy_radius(p, 0.5);
      case design_metric::brightness:
        return p.brightness();
      case design_metric::luminance_cd_m2:
        return p.brightness() * white_radiance(s_.source);
      default:
        return 0;
    }
  }

 private:
  const psf_samples& psf() {
    if (!psf_) psf_ = scene_psf(s_, spec_.search.psf_samples);
    return *psf_;
  }
  const mtf_summary& mtf() {
    if (!mtf_) mtf_ = psf_route_mtf(psf(), 0.0);
    return *mtf_;
  }
  const eye_view_metrics& view() {
    if (!view_) view_ = eye_view_from(s_, eye_, expressions_, {.contrast_thresholds = {spec_.legible_contrast}});
    return *view_;
  }

  const design_spec& spec_;
  scene s_;
  glm::dvec3 eye_;
  const viewing_parts* parts_;
  std::optional<psf_samples> psf_;
  std::optional<mtf_summary> mtf_;
  std::vector<std::string> expressions_;
  std::optional<eye_view_metrics> view_;
};

// A metric as a spec asks for it: with its path expression, for the ghost metrics.
struct asked_metric {
  design_metric metric;
  std::string expression;
  auto operator<=>(const asked_metric&) const = default;
};

}  // namespace

scene observer_at(scene s, const glm::dvec3& eye) {
  const glm::dvec3 target = aerial_image_center(s);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {eye.x, eye.y, eye.z};
  s.observer.look_at_mm = {target.x, target.y, target.z};
  return s;
}

glm::dvec3 device_size_mm(const scene& s) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  auto add = [&](const part_frame& f) {
    for (const glm::dvec3& c : corners(f)) lo = glm::min(lo, c), hi = glm::max(hi, c);
  };
  add(source_panel_frame(s));
  add(half_mirror_frame(s));
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) add(retroreflector_frame(s, i));
  return hi - lo;
}

double prop_cut_length_mm(const scene& s) {
  std::vector<part_frame> parts = {source_panel_frame(s), half_mirror_frame(s)};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) parts.push_back(retroreflector_frame(s, i));
  double length = 0;
  for (const prop_params& p : s.props) {
    if (!p.visible) continue;
    const auto mesh = prop_mesh(s, p);
    const glm::dmat4 to_world = prop_transform(p);
    // Fixed blocks of triangles summed in order: the same length on any number of threads.
    constexpr std::size_t block = 4096;
    const std::size_t triangles = mesh->indices.size() / 3;
    std::vector<double> sums((triangles + block - 1) / block, 0.0);
    tbb::parallel_for(std::size_t(0), sums.size(), [&](std::size_t b) {
      for (std::size_t t = b * block; t < std::min(triangles, (b + 1) * block); ++t) {
        std::array<glm::dvec3, 3> tri;
        for (int k = 0; k < 3; ++k)
          tri[k] = glm::dvec3(to_world * glm::dvec4(glm::dvec3(mesh->positions[mesh->indices[3 * t + k]]), 1.0));
        for (const part_frame& f : parts) sums[b] += part_cut_length(f, tri);
      }
    });
    for (double v : sums) length += v;
  }
  return length;
}

double constraint_violation(const design_constraint& c, double value) {
  double v = 0;
  if (c.min && value < *c.min) v = *c.min - value;
  if (c.max && value > *c.max) v = value - *c.max;
  return v;
}

double design_score(const design_spec& spec, const std::vector<double>& objective_values) {
  double score = 0;
  for (std::size_t i = 0; i < spec.objectives.size() && i < objective_values.size(); ++i)
    score += (spec.objectives[i].maximise ? 1 : -1) * spec.objectives[i].weight * objective_values[i];
  return score;
}

std::vector<std::string> broken_constraints(const design_spec& spec, const std::vector<double>& constraint_values) {
  std::vector<std::string> broken;
  for (std::size_t i = 0; i < spec.constraints.size() && i < constraint_values.size(); ++i) {
    const design_constraint& c = spec.constraints[i];
    const double v = constraint_values[i];
    if (constraint_violation(c, v) > 0)
      broken.push_back(std::string(to_string(c.metric)) + " " + number_text(v) +
                       (c.min && v < *c.min ? " < min " + number_text(*c.min) : " > max " + number_text(*c.max)));
  }
  return broken;
}

void check_design_expressions(const design_spec& spec) {
  const auto check = [&](const std::string& where, const std::string& expression) {
    try {
      path_expression::parse(expression).bound(spec.base, true);
    } catch (const input_error& e) {
      throw input_error(spec.path + ": " + where + ".expression: " + e.what());
    }
  };
  for (std::size_t i = 0; i < spec.objectives.size(); ++i)
    if (metric_takes_expression(spec.objectives[i].metric))
      check("objectives[" + std::to_string(i) + "]", spec.objectives[i].expression);
  for (std::size_t i = 0; i < spec.constraints.size(); ++i)
    if (metric_takes_expression(spec.constraints[i].metric))
      check("constraints[" + std::to_string(i) + "]", spec.constraints[i].expression);
}

void check_design_memory(const design_spec& spec, const std::string& what, std::size_t layouts) {
  auto takes_psf = [](design_metric m) {
    return metric_at_eye(m) && m != design_metric::visible_fraction && m != design_metric::stray_light &&
           m != design_metric::contrast && m != design_metric::legible_share && !metric_takes_expression(m);
  };
  const bool psfs = std::any_of(spec.objectives.begin(), spec.objectives.end(),
                                [&](const design_objective& o) { return takes_psf(o.metric); }) ||
                    std::any_of(spec.constraints.begin(), spec.constraints.end(),
                                [&](const design_constraint& c) { return takes_psf(c.metric); });
  if (!psfs) return;
  const std::size_t threads =
      std::min({std::size_t(tbb::this_task_arena::max_concurrency()),
                tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)});
  const std::size_t at_once = std::max<std::size_t>(1, std::min(threads, layouts * design_eyes(spec).size()));
  check_memory_need(what + ": " + std::to_string(at_once) + (at_once == 1 ? " PSF" : " PSFs") + " at once of " +
                        std::to_string(spec.search.psf_samples) + " samples",
                    measuring_process_bytes + at_once * psf_memory_need(spec.search.psf_samples));
}

design_evaluation evaluate_design(const design_spec& spec, const scene& s) {
  std::vector<asked_metric> asked;  // the eye metrics the spec names
  for (const design_objective& o : spec.objectives) asked.push_back({o.metric, o.expression});
  for (const design_constraint& c : spec.constraints) asked.push_back({c.metric, c.expression});
  std::erase_if(asked, [](const asked_metric& m) { return !metric_at_eye(m.metric); });
  std::sort(asked.begin(), asked.end());
  asked.erase(std::unique(asked.begin(), asked.end()), asked.end());
  // Only a visible fraction needs the viewing parts (and the props' Embree scene); built once,
  // before the eyes are measured in parallel (each eye's values alone, so any threads agree).
  std::optional<viewing_parts> parts;
  if (std::any_of(asked.begin(), asked.end(),
                  [](const asked_metric& m) { return m.metric == design_metric::visible_fraction; }))
    parts.emplace(s, scene_prop_hits(s));
  std::vector<std::string> expressions;  // the ghost metrics', each once
  for (const asked_metric& m : asked)
    if (metric_takes_expression(m.metric) &&
        std::find(expressions.begin(), expressions.end(), m.expression) == expressions.end())
      expressions.push_back(m.expression);
  const std::vector<glm::dvec3> eyes = design_eyes(spec);
  std::vector<std::map<asked_metric, double>> at_eye(eyes.size());
  tbb::parallel_for(std::size_t(0), eyes.size(), [&](std::size_t i) {
    eye_metrics e(spec, s, eyes[i], parts ? &*parts : nullptr, expressions);
    for (const asked_metric& m : asked) at_eye[i][m] = e.value(m.metric, m.expression);
  });
  const glm::dvec3 size = device_size_mm(s);
  const bool cuts_asked =
      std::any_of(spec.constraints.begin(), spec.constraints.end(),
                  [](const design_constraint& c) { return c.metric == design_metric::prop_cut_mm; }) ||
      std::any_of(spec.objectives.begin(), spec.objectives.end(),
                  [](const design_objective& o) { return o.metric == design_metric::prop_cut_mm; });
  const double cut = cuts_asked ? prop_cut_length_mm(s) : 0;
  auto value = [&](design_metric m, const std::string& expression, over_eyes over, double threshold) {
    if (m == design_metric::size_x_mm) return size.x;
    if (m == design_metric::size_y_mm) return size.y;
    if (m == design_metric::size_z_mm) return size.z;
    if (m == design_metric::prop_cut_mm) return cut;
    double sum = 0, least = std::numeric_limits<double>::infinity();
    int above = 0;
    for (const auto& values : at_eye) {
      const double v = values.at({m, expression});
      sum += v;
      least = std::min(least, v);
      above += v >= threshold;
    }
    if (over == over_eyes::share_above) return double(above) / double(at_eye.size());
    return over == over_eyes::min ? least : sum / double(at_eye.size());
  };
  design_evaluation out;
  for (const design_objective& o : spec.objectives)
    out.objective_values.push_back(value(o.metric, o.expression, o.over, o.threshold));
  out.score = design_score(spec, out.objective_values);
  for (const design_constraint& c : spec.constraints)
    out.constraint_values.push_back(value(c.metric, c.expression, c.over, c.threshold));
  out.broken = broken_constraints(spec, out.constraint_values);
  return out;
}

}  // namespace airr
