#pragma once
// The retroreflector models of a scene's sheets, built with what the layout tells them: files
// resolve against the scene's folder, and per-render lookups use the sheet's chief-ray angle.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "airr/layout/scene.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

// The retroreflector models of a scene's sheets, in order.
using retro_model_list = std::vector<std::shared_ptr<const retro_model>>;

// Sheet i's model; throws input_error naming "retroreflectors[i].model".
std::unique_ptr<retro_model> make_sheet_model(const scene& s, std::size_t sheet = 0);
retro_model_list make_sheet_models(const scene& s);

// Throws input_error "<what>: N models for M sheets" unless `models` has one per sheet (and the
// scene a sheet).
void check_sheet_models(const scene& s, const retro_model_list& models, const std::string& what);

}  // namespace airr
