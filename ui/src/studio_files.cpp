// The designer's file actions: open, save, add a prop, drop a file, export the layout, render and plots.
#include <filesystem>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/render_metadata.hpp"
#include "studio_private.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

void studio_open(studio& st, const std::string& path) {
  try {
    std::vector<std::string> notes;  // a glTF layout's: which observer, a doubtful scale
    const scene s = load_scene(path, {}, notes);
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
    const auto failed = write_recovery_copy(st);
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
    // EXR: the whole image with its components as layers; PNG: what the view shows.
    std::vector<image_layer> layers;
    for (std::size_t k = 0; k < parts.size() && exr; ++k) layers.push_back({component_names[k], &parts[k]});
    const int shown = st.view.component;
    const bool one = !exr && shown >= 0 && std::size_t(shown) < parts.size();
    if (one) meta["airr:component"] = component_names[shown];
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

}  // namespace airr::ui
