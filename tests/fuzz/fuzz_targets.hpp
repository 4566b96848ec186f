#pragma once
// The loaders of users' files as fuzz targets: each takes one input as a file of its kind and
// says whether its loader read it. An input_error (or measurement_error) is the expected answer
// to bad input; a crash, a sanitizer report or any other exception is a finding. Compiled into
// the ordinary build too, where a test replays every kept crash input
// (tests/fuzz/regressions/<target>/).
#include <string>
#include <string_view>

namespace airr::fuzz {

bool scene_json(std::string_view bytes);   // scene files, version 1 and the current one
bool gltf(std::string_view bytes);         // glTF (JSON) and GLB, as a prop mesh and as a layout
bool preset(std::string_view bytes);       // sheet presets
bool shift_table(std::string_view bytes);  // corner-cube shift tables
bool fit_json(std::string_view bytes);     // a fit's fit.json beside the example measurements
bool csv(std::string_view bytes);          // measurement CSV tables
bool image(std::string_view bytes);        // source and measurement images (PNG, EXR, TIFF, JPEG)
bool onnx(std::string_view bytes);         // an LPIPS model's inputs, as the project reads them
bool design_spec(std::string_view bytes);  // optimise and tolerance specs, over the two-sheet kiosk
bool partial(std::string_view bytes);      // the partials of sweep, viewzone and tolerance shards
// Render shard headers: blocks "WIDTH ROWS" then "key=value" and "layer NAME" lines, one block a
// shard, blank lines between, checked and merged as airr merge checks shard files.
bool render_shard(std::string_view bytes);
// A Python value set on a scene (Scene.set): the key on the first line, then the value as the
// module passes it on (strings as they are, True/False, nan/inf, numbers and lists as JSON).
bool scene_set(std::string_view bytes);
bool step(std::string_view bytes);  // STEP housings, tessellated at 0.5 mm
// A path expression (docs/path-expressions.md), matched against a few labels when it parses.
bool path_expression(std::string_view bytes);

// Every target's name.
inline constexpr const char* targets[] = {"scene_json", "gltf",         "preset",    "sheet_json", "shift_table",
                                          "fit_json",   "csv",          "image",     "onnx",       "design_spec",
                                          "partial",    "render_shard", "scene_set", "step",       "path_expression"};

// Runs one target by name (one of `targets`, else std::invalid_argument): whether the loader read
// the input.
bool run(const std::string& target, std::string_view bytes);

}  // namespace airr::fuzz
