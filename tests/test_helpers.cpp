#include "test_helpers.hpp"

#include <sys/wait.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "airr/core/assets.hpp"
#include "airr/core/geometry.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/tracer.hpp"
#include "plate_mesh.hpp"

namespace airr::test {

temp_dir::temp_dir() {
  std::random_device rd;
  path = std::filesystem::temp_directory_path() / ("airr-test-" + std::to_string(rd()) + std::to_string(rd()));
  std::filesystem::create_directories(path);
}
temp_dir::~temp_dir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

scene uniform_source_scene(double source_mm, int resolution) {
  scene s;
  const std::string panel = airr::asset_dir() + "/models/panel.gltf";
  s.source.mesh = s.half_mirror.mesh = s.sheet().mesh = panel;
  s.source.image.clear();
  s.source.width_mm = s.source.height_mm = source_mm;
  s.observer.width = s.observer.height = resolution;
  return s;
}

scene display_in_mirror_scene(const temp_dir& dir, int resolution) {
  write_plate(plate(2, -60, -60, 60, -200, -80), dir.file("mirror.glb"));
  scene s = uniform_source_scene(50, resolution);
  prop_params p;
  p.name = "mirror";
  p.mesh = dir.file("mirror.glb");
  p.surface = prop_surface::mirror;
  s.props.push_back(p);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, 150, 410};
  s.observer.look_at_mm = {0, -150, -120};
  return s;
}

// Pitch and yaw (deg) whose normal is the unit vector n.
static std::pair<double, double> pitch_yaw_of(const glm::dvec3& n) {
  return {degrees(std::asin(std::clamp(n.y, -1.0, 1.0))), degrees(std::atan2(n.x, n.z))};
}

scene chart_scene(const std::string& preset, int size, std::optional<double> tilt_deg) {
  std::vector<scene_override> overrides = {{"observer.width", std::to_string(size)},
                                           {"observer.height", std::to_string(size)},
                                           {"retroreflectors.0.model.type", "\"sinc_shift\""},
                                           {"retroreflectors.0.model.preset", "\"" + preset + "\""}};
  if (tilt_deg) overrides.push_back({"retroreflectors.0.pose.pitch_deg", std::to_string(*tilt_deg)});
  return load_scene(default_scene_path(), overrides);
}

double relative_rms_of_signal(const std::vector<float>& a, const std::vector<float>& b) {
  double diff2 = 0, sig2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = double(a[i]) - double(b[i]);
    diff2 += d * d;
    sig2 += double(b[i]) * b[i];
  }
  return std::sqrt(diff2 / sig2);
}

scene posed_layout(double alpha, const glm::dvec3& aerial, double display_tilt, double source_mm) {
  scene s = uniform_source_scene(source_mm, 96);
  s.half_mirror.pose.pitch_deg = alpha;
  s.half_mirror.width_mm = s.half_mirror.height_mm = 500;
  s.sheet().width_mm = s.sheet().height_mm = 500;
  s.sheet().pose.center_mm = {0, 0, -200};
  const part_frame hm = half_mirror_frame(s);
  const glm::dvec3 c = mirror_point(aerial, hm.center, hm.n);
  const auto [pitch, yaw] = pitch_yaw_of(reflect(glm::dvec3(0, 0, -1), hm.n));
  s.source.pose.center_mm = {c.x, c.y, c.z};
  s.source.pose.pitch_deg = pitch + display_tilt;
  s.source.pose.yaw_deg = yaw;
  return s;
}

scene random_general_layout(pcg32& rng, double source_mm) {
  const double alpha = 30 + 30 * rng.next_double();
  const glm::dvec3 aerial(-10 + 20 * rng.next_double(), -10 + 20 * rng.next_double(), 120 + 100 * rng.next_double());
  scene s = posed_layout(alpha, aerial, -20 + 40 * rng.next_double(), source_mm);
  s.sheet().pose.center_mm[0] = -20 + 40 * rng.next_double();
  s.sheet().pose.pitch_deg = -10 + 20 * rng.next_double();
  // Observer up to 30 deg off axis in any direction.
  const double off = 30 * std::sqrt(rng.next_double()), dir = 2 * pi * rng.next_double();
  s.observer.azimuth_deg = off * std::cos(dir);
  s.observer.elevation_deg = off * std::sin(dir);
  return s;
}

render_snapshot render_to(const scene& s, std::uint64_t spp, int threads) {
  render_session session(s, {.threads = threads, .target_spp = spp});
  return session.wait_for(0, spp);
}

double centre_mean(const render_snapshot& snap, int half, int channel) {
  double sum = 0;
  int n = 0;
  for (int y = snap.height / 2 - half; y < snap.height / 2 + half; ++y) {
    for (int x = snap.width / 2 - half; x < snap.width / 2 + half; ++x) {
      sum += (*snap.rgb)[3 * (std::size_t(y) * snap.width + x) + std::size_t(channel)];
      ++n;
    }
  }
  return sum / n;
}

scene white_bench(double luminance_cd_m2, int size) {
  scene s = load_scene(asset_dir() + "/scenes/ideal_bench.json");
  s.source.image.clear();
  s.source.luminance_cd_m2 = luminance_cd_m2;
  s.observer.width = s.observer.height = size;
  return s;
}

double traced_aerial_at_centre(const scene& s, std::uint64_t spp, int half) {
  render_session session(s, {.threads = 2, .target_spp = spp, .components = true});
  const render_snapshot snap = session.wait_for(0, spp);
  EXPECT_TRUE(snap.components);
  if (!snap.components) return 0;
  // The pixel corner nearest the projected centre (which may fall a rounding error short of one).
  const glm::dvec2 c = camera_project(make_camera(s), aerial_image_center(s));
  const int cx = int(std::lround(c.x)), cy = int(std::lround(c.y));
  double sum = 0;
  int n = 0;
  for (int y = cy - half; y < cy + half; ++y) {
    for (int x = cx - half; x < cx + half; ++x) {
      sum += (*snap.components)[3 * (component_count * (std::size_t(y) * snap.width + x) + component_aerial) + 1];
      ++n;
    }
  }
  return sum / n;
}

glm::dvec3 unit_direction(double theta_deg, double phi_deg) {
  const double t = radians(theta_deg), p = radians(phi_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

centroid luminance_centroid(const render_snapshot& snap) {
  centroid c;
  for (int y = 0; y < snap.height; ++y) {
    for (int x = 0; x < snap.width; ++x) {
      const float* p = snap.rgb->data() + 3 * (std::size_t(y) * snap.width + x);
      const double v = (p[0] + p[1] + p[2]) / 3.0;
      c.x += v * (x + 0.5);
      c.y += v * (y + 0.5);
      c.total += v;
    }
  }
  if (c.total > 0) {
    c.x /= c.total;
    c.y /= c.total;
  }
  return c;
}

command_result run_cli(const std::string& args) { return run_command(std::string(AIRR_CLI) + " " + args); }

void expect_one_line_error(const command_result& r, const std::vector<std::string>& must_contain) {
  const auto lines = std::count(r.out.begin(), r.out.end(), '\n');
  EXPECT_NE(r.exit_code, 0) << r.out;
  EXPECT_EQ(lines, 1) << r.out;
  EXPECT_EQ(r.out.rfind("error: ", 0), 0u) << r.out;
  for (const auto& m : must_contain)
    EXPECT_NE(r.out.find(m), std::string::npos) << "missing '" << m << "' in: " << r.out;
}

std::string scene_file(const temp_dir& dir, const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = scene_to_json(uniform_source_scene(20));
  edit(j);
  const std::string path = dir.file("scene.json");
  std::ofstream(path) << j.dump(2);
  return path;
}

command_result run_command(const std::string& shell_command) {
  command_result r;
  const std::string cmd = "{ " + shell_command + "; } 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

void expect_preset_near_table(const sheet_preset& fitted, const sheet_preset& table, double relative) {
  ASSERT_EQ(fitted.theta_deg, table.theta_deg);
  std::printf("%8s %9s %9s %7s %9s %9s %7s\n", "tilt", "a_table", "a_fit", "a_err", "mu_table", "mu_fit", "mu_err");
  for (std::size_t i = 0; i < table.theta_deg.size(); ++i) {
    std::printf("%8g %9.5f %9.5f %+6.2f%% %9.5f %9.5f %+6.2f%%\n", table.theta_deg[i], table.a_per_mm[i],
                fitted.a_per_mm[i], 100 * (fitted.a_per_mm[i] / table.a_per_mm[i] - 1), table.mu[i], fitted.mu[i],
                100 * (fitted.mu[i] / table.mu[i] - 1));
    EXPECT_NEAR(fitted.a_per_mm[i], table.a_per_mm[i], relative * table.a_per_mm[i]) << "tilt " << table.theta_deg[i];
    EXPECT_NEAR(fitted.mu[i], table.mu[i], relative * table.mu[i]) << "tilt " << table.theta_deg[i];
  }
  std::printf("c: table %.5f mm, fitted %.5f mm (%+.2f%%)\n", table.c_mm, fitted.c_mm,
              100 * (fitted.c_mm / table.c_mm - 1));
  EXPECT_NEAR(fitted.c_mm, table.c_mm, relative * table.c_mm);
}

}  // namespace airr::test
