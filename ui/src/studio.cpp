#include "airr/ui/studio.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>

#include <imgui.h>

#include "airr/optics/assets.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/gltf_layout.hpp"
#include "airr/optics/image.hpp"
#include "airr/optics/json_reader.hpp"
#include "airr/optics/scene_json.hpp"
#include "airr/render/render_metadata.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

// New scene files end in .airr.json, the name their MIME type (application/x-airr-scene) claims.
static std::string suggested_scene_name(const std::string& doc_path) {
  if (doc_path.empty()) return "scene.airr.json";
  const fs::path p(doc_path);
  return p.extension() == ".json" ? p.filename().string() : p.stem().string() + ".airr.json";
}

static std::string recovery_path() { return state_dir() + "/recovery.json"; }

// Writes the open scene where the next start offers it back; the reason when it cannot.
static std::optional<std::string> write_recovery_copy(const studio& st) {
  const nlohmann::json j = {{"path", st.doc_path}, {"base_dir", st.doc.base_dir}, {"scene", scene_to_json(st.doc)}};
  try {
    write_file_atomic(recovery_path(), j.dump(2) + "\n");
    return std::nullopt;
  } catch (const std::exception& e) {
    return e.what();
  }
}

static std::string display_name(const studio& st) {
  return st.doc_path.empty() ? "untitled" : fs::path(st.doc_path).filename().string();
}

// Every prop's mesh (from the mesh cache, which check_scene filled) and its bounds, computed only
// for a mesh that was not there before (an edit that moves a prop keeps them).
static void keep_prop_meshes(studio& st, const scene& s) {
  std::vector<std::shared_ptr<const triangle_mesh>> meshes;
  std::vector<mesh_bounds> bounds;
  for (const auto& p : s.props) {
    std::shared_ptr<const triangle_mesh> m;
    try {
      m = cached_prop_mesh(resolve_scene_path(s, p.mesh), p.node);
    } catch (const std::exception&) {
    }
    const auto kept = std::find(st.prop_meshes.begin(), st.prop_meshes.end(), m);
    if (m && kept != st.prop_meshes.end())
      bounds.push_back(st.prop_bounds[std::size_t(kept - st.prop_meshes.begin())]);
    else
      bounds.push_back(m ? bounds_of(*m) : mesh_bounds{});
    meshes.push_back(std::move(m));
  }
  st.prop_meshes = std::move(meshes);
  st.prop_bounds = std::move(bounds);
}

// A shipped scene opens untitled, so that saving asks where: the assets are never written.
void studio_start(studio& st, const scene& s, const std::string& path) {
  keep_prop_meshes(st, s);
  st.view_3d.framed = false;
  st.doc = s;
  st.doc_path = is_shipped_asset(path) ? "" : path;
  st.saved = s;
  st.applied = s;
  st.doc_error.clear();
  if (!st.session) {
    st.session = std::make_unique<render_session>(s, st.session_options);
    st.generation = 0;
  } else {
    st.generation = st.session->edit(s);
  }
  st.analysis.submit_scene(s, st.generation, nullptr);
  st.view.uploaded_generation = ~0ull;
  if (!st.doc_path.empty()) add_recent_file(st.settings, st.doc_path);
}

bool studio_dirty(const studio& st) { return !st.saved || !(st.doc == *st.saved); }

void studio_apply_edits(studio& st, double now) {
  if (st.doc == st.applied) return;
  st.applied = st.doc;
  try {
    // The models are built once per accepted edit and shared by the tracer and the plots.
    const retro_model_list models = check_scene(st.doc, "layout");
    keep_prop_meshes(st, st.doc);
    st.doc_error.clear();
    st.generation = st.session->edit(st.doc, models);
    st.analysis.submit_scene(st.doc, st.generation, models.front());
    st.edit_time = now;
  } catch (const std::exception& e) {
    st.doc_error = e.what();
  }
}

void studio_open(studio& st, const std::string& path) {
  try {
    const scene s = load_scene(path);
    studio_start(st, s, path);
    st.settings.last_dir = fs::path(path).parent_path().string();
    st.status = "opened " + path;
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

// ---------------------------------------------------------------- recovery

void studio_keep_recovery(studio& st, double now) {
  if (!st.keep_recovery) return;
  if (!studio_dirty(st)) {
    if (st.last_recovery_write >= 0) studio_clear_recovery();
    st.last_recovery_write = -1;
    return;
  }
  if (st.last_recovery_write >= 0 && now - st.last_recovery_write < 10.0) return;
  st.last_recovery_write = now;
  if (const auto failed = write_recovery_copy(st)) st.status = "cannot write the recovery copy: " + *failed;
}

void studio_clear_recovery() {
  std::error_code ec;
  fs::remove(recovery_path(), ec);
}

void studio_check_recovery(studio& st) {
  std::error_code ec;
  if (!fs::exists(recovery_path(), ec)) return;
  try {
    st.recovery_text = read_text_file(recovery_path());
  } catch (const std::exception&) {
    st.recovery_text.clear();
  }
}

static void draw_recovery_prompt(studio& st) {
  if (st.recovery_text.empty()) return;
  if (!st.recovery_offered) {
    ImGui::OpenPopup("Recover unsaved changes?");
    st.recovery_offered = true;
  }
  if (ImGui::BeginPopupModal("Recover unsaved changes?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("A previous session ended with unsaved changes.");
    if (ImGui::Button("Recover")) {
      try {
        const auto j = parse_json(st.recovery_text, recovery_path());
        scene s = scene_from_json(j.at("scene"), recovery_path());
        s.base_dir = j.value("base_dir", std::string());
        st.doc = s;
        st.doc_path = j.value("path", std::string());
        st.saved.reset();  // recovered edits are unsaved
        st.status = "recovered unsaved changes" + (st.doc_path.empty() ? std::string() : " of " + st.doc_path);
      } catch (const std::exception& e) {
        st.status = std::string("cannot recover: ") + e.what();
      }
      st.recovery_text.clear();
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      studio_clear_recovery();
      st.recovery_text.clear();
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

// ---------------------------------------------------------------- frame

static std::string start_dir(const studio& st) {
  if (!st.doc_path.empty()) return fs::path(st.doc_path).parent_path().string();
  return st.settings.last_dir;
}

static void request_save_as(studio& st) {
  st.dialog.request(file_purpose::save_scene, true, "Save scene as", start_dir(st), {".json"},
                    suggested_scene_name(st.doc_path));
}

// Save: to the scene's own file, unless it came from a glTF layout (saved as a scene file instead).
static void save_or_ask(studio& st) {
  if (st.doc_path.empty() || is_gltf_path(st.doc_path))
    request_save_as(st);
  else
    studio_save(st, st.doc_path);
}

// Continues whatever waited for the unsaved-changes question.
static void run_pending(studio& st) {
  const auto action = st.after_save_prompt;
  st.after_save_prompt = studio::pending_action::none;
  switch (action) {
    case studio::pending_action::quit:
      st.quit_requested = true;
      break;
    case studio::pending_action::open_file:
      st.dialog.request(file_purpose::open_scene, false, "Open scene or glTF layout", start_dir(st),
                        {".json", ".glb", ".gltf"});
      break;
    case studio::pending_action::open_path:
      studio_open(st, st.pending_path);
      break;
    case studio::pending_action::new_scene: {
      scene s;
      s.base_dir = asset_dir() + "/scenes";  // the defaults' relative paths point into assets/
      s.source.image = "../charts/test_chart.png";
      studio_start(st, s, "");
      break;
    }
    case studio::pending_action::none:
      break;
  }
}

static void ask_or_run(studio& st, studio::pending_action action) {
  st.after_save_prompt = action;
  if (studio_dirty(st))
    st.show_save_prompt = true;
  else
    run_pending(st);
}

static void draw_menu(studio& st) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New scene")) ask_or_run(st, studio::pending_action::new_scene);
    if (ImGui::MenuItem("Open scene...", "Ctrl+O")) ask_or_run(st, studio::pending_action::open_file);
    if (ImGui::BeginMenu("Open recent", !st.settings.recent_files.empty())) {
      for (const auto& f : st.settings.recent_files) {
        if (ImGui::MenuItem(f.c_str())) {
          st.pending_path = f;
          ask_or_run(st, studio::pending_action::open_path);
        }
      }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Save", "Ctrl+S")) save_or_ask(st);
    if (ImGui::MenuItem("Save as...")) request_save_as(st);
    ImGui::Separator();
    if (ImGui::MenuItem("Source image...")) {
      st.dialog.request(file_purpose::choose_source_image, false, "Source image", start_dir(st),
                        {".png", ".jpg", ".jpeg", ".exr", ".tif", ".tiff", ".hdr"});
    }
    if (ImGui::MenuItem("Export render...")) {
      st.dialog.request(file_purpose::export_render, true, "Export render (.exr or .png)", start_dir(st),
                        {".exr", ".png"}, "render.exr");
    }
    if (ImGui::MenuItem("Add prop (glTF)...")) {
      st.dialog.request(file_purpose::add_prop, false, "Add a glTF model as a prop", start_dir(st), {".glb", ".gltf"});
    }
    if (ImGui::MenuItem("Export layout (glTF)...")) {
      st.dialog.request(file_purpose::export_gltf, true, "Export the layout as glTF (.glb or .gltf)", start_dir(st),
                        {".glb", ".gltf"}, "layout.glb");
    }
    if (ImGui::MenuItem("Export plot data...")) {
      st.dialog.request(file_purpose::export_plots, true, "Export plot data (CSV)", start_dir(st), {".csv"},
                        "plots.csv");
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Fit a sheet preset...")) st.show_fit = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) ask_or_run(st, studio::pending_action::quit);
    ImGui::EndMenu();
  }
  ImGui::TextDisabled("  %s%s", display_name(st).c_str(), studio_dirty(st) ? " (unsaved changes)" : "");
  ImGui::EndMainMenuBar();
}

static void draw_save_prompt(studio& st) {
  if (st.show_save_prompt) {
    ImGui::OpenPopup("Unsaved changes");
    st.show_save_prompt = false;
  }
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.", display_name(st).c_str());
    if (ImGui::Button("Save")) {
      ImGui::CloseCurrentPopup();
      if (st.doc_path.empty() || is_gltf_path(st.doc_path))
        request_save_as(st);  // the pending action runs after the dialog
      else if (studio_save(st, st.doc_path))
        run_pending(st);
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      ImGui::CloseCurrentPopup();
      st.saved = st.doc;
      run_pending(st);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      st.after_save_prompt = studio::pending_action::none;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

static void handle_dialog(studio& st) {
  const std::string path = st.dialog.draw();
  if (path.empty()) return;
  switch (st.dialog.purpose) {
    case file_purpose::open_scene:
      studio_open(st, path);
      break;
    case file_purpose::save_scene:
      if (studio_save(st, path)) run_pending(st);
      break;
    case file_purpose::export_render:
      studio_export_render(st, path);
      break;
    case file_purpose::export_plots:
      studio_export_plots(st, path);
      break;
    case file_purpose::choose_source_image:
      studio_drop_file(st, path);
      break;
    case file_purpose::choose_fit_data:
      st.fit_dir = fs::path(path).parent_path().string();
      break;
    case file_purpose::save_preset:
      save_fitted_preset(st, path);
      break;
    case file_purpose::add_prop:
      studio_add_prop(st, path);
      break;
    case file_purpose::export_gltf:
      studio_export_gltf(st, path);
      break;
  }
}

static void handle_shortcuts(studio& st) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.KeyCtrl || io.WantTextInput) return;
  // ImGui 1.86 indexes keys by the backend's codes; GLFW's letter codes are their ASCII capitals.
  if (ImGui::IsKeyPressed('S')) save_or_ask(st);
  if (ImGui::IsKeyPressed('O')) ask_or_run(st, studio::pending_action::open_file);
}

void studio_frame(studio& st, double now) {
  handle_shortcuts(st);
  draw_menu(st);
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float top = vp->WorkPos.y, w = vp->WorkSize.x, h = vp->WorkSize.y - ImGui::GetFrameHeight();
  const float left_w = std::min(0.26f * w, 30.0f * ImGui::GetFontSize()), right_w = 0.28f * w;
  const float mid_w = w - left_w - right_w, render_h = 0.62f * h;
  auto place = [&](float x, float y, float ww, float hh) {
    ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + x, top + y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(ww, hh), ImGuiCond_FirstUseEver);
  };
  place(0, 0, left_w, h);
  draw_layout_panel(st);
  place(left_w, 0, mid_w, render_h);
  draw_render_view(st, now);
  place(left_w, render_h, mid_w, h - render_h);
  draw_layout_view(st);
  place(left_w + mid_w, 0, right_w, h);
  draw_plots_panel(st);
  draw_fit_window(st);

  // Status bar.
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x, vp->WorkPos.y + vp->WorkSize.y - ImGui::GetFrameHeight()));
  ImGui::SetNextWindowSize(ImVec2(vp->WorkSize.x, ImGui::GetFrameHeight()));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  if (!st.doc_error.empty())
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", st.doc_error.c_str());
  else
    ImGui::TextUnformatted(st.status.c_str());
  ImGui::End();

  draw_save_prompt(st);
  draw_recovery_prompt(st);
  handle_dialog(st);
  studio_apply_edits(st, now);
  studio_keep_recovery(st, now);
}

}  // namespace airr::ui
