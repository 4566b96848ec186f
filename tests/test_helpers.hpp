#pragma once
// Shared by the tests: scenes built in code, temporary directories, running the CLI.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/optics/image.hpp"
#include "airr/optics/random.hpp"
#include "airr/optics/retro_model.hpp"
#include "airr/optics/scene.hpp"
#include "airr/render/render_session.hpp"
#include "error_of.hpp"

namespace airr::test {

// A retroreflection's named samples, all drawn from one generator.
inline retro_samples random_retro_samples(pcg32& rng) {
  retro_samples u;
  u.lobe = {rng.next_double(), rng.next_double()};
  u.shift = {rng.next_double(), rng.next_double()};
  u.more = rng.split();
  return u;
}

// A fresh empty directory under the system temp dir, removed when the object dies.
struct temp_dir {
  std::filesystem::path path;
  temp_dir();
  ~temp_dir();
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// The default layout with absolute mesh paths, a uniform white source of the given size and a
// small camera image; valid without any scene file.
scene uniform_source_scene(double source_mm, int resolution = 96);

// Renders to exactly `spp` samples per pixel.
render_snapshot render_to(const scene& s, std::uint64_t spp, int threads = 0);

struct centroid {
  double x = 0, y = 0, total = 0;
};
centroid luminance_centroid(const render_snapshot& snap);

struct command_result {
  int exit_code = 0;
  std::string out;  // stdout and stderr together
};
// Runs a shell command; `airr` with these arguments.
command_result run_command(const std::string& shell_command);
command_result run_cli(const std::string& args);
// The command failed with exactly one line, "error: ...", holding every one of `must_contain`.
void expect_one_line_error(const command_result& r, const std::vector<std::string>& must_contain);
// uniform_source_scene(20) as JSON, changed by `edit`, written to `dir`/scene.json; its path.
std::string scene_file(const temp_dir& dir, const std::function<void(nlohmann::json&)>& edit);

}  // namespace airr::test
