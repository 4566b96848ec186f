#include "airr/ui/platform/recovery_copy.hpp"

#include <filesystem>

#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/ui/platform/settings.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

std::string recovery_path() { return state_dir() + "/recovery.json"; }

std::optional<std::string> write_recovery_copy(const recovery_copy& copy) {
  const nlohmann::json j = {{"path", copy.path}, {"base_dir", copy.doc.base_dir}, {"scene", scene_to_json(copy.doc)}};
  try {
    write_file_atomic(recovery_path(), j.dump(2) + "\n");
    return std::nullopt;
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string read_recovery_text() {
  std::error_code ec;
  if (!fs::exists(recovery_path(), ec)) return {};
  try {
    return read_text_file(recovery_path());
  } catch (const std::exception&) {
    return {};
  }
}

recovery_copy parse_recovery_copy(const std::string& text) {
  const auto j = parse_json(text, recovery_path());
  recovery_copy copy;
  copy.doc = scene_from_json(j.at("scene"), recovery_path());
  copy.doc.base_dir = j.value("base_dir", std::string());
  copy.path = j.value("path", std::string());
  return copy;
}

void remove_recovery_copy() {
  std::error_code ec;
  fs::remove(recovery_path(), ec);
}

}  // namespace airr::ui
