// The designer's state across frames: starting on a scene, applying edits, undo and redo.
#include "airr/ui/studio/studio.hpp"

#include <algorithm>
#include <filesystem>

#include "airr/core/assets.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/render/memory_need.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

std::string suggested_scene_name(const std::string& doc_path) {
  if (doc_path.empty()) return "scene.airr.json";
  const fs::path p(doc_path);
  return p.extension() == ".json" ? p.filename().string() : p.stem().string() + ".airr.json";
}

std::string display_name(const studio& st) {
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
      m = prop_mesh(s, p);
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
  st.analysis.submit_scene(s, st.generation, {});
  st.view.uploaded_generation = ~0ull;
  // Another scene: its own history, and no results of the last one's design runs.
  st.history.reset(s);
  st.design.job.reset();
  st.design.optimised.reset();
  st.design.tolerances.reset();
  st.design.ghost.reset();
  st.design.chosen = -1;
  st.design.spec_started = false;
  if (!st.doc_path.empty()) add_recent_file(st.settings, st.doc_path);
}

bool studio_dirty(const studio& st) { return !st.saved || !(st.doc == *st.saved); }

void studio_apply_edits(studio& st, double now) {
  if (st.doc == st.applied) return;
  st.applied = st.doc;
  try {
    // The models are built once per accepted edit and shared by the tracer and the plots.
    const retro_model_list models = check_scene(st.doc, "layout");
    check_render_memory(st.doc, st.session_options);  // e.g. an observer of 8192 x 4096: the last image stays
    keep_prop_meshes(st, st.doc);
    st.doc_error.clear();
    st.generation = st.session->edit(st.doc, models);
    st.analysis.submit_scene(st.doc, st.generation, models);
    st.edit_time = now;
  } catch (const std::exception& e) {
    st.doc_error = e.what();
  }
}

void studio_undo(studio& st) {
  if (st.history.undo(st.doc)) st.status = "undid " + st.history.redo_name();
}

void studio_redo(studio& st) {
  if (st.history.redo(st.doc)) st.status = "redid " + st.history.undo_name();
}

}  // namespace airr::ui
