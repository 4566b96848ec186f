// The Optimise window: the design spec's variables (from the layout panel's rows or the common
// ones), the eyes, the objectives and constraints from the metrics, the search. It runs in the
// background as `airr optimise` does, the best layout so far drawn in the layout views; the best
// layout, or a Pareto front's member clicked in its plot, is applied as one undoable step.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/ui/views/plot_widget.hpp"
#include "design_widgets.hpp"

namespace airr::ui {

namespace {

void variables_section(studio& st) {
  std::vector<design_variable>& vars = st.design.spec.variables;
  std::optional<std::size_t> remove;
  const float w = ImGui::GetFontSize();
  for (std::size_t i = 0; i < vars.size(); ++i) {
    design_variable& v = vars[i];
    ImGui::PushID(int(i));
    ImGui::SetNextItemWidth(5 * w);
    ImGui::InputDouble("##min", &v.min, 0, 0, "%.3g");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(5 * w);
    ImGui::InputDouble("##max", &v.max, 0, 0, "%.3g");
    ImGui::SameLine();
    const auto now = design_value(st.doc, v.key);
    if (now)
      ImGui::Text("%s (now %.4g)", v.key.c_str(), *now);
    else
      ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s (not a value of the scene)", v.key.c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("x")) remove = i;
    ImGui::PopID();
  }
  if (remove) vars.erase(vars.begin() + std::ptrdiff_t(*remove));
  std::string key;
  ImGui::SetNextItemWidth(10 * w);
  if (design_key_combo("variable##add", key, st.doc)) add_design_pick(st, key, false);
}

void objectives_section(studio& st) {
  design_spec& spec = st.design.spec;
  std::optional<std::size_t> remove;
  const float w = ImGui::GetFontSize();
  for (std::size_t i = 0; i < spec.objectives.size(); ++i) {
    design_objective& o = spec.objectives[i];
    ImGui::PushID(int(i));
    int goal = o.maximise ? 0 : 1;
    const char* goals[] = {"maximise", "minimise"};
    ImGui::SetNextItemWidth(6 * w);
    if (ImGui::Combo("##goal", &goal, goals, 2)) o.maximise = goal == 0;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(9 * w);
    design_metric_combo("##metric", o.metric);
    ImGui::SameLine();
    if (metric_takes_expression(o.metric)) {
      ImGui::SetNextItemWidth(10 * w);
      ImGui::InputTextWithHint("##expression", "path expression, e.g. D .* H:r1 .* E", &o.expression);
      ImGui::SameLine();
    }
    if (metric_at_eye(o.metric)) {
      over_eyes_combo("##over", o.over, o.threshold);
      ImGui::SameLine();
    }
    ImGui::SetNextItemWidth(4 * w);
    ImGui::InputDouble("weight##w", &o.weight, 0, 0, "%.3g");
    ImGui::SameLine();
    if (ImGui::SmallButton("x") && spec.objectives.size() > 1) remove = i;
    ImGui::PopID();
  }
  if (remove) spec.objectives.erase(spec.objectives.begin() + std::ptrdiff_t(*remove));
  if (ImGui::Button("add an objective")) spec.objectives.push_back({.metric = design_metric::visible_fraction});
  if (spec.objectives.size() == 2) {
    bool front = spec.front.points > 0;
    ImGui::SameLine();
    if (ImGui::Checkbox("Pareto front of the two", &front)) spec.front.points = front ? 9 : 0;
    if (front) {
      ImGui::SameLine();
      ImGui::SetNextItemWidth(5 * w);
      ImGui::InputInt("points", &spec.front.points);
    }
  } else {
    spec.front.points = 0;
  }
}

void constraints_section(studio& st) {
  std::vector<design_constraint>& cons = st.design.spec.constraints;
  std::optional<std::size_t> remove;
  const float w = ImGui::GetFontSize();
  for (std::size_t i = 0; i < cons.size(); ++i) {
    design_constraint& c = cons[i];
    ImGui::PushID(int(i));
    ImGui::SetNextItemWidth(9 * w);
    design_metric_combo("##metric", c.metric);
    if (metric_takes_expression(c.metric)) {
      ImGui::SameLine();
      ImGui::SetNextItemWidth(10 * w);
      ImGui::InputTextWithHint("##expression", "path expression", &c.expression);
    }
    if (metric_at_eye(c.metric)) {
      ImGui::SameLine();
      over_eyes_combo("##over", c.over, c.threshold);
    }
    for (auto [name, bound] : {std::pair{"min", &c.min}, std::pair{"max", &c.max}}) {
      ImGui::SameLine();
      bool on = bound->has_value();
      ImGui::PushID(name);
      if (ImGui::Checkbox(name, &on)) *bound = on ? std::optional<double>(0.0) : std::nullopt;
      if (*bound) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(5 * w);
        ImGui::InputDouble("##v", &**bound, 0, 0, "%.4g");
      }
      ImGui::PopID();
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("x")) remove = i;
    ImGui::PopID();
  }
  if (remove) cons.erase(cons.begin() + std::ptrdiff_t(*remove));
  if (ImGui::Button("add a constraint"))
    cons.push_back(
        {.metric = design_metric::size_z_mm, .min = std::nullopt, .max = st.applied.half_mirror.width_mm * 2});
}

void search_section(design_spec& spec) {
  const float w = ImGui::GetFontSize();
  int seed = int(spec.search.seed);
  ImGui::SetNextItemWidth(5 * w);
  if (ImGui::InputInt("seed", &seed)) spec.search.seed = std::uint64_t(std::max(0, seed));
  ImGui::SameLine();
  ImGui::SetNextItemWidth(5 * w);
  ImGui::InputInt("global", &spec.search.global_evaluations);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(5 * w);
  ImGui::InputInt("local evaluations", &spec.search.local_evaluations);
}

// The front over every feasible evaluation; a click chooses the front's nearest member.
void front_plot(studio& st) {
  design_windows& d = st.design;
  const design_result& r = *d.optimised;
  plot_curve all{"feasible evaluations", {}, {}, IM_COL32(150, 150, 150, 255)};
  all.points = true;
  plot_curve front{"Pareto front", {}, {}, plot_palette(0)};
  plot_curve chosen{"chosen", {}, {}, IM_COL32(255, 120, 200, 255)};
  chosen.points = true;
  for (const design_trial& t : r.trials) {
    if (!t.valid || !t.evaluation.feasible()) continue;
    all.x.push_back(t.evaluation.objective_values[0]);
    all.y.push_back(t.evaluation.objective_values[1]);
  }
  for (int i : r.front) {
    front.x.push_back(r.trials[std::size_t(i)].evaluation.objective_values[0]);
    front.y.push_back(r.trials[std::size_t(i)].evaluation.objective_values[1]);
  }
  if (d.chosen >= 0) {
    chosen.x.push_back(r.trials[std::size_t(d.chosen)].evaluation.objective_values[0]);
    chosen.y.push_back(r.trials[std::size_t(d.chosen)].evaluation.objective_values[1]);
  }
  plot_params p;
  p.title = "Pareto front (click to choose a layout)";
  p.x_title = to_string(d.optimised_spec.objectives[0].metric);
  p.y_title = to_string(d.optimised_spec.objectives[1].metric);
  p.auto_y = true;
  p.height = 220;
  const plot_hover h = draw_plot("##front", {all, front, chosen}, p);
  st.regions["optimise_front"] = {h.area[0], h.area[1], h.area[2], h.area[3]};
  if (!h.clicked || r.front.empty()) return;
  // Nearest on screen: each axis scaled to its range.
  double best = 1e300;
  for (int i : r.front) {
    const auto& v = r.trials[std::size_t(i)].evaluation.objective_values;
    const double dx = (v[0] - h.x) / (h.range[1] - h.range[0]), dy = (v[1] - h.y) / (h.range[3] - h.range[2]);
    if (dx * dx + dy * dy < best) {
      best = dx * dx + dy * dy;
      d.chosen = i;
    }
  }
  try {
    d.ghost = design_scene(d.optimised_spec, r.trials[std::size_t(d.chosen)].x);
  } catch (const std::exception&) {
    d.ghost.reset();
  }
}

void result_section(studio& st) {
  design_windows& d = st.design;
  const design_result& r = *d.optimised;
  const design_spec& spec = d.optimised_spec;
  if (d.chosen < 0) {
    ImGui::TextUnformatted("no layout was evaluated");
    return;
  }
  const design_trial& t = r.trials[std::size_t(d.chosen)];
  ImGui::Text("%zu evaluations%s; %s layout:", r.trials.size(), r.cancelled ? " (cancelled)" : "",
              d.chosen == r.best ? "the best" : "the chosen");
  if (!t.valid || !t.evaluation.feasible()) {
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "infeasible: no layout met the constraints; the closest breaks %s",
                       t.evaluation.broken.empty() ? "?" : t.evaluation.broken.front().c_str());
  }
  if (ImGui::BeginTable("##result", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("value");
    ImGui::TableSetupColumn("found");
    ImGui::TableSetupColumn("now");
    ImGui::TableHeadersRow();
    auto row = [](const std::string& name, double found, std::optional<double> now) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.6g", found);
      ImGui::TableNextColumn();
      if (now) ImGui::Text("%.6g", *now);
    };
    for (std::size_t i = 0; i < spec.variables.size(); ++i)
      row(spec.variables[i].key, t.x[i], design_value(st.doc, spec.variables[i].key));
    if (t.valid) {
      for (std::size_t i = 0; i < spec.objectives.size(); ++i)
        row(std::string(spec.objectives[i].maximise ? "max " : "min ") + to_string(spec.objectives[i].metric),
            t.evaluation.objective_values[i], std::nullopt);
      for (std::size_t i = 0; i < spec.constraints.size(); ++i)
        row(std::string("constraint ") + to_string(spec.constraints[i].metric), t.evaluation.constraint_values[i],
            std::nullopt);
    }
    ImGui::EndTable();
  }
  if (!r.front.empty()) front_plot(st);
  ImGui::BeginDisabled(!t.valid);
  if (ImGui::Button("Apply this layout")) apply_design_choice(st);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Hide it in the layout view")) d.ghost.reset();
}

}  // namespace

void draw_optimise_window(studio& st) {
  design_windows& d = st.design;
  if (!d.show_optimise) return;
  start_design_spec(st);
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + 0.27f * vp->WorkSize.x, vp->WorkPos.y + 2 * ImGui::GetFontSize()),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(36 * ImGui::GetFontSize(), 44 * ImGui::GetFontSize()), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Optimise", &d.show_optimise)) {
    ImGui::End();
    return;
  }
  const bool running = d.job && d.job->running();
  ImGui::BeginDisabled(running);
  if (ImGui::CollapsingHeader("Variables (min, max)", ImGuiTreeNodeFlags_DefaultOpen)) variables_section(st);
  if (ImGui::CollapsingHeader("Eyes (mm)")) edit_design_eyes(st);
  if (ImGui::CollapsingHeader("Objectives", ImGuiTreeNodeFlags_DefaultOpen)) objectives_section(st);
  if (ImGui::CollapsingHeader("Constraints", ImGuiTreeNodeFlags_DefaultOpen)) constraints_section(st);
  if (ImGui::CollapsingHeader("Search")) search_section(d.spec);
  ImGui::EndDisabled();
  ImGui::Separator();
  if (running && d.job->what() == design_job::kind::optimise) {
    if (ImGui::Button("Cancel")) d.job->cancel();
    ImGui::SameLine();
    const design_progress p = d.job->progress();
    char detail[120] = "";
    if (p.have_best)
      std::snprintf(detail, sizeof detail, "%s, best %.6g%s", p.stage.c_str(), p.best_score,
                    p.best_feasible ? "" : " (infeasible)");
    design_progress_bar(*d.job, detail);
  } else {
    ImGui::BeginDisabled(running);
    if (ImGui::Button("Run the search")) start_design_job(st, design_job::kind::optimise);
    ImGui::EndDisabled();
  }
  if (!d.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", d.error.c_str());
  if (d.optimised && !running) result_section(st);
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  st.regions["optimise_window"] = {p.x, p.y, p.x + s.x, p.y + s.y};
  ImGui::End();
}

}  // namespace airr::ui
