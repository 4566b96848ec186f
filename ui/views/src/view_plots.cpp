// The plots, in two tabs. MTF: predicted from the model PSF (every edit) and measured on the
// render (when the source shows a slanted edge), the PSF's cross-section, and mean MTF against
// floating distance. Bokeh: panel_bokeh.cpp.
// "Pin" keeps the current predicted curve for before/after comparisons. The viewing zone shows
// where on the observer's orbit the aerial image can be seen; a click moves the observer there.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <imgui.h>

#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/ui/views/plot_widget.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

bool start_full_zone(studio& st) {
  const auto pred = st.analysis.predicted();
  if (!pred || pred->zone.visible.empty() || pred->generation != st.generation) return false;
  eye_grid g = pred->zone.grid;
  g.nx = g.ny = 15;
  st.zone_job_ = std::make_unique<zone_job>(
      st.applied, g, full_zone_params{.rows_per_eye = 32, .render_size = 32, .render_spp = 8}, st.generation);
  return true;
}

// The full pass's quantities from "brightness (full)" on, in the order of the zone menu; the
// legibility maps are the share of the image at each default contrast threshold.
static constexpr int first_legible_quantity = 6, first_char_quantity = 9;
static const std::vector<double>* zone_values(const full_zone_map& m, int quantity, std::vector<double>& shown) {
  switch (quantity) {
    case 1:
      return &m.brightness;
    case 2:
      return &m.mean_mtf;
    case 3:
      return &m.stray_ratio;
    case 4:
      return &m.luminance;
    case 5: {
      double top = 1;
      shown = contrast_shown(m, top);
      return &shown;
    }
    case first_char_quantity: {
      // Illegible eyes (an infinite height) at the top of the scale, with the largest legible one.
      double top = 0;
      for (double v : m.char_height_mm) top = std::isfinite(v) ? std::max(top, v) : top;
      shown = m.char_height_mm;
      for (double& v : shown) v = std::isinf(v) ? top : v;
      return &shown;
    }
    default:
      return &m.contrast_share.at(std::size_t(quantity - first_legible_quantity));
  }
}

// The eye from which the smallest character is legible (the eye count when every eye's is
// infinite or unseen).
static std::size_t best_character_eye(const full_zone_map& m) {
  const std::vector<double>& h = m.char_height_mm;
  std::size_t best = h.size();
  for (std::size_t e = 0; e < h.size(); ++e) {
    if (std::isfinite(h[e]) && (best == h.size() || h[e] < h[best])) best = e;
  }
  return best;
}

// One map of the zone: the values on the grid, the observer (and any marked eye) on top.
static plot_hover draw_zone_map(const char* id, const eye_grid& g, const plot_heatmap& map,
                                const std::vector<plot_curve>& marks, const char* title, float h) {
  const double hx = 0.5 * (g.x_max - g.x_min) / std::max(1, g.nx - 1),
               hy = 0.5 * (g.y_max - g.y_min) / std::max(1, g.ny - 1);
  return draw_plot(id, marks,
                   {.title = title,
                    .x_title = "observer azimuth (deg)",
                    .y_title = "elevation (deg)",
                    .x_min = g.x_min - hx,
                    .x_max = g.x_max + hx,
                    .y_min = g.y_min - hy,
                    .y_max = g.y_max + hy,
                    .auto_x = false,
                    .auto_y = false,
                    .height = h,
                    .heatmap = &map});
}

// The contrast threshold of the legibility map beside the zone, chosen among the full pass's.
static void choose_legibility_threshold(studio& st, const full_zone_map& full) {
  const int n = int(full.thresholds.size());
  st.legibility_threshold = std::clamp(st.legibility_threshold, 0, std::max(0, n - 1));
  if (n == 0) return;
  char label[32];
  std::snprintf(label, sizeof label, "%g", full.thresholds[std::size_t(st.legibility_threshold)]);
  ImGui::SetNextItemWidth(4 * ImGui::GetFontSize());
  if (ImGui::BeginCombo("legible at", label)) {
    for (int k = 0; k < n; ++k) {
      std::snprintf(label, sizeof label, "%g", full.thresholds[std::size_t(k)]);
      if (ImGui::Selectable(label, k == st.legibility_threshold)) st.legibility_threshold = k;
    }
    ImGui::EndCombo();
  }
}

// The legibility map beside the zone's quantity: from each eye, the share of the aerial image
// legible at the chosen contrast threshold.
static plot_hover draw_legibility_map(const studio& st, const full_zone_map& full, float h) {
  if (full.thresholds.empty()) return {};
  const std::size_t k = std::size_t(st.legibility_threshold);
  const eye_grid& g = full.grid;
  const plot_heatmap map{full.contrast_share.at(k), g.nx, g.ny, g.x_min, g.x_max, g.y_min, g.y_max, 0, 1};
  const glm::dvec2 at = eye_grid_coordinates(st.doc, g, observer_position(st.doc));
  char title[64];
  std::snprintf(title, sizeof title, "share legible at %g", full.thresholds[k]);
  // The observer's dot without a legend: the map beside it names it, and a small map keeps its cells.
  return draw_zone_map("zone_legibility", g, map, {{"", {at.x}, {at.y}, IM_COL32(255, 255, 255, 255)}}, title, h);
}

// The viewing zone: the geometric visible fraction from the predicted plots, or a quantity of
// the full pass (started on demand, for the current layout only), and once the full pass exists
// the legibility map beside it.
template <typename Keep>
static void draw_viewing_zone(studio& st, const predicted_plots* pred, float h, const Keep& keep) {
  static const char* const quantities[] = {"visible fraction",         "brightness (full)",   "mean MTF (full)",
                                           "stray light (full)",       "luminance (full)",    "contrast (full)",
                                           "legible at 1.5 (full)",    "legible at 3 (full)", "legible at 25 (full)",
                                           "smallest character (full)"};
  static_assert(IM_ARRAYSIZE(quantities) == IM_ARRAYSIZE(zone_quantity_keys));
  ImGui::SetNextItemWidth(10 * ImGui::GetFontSize());
  ImGui::Combo("viewing zone", &st.zone_quantity, quantities, IM_ARRAYSIZE(quantities));
  const bool geometric = st.zone_quantity == 0;
  const bool legibility_quantity = st.zone_quantity >= first_legible_quantity && st.zone_quantity < first_char_quantity;
  const bool has_zone = pred && !pred->zone.visible.empty();
  zone_job* job = st.zone_job_.get();
  const bool current = job && job->generation() == st.generation;
  std::optional<full_zone_map> full;
  if (current && !job->running()) full = job->result();
  const bool beside = full && !legibility_quantity;
  if (beside) {
    ImGui::SameLine();
    choose_legibility_threshold(st, *full);
  }
  if (current && job->running()) {
    ImGui::ProgressBar(float(job->progress()), ImVec2(-6 * ImGui::GetFontSize(), 0));
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) st.zone_job_.reset();
  } else if (has_zone && !full) {
    if (current && !job->error().empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", job->error().c_str());
    if (ImGui::Button("Compute the full pass (15 x 15 eyes)")) start_full_zone(st);
    if (geometric) {
      ImGui::SameLine();
      ImGui::TextDisabled("(the zone's other maps and its legibility)");
    }
  }
  const eye_grid* grid = nullptr;
  const std::vector<double>* values = nullptr;
  double hi = 1;
  std::vector<double> shown;  // the contrast, infinite values at its top
  std::optional<double> legible;
  if (geometric) {
    if (has_zone) {
      grid = &pred->zone.grid;
      values = &pred->zone.visible;
    }
  } else if (full) {
    grid = &full->grid;
    values = zone_values(*full, st.zone_quantity, shown);
    if (legibility_quantity) {
      legible = legible_share(*full, std::size_t(st.zone_quantity - first_legible_quantity));
    } else if (st.zone_quantity != 1) {
      hi = 0;
      for (double v : *values) hi = std::isfinite(v) ? std::max(hi, v) : hi;
      if (!(hi > 0)) hi = 1;
    }
  }
  if (!grid || !values) return;
  const eye_grid& g = *grid;
  const bool character = full && st.zone_quantity == first_char_quantity;
  // The character heights span a narrow band: the scale starts at the smallest.
  double lo = 0;
  if (character) {
    lo = hi;
    for (double v : *values) lo = std::isfinite(v) ? std::min(lo, v) : lo;
    if (!(lo < hi)) lo = 0;
  }
  const plot_heatmap map{*values, g.nx, g.ny, g.x_min, g.x_max, g.y_min, g.y_max, lo, hi};
  const glm::dvec2 at = eye_grid_coordinates(st.doc, g, observer_position(st.doc));
  std::vector<plot_curve> observer = {{"observer", {at.x}, {at.y}, IM_COL32(255, 255, 255, 255)}};
  char title[160];
  const std::size_t eyes = values->size();
  const std::size_t best_eye = character ? best_character_eye(*full) : eyes;
  const bool best = best_eye < eyes;
  if (best) {
    const int ix = int(best_eye) % g.nx, iy = int(best_eye) / g.nx;
    observer.push_back({"best eye", {g.x_at(ix)}, {g.y_at(iy)}, IM_COL32(255, 90, 90, 255)});
  }
  if (legible) {
    std::snprintf(title, sizeof title, "%s: share of the image; legible share of the zone %.2f",
                  quantities[st.zone_quantity], *legible);
  } else if (character) {
    std::snprintf(title, sizeof title, best ? "smallest character, %.3g to %.3g mm" : "illegible from every eye", lo,
                  hi);
  } else {
    std::snprintf(title, sizeof title, "%s, 0 to %.3g", quantities[st.zone_quantity], hi);
  }
  const bool table = beside && ImGui::BeginTable("zone_maps", 2);
  if (table) ImGui::TableNextColumn();
  const plot_hover zone = draw_zone_map("zone", g, map, observer, title, h);
  keep("plot_zone", zone);
  st.regions["plot_zone_title"] = {zone.title_box[0], zone.title_box[1], zone.title_box[2], zone.title_box[3]};
  st.regions["plot_zone_y_title"] = {zone.y_title_box[0], zone.y_title_box[1], zone.y_title_box[2],
                                     zone.y_title_box[3]};
  plot_hover legibility{};
  if (table) {
    ImGui::TableNextColumn();
    legibility = draw_legibility_map(st, *full, h);
    keep("plot_zone_legibility", legibility);
    ImGui::EndTable();
  }
  if (geometric && pred) {
    ImGui::TextDisabled("%.0f ms (%d x %d eyes, geometric); click: move the observer", pred->zone_ms, g.nx, g.ny);
  }
  if (full) {
    ImGui::TextDisabled("full pass %.1f s (%d x %d eyes); grey: nothing seen; click: move the observer", full->seconds,
                        full->grid.nx, full->grid.ny);
    if (table && !full->thresholds.empty()) {
      const std::size_t k = std::size_t(st.legibility_threshold);
      ImGui::TextDisabled("legible share of the zone at %g: %.2f (the eyes that see %.0f%% of the image legible)",
                          full->thresholds[k], legible_share(*full, k), 100 * legible_image_share);
    }
    if (best) {
      ImGui::TextDisabled(
          "best eye (red): %.3g mm, %.3g arcmin; the top of the scale also holds the eyes where the "
          "contrast leaves too little for any character",
          full->char_height_mm[best_eye], full->char_arcmin[best_eye]);
    }
  }
  const auto move_observer = [&](const plot_hover& p, const eye_grid& on) {
    place_observer(st.doc, on, p.x, p.y);
    char msg[96];
    std::snprintf(msg, sizeof msg, "observer moved to azimuth %.1f, elevation %.1f deg", p.x, p.y);
    st.status = msg;
  };
  if (zone.clicked) move_observer(zone, g);
  if (legibility.clicked) move_observer(legibility, full->grid);
}

static void draw_mtf_tab(studio& st) {
  const auto pred = st.analysis.predicted();
  const auto meas = st.analysis.measured();
  const bool current = pred && pred->generation == st.generation;

  if (pred && !pred->error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", pred->error.c_str());
  if (pred) {
    ImGui::Text("model PSF: r50 %.3f mm   mean MTF (0-1 lp/mm) %.3f", pred->r50_mm, pred->mean_mtf);
    if (in_cd_m2(st.doc.source)) {
      ImGui::Text("MTF50 %.2f lp/mm   brightness %.4f x source = %.4g cd/m2", pred->mtf50, pred->brightness,
                  pred->brightness * st.doc.source.luminance_cd_m2);
    } else {
      ImGui::Text("MTF50 %.2f lp/mm   brightness %.4f x source", pred->mtf50, pred->brightness);
    }
    ImGui::TextDisabled("PSF %.1f ms, sweep %.1f ms%s", pred->psf_ms, pred->sweep_ms, current ? "" : "   (updating)");
  }
  if (ImGui::Button("Pin MTF") && pred && !pred->mtf.empty()) {
    char label[64];
    std::snprintf(label, sizeof label, "pinned D=%.0f tilt=%.0f", airr::floating_distance(st.doc),
                  st.doc.sheet().pose.pitch_deg);
    st.pinned_mtf.push_back({label, pred->lp_per_mm, pred->mtf});
    if (st.pinned_mtf.size() > 4) st.pinned_mtf.erase(st.pinned_mtf.begin());
  }
  ImGui::SameLine();
  if (ImGui::Button("Clear pins")) st.pinned_mtf.clear();

  const float h = std::max(120.0f, (ImGui::GetContentRegionAvail().y - 3 * ImGui::GetFrameHeightWithSpacing()) / 4.0f /
                                       (ImGui::GetFontSize() / 13.0f));
  std::vector<plot_curve> mtf;
  if (pred) mtf.push_back({"predicted (model PSF)", pred->lp_per_mm, pred->mtf});
  if (meas && meas->found && meas->generation == st.generation && meas->readable_lp_per_mm > 0) {
    // Only where the noise allows a reading, with a band of two standard deviations.
    plot_curve c;
    char label[80];
    std::snprintf(label, sizeof label, "measured on render (%llu spp, +-2 sd)",
                  static_cast<unsigned long long>(meas->spp));
    c.label = label;
    for (std::size_t i = 0; i < meas->lp_per_mm.size() && meas->lp_per_mm[i] <= meas->readable_lp_per_mm; ++i) {
      c.x.push_back(meas->lp_per_mm[i]);
      c.y.push_back(meas->mtf[i]);
      c.band.push_back(2 * meas->mtf_sigma[i]);
    }
    mtf.push_back(std::move(c));
  }
  for (std::size_t i = 0; i < st.pinned_mtf.size(); ++i) {
    mtf.push_back({st.pinned_mtf[i].label, st.pinned_mtf[i].x, st.pinned_mtf[i].y, plot_palette(int(i) + 2), true});
  }
  auto keep = [&](const char* name, const plot_hover& h) {
    st.regions[name] = {h.area[0], h.area[1], h.area[2], h.area[3]};
  };
  keep("plot_mtf", draw_plot("mtf", mtf,
                             {.title = "MTF",
                              .x_title = "spatial frequency (lp/mm)",
                              .y_title = "MTF",
                              .x_min = 0,
                              .x_max = 2,
                              .y_min = 0,
                              .y_max = 1.05,
                              .auto_x = false,
                              .auto_y = false,
                              .height = h}));
  if (meas && !meas->found && !meas->note.empty()) ImGui::TextDisabled("render MTF: %s", meas->note.c_str());
  if (meas && meas->found && meas->generation == st.generation) {
    const double top = meas->lp_per_mm.empty() ? 0 : meas->lp_per_mm.back();
    if (meas->readable_lp_per_mm <= 0) {
      ImGui::TextDisabled("render MTF: held back until its noise allows a reading (%llu spp)",
                          static_cast<unsigned long long>(meas->spp));
    } else if (meas->readable_lp_per_mm < top) {
      ImGui::TextDisabled("render MTF: readable to %.2f lp/mm at %llu spp (sd <= %.2f); beyond, noise",
                          meas->readable_lp_per_mm, static_cast<unsigned long long>(meas->spp), measured_mtf_max_sigma);
    }
  }

  std::vector<plot_curve> psf;
  if (pred) psf.push_back({"PSF cross-section", pred->psf_x_mm, pred->psf_density});
  keep("plot_psf", draw_plot("psf", psf,
                             {.title = "PSF through the centre (y = 0)",
                              .x_title = "x on the aerial-image plane (mm)",
                              .y_title = "energy density (1/mm^2)",
                              .auto_x = true,
                              .auto_y = true,
                              .height = h}));

  std::vector<plot_curve> sweep;
  if (pred && !pred->sweep_d_mm.empty()) {
    sweep.push_back({"mean MTF (0-1 lp/mm)", pred->sweep_d_mm, pred->sweep_mean_mtf});
    // Distances where the layout is no layout: the curve's gap, marked on the axis.
    plot_curve none{"no layout", {}, {}, IM_COL32(230, 80, 60, 255)};
    none.points = true;
    for (std::size_t i = 0; i < pred->sweep_reasons.size() && i < pred->sweep_d_mm.size(); ++i) {
      if (pred->sweep_reasons[i].empty()) continue;
      none.x.push_back(pred->sweep_d_mm[i]);
      none.y.push_back(0.02);
    }
    if (!none.x.empty()) sweep.push_back(std::move(none));
    sweep.push_back({"current D",
                     {airr::floating_distance(st.doc), airr::floating_distance(st.doc)},
                     {0.0, 1.0},
                     IM_COL32(160, 160, 160, 255),
                     true});
  }
  keep("plot_sweep", draw_plot("sweep", sweep,
                               {.title = "Mean MTF against floating distance",
                                .x_title = "floating distance D (mm)",
                                .y_title = "mean MTF",
                                .x_min = 140,
                                .x_max = 310,
                                .y_min = 0,
                                .y_max = 1.05,
                                .auto_x = false,
                                .auto_y = false,
                                .height = h}));

  draw_viewing_zone(st, pred.get(), h, keep);
}

void draw_plots_panel(studio& st) {
  ImGui::Begin("Plots");
  if (ImGui::BeginTabBar("plots_tabs")) {
    const char* names[] = {"MTF", "Bokeh"};
    for (int k = 0; k < 2; ++k) {
      const ImGuiTabItemFlags flags = st.select_plots_tab && st.plots_tab == k ? ImGuiTabItemFlags_SetSelected : 0;
      if (ImGui::BeginTabItem(names[k], nullptr, flags)) {
        if (!st.select_plots_tab) st.plots_tab = k;
        k == 0 ? draw_mtf_tab(st) : draw_bokeh_tab(st);
        ImGui::EndTabItem();
      }
    }
    st.select_plots_tab = false;
    ImGui::EndTabBar();
  }
  ImGui::End();
}

}  // namespace airr::ui
