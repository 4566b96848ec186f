// The designer's file actions: open, save, add a prop, drop a file, export the layout, render and plots.
#include <filesystem>

#include "airr/analysis/plot_png.hpp"
#include "airr/analysis/psf_png.hpp"
#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/mesh_step.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/memory_need.hpp"
#include "airr/render/render_metadata.hpp"
#include "airr/ui/platform/recovery_copy.hpp"
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

void studio_open(studio& st, const std::string& path) {
  try {
    std::vector<std::string> notes;  // a glTF layout's: which observer, a doubtful scale
    const scene s = load_scene(path, {}, notes);
    check_render_memory(s, st.session_options);  // the scene open now stays
    studio_start(st, s, path);
    st.settings.last_dir = fs::path(path).parent_path().string();
    st.status = "opened " + path;
    for (const auto& n : notes) st.status += "; " + n;
  } catch (const std::exception& e) {
    st.status = std::string("cannot open: ") + e.what();
  }
}

bool studio_save(studio& st, const std::string& path) {
  try {
    const std::string dir = fs::absolute(path).parent_path().string();
    const scene s = rebase_scene_paths(st.doc, dir);
    save_scene(s, path);
    st.doc = s;
    st.doc_path = path;
    st.saved = s;
    st.applied = s;  // same files, same layout: nothing to re-render
    add_recent_file(st.settings, path);
    st.settings.last_dir = dir;
    st.status = "saved " + path;
    return true;
  } catch (const std::exception& e) {
    // The scene stays open and unsaved; a copy goes where a restart offers it back.
    const auto failed = write_recovery_copy({st.doc_path, st.doc});
    st.status =
        std::string("cannot save: ") + e.what() + "; the changes are still here, unsaved, " +
        (failed ? "and no recovery copy could be written: " + *failed : "with a recovery copy in " + recovery_path());
    return false;
  }
}

bool studio_add_prop(studio& st, const std::string& path) {
  try {
    const std::string full = absolute_path(path);
    const auto mesh = cached_prop_mesh(full, "");
    prop_params p;
    p.name = fs::path(path).stem().string();
    p.mesh = full;
    p.surface = prop_surface::material;
    st.doc.props.push_back(p);
    st.status = "added prop " + p.name + " (" + std::to_string(mesh->indices.size() / 3) + " triangles)";
    return true;
  } catch (const std::exception& e) {
    st.status = std::string("cannot add the prop: ") + e.what();
    return false;
  }
}

bool studio_export_gltf(studio& st, const std::string& path) {
  try {
    export_gltf_layout(st.doc, path);
    st.status = "exported the layout to " + path;
    return true;
  } catch (const std::exception& e) {
    st.status = std::string("cannot export: ") + e.what();
    return false;
  }
}

void studio_drop_file(studio& st, const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (is_step_path(path)) {
    studio_add_prop(st, path);  // a CAD housing
    return;
  }
  if (is_gltf_path(path)) {
    // A file with parts in it is a layout to open; any other model is a prop.
    bool layout = false;
    try {
      layout = gltf_has_layout_roles(path);
    } catch (const std::exception& e) {
      st.status = std::string("cannot read: ") + e.what();
      return;
    }
    if (!layout) {
      studio_add_prop(st, path);
      return;
    }
  }
  if (ext == ".json" || is_gltf_path(path)) {
    if (studio_dirty(st)) {
      st.pending_path = path;
      st.after_save_prompt = studio::pending_action::open_path;
      st.show_save_prompt = true;
    } else {
      studio_open(st, path);
    }
    return;
  }
  try {
    load_image(path);  // refuse unreadable images before they reach the layout
    st.doc.source.image = absolute_path(path);
    st.status = "source image: " + path;
  } catch (const std::exception& e) {
    st.status = std::string("not an image: ") + e.what();
  }
}

bool studio_export_render(studio& st, const std::string& path) {
  try {
    const render_snapshot snap = st.session->snapshot();
    if (!snap.rgb || snap.spp == 0) throw input_error("nothing rendered yet");
    const float exposure = float(default_exposure(st.doc) * std::exp2(st.settings.exposure_ev));
    image_metadata meta = render_metadata(st.doc, snap, exposure);
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool exr = ext == ".exr";
    const std::vector<image_rgb> parts = snap.component_images();
    const std::vector<std::string> names = snap.component_image_names();
    // EXR: the whole image with its components as layers; PNG: what the view shows.
    std::vector<image_layer> layers;
    for (std::size_t k = 0; k < parts.size() && exr; ++k) layers.push_back({names[k], &parts[k]});
    const int shown = st.view.component;
    const bool one = !exr && shown >= 0 && std::size_t(shown) < parts.size();
    if (one) meta["airr:component"] = names[std::size_t(shown)];
    write_image(path, one ? parts[std::size_t(shown)] : snap.image(), meta, exposure, layers);
    st.status = "exported " + path + " (" + std::to_string(snap.spp) + " spp)";
    return true;
  } catch (const std::exception& e) {
    st.status = std::string("cannot export: ") + e.what();
    return false;
  }
}

bool studio_export_plots(studio& st, const std::string& path) {
  const auto pred = st.analysis.predicted();
  const auto meas = st.analysis.measured();
  std::string csv = "curve,x,y\n";
  auto add = [&](const std::string& name, const std::vector<double>& x, const std::vector<double>& y) {
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
      csv += name + "," + std::to_string(x[i]) + "," + std::to_string(y[i]) + "\n";
    }
  };
  if (pred) {
    add("mtf_predicted(lp_per_mm)", pred->lp_per_mm, pred->mtf);
    add("psf_cross_section(mm)", pred->psf_x_mm, pred->psf_density);
    add("mean_mtf_vs_floating_distance(mm)", pred->sweep_d_mm, pred->sweep_mean_mtf);
  }
  if (meas && meas->found) add("mtf_measured_on_render(lp_per_mm)", meas->lp_per_mm, meas->mtf);
  // The Bokeh tab's numbers, when they are the current layout's.
  if (const auto b = st.analysis.bokeh(); b && b->generation == st.generation) {
    std::vector<double> offsets, r50, r80, row_x, row;
    for (const auto& p : b->focus.planes) {
      offsets.push_back(p.offset_mm);
      r50.push_back(p.r50_mm);
      r80.push_back(p.r80_mm);
    }
    add("through_focus_r50(offset_mm)", offsets, r50);
    add("through_focus_r80(offset_mm)", offsets, r80);
    const int mid = b->psf.size / 2;
    for (int col = 0; col < b->psf.size; ++col) {
      row_x.push_back((col - mid) * b->psf.mm_per_pixel);
      row.push_back(b->psf.at(col, mid));
    }
    add("psf2d_middle_row(mm)", row_x, row);
    for (int r = 0; r < b->spots.n; ++r) {
      std::vector<double> x, y;
      for (int c = 0; c < b->spots.n; ++c) {
        const auto& spot = b->spots.spots[std::size_t(r) * b->spots.n + c];
        x.push_back(spot.x_mm);
        y.push_back(spot.missed.empty() ? spot.r50_mm : std::nan(""));
      }
      add("spot_r50_at_y_" + std::to_string(b->spots.spots[std::size_t(r) * b->spots.n].y_mm) + "(x_mm)", x, y);
    }
    for (std::size_t t = 0; t < b->map_tilt_deg.size(); ++t) {
      const auto first = b->map_r50_mm.begin() + std::ptrdiff_t(t * b->map_d_mm.size());
      add("blur_map_r50_at_tilt_" + std::to_string(b->map_tilt_deg[t]) + "(D_mm)", b->map_d_mm,
          std::vector<double>(first, first + std::ptrdiff_t(b->map_d_mm.size())));
    }
  }
  for (const auto& p : st.pinned_mtf) add("pinned:" + p.label, p.x, p.y);
  try {
    write_file_atomic(path, csv);
    st.status = "exported " + path;
    return true;
  } catch (const std::exception& e) {
    st.status = std::string("cannot export: ") + e.what();
    return false;
  }
}

bool studio_export_bokeh(studio& st, const std::string& path) {
  namespace an = analysis;
  const auto b = st.analysis.bokeh();
  if (!b || b->generation != st.generation || b->psf.size == 0) {
    st.status = "cannot export: the bokeh views are not yet those of the current layout";
    return false;
  }
  const fs::path base(path);
  const std::string stem = (base.parent_path() / base.stem()).string();
  char layout[96];
  std::snprintf(layout, sizeof layout, "D %.1f mm, tilt %.1f deg", b->floating_distance_mm, b->tilt_deg);
  try {
    an::write_psf_panels_png(path, {{&b->psf, "aerial-image plane"}},
                             {.title = "model PSF, " + std::string(layout), .panel_width = 640, .panel_height = 560});
    an::write_focus_plot_png(stem + "_focus.png", b->focus, "through focus, " + std::string(layout));
    std::vector<an::psf_panel> strip, spots;
    for (std::size_t i : b->strip)
      strip.push_back({&b->focus.planes[i].grid, std::to_string(int(b->focus.planes[i].offset_mm)) + " mm"});
    an::write_psf_panels_png(stem + "_strip.png", strip,
                             {.title = "through focus, " + std::string(layout), .columns = int(strip.size())});
    for (const auto& s : b->spots.spots) {
      char label[64];
      std::snprintf(label, sizeof label, "(%+.3g, %+.3g) mm, r50 %.3g mm", s.x_mm, s.y_mm, s.r50_mm);
      spots.push_back({&s.grid, s.missed.empty() ? label : "not reached"});
    }
    an::write_psf_panels_png(stem + "_spots.png", spots,
                             {.title = "spot matrix, " + std::string(layout), .columns = b->spots.n});
    double lo = 1e300, hi = -1e300;
    for (double v : b->map_r50_mm)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(hi > lo)) lo = 0, hi = std::max(hi, 1e-6);
    an::write_heatmap_png(stem + "_map.png", b->map_r50_mm, int(b->map_d_mm.size()), int(b->map_tilt_deg.size()),
                          {.title = "r50 over floating distance and tilt",
                           .x_title = "floating distance D (mm)",
                           .y_title = "retroreflector tilt (deg)",
                           .value_title = "r50 (mm)",
                           .x_min = b->map_d_mm.front(),
                           .x_max = b->map_d_mm.back(),
                           .y_min = b->map_tilt_deg.front(),
                           .y_max = b->map_tilt_deg.back(),
                           .value_min = lo,
                           .value_max = hi,
                           .marker = std::make_pair(b->floating_distance_mm, b->tilt_deg),
                           .marker_label = "design",
                           .scale_bar_unit = "",
                           .width = 900,
                           .height = 760});
    st.status = "exported " + path + " and " + stem + "_{focus,strip,spots,map}.png";
    return true;
  } catch (const std::exception& e) {
    st.status = std::string("cannot export: ") + e.what();
    return false;
  }
}

}  // namespace airr::ui
