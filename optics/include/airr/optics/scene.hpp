#pragma once
// The AIRR layout description: plain structs with the defaults of the canonical layout.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace airr {

inline constexpr int scene_format_version = 1;

// Largest accepted render size, per side and in total.
inline constexpr int max_resolution_side = 8192;
inline constexpr long long max_resolution_pixels = 8192LL * 8192LL / 2;

enum class retro_model_type { ideal, sinc_shift, microfacet };
inline constexpr std::array retro_model_type_names = {"ideal", "sinc_shift", "microfacet"};

struct source_params {
  std::string image;  // path relative to the scene file; empty = uniform white
  std::string mesh;   // glTF file relative to the scene file; empty: the built-in unit panel
  double width_mm = 50.0;
  double height_mm = 50.0;
  double intensity = 10.0;                   // radiance = image value x intensity
  std::array<double, 3> offset_mm{0, 0, 0};  // added to the canonical centre (0, -D, 0)

  bool operator==(const source_params&) const = default;
};

struct half_mirror_params {
  std::string mesh;  // glTF file relative to the scene file; empty: the built-in unit panel
  double width_mm = 300.0;
  double height_mm = 300.0;
  double reflectance = 0.5;
  double transmittance = 0.5;

  bool operator==(const half_mirror_params&) const = default;
};

// Parameters of every retroreflector model; each model reads the ones that concern it.
// Unset optionals come from the preset (sinc_shift) or from the documented default.
struct retro_model_params {
  retro_model_type type = retro_model_type::ideal;
  std::optional<double> mu;  // reflectance weight; default: the preset's mu(theta), else 1
  // sinc_shift
  std::string preset;                           // a name in assets/presets or a path; empty: none
  std::optional<double> a_per_mm;               // spread parameter a; default: the preset's a(theta)
  std::optional<double> c_mm;                   // corner size c; default: the preset's c
  std::optional<double> reference_distance_mm;  // R; default: the preset's, else 300
  std::string shift_table;                      // path; empty: the shipped corner-cube table
  // microfacet (the baseline model)
  double alpha_surface = 0.0;
  double alpha_internal = 0.0005;
  double internal_reflectance = 0.83;
  double eta = 1.5046;

  bool operator==(const retro_model_params&) const = default;
};

struct retroreflector_params {
  std::string mesh;  // glTF file relative to the scene file; empty: the built-in unit panel
  double width_mm = 300.0;
  double height_mm = 300.0;
  double distance_mm = 150.0;  // d_rr: the sheet centre sits at z = -d_rr
  double tilt_deg = 0.0;       // rotation about x; positive leans the top edge away from the mirror
  retro_model_params model;

  bool operator==(const retroreflector_params&) const = default;
};

struct camera_params {
  double distance_mm = 300.0;  // in front of the aerial image, on the +z axis
  double fov_deg = 14.0;       // vertical field of view
  int width = 256;
  int height = 256;

  bool operator==(const camera_params&) const = default;
};

struct render_params {
  int max_depth = 8;  // surface interactions per path

  bool operator==(const render_params&) const = default;
};

struct scene {
  int version = scene_format_version;
  double floating_distance_mm = 150.0;  // D: half mirror to aerial image
  std::uint64_t seed = 1;
  source_params source;
  half_mirror_params half_mirror;
  retroreflector_params retroreflector;
  camera_params camera;
  render_params render;
  std::string base_dir;  // directory relative paths resolve against; not saved

  bool operator==(const scene&) const = default;
};

// Resolves a path from the scene file against the scene's directory.
std::string resolve_scene_path(const scene& s, const std::string& path);

}  // namespace airr
