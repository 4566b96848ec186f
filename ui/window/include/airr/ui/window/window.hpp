#pragma once
// The designer's window, frame by frame: the menu, the panels and views placed side by side, the
// status bar, the prompts (unsaved changes, recovery) and the file dialog's answers.
#include "airr/ui/studio/studio.hpp"

namespace airr::ui {

// Runs the whole UI for one frame, then applies the frame's edits and keeps the recovery copy.
void studio_frame(studio& st, double now_seconds);

}  // namespace airr::ui
