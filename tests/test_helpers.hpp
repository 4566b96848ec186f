#pragma once
// Shared by the tests: scenes built in code, temporary directories, running the CLI.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "airr/core/random.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/path_label.hpp"
#include "airr/render/render_session.hpp"
#include "error_of.hpp"

namespace airr::test {

// Sanitizers reserve terabytes of address space up front, so a test that caps it (ulimit -v,
// RLIMIT_AS) skips itself under them.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool address_space_reserved = true;
#else
inline constexpr bool address_space_reserved = false;
#endif
#define AIRR_SKIP_WHEN_ADDRESS_SPACE_RESERVED() \
  if (::airr::test::address_space_reserved) GTEST_SKIP() << "a sanitizer reserves the address space this test caps"

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

// uniform_source_scene(50, resolution) with a mirror prop (dir/mirror.glb, named "mirror": 120 x
// 120 mm standing in z = -60 beside the display) that shows the display to the observer, placed
// at (0, 150, 410) mm looking at (0, -150, -120).
scene display_in_mirror_scene(const temp_dir& dir, int resolution);

// The default scene (its chart on the display) at size x size pixels, its sheet the sinc-shift
// model with the given preset, tilted to `tilt_deg` when given.
scene chart_scene(const std::string& preset, int size, std::optional<double> tilt_deg = std::nullopt);

// RMS of a - b relative to the RMS of b.
double relative_rms_of_signal(const std::vector<float>& a, const std::vector<float>& b);

// A layout with the half mirror at `alpha`, the aerial image at `aerial`, the display mirrored
// from it and facing the half mirror, then tilted by `display_tilt`; large mirror and sheet.
scene posed_layout(double alpha, const glm::dvec3& aerial, double display_tilt, double source_mm);
// A random general layout as the layout tests draw them: half mirror at 30-60 deg, aerial image
// within 10 mm of the axis and 120-220 mm out, display tilted up to 20 deg, sheet shifted and
// pitched, observer up to 30 deg off axis. Not checked: parts may meet.
scene random_general_layout(pcg32& rng, double source_mm = 4.0);

// Renders to exactly `spp` samples per pixel.
render_snapshot render_to(const scene& s, std::uint64_t spp, int threads = 0);

// The mean of one channel over the (2 half)^2 pixels around the image's centre.
double centre_mean(const render_snapshot& snap, int half, int channel = 1);

// The traced aerial component's mean (green channel) over the (2 half)^2 pixels around the pixel
// corner nearest where the aerial image's centre projects, rendered to `spp` samples per pixel.
double traced_aerial_at_centre(const scene& s, std::uint64_t spp, int half = 2);
// The ideal bench with a uniform white display whose white is `luminance_cd_m2` (0: relative
// units), seen in a size x size image.
scene white_bench(double luminance_cd_m2, int size = 64);

// The unit direction at polar angle theta and azimuth phi (degrees) about +z.
glm::dvec3 unit_direction(double theta_deg, double phi_deg);

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
// A fitted preset against the table it was synthesised from: the same tilts, and a, mu (each
// tilt) and c within `relative` of the table's; prints the table of both.
void expect_preset_near_table(const sheet_preset& fitted, const sheet_preset& table, double relative);

// uniform_source_scene(20) as JSON, changed by `edit`, written to `dir`/scene.json; its path.
std::string scene_file(const temp_dir& dir, const std::function<void(nlohmann::json&)>& edit);

// A path label from events in the light's order (the tracer records them eye first).
inline path_label label_of(const std::vector<path_event>& light_order) {
  path_label l;
  for (auto it = light_order.rbegin(); it != light_order.rend(); ++it) l.push(*it);
  return l;
}

}  // namespace airr::test
