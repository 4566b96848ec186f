#include "airr/models/preset.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/interpolate.hpp"
#include "airr/core/json_reader.hpp"

namespace airr {

using nlohmann::json;

bool is_preset_path(const std::string& name_or_path) {
  return name_or_path.find('/') != std::string::npos || std::filesystem::path(name_or_path).extension() == ".json";
}

std::string resolve_preset_path(const std::string& name_or_path, const std::string& base_dir) {
  if (!is_preset_path(name_or_path)) return asset_dir() + "/presets/" + name_or_path + ".json";
  return resolve_path(name_or_path, base_dir);
}

// A number or an array of numbers.
static std::vector<double> read_values(json_reader& r, const std::string& key) {
  r.require(key);
  const json& v = r.raw(key);
  if (v.is_number()) return {r.number(key)};
  if (!v.is_array() || v.empty()) r.fail(key, "must be a number or a non-empty array of numbers");
  return r.number_array(key);
}

// One Mueller matrix (4 rows of 4 numbers) relative to the model's weight: m00 is the share of the
// weight unpolarized light keeps (about 1), and no entry is larger in size than m00.
static mueller read_mueller(json_reader& r, const json& v, const std::string& key) {
  mueller m;
  if (!v.is_array() || v.size() != 4) r.fail(key, "must be a Mueller matrix: 4 rows of 4 numbers");
  for (std::size_t i = 0; i < 4; ++i) {
    if (!v[i].is_array() || v[i].size() != 4) r.fail(key, "must be a Mueller matrix: 4 rows of 4 numbers");
    for (std::size_t k = 0; k < 4; ++k) {
      if (!v[i][k].is_number() || !std::isfinite(v[i][k].get<double>())) r.fail(key, "must hold finite numbers");
      m.m[i][k] = v[i][k].get<double>();
    }
  }
  if (!(m.m[0][0] > 0) || m.m[0][0] > 2) r.fail(key, "m00 must be in (0, 2]");
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t k = 0; k < 4; ++k)
      if (std::abs(m.m[i][k]) > m.m[0][0] * (1 + 1e-9)) r.fail(key, "no entry of a Mueller matrix exceeds m00 in size");
  return m;
}

// One matrix, or one per tilt.
static std::vector<mueller> read_polarization(json_reader& r, std::size_t tilts) {
  const json& v = r.raw("polarization");
  if (v.is_array() && !v.empty() && v[0].is_array() && !v[0].empty() && v[0][0].is_array()) {
    if (v.size() != tilts)
      r.fail("polarization", "needs one Mueller matrix or one per tilt_deg entry (" + std::to_string(tilts) + ")");
    std::vector<mueller> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(read_mueller(r, v[i], "polarization[" + std::to_string(i) + "]"));
    return out;
  }
  return {read_mueller(r, v, "polarization")};
}

sheet_preset preset_from_json(const json& j, const std::string& origin) {
  json_reader r(j, origin, "");
  sheet_preset p;
  std::string format;
  r.string("format", format);
  if (format != "airr-preset") r.fail("format", "expected \"airr-preset\"");
  int version = 0;
  r.integer("version", version);
  if (version != 1) r.fail("version", "unsupported version " + std::to_string(version));
  std::string model = "sinc_shift";
  r.string("model", model);
  if (model != "sinc_shift") r.fail("model", "presets hold sinc_shift parameters, not '" + model + "'");
  r.string("name", p.name);
  if (r.has("tilt_deg")) p.theta_deg = read_values(r, "tilt_deg");
  p.a_per_mm = read_values(r, "a_per_mm");
  p.mu = read_values(r, "mu");
  p.c_mm = r.number("c_mm");
  r.number("reference_distance_mm", p.reference_distance_mm);
  r.number("shift_index", p.shift_index);
  if (r.has("polarization")) p.polarization = read_polarization(r, p.theta_deg.size());
  r.string("shift_table", p.shift_table);
  if (!p.shift_table.empty()) {
    p.shift_table = resolve_path(p.shift_table, std::filesystem::path(origin).parent_path().string());
    if (!std::filesystem::is_regular_file(p.shift_table))
      r.fail("shift_table", "no such file '" + p.shift_table + "' (a predicted preset's table lies beside it)");
  }
  if (r.has("provenance")) p.provenance = r.raw("provenance");
  r.finish();

  for (std::size_t i = 1; i < p.theta_deg.size(); ++i) {
    if (!(p.theta_deg[i] > p.theta_deg[i - 1])) r.fail("tilt_deg", "must be strictly ascending");
  }
  auto check_size = [&](const std::vector<double>& v, const char* key) {
    if (v.size() != 1 && v.size() != p.theta_deg.size()) {
      r.fail(key, "needs one value or one per tilt_deg entry (" + std::to_string(p.theta_deg.size()) + ")");
    }
  };
  check_size(p.a_per_mm, "a_per_mm");
  check_size(p.mu, "mu");
  for (double a : p.a_per_mm) {
    if (a <= 0) r.fail("a_per_mm", "must be positive");
  }
  for (double m : p.mu) {
    if (m < 0 || m > 1) r.fail("mu", "must be in [0, 1]");
  }
  if (p.c_mm < 0) r.fail("c_mm", "must not be negative");
  if (p.reference_distance_mm <= 0) r.fail("reference_distance_mm", "must be positive");
  if (!(p.shift_index >= 1 && p.shift_index <= 3)) r.fail("shift_index", "must be in [1, 3]");
  return p;
}

sheet_preset load_preset(const std::string& name_or_path, const std::string& base_dir) {
  const std::string path = resolve_preset_path(name_or_path, base_dir);
  // Cached while the file is unchanged, so the designer's frame loop does not re-read it.
  static file_cache<sheet_preset> cache;
  return *cache.get(path, path,
                    [&] { return std::make_shared<const sheet_preset>(preset_from_json(read_json_file(path), path)); });
}

static json values_to_json(const std::vector<double>& v) { return v.size() == 1 ? json(v[0]) : json(v); }

json preset_to_json(const sheet_preset& p) {
  json j = {{"format", "airr-preset"},
            {"version", 1},
            {"model", "sinc_shift"},
            {"name", p.name},
            {"a_per_mm", values_to_json(p.a_per_mm)},
            {"mu", values_to_json(p.mu)},
            {"c_mm", p.c_mm},
            {"reference_distance_mm", p.reference_distance_mm}};
  if (!p.theta_deg.empty()) j["tilt_deg"] = p.theta_deg;
  if (p.shift_index != 1.0) j["shift_index"] = p.shift_index;
  if (!p.shift_table.empty()) j["shift_table"] = p.shift_table;
  if (!p.polarization.empty()) {
    json all = json::array();
    for (const mueller& m : p.polarization) all.push_back(m.m);
    j["polarization"] = p.polarization.size() == 1 ? all[0] : all;
  }
  if (!p.provenance.is_null()) j["provenance"] = p.provenance;
  return j;
}

void save_preset(const sheet_preset& p, const std::string& path) {
  sheet_preset written = p;
  if (!p.shift_table.empty()) {
    // The table goes beside the preset (a copy, unless it is there already), so the two travel together.
    const std::filesystem::path target = std::filesystem::absolute(path);
    const std::filesystem::path table = target.parent_path() / (target.stem().string() + "_shifts.json");
    copy_file_atomic(p.shift_table, table.string());
    written.shift_table = table.filename().string();
  }
  write_file_atomic(path, preset_to_json(written).dump(2) + "\n");
}

double interpolate_by_angle(const std::vector<double>& theta_deg, const std::vector<double>& values, double theta) {
  return interpolate_linear(theta_deg, values, theta);
}

mueller interpolate_by_angle(const std::vector<double>& theta_deg, const std::vector<mueller>& values, double theta) {
  if (values.size() == 1) return values.front();
  const interpolation_segment g = segment_at(theta_deg, theta);
  return mueller::scale(1 - g.t) * values[g.lo] + mueller::scale(g.t) * values[g.hi];
}

}  // namespace airr
