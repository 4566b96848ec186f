#include "airr/formats/sheet_json.hpp"

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

namespace {
constexpr const char* sheet_format = "airr-sheet";
constexpr int sheet_version = 1;
}  // namespace

sheet_description load_sheet(const std::string& path) {
  const nlohmann::json j = read_json_file(path);
  json_reader r(j, path, "");
  std::string format;
  r.string("format", format);
  if (format != sheet_format) r.fail("format", std::string("expected \"") + sheet_format + "\"");
  int version = 0;
  r.integer("version", version);
  if (version != sheet_version) r.fail("version", "unsupported version " + std::to_string(version));
  sheet_description out;
  out.name = r.string("name");
  r.string("note", out.note);
  r.require("model");
  read_model(r.child("model"), j.at("model"), "model", out.model);
  r.finish();
  out.base_dir = std::filesystem::absolute(path).parent_path().string();
  try {
    make_retro_model(out.model, {.base_dir = out.base_dir}, "model");
  } catch (const input_error& e) {
    throw input_error(path + ": " + e.what());
  }
  return out;
}

void save_sheet(const sheet_description& sheet, const std::string& path) {
  retro_model_params model = sheet.model;
  rebase_model_paths(model, sheet.base_dir, std::filesystem::absolute(path).parent_path().string());
  const nlohmann::json j = {{"format", sheet_format},
                            {"version", sheet_version},
                            {"name", sheet.name},
                            {"note", sheet.note},
                            {"model", model_values_to_json(model, find_retro_model_kind(model.type).fields)}};
  write_file_atomic(path, j.dump(2) + "\n");
}

std::vector<std::string> shipped_sheet_names() { return shipped_json_names("sheets"); }

sheet_description load_named_sheet(const std::string& name_or_path) {
  if (name_or_path.ends_with(".json")) return load_sheet(name_or_path);
  const std::vector<std::string> names = shipped_sheet_names();
  if (std::find(names.begin(), names.end(), name_or_path) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw input_error("no shipped sheet '" + name_or_path + "' (" + list + "; or a sheet file's path, *.json)");
  }
  return load_sheet(asset_dir() + "/sheets/" + name_or_path + ".json");
}

void use_sheet_model(retroreflector_params& sheet, const sheet_description& named, const std::string& scene_dir) {
  sheet.model = named.model;
  rebase_model_paths(sheet.model, named.base_dir, scene_dir);
}

}  // namespace airr
