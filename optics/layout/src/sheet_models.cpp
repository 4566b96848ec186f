#include "airr/layout/sheet_models.hpp"

#include <string>

#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

std::unique_ptr<retro_model> make_sheet_model(const scene& s, std::size_t sheet) {
  const model_setting setting{.base_dir = s.base_dir, .chief_incidence_deg = sheet_chief_incidence_deg(s, sheet)};
  return make_retro_model(s.retroreflectors.at(sheet).model, setting,
                          "retroreflectors[" + std::to_string(sheet) + "].model");
}

retro_model_list make_sheet_models(const scene& s) {
  retro_model_list models;
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) models.push_back(make_sheet_model(s, i));
  return models;
}

void check_sheet_models(const scene& s, const retro_model_list& models, const std::string& what) {
  if (models.size() != s.retroreflectors.size() || s.retroreflectors.empty()) {
    throw input_error(what + ": " + std::to_string(models.size()) + " models for " +
                      std::to_string(s.retroreflectors.size()) + " sheets");
  }
}

}  // namespace airr
