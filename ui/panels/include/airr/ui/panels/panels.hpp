#pragma once
// The panels: what the user edits, one file each (panel_layout.cpp, panel_environment.cpp, panel_fit.cpp,
// panel_optimise.cpp, panel_tolerance.cpp, panel_ghosts.cpp; design_windows.cpp runs the
// optimise and tolerance jobs).
#include <string>

#include "airr/models/preset.hpp"
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

void draw_layout_panel(studio& st);
// Its Environment section: the room's light (panel_environment.cpp).
void environment_section(studio& st);

void draw_fit_window(studio& st);
// Starts predicting a preset for the first sheet's model in the background (the fit window shows
// it); sets fit_error when the model cannot be measured (a sinc-shift sheet already has a preset).
void start_preset_prediction(studio& st);
void save_fitted_preset(studio& st, const std::string& path);
// Saves the preset (to config_dir()/presets unless saved already) and points the model at it.
void apply_fitted_preset(studio& st, const sheet_preset& preset);

// The Optimise and Tolerance windows.
void draw_optimise_window(studio& st);
void draw_tolerance_window(studio& st);
// A layout panel row picked by its --set key: a variable of the Optimise window (its range about
// the value) or a tolerance of the Tolerance window; opens the window.
void add_design_pick(studio& st, const std::string& key, bool tolerance);
// Starts the search or the analysis of the windows' spec over the applied layout (false with
// design.error when the spec cannot run).
bool start_design_job(studio& st, design_job::kind k);
// Takes a finished run's result into the windows (call once per frame); true when one finished.
bool collect_design_job(studio& st);
// Puts the chosen trial's layout into the scene as one undoable step (false when there is none).
bool apply_design_choice(studio& st);
// A scripted run of the design windows (airr-studio --optimise, --tolerance): once the scene's
// edits are applied, the search and then the analysis run to their ends; then the optimised layout
// is applied and `undo` steps undone, as asked.
struct design_script {
  bool optimise = false, tolerance = false, apply = false;
  int undo = 0;
  bool optimise_started = false, tolerance_started = false, finished = false;
  std::string error;  // why it failed
};
// Advances the script by a frame: true while it needs more frames.
bool run_design_script(studio& st, design_script& script);

// The Ghosts window (panel_ghosts.cpp).
void draw_ghosts_window(studio& st);
// Finds the ghost table of the applied layout in the background (false with ghosts.error when the
// layout or a typed expression is wrong).
bool start_ghost_job(studio& st);
// Takes a finished job's table into the window (draw_ghosts_window calls it); true when one ended.
bool collect_ghost_job(studio& st);
// A scripted run (airr-studio --ghosts [--ghost-class K]): the table found, printed, and class K
// (from 1) shown.
struct ghost_script {
  bool run = false;
  int show = 0;
  bool started = false, finished = false;
  std::string error;  // why it failed
};
bool run_ghost_script(studio& st, ghost_script& script);

}  // namespace airr::ui
