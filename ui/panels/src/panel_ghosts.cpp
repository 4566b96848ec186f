// The Ghosts window: the ghost table of the applied layout (airr ghosts), ranked; a click on a row
// shows that class's image in the render view and a few of its paths in the 3D and layout views;
// a typed path expression is measured as a class of its own.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/core/error.hpp"
#include "airr/render/path_expression.hpp"
#include "airr/ui/panels/panels.hpp"

namespace airr::ui {

bool start_ghost_job(studio& st) {
  ghost_window& g = st.ghosts;
  g.error.clear();
  if (!st.doc_error.empty()) {
    g.error = "the layout has an error: " + st.doc_error;
    return false;
  }
  const ghost_params p{.census_spp = 1, .spp = std::uint64_t(std::max(1, g.spp)), .expressions = g.expressions};
  try {
    for (const std::string& e : p.expressions) path_expression::parse(e).bound(st.applied, true);
    g.job = std::make_unique<ghost_job>(st.applied, p, st.generation);
  } catch (const std::exception& e) {
    g.error = one_line(e.what());
    return false;
  }
  st.status = "finding the ghosts";
  return true;
}

bool collect_ghost_job(studio& st) {
  ghost_window& g = st.ghosts;
  if (!g.job || g.job->running()) return false;
  if (auto r = g.job->result()) {
    g.found = std::move(*r);
    g.found_generation = g.job->generation();
    g.shown = -1;
    st.status = "found " + std::to_string(g.found->table.classes.size()) + " path classes in " +
                std::to_string(int(std::lround(g.job->seconds()))) + " s";
  } else if (!g.job->error().empty()) {
    g.error = g.job->error();
  }
  g.job.reset();
  return true;
}

static void ghost_table_rows(studio& st) {
  ghost_window& g = st.ghosts;
  const ghost_table& t = g.found->table;
  const ImGuiTableFlags flags =
      ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("ghost_table", 7, flags, ImVec2(0, ImGui::GetContentRegionAvail().y))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  for (const char* h : {"#", "peak #", "share", "peak", "arcmin", "depth mm", "path"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (std::size_t k = 0; k < t.classes.size(); ++k) {
    const ghost_class& c = t.classes[k];
    const auto peak_rank = std::find(t.by_peak.begin(), t.by_peak.end(), k) - t.by_peak.begin() + 1;
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    char rank[24];
    std::snprintf(rank, sizeof rank, "%zu", k + 1);
    if (ImGui::Selectable(rank, g.shown == int(k), ImGuiSelectableFlags_SpanAllColumns))
      g.shown = g.shown == int(k) ? -1 : int(k);
    ImGui::TableNextColumn();
    ImGui::Text("%td", peak_rank);
    ImGui::TableNextColumn();
    ImGui::Text("%.4f", c.share);
    ImGui::TableNextColumn();
    ImGui::Text("%.3g", c.peak);
    ImGui::TableNextColumn();
    if (std::isfinite(c.separation_arcmin)) ImGui::Text("%.1f", c.separation_arcmin);
    ImGui::TableNextColumn();
    if (std::isfinite(c.distance_mm) && std::isfinite(t.aerial_distance_mm))
      ImGui::Text("%+.1f", c.distance_mm - t.aerial_distance_mm);
    ImGui::TableNextColumn();
    ImGui::TextUnformatted((c.expression + (c.typed ? "  (typed)" : "")).c_str());
  }
  ImGui::EndTable();
}

void draw_ghosts_window(studio& st) {
  ghost_window& g = st.ghosts;
  collect_ghost_job(st);
  if (!g.show) return;
  ImGui::SetNextWindowSize(ImVec2(46 * ImGui::GetFontSize(), 22 * ImGui::GetFontSize()), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Ghosts", &g.show)) {
    ImGui::End();
    return;
  }
  const bool running = g.job && g.job->running();
  ImGui::BeginDisabled(running);
  if (ImGui::Button("Find ghosts")) start_ghost_job(st);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(5 * ImGui::GetFontSize());
  ImGui::InputInt("spp", &g.spp);
  g.spp = std::clamp(g.spp, 1, 4096);
  ImGui::SetNextItemWidth(18 * ImGui::GetFontSize());
  const bool entered = ImGui::InputTextWithHint("##typed", "a path expression, e.g. D .* H:r1 .* E", &g.typed,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Add a class") || entered) && !g.typed.empty()) {
    try {
      path_expression::parse(g.typed).bound(st.applied, true);
      g.expressions.push_back(g.typed);
      g.typed.clear();
      start_ghost_job(st);
    } catch (const std::exception& e) {
      g.error = one_line(e.what());
    }
  }
  ImGui::EndDisabled();
  if (running) {
    ImGui::ProgressBar(float(g.job->progress()), ImVec2(-6 * ImGui::GetFontSize(), 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) g.job->cancel();
  }
  if (!g.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", g.error.c_str());
  if (g.found) {
    if (g.found_generation != st.generation) ImGui::TextDisabled("(of an earlier layout: find them again)");
    ImGui::TextDisabled("the aerial image %.1f mm from the observer; click a row to show its class",
                        g.found->table.aerial_distance_mm);
    ghost_table_rows(st);
  }
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  st.regions["ghosts_window"] = {at.x, at.y, at.x + size.x, at.y + size.y};
  ImGui::End();
}

bool run_ghost_script(studio& st, ghost_script& script) {
  if (!script.run || script.finished) return false;
  if (!script.started) {
    script.started = true;
    st.ghosts.show = true;
    if (!start_ghost_job(st)) {
      script.error = st.ghosts.error;
      script.finished = true;
      return false;
    }
    return true;
  }
  if (st.ghosts.job) return true;  // draw_ghosts_window collects it when it ends
  script.finished = true;
  if (!st.ghosts.found) {
    script.error = st.ghosts.error.empty() ? "no ghost table" : st.ghosts.error;
    return false;
  }
  const ghost_table& t = st.ghosts.found->table;
  for (std::size_t k = 0; k < t.classes.size(); ++k)
    std::fprintf(stderr, "ghost class %zu: %s share %.5f peak %.5g paths %zu\n", k + 1, t.classes[k].expression.c_str(),
                 t.classes[k].share, t.classes[k].peak, st.ghosts.found->paths[k].size());
  if (script.show > 0 && script.show <= int(t.classes.size())) st.ghosts.shown = script.show - 1;
  return true;  // one more frame, to draw what is shown
}

}  // namespace airr::ui
