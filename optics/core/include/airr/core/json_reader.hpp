#pragma once
// Reading JSON files strictly: one parser entry with one "malformed JSON" message, and a reader
// of one object with typed fields whose errors read "<file>: <dotted.field>: <problem>".
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/core/error.hpp"

namespace airr {

// Deepest nesting of arrays and objects accepted (the project's files nest fewer than 10 levels).
inline constexpr int max_json_depth = 64;

// Parses JSON text; throws input_error "<origin>: malformed JSON: <where and what>", also for
// nesting deeper than max_json_depth (refused before parsing).
nlohmann::json parse_json(std::string_view text, const std::string& origin);
// Throws that input_error when JSON text nests deeper than max_json_depth, without parsing it
// (for text another parser reads, e.g. a glTF file's JSON).
void check_json_depth(std::string_view text, const std::string& origin);
// Reads and parses a file (errors name the file).
nlohmann::json read_json_file(const std::string& path);

class json_reader {
 public:
  const std::string& origin() const { return origin_; }
  json_reader(const nlohmann::json& j, std::string origin, std::string path)
      : j_(j), origin_(std::move(origin)), path_(std::move(path)) {
    if (!j_.is_object()) fail(path_.empty() ? "top level" : path_, "must be a JSON object");
  }

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw input_error(origin_ + ": " + field + ": " + problem);
  }
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  bool has(const std::string& key) {
    seen_.insert(key);
    return j_.contains(key);
  }
  // A value as given, for messages: its JSON, cut short after 40 characters.
  static std::string given(const nlohmann::json& v) {
    // Bytes that are not UTF-8 (a user's text) shown replaced, not thrown over.
    const std::string text = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return text.size() <= 40 ? text : text.substr(0, 40) + "...";
  }
  // Fails with "missing" unless the key is present.
  void require(const std::string& key) {
    if (!has(key)) fail(field(key), "missing");
  }
  // A required finite number.
  double number(const std::string& key) {
    require(key);
    double v = 0;
    number(key, v);
    return v;
  }
  // A finite number, or nothing when the key is absent.
  std::optional<double> optional_number(const std::string& key) {
    if (!has(key)) return std::nullopt;
    return number(key);
  }
  // A required non-empty string.
  std::string string(const std::string& key) {
    require(key);
    std::string v;
    string(key, v);
    if (v.empty()) fail(field(key), "must be a non-empty string");
    return v;
  }
  // A required array of finite numbers; errors name the element.
  std::vector<double> number_array(const std::string& key) {
    require(key);
    const auto& v = j_.at(key);
    if (!v.is_array()) fail(field(key), "must be an array of numbers");
    std::vector<double> out;
    out.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string where = field(key) + "[" + std::to_string(i) + "]";
      if (!v[i].is_number()) fail(where, "must be a number");
      out.push_back(v[i].get<double>());
      if (!std::isfinite(out.back())) fail(where, "must be finite");
    }
    return out;
  }

  void number(const std::string& key, double& out) {
    if (!has(key)) return;
    const auto& v = j_.at(key);
    if (!v.is_number()) fail(field(key), "must be a number (is " + given(v) + ")");
    out = v.get<double>();
    if (!std::isfinite(out)) fail(field(key), "must be finite");
  }
  // A number, or null for "unset"; an absent key leaves out as it is.
  void nullable_number(const std::string& key, std::optional<double>& out) {
    if (!has(key)) return;
    if (j_.at(key).is_null()) {
      out.reset();
      return;
    }
    double v = 0;
    number(key, v);
    out = v;
  }
  // An integer that fits Int; a larger one is reported as given, never narrowed.
  template <class Int>
  void integer(const std::string& key, Int& out) {
    integer(key, out, std::numeric_limits<Int>::min(), std::numeric_limits<Int>::max());
  }
  // An integer in [lo, hi]; one outside is reported as given, with the field's range.
  template <class Int>
  void integer(const std::string& key, Int& out, Int lo, Int hi) {
    if (!has(key)) return;
    const auto& v = j_.at(key);
    if (!v.is_number_integer()) fail(field(key), "must be an integer (is " + given(v) + ")");
    const auto check = [&](auto given) {
      if (std::cmp_less(given, lo) || std::cmp_greater(given, hi))
        fail(field(key),
             "must be " + std::to_string(lo) + " to " + std::to_string(hi) + " (is " + std::to_string(given) + ")");
      out = static_cast<Int>(given);
    };
    if (v.is_number_unsigned())
      check(v.get<std::uint64_t>());
    else
      check(v.get<std::int64_t>());
  }
  void string(const std::string& key, std::string& out) {
    if (!has(key)) return;
    const auto& v = j_.at(key);
    if (!v.is_string()) fail(field(key), "must be a string");
    out = v.get<std::string>();
  }
  void boolean(const std::string& key, bool& out) {
    if (!has(key)) return;
    const auto& v = j_.at(key);
    if (!v.is_boolean()) fail(field(key), "must be true or false");
    out = v.get<bool>();
  }
  template <std::size_t N>
  void numbers(const std::string& key, std::array<double, N>& out) {
    if (!has(key)) return;
    const auto& v = j_.at(key);
    if (!v.is_array() || v.size() != N) fail(field(key), "must be an array of " + std::to_string(N) + " numbers");
    for (std::size_t i = 0; i < N; ++i) {
      if (!v[i].is_number()) fail(field(key), "must be an array of " + std::to_string(N) + " numbers");
      out[i] = v[i].get<double>();
      if (!std::isfinite(out[i])) fail(field(key), "must be finite");
    }
  }
  json_reader child(const std::string& key) {
    seen_.insert(key);
    return json_reader(j_.at(key), origin_, field(key));
  }
  const nlohmann::json& raw(const std::string& key) {
    seen_.insert(key);
    return j_.at(key);
  }

  // Every key of the object must have been read.
  void finish() const {
    for (const auto& [key, value] : j_.items()) {
      if (!seen_.count(key)) fail(field(key), "unknown key");
    }
  }

 private:
  const nlohmann::json& j_;
  std::string origin_;
  std::string path_;
  std::set<std::string> seen_;
};

}  // namespace airr
