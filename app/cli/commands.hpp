#pragma once
// The subcommands of the `airr` command line; each registers itself on the app.
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"

void add_render_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_make_assets_command(CLI::App& app);
void add_shift_table_command(CLI::App& app);
void add_mtf_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_psf_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_predict_preset_command(CLI::App& app);
void add_optimise_command(CLI::App& app);
void add_tolerance_command(CLI::App& app);
void add_viewzone_command(CLI::App& app);
void add_export_gltf_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_gain_command(CLI::App& app);
void add_ghosts_command(CLI::App& app);
// Every command above (the program's, and a merge's run of a shard's command line).
void add_commands(CLI::App& app);

// --linear-input / --srgb-input: how integer image files are decoded (default: the loader's rule).
inline void add_image_encoding_flags(CLI::App* cmd, airr::image_encoding& encoding) {
  auto* linear = cmd->add_flag_callback(
      "--linear-input", [&encoding] { encoding = airr::image_encoding::linear; },
      "Take every file's code values as linear (default: 8-bit files are sRGB-decoded unless tagged linear; "
      "16-bit and float files are linear)");
  auto* srgb = cmd->add_flag_callback(
      "--srgb-input", [&encoding] { encoding = airr::image_encoding::srgb; },
      "Decode every file's code values with the sRGB curve (e.g. a 16-bit sRGB-encoded PNG)");
  linear->excludes(srgb);
}

// load_scene for a command: what reading the scene noted (a glTF layout's notes and warnings, e.g.
// which observer it used) goes to stderr, one "note: ..." or "warning: ..." line each.
inline airr::scene load_scene_noting(const std::string& path, const std::vector<airr::scene_override>& overrides = {}) {
  std::vector<std::string> notes;
  airr::scene s = airr::load_scene(path, overrides, notes);
  for (const auto& line : notes) std::fprintf(stderr, "%s\n", line.c_str());
  return s;
}
