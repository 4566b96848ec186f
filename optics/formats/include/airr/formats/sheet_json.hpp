#pragma once
// A sheet described by its model alone, for predicting its preset before it is bought or made:
//   {"format": "airr-sheet", "version": 1, "name": "...", "note": "...", "model": {"type": ...}}
// The model object is a scene's retroreflector model (its fields, its files relative to the
// sheet file). Loading is strict; saving is atomic.
#include <string>

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

}  // namespace airr
