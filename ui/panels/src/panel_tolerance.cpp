// The Tolerance window: assembly tolerances (from the layout panel's rows or the common ones), the
// Monte Carlo's samples, and the result as `airr tolerance` reports it: each metric of the Optimise
// window's objectives and constraints as a histogram with its statistics, the yield against the
// constraints, the worst layouts with their drawn values, and the sensitivity table (each
// tolerance alone), the largest change per metric marked so the designer sees which tolerance to
// tighten.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "airr/core/error.hpp"
#include "airr/ui/views/plot_widget.hpp"
#include "design_widgets.hpp"

namespace airr::ui {

namespace {

void tolerances_section(studio& st) {
  std::vector<design_tolerance>& tols = st.design.spec.tolerances;
  std::optional<std::size_t> remove;
  const float w = ImGui::GetFontSize();
  for (std::size_t i = 0; i < tols.size(); ++i) {
    design_tolerance& t = tols[i];
    ImGui::PushID(int(i));
    int kind = t.uniform ? 1 : 0;
    const char* kinds[] = {"normal, sd", "uniform, +-"};
    ImGui::SetNextItemWidth(7 * w);
    if (ImGui::Combo("##kind", &kind, kinds, 2)) t.uniform = kind == 1;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(4 * w);
    ImGui::InputDouble("##size", &t.size, 0, 0, "%.3g");
    ImGui::SameLine();
    ImGui::Checkbox("%", &t.percent);
    ImGui::SameLine();
    const auto now = design_value(st.doc, t.key);
    if (now)
      ImGui::Text("%s (now %.4g)", t.key.c_str(), *now);
    else
      ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s (not a value of the scene)", t.key.c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("x")) remove = i;
    ImGui::PopID();
  }
  if (remove) tols.erase(tols.begin() + std::ptrdiff_t(*remove));
  std::string key;
  ImGui::SetNextItemWidth(10 * w);
  if (design_key_combo("tolerance##add", key, st.doc)) add_design_pick(st, key, true);
}

void metrics_line(const design_spec& spec) {
  std::string names;
  for (const design_objective& o : spec.objectives)
    names += (names.empty() ? "" : ", ") + std::string(to_string(o.metric));
  for (const design_constraint& c : spec.constraints) {
    char bound[80] = "";
    if (c.min && c.max)
      std::snprintf(bound, sizeof bound, " in [%.4g, %.4g]", *c.min, *c.max);
    else
      std::snprintf(bound, sizeof bound, " %s %.4g", c.min ? ">=" : "<=", c.min ? *c.min : *c.max);
    names += (names.empty() ? "" : ", ") + std::string(to_string(c.metric)) + bound;
  }
  ImGui::TextWrapped("Metrics (the Optimise window's objectives and constraints): %s", names.c_str());
}

// The worst layouts drawn, with what was drawn for each tolerance, so the deviation that spoilt
// one can be read off.
void worst_layouts_table(const tolerance_result& r, const design_spec& spec) {
  const std::vector<std::size_t> worst = worst_layouts(r, 5);
  if (worst.empty()) return;
  ImGui::TextUnformatted("Worst layouts: the values drawn, and what each broke");
  const int columns = int(2 + spec.tolerances.size());
  if (!ImGui::BeginTable("##worst", columns, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp)) return;
  ImGui::TableSetupColumn("sample");
  for (const design_tolerance& t : spec.tolerances) ImGui::TableSetupColumn(t.key.c_str());
  ImGui::TableSetupColumn("result");
  ImGui::TableHeadersRow();
  for (std::size_t i : worst) {
    const tolerance_layout& l = r.layouts[i];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%zu", i);
    for (double v : l.values) {
      ImGui::TableNextColumn();
      ImGui::Text("%.5g", v);
    }
    ImGui::TableNextColumn();
    std::string result = layout_failures(l);
    if (result.empty()) result = "score " + number_text(l.score, 4);
    ImGui::TextUnformatted(result.c_str());
  }
  ImGui::EndTable();
}

void result_section(studio& st) {
  const tolerance_result& r = *st.design.tolerances;
  const design_spec& spec = st.design.tolerance_spec;
  ImGui::Text("%d layouts%s, %d no valid layout; yield %.1f%%", r.samples, r.cancelled ? " (cancelled)" : "", r.invalid,
              100 * r.yield);
  if (ImGui::BeginTable("##stats", 6, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp)) {
    for (const char* h : {"metric", "mean", "sd", "p5", "p50", "p95"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const metric_distribution& m : r.metrics) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(m.name.c_str());
      for (double v : {m.mean, m.sd, m.p5, m.p50, m.p95}) {
        ImGui::TableNextColumn();
        ImGui::Text("%.5g", v);
      }
    }
    ImGui::EndTable();
  }
  // Sensitivities: each metric's change per tolerance, the largest of each metric marked.
  ImGui::TextUnformatted("Sensitivity: each metric's change with each tolerance alone (per its size)");
  const std::size_t columns = 1 + r.metrics.size();
  if (!r.sensitivity.empty() && ImGui::BeginTable("##sensitivity", int(columns), ImGuiTableFlags_Borders)) {
    ImGui::TableSetupColumn("tolerance");
    for (const metric_distribution& m : r.metrics) ImGui::TableSetupColumn(m.name.substr(0, m.name.find(' ')).c_str());
    ImGui::TableHeadersRow();
    for (std::size_t t = 0; t < r.sensitivity.size() && t < spec.tolerances.size(); ++t) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(spec.tolerances[t].key.c_str());
      for (std::size_t m = 0; m < r.metrics.size(); ++m) {
        ImGui::TableNextColumn();
        const double v = r.sensitivity[t][m];
        bool largest = std::isfinite(v);
        for (std::size_t u = 0; u < r.sensitivity.size(); ++u)
          if (std::abs(r.sensitivity[u][m]) > std::abs(v)) largest = false;
        if (largest && r.sensitivity.size() > 1)
          ImGui::TextColored(ImVec4(1, 0.75f, 0.3f, 1), "%.4g (largest)", v);
        else
          ImGui::Text("%.4g", v);
      }
    }
    ImGui::EndTable();
  }
  // One histogram per metric; a constraint's limits as dashed lines.
  for (std::size_t m = 0; m < r.metrics.size(); ++m) {
    const metric_distribution& d = r.metrics[m];
    const histogram_steps h = metric_histogram(d, 30);
    std::vector<plot_curve> curves = {{d.name, h.x, h.y}};
    double top = 1;
    for (double y : h.y) top = std::max(top, y);
    if (m >= spec.objectives.size()) {
      const design_constraint& c = spec.constraints[m - spec.objectives.size()];
      for (const std::optional<double>& b : {c.min, c.max}) {
        if (b) curves.push_back({"", {*b, *b}, {0, top}, IM_COL32(255, 120, 120, 255), true});
      }
    }
    plot_params p;
    p.x_title = d.name.substr(0, d.name.find(' '));
    p.y_title = "layouts";
    p.y_min = 0;
    p.y_max = top * 1.1;
    p.height = 150;
    ImGui::PushID(int(m));
    const plot_hover hov = draw_plot("##histogram", curves, p);
    ImGui::PopID();
    st.regions["tolerance_histogram_" + std::to_string(m)] = {hov.area[0], hov.area[1], hov.area[2], hov.area[3]};
  }
  worst_layouts_table(r, spec);
}

}  // namespace

void draw_tolerance_window(studio& st) {
  design_windows& d = st.design;
  if (!d.show_tolerance) return;
  start_design_spec(st);
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + 0.30f * vp->WorkSize.x, vp->WorkPos.y + 3 * ImGui::GetFontSize()),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(36 * ImGui::GetFontSize(), 44 * ImGui::GetFontSize()), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Tolerance", &d.show_tolerance)) {
    ImGui::End();
    return;
  }
  const bool running = d.job && d.job->running();
  ImGui::BeginDisabled(running);
  if (ImGui::CollapsingHeader("Tolerances", ImGuiTreeNodeFlags_DefaultOpen)) tolerances_section(st);
  metrics_line(d.spec);
  const float w = ImGui::GetFontSize();
  ImGui::SetNextItemWidth(6 * w);
  ImGui::InputInt("samples", &d.spec.tolerance.samples, 100, 1000);
  ImGui::SameLine();
  int seed = int(d.spec.tolerance.seed);
  ImGui::SetNextItemWidth(5 * w);
  if (ImGui::InputInt("seed", &seed)) d.spec.tolerance.seed = std::uint64_t(std::max(0, seed));
  ImGui::EndDisabled();
  ImGui::Separator();
  if (running && d.job->what() == design_job::kind::tolerance) {
    if (ImGui::Button("Cancel")) d.job->cancel();
    ImGui::SameLine();
    design_progress_bar(*d.job, "layouts");
  } else {
    ImGui::BeginDisabled(running);
    if (ImGui::Button("Run the analysis")) start_design_job(st, design_job::kind::tolerance);
    ImGui::EndDisabled();
  }
  if (!d.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", d.error.c_str());
  if (d.tolerances && !running) result_section(st);
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  st.regions["tolerance_window"] = {p.x, p.y, p.x + s.x, p.y + s.y};
  ImGui::End();
}

}  // namespace airr::ui
