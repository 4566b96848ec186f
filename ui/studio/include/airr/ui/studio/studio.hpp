#pragma once
// The designer's state: the scene being edited, the render session and analysis behind it, the
// files, and what the panels show. The panels edit `doc`; once per frame the studio validates the
// edit and hands it to the render session and the analysis worker.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <optional>

#include <imgui.h>

#include "airr/formats/mesh_gltf.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/preset.hpp"
#include "airr/render/render_session.hpp"
#include "airr/ui/jobs/analysis_worker.hpp"
#include "airr/ui/jobs/design_job.hpp"
#include "airr/ui/jobs/fit_job.hpp"
#include "airr/ui/jobs/ghost_job.hpp"
#include "airr/ui/jobs/zone_job.hpp"
#include "airr/ui/platform/file_dialog.hpp"
#include "airr/ui/platform/gl_layout_renderer.hpp"
#include "airr/ui/platform/gl_texture.hpp"
#include "airr/ui/platform/settings.hpp"
#include "airr/ui/studio/edit_history.hpp"

namespace airr::ui {

struct projection_view;  // views/layout_projection.hpp

struct pinned_curve {
  std::string label;
  std::vector<double> x, y;
};

struct render_view_state {
  float zoom = 1.0f;  // screen pixels per image pixel, relative to fit
  float pan_x = 0, pan_y = 0;
  bool paused = false;
  std::uint64_t uploaded_generation = ~0ull, uploaded_spp = 0;
  bool uploaded_model_image = false;  // the shown image is a model image (render_snapshot::model_image)
  std::string uploaded_estimate;      // which (estimate_name)
  int component = -1;                 // the image component shown (tracer.hpp); -1: the whole image
  int uploaded_component = -1;
  int uploaded_ghost = -1;  // the ghost class shown instead of the render (-1: none)
  bool luminance = false;   // the luminance view: false colour with its scale (luminance_scale.hpp)
  bool uploaded_luminance = false;
  bool contrast = false;  // the contrast view, likewise (it needs the image's components)
  bool uploaded_contrast = false;
  float uploaded_exposure = -1;
  gl_texture texture;
};

// The 3D layout view's camera: it orbits `target` (yaw from +z towards +x, pitch towards +y).
struct view_3d_state {
  float yaw_deg = -40, pitch_deg = 25, distance_mm = 600;
  glm::vec3 target{0.0f};
  bool framed = false;  // false: frame the layout at the next frame
  std::unique_ptr<gl_layout_renderer> renderer;
};

// The Optimise and Tolerance windows: the design spec they edit (its base becomes the applied
// layout when a run starts), the run, and the last results.
struct design_windows {
  bool show_optimise = false, show_tolerance = false;
  design_spec spec;           // variables, eyes, objectives, constraints, search, tolerances
  bool spec_started = false;  // filled with a first variable and objective for the opened scene
  std::string error;          // why the spec cannot run
  std::unique_ptr<design_job> job;
  std::optional<design_result> optimised;  // the last finished search, and its spec
  design_spec optimised_spec;
  int chosen = -1;                             // the trial to apply: the best, or a Pareto front's member clicked
  std::optional<scene> ghost;                  // drawn in the layout views: the best so far, or the chosen trial
  std::optional<tolerance_result> tolerances;  // the last finished analysis, and its spec
  design_spec tolerance_spec;
};

// The Ghosts window: the ghost table of the applied layout and the class shown in the render
// view (its image) and in the 3D and layout views (a few of its paths).
struct ghost_window {
  bool show = false;
  int spp = 8;
  std::string typed;                     // the expression being typed
  std::vector<std::string> expressions;  // typed classes, measured besides the census's
  std::unique_ptr<ghost_job> job;
  std::optional<ghost_findings> found;
  std::uint64_t found_generation = 0;  // the layout it was found for
  int shown = -1;                      // index into found->table.classes; -1: none
  std::string error;

  // The shown class's image and paths (null when none is shown).
  const image_rgb* shown_image() const {
    return found && shown >= 0 && shown < int(found->table.classes.size())
               ? &found->table.classes[std::size_t(shown)].image
               : nullptr;
  }
  const std::vector<std::vector<glm::vec3>>* shown_paths() const {
    return found && shown >= 0 && shown < int(found->paths.size()) ? &found->paths[std::size_t(shown)] : nullptr;
  }
};

struct studio {
  scene doc;                   // what the panels edit
  edit_history history;        // undo and redo of `doc`
  std::string doc_path;        // empty: untitled
  std::optional<scene> saved;  // as last loaded or saved, for "unsaved changes"; empty: never saved
  scene applied;               // as last handed to the session
  std::string doc_error;       // why the current edit cannot be rendered
  // The props' meshes (null where one does not load) and their bounds in their own frames, as of
  // the last accepted edit, for the layout views (the frame loop reads no files).
  std::vector<std::shared_ptr<const triangle_mesh>> prop_meshes;
  std::vector<mesh_bounds> prop_bounds;
  std::uint64_t generation = 0;

  std::unique_ptr<render_session> session;
  session_params session_options;  // threads for the tracer (0: all cores)
  analysis_worker analysis;
  studio_settings settings;
  render_view_state view;
  view_3d_state view_3d;
  std::vector<pinned_curve> pinned_mtf;
  std::string status;  // last message for the status bar
  double last_measure_time = -1;
  std::uint64_t last_measured_spp = 0;

  file_dialog dialog;
  enum class pending_action { none, quit, open_file, open_path, new_scene } after_save_prompt = pending_action::none;
  std::string pending_path;
  bool show_save_prompt = false;
  bool quit_requested = false;  // the app may close

  // Screen rectangles (x0, y0, x1, y1) of what scripted runs check: "render_image", "plot_mtf", ...
  std::map<std::string, std::array<float, 4>> regions;
  // What the layout view's side and top projections drew last ("side", "top"): their labels, the
  // parts' outlines, handles and scale bar, for scripted checks that no label overprints.
  std::map<std::string, std::shared_ptr<const projection_view>> layout_views;

  // The fit window.
  bool show_fit = false;
  std::string fit_dir;
  std::string fit_error;
  std::string fit_saved_path;
  std::unique_ptr<fit_job> fit_job_;
  bool fit_applied = false;  // scripted runs apply a finished fit once
  // A preset predicted from the sheet's own model: the bench's samples per measurement (the fit
  // simulates with a fifth of them).
  std::uint64_t predict_samples = 1000000;

  // The viewing zone's map: 0 the visible fraction (geometric, every edit), the others from the
  // full pass (zone_quantity_keys), run on demand for one layout generation. Beside a map that is
  // not itself a legibility map, once the full pass exists: the legibility map at the full pass's
  // contrast threshold legibility_threshold (an index; default 3).
  int zone_quantity = 0;
  int legibility_threshold = 1;
  std::unique_ptr<zone_job> zone_job_;

  // The Plots window's tab (0 MTF, 1 Bokeh), chosen by the next frame when select_plots_tab.
  int plots_tab = 0;
  bool select_plots_tab = false;
  // What the Bokeh tab showed last, for scripted checks: the generation of its numbers, r50, the
  // 2D PSF's plot area (screen) and x range (mm), the design marker on the D x tilt map.
  struct bokeh_shown_state {
    std::uint64_t generation = 0;
    bool current = false;
    double r50_mm = 0;
    std::array<float, 4> psf_area{};
    std::array<double, 2> psf_x_mm{};
    std::array<float, 2> marker{};
    std::array<double, 2> marker_d_tilt{};
  } bokeh_shown;

  design_windows design;
  ghost_window ghosts;

  // Crash recovery: unsaved edits are copied to config_dir()/recovery.json every few seconds.
  bool keep_recovery = true;  // off in scripted runs
  double last_recovery_write = -1;
  bool recovery_offered = false;
  std::string recovery_text;  // a recovery file found at start, offered to the user

  // Latency measurement: when the last edit was applied (the start of the frame that made it);
  // for each edit, when the session published its first image, and whether that image was the
  // model image's first look. The frame loop adds when it reached the screen (after the swap).
  double edit_time = -1;
  bool first_image_uploaded = false;  // in this frame, not yet on screen
  std::vector<double> first_image_ready_ms;
  int first_images_from_model = 0;
  std::vector<double> edit_latencies_ms;
};

// Starts with a scene (already loaded and validated by the caller).
void studio_start(studio& st, const scene& s, const std::string& path);

bool studio_dirty(const studio& st);
// New scene files end in .airr.json, the name their MIME type (application/x-airr-scene) claims.
std::string suggested_scene_name(const std::string& doc_path);
// The open scene's file name, or "untitled".
std::string display_name(const studio& st);
// Validates and applies `doc` if it changed; called once per frame.
void studio_apply_edits(studio& st, double now_seconds);

void studio_open(studio& st, const std::string& path);  // with an error in st.status on failure
bool studio_save(studio& st, const std::string& path);  // atomic; false with st.status on failure
// Makes an image file the source (drag and drop); scene files and glTF layouts are opened instead,
// and any other glTF file becomes a prop.
void studio_drop_file(studio& st, const std::string& path);
// Adds a glTF file as a prop at the origin (its own coordinates place it), its surface its glTF
// materials; false with st.status when it cannot be read.
bool studio_add_prop(studio& st, const std::string& path);
bool studio_export_gltf(studio& st, const std::string& path);
bool studio_export_render(studio& st, const std::string& path);
bool studio_export_plots(studio& st, const std::string& path);
// The Bokeh tab's views as PNG pictures: the 2D PSF at `path`, and beside it <stem>_focus.png (r50
// and r80 through focus), <stem>_strip.png, <stem>_spots.png and <stem>_map.png. Only views of
// the current layout are written (false with st.status otherwise).
bool studio_export_bokeh(studio& st, const std::string& path);

// Writes or removes the recovery copy as the dirty state requires; call once per frame.
void studio_keep_recovery(studio& st, double now_seconds);
// Removes the recovery copy (after a clean exit).
void studio_clear_recovery();
// Looks for a recovery copy left by a session that did not exit cleanly.
void studio_check_recovery(studio& st);
// Takes the recovery copy found at start as the scene (unsaved), or says why it cannot.
void studio_recover(studio& st);

// Undo and redo of the scene (Edit menu, Ctrl+Z, Ctrl+Y).
void studio_undo(studio& st);
void studio_redo(studio& st);

}  // namespace airr::ui
