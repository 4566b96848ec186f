#pragma once
// What the window's own files share (frame.cpp, menu.cpp, recovery_prompt.cpp).
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

// The menu bar, the unsaved-changes question, the file dialog's answers, Ctrl shortcuts.
void draw_menu(studio& st);
void draw_save_prompt(studio& st);
void handle_dialog(studio& st);
void handle_shortcuts(studio& st);
// Offers the recovery copy a previous session left, once.
void draw_recovery_prompt(studio& st);

}  // namespace airr::ui
