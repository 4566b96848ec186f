#include "airr/ui/window/screenshot_notes.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "airr/core/files.hpp"
#include "airr/ui/views/layout_projection.hpp"
#include "airr/ui/views/luminance_scale.hpp"

namespace airr::ui {

void write_screenshot_notes(const studio& st, const std::string& path, int fw, int fh, float sx, float sy) {
  nlohmann::json regions;
  for (const auto& [name, r] : st.regions) regions[name] = {r[0] * sx, r[1] * sy, r[2] * sx, r[3] * sy};
  // The layout view's labels, the parts' outlines and the marks (scale bar, handles) they keep clear of.
  auto rect = [&](const screen_rect& r) { return nlohmann::json{r.x0 * sx, r.y0 * sy, r.x1 * sx, r.y1 * sy}; };
  nlohmann::json views;
  for (const auto& [name, drawn] : st.layout_views) {
    const projection_view& v = *drawn;
    nlohmann::json& j = views[name];
    j["labels"] = nlohmann::json::array();
    for (const auto& t : v.labels) j["labels"].push_back({{"text", t.text}, {"box", rect(t.place.box)}});
    j["outlines"] = nlohmann::json::array();
    for (const auto& g : v.outlines) j["outlines"].push_back({g.a.x * sx, g.a.y * sy, g.b.x * sx, g.b.y * sy});
    j["marks"] = nlohmann::json::array({rect(v.scale_box)});
    for (const auto& r : v.handles) j["marks"].push_back(rect(r));
  }
  // What the Bokeh tab showed (when it was open), its views' times per edit.
  nlohmann::json bokeh;
  if (const auto b = st.analysis.bokeh(); b && st.plots_tab == 1) {
    const auto& shown = st.bokeh_shown;
    bokeh = {
        {"generation", shown.generation},
        {"current", shown.current},
        {"r50_mm", shown.r50_mm},
        {"psf_area", {shown.psf_area[0] * sx, shown.psf_area[1] * sy, shown.psf_area[2] * sx, shown.psf_area[3] * sy}},
        {"psf_x_mm", shown.psf_x_mm},
        {"marker", {shown.marker[0] * sx, shown.marker[1] * sy}},
        {"marker_d_tilt", shown.marker_d_tilt},
        {"best_focus_mm", b->focus.best_offset_mm},
        {"ms", {{"psf", b->psf_ms}, {"focus", b->focus_ms}, {"spots", b->spots_ms}, {"map", b->map_ms}}}};
    std::fprintf(stderr,
                 "bokeh views (generation %llu%s): 2D PSF %.1f ms, through focus %.1f ms, spot matrix %.1f "
                 "ms, D x tilt map %.0f ms; MTF plot %.1f ms\n",
                 static_cast<unsigned long long>(b->generation), shown.current ? ", current" : ", previous", b->psf_ms,
                 b->focus_ms, b->spots_ms, b->map_ms, st.analysis.predicted() ? st.analysis.predicted()->psf_ms : 0.0);
  }
  // The Ghosts window's table and the class shown.
  nlohmann::json ghosts;
  if (const auto& found = st.ghosts.found) {
    ghosts["classes"] = nlohmann::json::array();
    for (const auto& c : found->table.classes) ghosts["classes"].push_back(c.expression);
    ghosts["shown"] = st.ghosts.shown;
    ghosts["render_shows_it"] = st.view.uploaded_ghost >= 0 && st.view.uploaded_ghost == st.ghosts.shown;
  }
  // What the render view shows and in which units.
  const nlohmann::json render_view = {{"units", image_units(st.doc.source)},
                                      {"luminance_view", st.view.uploaded_luminance},
                                      {"contrast_view", st.view.uploaded_contrast},
                                      {"scale_top", luminance_scale::for_exposure(st.view.uploaded_exposure).top},
                                      {"exposure", st.view.uploaded_exposure}};
  airr::write_file_atomic(path, nlohmann::json{{"width", fw},
                                               {"height", fh},
                                               {"regions", regions},
                                               {"layout_views", views},
                                               {"bokeh", bokeh},
                                               {"ghosts", ghosts},
                                               {"render_view", render_view}}
                                        .dump(2) +
                                    "\n");
}

}  // namespace airr::ui
