#include "airr/models/model_fields.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "airr/core/error.hpp"

namespace airr {

model_field number_field(std::string key, std::string unit, double lo, double hi, double fallback, std::string help,
                         double slider_hi) {
  model_field f;
  f.key = std::move(key);
  f.kind = field_kind::number;
  f.unit = std::move(unit);
  f.lo = lo;
  f.hi = hi;
  f.fallback = fallback;
  f.slider_hi = slider_hi;
  f.help = std::move(help);
  return f;
}

model_field optional_number_field(std::string key, std::string unit, double lo, double hi, bool lo_open,
                                  std::string help, double slider_hi) {
  model_field f = number_field(std::move(key), std::move(unit), lo, hi, 0, std::move(help), slider_hi);
  f.kind = field_kind::optional_number;
  f.lo_open = lo_open;
  return f;
}

model_field text_field(std::string key, field_kind kind, std::string help) {
  model_field f;
  f.key = std::move(key);
  f.kind = kind;
  f.help = std::move(help);
  return f;
}

model_field choice_field(std::string key, std::vector<std::string> choices, std::string help) {
  model_field f = text_field(std::move(key), field_kind::choice, std::move(help));
  f.choices = std::move(choices);
  return f;
}

const model_field* find_field(const model_fields& fields, const std::string& key) {
  for (const auto& f : fields) {
    if (f.key == key) return &f;
  }
  return nullptr;
}

static bool is_numeric(field_kind k) { return k == field_kind::number || k == field_kind::optional_number; }

model_values::model_values(const retro_model_params& p, const model_fields& fields, std::string where)
    : p_(p), fields_(fields), where_(std::move(where)) {}

const model_field& model_values::field(const std::string& key) const {
  const model_field* f = find_field(fields_, key);
  if (!f) throw std::logic_error("model field '" + key + "' is not in the model's table");
  return *f;
}

void model_values::fail(const std::string& key, const std::string& problem) const {
  throw input_error(where_ + "." + key + ": " + problem);
}

double model_values::number(const std::string& key) const {
  const model_field& f = field(key);
  const auto it = p_.values.find(key);
  if (it == p_.values.end() || !std::holds_alternative<double>(it->second)) return f.fallback;
  return std::get<double>(it->second);
}

std::optional<double> model_values::optional_number(const std::string& key) const {
  field(key);
  const auto it = p_.values.find(key);
  if (it == p_.values.end() || !std::holds_alternative<double>(it->second)) return std::nullopt;
  return std::get<double>(it->second);
}

std::string model_values::text(const std::string& key) const {
  const model_field& f = field(key);
  const auto it = p_.values.find(key);
  if (it == p_.values.end() || !std::holds_alternative<std::string>(it->second)) {
    return f.kind == field_kind::choice && !f.choices.empty() ? f.choices.front() : std::string();
  }
  return std::get<std::string>(it->second);
}

void set_model_value(retro_model_params& p, const model_fields& fields, const std::string& key,
                     std::optional<param_value> value) {
  const model_field* f = find_field(fields, key);
  if (!f) throw input_error("model '" + p.type + "' has no parameter '" + key + "'");
  bool is_default = !value.has_value();
  if (value) {
    if (const double* d = std::get_if<double>(&*value)) {
      is_default = f->kind == field_kind::number && *d == f->fallback;
    } else {
      const std::string& s = std::get<std::string>(*value);
      is_default = s.empty() || (f->kind == field_kind::choice && !f->choices.empty() && s == f->choices.front());
    }
  }
  if (is_default) {
    p.values.erase(key);
  } else {
    p.values[key] = *value;
  }
}

void validate_model_values(const retro_model_params& p, const model_fields& fields, const std::string& where) {
  for (const auto& [key, value] : p.values) {
    const model_field* f = find_field(fields, key);
    const std::string name = where + "." + key;
    if (!f) throw input_error(name + ": not a parameter of the " + p.type + " model");
    if (is_numeric(f->kind)) {
      const double* d = std::get_if<double>(&value);
      if (!d) throw input_error(name + ": must be a number");
      if (!std::isfinite(*d)) throw input_error(name + ": must be a finite number");
      const bool low = f->lo_open ? *d <= f->lo : *d < f->lo;
      if (low || *d > f->hi) {
        throw input_error(name + ": must be in " + (f->lo_open ? "(" : "[") + number_text(f->lo) + ", " +
                          number_text(f->hi) + "] (is " + number_text(*d) + ")");
      }
    } else {
      const std::string* s = std::get_if<std::string>(&value);
      if (!s) throw input_error(name + ": must be a string");
      if (f->kind == field_kind::choice && std::find(f->choices.begin(), f->choices.end(), *s) == f->choices.end()) {
        std::string list;
        for (const auto& c : f->choices) list += (list.empty() ? "" : ", ") + c;
        throw input_error(name + ": unknown value '" + *s + "' (" + list + ")");
      }
    }
  }
}

nlohmann::json model_values_to_json(const retro_model_params& p, const model_fields& fields) {
  nlohmann::json j = nlohmann::json::object();
  j["type"] = p.type;
  const model_values v(p, fields, "");
  for (const auto& f : fields) {
    switch (f.kind) {
      case field_kind::number:
        j[f.key] = v.number(f.key);
        break;
      case field_kind::optional_number: {
        const auto n = v.optional_number(f.key);
        j[f.key] = n ? nlohmann::json(*n) : nlohmann::json(nullptr);
        break;
      }
      default:
        j[f.key] = v.text(f.key);
    }
  }
  return j;
}

void model_value_from_json(retro_model_params& p, const model_fields& fields, const std::string& key,
                           const nlohmann::json& v, const std::string& origin, const std::string& where) {
  const model_field* f = find_field(fields, key);
  const std::string name = origin + ": " + where + "." + key;
  if (!f) throw input_error(name + ": unknown key (not a parameter of the " + p.type + " model)");
  if (is_numeric(f->kind)) {
    if (v.is_null() && f->kind == field_kind::optional_number) {
      set_model_value(p, fields, key, std::nullopt);
      return;
    }
    if (!v.is_number()) {
      throw input_error(name +
                        (f->kind == field_kind::optional_number ? ": must be a number or null" : ": must be a number"));
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw input_error(name + ": must be finite");
    set_model_value(p, fields, key, d);
    return;
  }
  if (!v.is_string()) throw input_error(name + ": must be a string");
  set_model_value(p, fields, key, v.get<std::string>());
}

void check_model_number(const std::string& model, const std::string& name, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) {
    throw input_error(model + " model: " + name + ": " + number_text(v) + " is outside [" + number_text(lo) + ", " +
                      number_text(hi) + "]");
  }
}

void check_model_numbers(const std::string& model, const model_fields& fields,
                         std::initializer_list<std::pair<const char*, double>> values) {
  for (const auto& [name, v] : values) {
    const model_field* f = find_field(fields, name);
    check_model_number(model, name, v, f->lo, f->hi);
  }
}

}  // namespace airr
