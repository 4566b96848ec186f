#pragma once
// A sheet described by its model alone, for predicting its preset before it is bought or made:
//   {"format": "airr-sheet", "version": 1, "name": "...", "note": "...", "model": {"type": ...}}
// The model object is a scene's retroreflector model (its fields, its files relative to the
// sheet file). Loading is strict; saving is atomic.
#include <string>
#include <vector>

#include "airr/layout/scene.hpp"
#include "airr/models/model_params.hpp"

namespace airr {

struct sheet_description {
  std::string name;
  std::string note;          // where the values come from
  retro_model_params model;  // its relative files count from base_dir
  std::string base_dir;
};

// Throws input_error "<path>: <field>: <problem>"; the model is checked by building it.
sheet_description load_sheet(const std::string& path);
void save_sheet(const sheet_description& sheet, const std::string& path);

// The shipped sheets (assets/sheets), by name (the file's stem), sorted.
std::vector<std::string> shipped_sheet_names();
// A sheet by its shipped name, or a path to a sheet file (it ends in .json); an unknown name is
// an input_error listing the shipped ones.
sheet_description load_named_sheet(const std::string& name_or_path);
// The scene's sheet given the named sheet's model, its files made relative to the scene's directory.
void use_sheet_model(retroreflector_params& sheet, const sheet_description& named, const std::string& scene_dir);

}  // namespace airr
