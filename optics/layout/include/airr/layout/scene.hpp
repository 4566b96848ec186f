#pragma once
// The AIRR layout description: plain structs with the defaults of the canonical layout (the
// paper's measurement bench). Every part has a pose; the floating distance is derived from the
// display's pose (see layout.hpp).
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "airr/layout/polarizing_parts.hpp"
#include "airr/models/model_params.hpp"
#include "airr/models/plate.hpp"

namespace airr {

inline constexpr int scene_format_version = 2;

// Largest accepted render size per side (8192 x 8192 with components takes about 7 GB: whether a
// machine has that is render_memory_need's to say).
inline constexpr int max_resolution_side = 8192;
// Most retroreflective sheets in one layout.
inline constexpr int max_retroreflectors = 8;
// Most props in one layout.
inline constexpr int max_props = 256;
// Every position and size stays within 100 m of the origin (Embree traces in float), and a
// part is at least 0.1 mm across (smaller is a typing slip, not a device).
inline constexpr double max_distance_mm = 1e5;
inline constexpr double min_part_size_mm = 0.1;

// Where a part is. Its optical face is its local +z, its width runs along local +x and its height
// along local +y. The world orientation is R = Ry(yaw) Rx(-pitch) Rz(roll), applied in that order
// from the right: roll turns the part about its own normal, pitch then raises the normal towards
// +y, yaw turns the result about the world's y axis from +z towards +x. The normal is therefore
// (sin yaw cos pitch, sin pitch, cos yaw cos pitch).
struct pose {
  std::array<double, 3> center_mm{0, 0, 0};
  double yaw_deg = 0;
  double pitch_deg = 0;
  double roll_deg = 0;

  bool operator==(const pose&) const = default;
};

// What every part has: a rectangle (or a mesh scaled to it) at a pose.
struct part_params {
  std::string mesh;  // glTF file relative to the scene file; empty: the built-in unit panel
  double width_mm = 300.0;
  double height_mm = 300.0;
  airr::pose pose;
  std::vector<film_params> films;  // laid on its faces (polarizing_parts.hpp)

  bool operator==(const part_params&) const = default;
};

// The display. width/height are its active (emitting) area; the bezel is a black border around it.
struct source_params : part_params {
  std::string image;        // path relative to the scene file; empty = uniform white
  double intensity = 10.0;  // radiance = image value x intensity (relative units)
  // The white's luminance in cd/m2 (CIE Y of the linear RGB, face on); above 0 it takes the place
  // of intensity and every image of the layout is in cd/m2.
  double luminance_cd_m2 = 0.0;
  std::string emission_profile;  // CSV of angle (deg) -> relative luminance; empty: Lambertian
  double bezel_mm = 0.0;
  source_polarization polarization;

  source_params() {
    width_mm = height_mm = 50.0;
    pose.center_mm = {0, -150, 0};
    pose.pitch_deg = 90;  // facing +y; the image's top lies towards -z
  }
  bool operator==(const source_params&) const = default;
};

// The radiance of the display's white (image value 1) in the units of the layout's images.
inline double white_radiance(const source_params& s) { return s.luminance_cd_m2 > 0 ? s.luminance_cd_m2 : s.intensity; }
// Whether the layout's images are in cd/m2 (else relative to `intensity`).
inline bool in_cd_m2(const source_params& s) { return s.luminance_cd_m2 > 0; }
// The name of those units, as files and readouts give it.
inline const char* image_units(const source_params& s) { return in_cd_m2(s) ? "cd/m2" : "relative"; }

// The half mirror: a thin sheet with fixed reflectance and transmittance, a reflective polarizer,
// or a glass plate with coated faces whose pose is its mid-plane's.
enum class half_mirror_kind { half_mirror, reflective_polarizer, plate };

struct half_mirror_params : part_params {
  half_mirror_kind kind = half_mirror_kind::half_mirror;
  // The other kinds' parts; their reflectance and transmittance follow from them
  // (derive_half_mirror_light).
  reflective_polarizer_params polarizer;
  plate_params plate;
  double reflectance = 0.5;
  double transmittance = 0.5;

  half_mirror_params() { pose.pitch_deg = 45; }
  bool operator==(const half_mirror_params&) const = default;
};

// One retroreflective sheet. In the canonical layout, its tilt is the pose's pitch and its
// distance behind the half mirror is -center_mm[2]; the roll is the prism azimuth.
struct retroreflector_params : part_params {
  retro_model_params model;

  retroreflector_params() { pose.center_mm = {0, 0, -150}; }
  bool operator==(const retroreflector_params&) const = default;
};

// What a prop's surface does with light: absorber, nothing (black); diffuse, Lambertian with
// reflectance `albedo`; mirror, specular with reflectance `albedo`; material, each triangle as
// its glTF material maps (see prop_surface_of in mesh_gltf.hpp).
enum class prop_surface { absorber, diffuse, mirror, material };
inline constexpr const char* prop_surface_names[] = {"absorber", "diffuse", "mirror", "material"};

// A model placed in the layout: a housing, a hood, a baffle, a frame. It blocks and scatters light
// in the tracer and blocks it in the viewing-zone analysis. The mesh is read in millimetres (glTF's
// metres x 1000; a STEP file's own unit converted) and placed, times `scale`, in the frame of its
// pose (no size: the mesh has its own).
struct prop_params {
  std::string name;
  std::string mesh;  // glTF, GLB or STEP file relative to the scene file
  // A node of the file (glTF: its name, or "#index"; STEP: a product's name) with its descendants;
  // empty: all.
  std::string node;
  double scale = 1.0;
  airr::pose pose;
  prop_surface surface = prop_surface::absorber;
  std::array<double, 3> albedo{0.5, 0.5, 0.5};  // linear RGB, for diffuse and mirror
  bool visible = true;                          // a hidden prop takes no part in renders or analyses
  // STEP files: the farthest a triangle may stray from the surface it stands for (chordal tolerance).
  double tessellation_mm = 0.05;

  bool operator==(const prop_params&) const = default;
};

enum class observer_placement { orbit, look_at };
enum class observer_lens { pinhole, thin_lens };

// The camera (or eye) that looks at the layout.
struct observer_params {
  observer_placement placement = observer_placement::orbit;
  // Orbit around the aerial image's centre: azimuth turns from +z towards +x, elevation raises
  // towards +y; at 0, 0 the observer is on the aerial image's +z side.
  double azimuth_deg = 0;
  double elevation_deg = 0;
  double distance_mm = 300.0;
  // Position and look-at point (placement look_at).
  std::array<double, 3> position_mm{0, 0, 450};
  std::array<double, 3> look_at_mm{0, 0, 150};
  observer_lens lens = observer_lens::pinhole;
  double focal_length_mm = 50.0;
  double f_number = 4.0;
  std::optional<double> focus_distance_mm;  // default: the distance to the aim point (orbit: the aerial image)
  double fov_deg = 14.0;                    // vertical field of view
  int width = 256;
  int height = 256;
  // A linear polarizer before the observer: its pass axis from the image's right towards its up.
  std::optional<double> analyzer_deg;

  bool operator==(const observer_params&) const = default;
};

// The room around the device (spec section 11): a uniform surround, given by its luminance or by
// the illuminance it makes on any plane, a horizontal one included (E = pi L). Ambient light is in
// cd/m2, so a layout with any gives its display's luminance too (source.luminance_cd_m2).
struct room_params {
  double luminance_cd_m2 = 0.0;
  double illuminance_lux = 0.0;  // set instead of the luminance: it is illuminance / pi

  bool operator==(const room_params&) const = default;
};

// The sun (spec section 11): a disc of sun_angular_diameter_deg in the direction given by its
// azimuth (from +z towards +x, as the observer's orbit) and its elevation above the horizon (+y
// up), making illuminance_lux on a plane facing it (0: no sun).
struct sun_params {
  double azimuth_deg = 0;
  double elevation_deg = 45;
  double illuminance_lux = 0;

  bool operator==(const sun_params&) const = default;
};
inline constexpr double sun_angular_diameter_deg = 0.53;
// The brightest sun a scene takes, in lux (the clear-sky sun at noon makes about 100,000).
inline constexpr double max_sun_illuminance_lux = 150000;

// A luminaire: an emitting rectangle (width x height) or disc (width_mm its diameter) at a pose,
// Lambertian, from its front (the pose's normal) only; e.g. a ceiling panel facing down (pitch
// -90). Its brightness is a luminance, or a luminous flux (luminance = flux / (pi x area)).
enum class luminaire_shape { rectangle, disc };
struct luminaire_params {
  std::string name;
  luminaire_shape shape = luminaire_shape::rectangle;
  airr::pose pose;
  double width_mm = 600.0;
  double height_mm = 600.0;
  double luminance_cd_m2 = 0.0;
  double flux_lm = 0.0;

  bool operator==(const luminaire_params&) const = default;
};
// Most luminaires in one layout.
inline constexpr int max_luminaires = 32;

struct environment_params {
  room_params room;
  sun_params sun;
  std::vector<luminaire_params> luminaires;

  bool operator==(const environment_params&) const = default;
};

// The room's luminance in cd/m2 (0: a dark room).
double room_luminance(const room_params& r);
// The sun's luminance in cd/m2: its illuminance over the solid angle of its disc.
double sun_luminance(const sun_params& s);
// A luminaire's emitting area in mm2, and its luminance in cd/m2.
double luminaire_area_mm2(const luminaire_params& l);
double luminaire_luminance(const luminaire_params& l);
// Whether the layout has ambient light.
bool has_ambient_light(const environment_params& e);

struct render_params {
  int max_depth = 8;  // surface interactions per path

  bool operator==(const render_params&) const = default;
};

struct scene {
  int version = scene_format_version;
  std::uint64_t seed = 1;
  source_params source;
  half_mirror_params half_mirror;
  std::vector<retroreflector_params> retroreflectors{retroreflector_params{}};  // at least one
  std::vector<prop_params> props;
  observer_params observer;
  environment_params environment;
  render_params render;
  std::string base_dir;  // directory relative paths resolve against; not saved

  bool operator==(const scene&) const = default;

  // The first sheet: the one the tilt drag, sweeps, the PSF and the fit act on.
  retroreflector_params& sheet() { return retroreflectors.front(); }
  const retroreflector_params& sheet() const { return retroreflectors.front(); }
};

// A reflective polarizer's reflectance and transmittance for unpolarized light (the means of its
// pass and block values), or a plate's main reflection and its transmission for unpolarized light
// at 45 deg on its back face (the canonical layout's display side), set as the half mirror's
// scalars (the fast first look's); a plain half mirror is left as it is.
void derive_half_mirror_light(half_mirror_params& hm);

// True when something in the scene polarizes light or looks at its polarization: the display's
// light, a film, a reflective polarizer or the observer's polarizer. Scenes that do not are
// traced without polarization, as before there was any.
bool scene_polarizes(const scene& s);

// Resolves a path from the scene file against the scene's directory.
std::string resolve_scene_path(const scene& s, const std::string& path);

// True when the two scenes differ at most in where things are: the parts' and props' poses and
// the observer's placement (orbit angles and distance, position and aim), as while a designer drags.
bool differ_in_placement_alone(const scene& a, const scene& b);

}  // namespace airr
