#pragma once
// Where the shipped assets (scenes, presets, charts, models) are found.
#include <string>
#include <vector>

namespace airr {

// $AIRR_ASSETS when set; else share/airr-studio beside an installed program
// (<prefix>/bin/../share/airr-studio, wherever the prefix was moved); else, for a program still in
// the build tree, the source tree's assets/. An installed program never looks in the source tree.
std::string asset_dir();
// For a library loaded by another program (the Python module, run by python3): where its assets
// are, found from the library's own place; $AIRR_ASSETS still comes first.
void set_asset_dir(const std::string& dir);
// The scene the designer opens by default: the reference layout with an RF-Ay sheet.
std::string default_scene_path();
// The same layout with the ideal retroreflector (mu = 1): a sharp image, for exact comparisons.
std::string ideal_bench_scene_path();
// The names (file stems) of the shipped JSON files in one of the assets' folders ("presets",
// "sheets"), sorted; none when the folder is missing.
std::vector<std::string> shipped_json_names(const std::string& folder);
// Whether `path` is one of the shipped assets (the designer never saves over those).
bool is_shipped_asset(const std::string& path);

}  // namespace airr
