#pragma once
// One description per retroreflector-model parameter (key, unit, range, default, help) that drives
// reading, writing, validation, command-line overrides and the layout panel's rows.
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/models/model_params.hpp"

namespace airr {

enum class field_kind {
  number,           // a finite number with a default
  optional_number,  // a number or unset (null in files): the model derives it, e.g. from a preset
  text,             // a name or a path; empty: unset
  path,             // a file relative to the scene file; empty: unset
  preset,           // a preset name (assets/presets) or a JSON file relative to the scene file
  choice,           // one of `choices`; the first is the default
};

struct model_field {
  std::string key;
  field_kind kind = field_kind::number;
  std::string unit;      // shown beside the value; empty for plain numbers
  double lo = 0;         // accepted range of numbers, inclusive ...
  double hi = 0;         //
  bool lo_open = false;  // ... except lo itself when set (a strictly positive value)
  double fallback = 0;   // default of a number
  double slider_hi = 0;  // upper end of the layout panel's slider when below hi; 0: hi
  std::vector<std::string> choices;
  std::string help;
};
using model_fields = std::vector<model_field>;

// Field descriptions, spelled out.
model_field number_field(std::string key, std::string unit, double lo, double hi, double fallback, std::string help,
                         double slider_hi = 0);
model_field optional_number_field(std::string key, std::string unit, double lo, double hi, bool lo_open,
                                  std::string help, double slider_hi = 0);
model_field text_field(std::string key, field_kind kind, std::string help);
model_field choice_field(std::string key, std::vector<std::string> choices, std::string help);

const model_field* find_field(const model_fields& fields, const std::string& key);

// A model's values read through its field table: absent keys give the defaults. `where` names the
// model in errors, e.g. "retroreflectors[0].model".
class model_values {
 public:
  model_values(const retro_model_params& p, const model_fields& fields, std::string where);
  double number(const std::string& key) const;
  std::optional<double> optional_number(const std::string& key) const;
  std::string text(const std::string& key) const;  // text, path and choice fields
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  const std::string& where() const { return where_; }

 private:
  const model_field& field(const std::string& key) const;
  const retro_model_params& p_;
  const model_fields& fields_;
  std::string where_;
};

// Stores a value in its normal form: a value equal to the field's default is removed, so that
// equal layouts compare equal whatever route set them. Throws input_error for an unknown key.
void set_model_value(retro_model_params& p, const model_fields& fields, const std::string& key,
                     std::optional<param_value> value);

// A model's constructor's check of one number, for models built without a field table; throws
// input_error "<model> model: <name>: <v> is outside [lo, hi]".
void check_model_number(const std::string& model, const std::string& name, double v, double lo, double hi);
// The same for each named value against its field's range in `fields` (one home for the ranges).
void check_model_numbers(const std::string& model, const model_fields& fields,
                         std::initializer_list<std::pair<const char*, double>> values);

// Range and choice checks of every stored value; throws input_error "<where>.<key>: <problem>".
void validate_model_values(const retro_model_params& p, const model_fields& fields, const std::string& where);

// JSON form: every field of the model, unset optional numbers as null and unset texts as "".
nlohmann::json model_values_to_json(const retro_model_params& p, const model_fields& fields);
// Reads one value of the JSON form (any type errors name `where`.key) into p.
void model_value_from_json(retro_model_params& p, const model_fields& fields, const std::string& key,
                           const nlohmann::json& v, const std::string& origin, const std::string& where);

}  // namespace airr
