// Every fuzz target on the shipped assets it is seeded from and on every input kept from a
// finding (tests/fuzz/regressions/<target>/): each is read or refused with the project's error,
// never anything else (under the asan tree: never a sanitizer report either).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <vector>

#include "airr/optics/assets.hpp"
#include "airr/optics/files.hpp"
#include "fuzz/fuzz_targets.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> files_in(const fs::path& dir, const std::string& extension = "") {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && (extension.empty() || e.path().extension() == extension)) out.push_back(e.path());
  return out;
}

}  // namespace

TEST(FuzzReplay, SeedsAndKeptFindingsAreReadOrRefused) {
  const fs::path assets = airr::asset_dir();
  const std::map<std::string, std::vector<fs::path>> seeds = {
      {"scene_json", files_in(assets / "scenes", ".json")}, {"gltf", files_in(assets / "models", ".gltf")},
      {"preset", files_in(assets / "presets", ".json")},    {"shift_table", files_in(assets / "shift_tables", ".json")},
      {"fit_json", {assets / "fit_example/fit.json"}},      {"csv", files_in(assets / "fit_example", ".csv")},
      {"image", files_in(assets / "charts", ".png")},
  };
  int inputs = 0;
  for (const auto& [target, files] : seeds) {
    std::vector<fs::path> all = files;
    for (const auto& f : files_in(fs::path(AIRR_FUZZ_REGRESSIONS_DIR) / target)) all.push_back(f);
    EXPECT_FALSE(files.empty()) << target;
    for (const auto& f : all) {
      const std::string bytes = airr::read_text_file(f.string());
      EXPECT_NO_THROW(EXPECT_TRUE(airr::fuzz::run(target, bytes))) << target << ": " << f;
      ++inputs;
    }
  }
  EXPECT_GT(inputs, 20);
}
