#pragma once
// What the designer's own files share (studio.cpp, studio_files.cpp, studio_menu.cpp,
// studio_recovery.cpp) and nobody else needs.
#include <optional>
#include <string>

#include "airr/ui/studio.hpp"

namespace airr::ui {

// New scene files end in .airr.json, the name their MIME type (application/x-airr-scene) claims.
std::string suggested_scene_name(const std::string& doc_path);
// The open scene's file name, or "untitled".
std::string display_name(const studio& st);

// Where the recovery copy of unsaved changes lives (XDG_STATE_HOME).
std::string recovery_path();
// Writes the open scene where the next start offers it back; the reason when it cannot.
std::optional<std::string> write_recovery_copy(const studio& st);
// Offers the recovery copy a previous session left, once.
void draw_recovery_prompt(studio& st);

// The menu bar, the unsaved-changes question, the file dialog's answers, Ctrl shortcuts.
void draw_menu(studio& st);
void draw_save_prompt(studio& st);
void handle_dialog(studio& st);
void handle_shortcuts(studio& st);

}  // namespace airr::ui
