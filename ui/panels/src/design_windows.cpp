// The Optimise and Tolerance windows' spec and jobs: what a layout panel row adds to them, the
// runs over the applied layout, their results taken in, and the chosen layout applied as one step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include <imgui.h>

#include "airr/core/error.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "design_widgets.hpp"

namespace airr::ui {

std::optional<double> design_value(const scene& s, const std::string& key) {
  try {
    return scene_number(s, key);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A first range or tolerance for a value: angles by degrees, lengths by millimetres, anything else
// by a share of the value.
double design_span(const std::string& key, double v, bool tolerance) {
  if (ends_with(key, "_deg")) return tolerance ? 0.5 : 10.0;
  if (key.find("_mm") != std::string::npos) return tolerance ? 0.5 : std::max(10.0, 0.2 * std::abs(v));
  return std::max(tolerance ? 0.03 : 0.2, 1e-3) * std::max(std::abs(v), 1e-3);
}

}  // namespace

void start_design_spec(studio& st) {
  design_windows& d = st.design;
  if (d.spec_started) return;
  d.spec = design_spec{};
  const double tilt = st.doc.sheet().pose.pitch_deg;
  d.spec.variables = {{"tilt_deg", tilt - 10, tilt + 10}};
  d.spec.eyes_mm = {observer_position(st.doc)};
  d.spec.objectives = {design_objective{.metric = design_metric::mean_mtf}};
  d.spec.search.global_evaluations = 60;
  d.spec.search.local_evaluations = 40;
  d.spec.tolerances = {{"tilt_deg", 0.5, false, false}};
  d.spec.tolerance.samples = 200;
  d.spec_started = true;
}

std::vector<std::string> common_design_keys(const scene& s) {
  std::vector<std::string> keys = {"tilt_deg", "floating_distance_mm"};
  auto pose_keys = [&](const std::string& part) {
    for (const char* k : {"pitch_deg", "yaw_deg", "roll_deg", "center_mm.0", "center_mm.1", "center_mm.2"})
      keys.push_back(part + ".pose." + k);
  };
  pose_keys("half_mirror");
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) pose_keys("retroreflectors." + std::to_string(i));
  pose_keys("source");
  return keys;
}

bool design_key_combo(const char* label, std::string& key, const scene& s) {
  bool chosen = false;
  if (ImGui::BeginCombo(label, "add...")) {
    for (const std::string& k : common_design_keys(s)) {
      if (ImGui::Selectable(k.c_str())) {
        key = k;
        chosen = true;
      }
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("or right-click a row of the layout panel");
  return chosen;
}

bool design_metric_combo(const char* id, design_metric& m) {
  bool changed = false;
  if (ImGui::BeginCombo(id, to_string(m))) {
    for (int k = 0; k < design_metric_count; ++k) {
      const auto metric = design_metric(k);
      if (ImGui::Selectable(to_string(metric), metric == m)) {
        m = metric;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

void over_eyes_combo(const char* id, over_eyes& o, double& threshold) {
  int k = int(o);
  const char* names[] = {"mean over eyes", "min over eyes", "share of eyes at least"};
  ImGui::SetNextItemWidth(8 * ImGui::GetFontSize());
  if (ImGui::Combo(id, &k, names, 3)) o = over_eyes(k);
  if (o != over_eyes::share_above) return;
  ImGui::SameLine();
  ImGui::PushID(id);
  ImGui::SetNextItemWidth(4 * ImGui::GetFontSize());
  ImGui::InputDouble("##threshold", &threshold, 0, 0, "%.3g");
  ImGui::PopID();
}

void edit_design_eyes(studio& st) {
  std::vector<glm::dvec3>& eyes = st.design.spec.eyes_mm;
  std::optional<std::size_t> remove;
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    ImGui::PushID(int(i));
    float e[3] = {float(eyes[i].x), float(eyes[i].y), float(eyes[i].z)};
    ImGui::SetNextItemWidth(-3.0f * ImGui::GetFontSize());
    if (ImGui::InputFloat3("##eye", e, "%.1f")) eyes[i] = {e[0], e[1], e[2]};
    ImGui::SameLine();
    if (ImGui::SmallButton("x") && eyes.size() > 1) remove = i;
    ImGui::PopID();
  }
  if (remove) eyes.erase(eyes.begin() + std::ptrdiff_t(*remove));
  if (ImGui::Button("add the observer's position")) eyes.push_back(observer_position(st.doc));
  // A zone: eyes on the observer's orbit sphere, azimuth and elevation in degrees.
  std::optional<eye_grid>& zone = st.design.spec.eye_zone;
  bool on = zone.has_value();
  if (ImGui::Checkbox("a zone of eyes on the observer's orbit", &on)) {
    if (on) {
      eye_grid g;
      g.kind = eye_grid::shape::sphere;
      g.distance_mm = st.doc.observer.distance_mm;
      g.x_min = -20, g.x_max = 20, g.y_min = -10, g.y_max = 10, g.nx = 5, g.ny = 3;
      zone = g;
    } else {
      zone.reset();
    }
  }
  if (!zone) return;
  float az[2] = {float(zone->x_min), float(zone->x_max)}, el[2] = {float(zone->y_min), float(zone->y_max)};
  const float w = ImGui::GetFontSize();
  ImGui::SetNextItemWidth(8 * w);
  if (ImGui::InputFloat2("azimuth (deg)", az, "%.1f")) zone->x_min = az[0], zone->x_max = az[1];
  ImGui::SetNextItemWidth(8 * w);
  if (ImGui::InputFloat2("elevation (deg)", el, "%.1f")) zone->y_min = el[0], zone->y_max = el[1];
  int n[2] = {zone->nx, zone->ny};
  ImGui::SetNextItemWidth(8 * w);
  if (ImGui::InputInt2("eyes across, up", n)) zone->nx = std::clamp(n[0], 1, 20), zone->ny = std::clamp(n[1], 1, 20);
  ImGui::SetNextItemWidth(8 * w);
  ImGui::InputDouble("distance (mm)", &zone->distance_mm, 0, 0, "%.0f");
}

void design_progress_bar(const design_job& job, const std::string& detail) {
  const design_progress p = job.progress();
  const double f = p.total > 0 ? std::min(1.0, double(p.done) / p.total) : 0.0;
  const double s = job.seconds(), eta = f > 0 ? s * (1 - f) / f : 0;
  char text[200];
  std::snprintf(text, sizeof text, "%d/%d  %.0f s, %.0f s left%s%s", p.done, p.total, s, eta,
                detail.empty() ? "" : "  ", detail.c_str());
  ImGui::ProgressBar(float(f), ImVec2(-1, 0), text);
}

void add_design_pick(studio& st, const std::string& key, bool tolerance) {
  start_design_spec(st);
  design_spec& spec = st.design.spec;
  const double v = design_value(st.doc, key).value_or(0);
  const double span = design_span(key, v, tolerance);
  if (tolerance) {
    std::erase_if(spec.tolerances, [&](const design_tolerance& t) { return t.key == key; });
    const bool relative = !ends_with(key, "_deg") && key.find("_mm") == std::string::npos;
    spec.tolerances.push_back({key, relative ? 3.0 : span, false, relative});
    st.design.show_tolerance = true;
  } else {
    std::erase_if(spec.variables, [&](const design_variable& x) { return x.key == key; });
    spec.variables.push_back({key, v - span, v + span});
    st.design.show_optimise = true;
  }
  st.status = std::string(tolerance ? "tolerance of " : "optimising over ") + key;
}

bool start_design_job(studio& st, design_job::kind k) {
  design_windows& d = st.design;
  d.error.clear();
  if (!st.doc_error.empty()) {
    d.error = "the layout has an error: " + st.doc_error;
    return false;
  }
  if (k == design_job::kind::optimise && d.spec.variables.empty()) {
    d.error = "variables: the optimiser needs at least one";
    return false;
  }
  if (k == design_job::kind::tolerance && d.spec.tolerances.empty()) {
    d.error = "tolerances: the analysis needs at least one";
    return false;
  }
  try {
    // The spec read back as `airr optimise` reads a file: the same checks, errors naming the field.
    design_spec spec = parse_design_spec(design_spec_text(d.spec), "design spec", st.applied);
    check_design_expressions(spec);
    d.job = std::make_unique<design_job>(spec, k);
  } catch (const std::exception& e) {
    d.error = one_line(e.what());
    return false;
  }
  if (k == design_job::kind::optimise) {
    d.optimised.reset();
    d.chosen = -1;
  } else {
    d.tolerances.reset();
  }
  st.status = k == design_job::kind::optimise ? "optimising the layout" : "analysing the tolerances";
  return true;
}

namespace {

void show_trial(studio& st, const design_spec& spec, const std::vector<double>& x) {
  try {
    st.design.ghost = design_scene(spec, x);
  } catch (const std::exception&) {
    st.design.ghost.reset();
  }
}

}  // namespace

bool collect_design_job(studio& st) {
  design_windows& d = st.design;
  if (!d.job) return false;
  if (d.job->running()) {
    if (d.job->what() == design_job::kind::optimise) {
      const design_progress p = d.job->progress();
      if (p.have_best) show_trial(st, d.job->spec(), p.best_x);
    }
    return false;
  }
  const std::string error = d.job->error();
  if (!error.empty()) {
    d.error = one_line(error);
  } else if (d.job->what() == design_job::kind::optimise) {
    d.optimised = d.job->optimised();
    d.optimised_spec = d.job->spec();
    d.chosen = d.optimised && d.optimised->best >= 0 ? d.optimised->best : -1;
    if (d.chosen >= 0) show_trial(st, d.optimised_spec, d.optimised->best_trial().x);
    st.status = d.optimised && d.optimised->cancelled ? "the search was cancelled; its best so far is kept"
                                                      : "the search has finished";
  } else {
    d.tolerances = d.job->tolerances();
    d.tolerance_spec = d.job->spec();
    st.status = "the tolerance analysis has finished";
  }
  d.job.reset();
  return true;
}

bool apply_design_choice(studio& st) {
  design_windows& d = st.design;
  if (!d.optimised || d.chosen < 0 || d.chosen >= int(d.optimised->trials.size())) return false;
  const design_trial& t = d.optimised->trials[std::size_t(d.chosen)];
  if (!t.valid) return false;
  // Only the variables change: edits made to the scene since the search started stay.
  std::vector<scene_override> set;
  for (std::size_t i = 0; i < d.optimised_spec.variables.size(); ++i)
    set.push_back(design_override(d.optimised_spec.variables[i].key, t.x[i]));
  try {
    const scene next = with_overrides(st.doc, set, "the optimised layout");
    st.history.settle(st.doc, false);
    st.history.name_next("apply the optimised layout");
    st.doc = next;
    st.history.settle(st.doc, false);
  } catch (const std::exception& e) {
    st.status = one_line(e.what());
    return false;
  }
  d.ghost.reset();
  st.status = "applied the optimised layout (Ctrl+Z undoes it)";
  return true;
}

bool run_design_script(studio& st, design_script& script) {
  std::string& error = script.error;
  if (script.finished || (!script.optimise && !script.tolerance && !script.apply && script.undo == 0)) return false;
  if (!(st.doc == st.applied) || (st.design.job && st.design.job->running())) return true;
  collect_design_job(st);
  for (auto [wanted, started, k] :
       {std::tuple{script.optimise, &script.optimise_started, design_job::kind::optimise},
        std::tuple{script.tolerance, &script.tolerance_started, design_job::kind::tolerance}}) {
    if (!wanted || *started) continue;
    *started = true;
    if (!start_design_job(st, k)) {
      error = st.design.error;
      script.finished = true;
      return false;
    }
    return true;
  }
  if (!st.design.error.empty()) error = st.design.error;
  if (script.apply && error.empty() && !apply_design_choice(st)) error = "no optimised layout to apply";
  for (int i = 0; i < script.undo; ++i) studio_undo(st);
  script.finished = true;
  return true;  // a frame more to apply what changed
}

}  // namespace airr::ui
