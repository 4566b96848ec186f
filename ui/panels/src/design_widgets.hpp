#pragma once
// What the Optimise and Tolerance windows share (panel_optimise.cpp, panel_tolerance.cpp, and
// design_windows.cpp, which runs their jobs).
#include <optional>
#include <string>
#include <vector>

#include "airr/ui/panels/panels.hpp"

namespace airr::ui {

// Fills the windows' spec for the opened scene once: the sheet's tilt as a variable, the mean MTF
// at the observer as the objective, a tolerance of the tilt.
void start_design_spec(studio& st);
// The number a --set key names in the scene, when it names one.
std::optional<double> design_value(const scene& s, const std::string& key);
// The scene values most often varied (poses, D, tilt), by --set key.
std::vector<std::string> common_design_keys(const scene& s);
// A combo of those keys; true when one was chosen into `key`.
bool design_key_combo(const char* label, std::string& key, const scene& s);
// A combo of the metrics; true when changed.
bool design_metric_combo(const char* id, design_metric& m);
// A combo of the mean, the min and the share above a threshold over the eyes, and that threshold.
void over_eyes_combo(const char* id, over_eyes& o, double& threshold);
// The list of eyes: each row's position and a remove button, "add the observer's position", and a
// zone of eyes on the observer's orbit.
void edit_design_eyes(studio& st);
// A progress line: the bar, done of total, the seconds so far and the remaining ones.
void design_progress_bar(const design_job& job, const std::string& detail);

}  // namespace airr::ui
