#pragma once
// The recovery copy of unsaved changes: one file in the XDG state directory that the next start
// offers back, holding the scene, the path it was opened from and the folder its relative paths
// mean.
#include <optional>
#include <string>

#include "airr/layout/scene.hpp"

namespace airr::ui {

struct recovery_copy {
  std::string path;  // the scene's file; empty: untitled
  scene doc;         // with its base_dir
};

// Where it lives (state_dir()/recovery.json).
std::string recovery_path();
// Writes it atomically; the reason when it cannot.
std::optional<std::string> write_recovery_copy(const recovery_copy& copy);
// Its text, when a previous session left one (empty when there is none or it cannot be read).
std::string read_recovery_text();
// The copy its text holds (input_error naming recovery_path() when it is not one).
recovery_copy parse_recovery_copy(const std::string& text);
void remove_recovery_copy();

}  // namespace airr::ui
