#pragma once
// A retroreflector model's name and the parameter values a scene sets for it (see model_fields.hpp
// for how each model describes its values).
#include <map>
#include <string>
#include <variant>

namespace airr {

// A model's parameter values by key; an absent key takes the model's default (see the model's
// field table in retro_model.hpp), so only values that differ from the defaults are stored.
using param_value = std::variant<double, std::string>;

struct retro_model_params {
  std::string type = "ideal";  // a registered model name: ideal, sinc_shift, microfacet
  std::map<std::string, param_value> values;

  bool operator==(const retro_model_params&) const = default;
};

}  // namespace airr
