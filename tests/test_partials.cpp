// The commands whose work is numbered items (sweep, viewzone --full, tolerance) split into shards
// (--shard i/N --part FILE) and finished by airr merge write the files one process writes, byte for
// byte; merge refuses a missing or repeated partial, one of another command line, and partials whose
// input files changed since, each with one line naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "airr/core/assets.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Runs `command` (writing `outputs`) in one process, then as `n` shards merged, and compares.
void expect_merged_equals_one_process(const test::temp_dir& dir, const std::string& command,
                                      const std::vector<std::string>& outputs, int n) {
  ASSERT_EQ(test::run_cli(command).exit_code, 0) << command;
  for (const std::string& f : outputs) std::filesystem::rename(dir.file(f), dir.file("one_" + f));
  std::string parts;
  for (int i = n - 1; i >= 0; --i) {  // given in reverse order
    const std::string part = dir.file("part" + std::to_string(i) + ".json");
    const test::command_result r =
        test::run_cli(command + " --shard " + std::to_string(i) + "/" + std::to_string(n) + " --part " + part);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    parts += " " + part;
    for (const std::string& f : outputs) EXPECT_FALSE(std::filesystem::exists(dir.file(f))) << "a shard wrote " << f;
  }
  const test::command_result merged = test::run_cli("merge" + parts);
  ASSERT_EQ(merged.exit_code, 0) << merged.out;
  for (const std::string& f : outputs) {
    ASSERT_TRUE(std::filesystem::exists(dir.file(f))) << f;
    EXPECT_EQ(bytes_of(dir.file(f)), bytes_of(dir.file("one_" + f))) << f;
  }
}

}  // namespace

TEST(Partials, MergedPartialsWriteWhatOneProcessWrites) {
  test::temp_dir dir;
  const std::string scene = default_scene_path();
  expect_merged_equals_one_process(dir,
                                   "sweep " + scene +
                                       " --psf --vary floating_distance=150:250:50 --vary tilt=0:20:10 -o " +
                                       dir.file("sweep.csv") + " --png " + dir.file("sweep.png"),
                                   {"sweep.csv", "sweep.png"}, 3);
  // Points that are no layout travel without their reasons: the merge finds them again.
  expect_merged_equals_one_process(dir,
                                   "sweep " + asset_dir() +
                                       "/scenes/two_sheet_kiosk.json --psf --samples 5000 --vary "
                                       "floating_distance=210:300:30 -o " +
                                       dir.file("kiosk.csv"),
                                   {"kiosk.csv"}, 3);
  expect_merged_equals_one_process(
      dir,
      "viewzone " + scene + " --full --grid 4 --spp 2 -o " + dir.file("zone.csv") + " --png " + dir.file("zone.png"),
      {"zone.csv", "zone.png", "zone_mtf.png"}, 2);
  std::ofstream(dir.file("spec.json")) << R"({"format": "airr-design", "version": 1, "scene": ")" << scene << R"(",
 "objectives": [{"metric": "r50_mm", "goal": "minimise"}], "constraints": [{"metric": "r50_mm", "max": 0.5}],
 "search": {"psf_samples": 4000},
 "tolerances": [{"key": "retroreflectors.0.pose.pitch_deg", "sd": 0.5}, {"key": "floating_distance_mm", "sd": 5}],
 "tolerance": {"samples": 30, "seed": 4}})";
  expect_merged_equals_one_process(dir, "tolerance " + dir.file("spec.json") + " -o " + dir.file("tol.csv"),
                                   {"tol.csv"}, 3);
}

TEST(Partials, MergeRefusesMissingRepeatedForeignAndStalePartials) {
  test::temp_dir dir;
  const std::string sweep = "sweep " + default_scene_path() + " --psf --vary tilt=0:20:10 -o " + dir.file("s.csv");
  const std::string p0 = dir.file("p0.json"), p1 = dir.file("p1.json"), other = dir.file("other.json");
  ASSERT_EQ(test::run_cli(sweep + " --shard 0/2 --part " + p0).exit_code, 0);
  ASSERT_EQ(test::run_cli(sweep + " --shard 1/2 --part " + p1).exit_code, 0);
  ASSERT_EQ(test::run_cli(sweep + " --set floating_distance_mm=200 --shard 1/2 --part " + other).exit_code, 0);
  test::expect_one_line_error(test::run_cli("merge " + p0), {"shard 1/2 is missing", "p0.json"});
  test::expect_one_line_error(test::run_cli("merge " + p0 + " " + p0 + " " + p1), {"p0.json", "shard 0/2 again"});
  test::expect_one_line_error(test::run_cli("merge " + p0 + " " + other), {"other.json", "command differs"});
  test::expect_one_line_error(test::run_cli("merge " + p0 + " " + p1 + " -o " + dir.file("x.png")), {"-o"});
  test::expect_one_line_error(test::run_cli(sweep + " --shard 0/2"), {"--shard", "--part"});
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.csv")));

  // A spec edited after its shards ran.
  std::ofstream(dir.file("spec.json")) << R"({"format": "airr-design", "version": 1, "scene": ")"
                                       << default_scene_path()
                                       << R"(", "objectives": [{"metric": "size_z_mm", "goal": "minimise"}],
 "tolerances": [{"key": "floating_distance_mm", "sd": 5}], "tolerance": {"samples": 10}})";
  const std::string tol = "tolerance " + dir.file("spec.json") + " -o " + dir.file("t.csv");
  ASSERT_EQ(test::run_cli(tol + " --shard 0/2 --part " + dir.file("t0.json")).exit_code, 0);
  ASSERT_EQ(test::run_cli(tol + " --shard 1/2 --part " + dir.file("t1.json")).exit_code, 0);
  std::ofstream(dir.file("spec.json"), std::ios::app) << "\n";
  test::expect_one_line_error(test::run_cli("merge " + dir.file("t0.json") + " " + dir.file("t1.json")),
                              {"t0.json", "changed since the shards ran"});
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.csv")));
}

// Hand-made bad partials: each is one line naming the file and the field, and nothing is written.
TEST(Partials, BadPartialsNameTheFileAndTheField) {
  test::temp_dir dir;
  const std::string sweep = "sweep " + default_scene_path() + " --psf --vary tilt=0:20:10 -o " + dir.file("s.csv");
  const std::string p0 = dir.file("p0.json"), p1 = dir.file("p1.json"), bad = dir.file("bad.json");
  ASSERT_EQ(test::run_cli(sweep + " --shard 0/2 --part " + p0).exit_code, 0);
  ASSERT_EQ(test::run_cli(sweep + " --shard 1/2 --part " + p1).exit_code, 0);
  const nlohmann::json good = nlohmann::json::parse(std::ifstream(p0));
  ASSERT_EQ(test::run_cli("merge " + p0 + " " + p1).exit_code, 0);  // the unmutated pair merges
  std::filesystem::remove(dir.file("s.csv"));
  using edit = std::function<void(nlohmann::json&)>;
  const std::vector<std::pair<edit, std::string>> cases = {
      {[](nlohmann::json& j) { j["calls"][0]["n"] = "3"; }, "calls[0].n: must be a whole number"},
      {[](nlohmann::json& j) { j["calls"][0].erase("n"); }, "calls[0].n: missing"},
      {[](nlohmann::json& j) { j["calls"][0]["n"] = -1; }, "calls[0].n: must not be negative (is -1)"},
      {[](nlohmann::json& j) { j["calls"][0]["n"] = 1000000000000; },
       "calls[0].n: must be 0 to 10000000 (is 1000000000000)"},
      {[](nlohmann::json& j) { j["calls"][0]["width"] = 0; }, "calls[0].width: must be 1 to 65536 (is 0)"},
      {[](nlohmann::json& j) { j["calls"][0]["width"] = 1 << 20; }, "calls[0].width: must be 1 to 65536"},
      {[](nlohmann::json& j) { j["calls"][0]["items"][0][0] = 99; }, "calls[0].items[0][0]: must be 0 to 2 (is 99)"},
      {[](nlohmann::json& j) { j["calls"][0]["items"][0].erase(1); }, "calls[0].items[0]: must be an array of"},
      {[](nlohmann::json& j) { j["calls"][0]["items"][0][1] = "x"; }, "calls[0].items[0][1]: must be a number"},
      {[](nlohmann::json& j) { j["calls"][0]["items"] = 3; }, "calls[0].items: must be an array"},
      {[](nlohmann::json& j) { j["calls"] = nlohmann::json::object(); }, "calls: must be an array of batches"},
      {[](nlohmann::json& j) { j["calls"][0] = 1; }, "calls[0]: must be a JSON object"},
      {[](nlohmann::json& j) { j["command"] = 5; }, "command: must be a non-empty array"},
      {[](nlohmann::json& j) { j["command"][0] = 5; }, "command[0]: must be a string"},
      {[](nlohmann::json& j) { j.erase("directory"); }, "directory: missing"},
      {[](nlohmann::json& j) { j["inputs"] = "x"; }, "inputs: must be an object"},
      {[](nlohmann::json& j) { j["version"] = 4294967297; }, "version: must be 1"},
      {[](nlohmann::json& j) { j["shard"] = "3/2"; }, "shard"},
      {[](nlohmann::json& j) { j["extra"] = 1; }, "extra: unknown key"},
      {[](nlohmann::json& j) { j["format"] = "airr-render"; }, "not a partial result"},
  };
  for (const auto& [mutate, message] : cases) {
    nlohmann::json j = good;
    mutate(j);
    std::ofstream(bad) << j.dump();
    const test::command_result r = test::run_cli("merge " + bad + " " + p1);
    test::expect_one_line_error(r, {"bad.json: " + message});
    EXPECT_FALSE(std::filesystem::exists(dir.file("s.csv"))) << message;
  }
  // Truncated, and empty.
  const std::string text = good.dump();
  std::ofstream(bad) << text.substr(0, text.size() / 2);
  test::expect_one_line_error(test::run_cli("merge " + bad + " " + p1), {"bad.json: malformed JSON"});
  std::ofstream(bad) << "{}";
  test::expect_one_line_error(test::run_cli("merge " + bad + " " + p1), {"bad.json: not a partial result"});
}
