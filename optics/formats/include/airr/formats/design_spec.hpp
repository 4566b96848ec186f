#pragma once
// Design specs (format "airr-design", version 1): what a designer asks the optimiser for. A base
// scene, the free variables (scene values by their --set keys, with ranges), the eye positions the
// metrics are taken at, the objectives (metrics to maximise or minimise, weighted), the
// constraints (metrics bounded from below or above) and the assembly tolerances `airr tolerance`
// draws. Read strictly: errors name the file and field.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/formats/scene_json.hpp"
#include "airr/layout/legibility.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/viewing_zone.hpp"

namespace airr {

// The metrics of a layout (spec section 9) a spec may name.
enum class design_metric {
  visible_fraction,         // of the aerial image, at the eye (geometric)
  mean_mtf,                 // of the model PSF seen from the eye, over (0, 1] lp/mm
  mtf50_lp_per_mm,          // where that MTF first falls to 0.5
  r50_mm,                   // radius holding half the model PSF's energy
  brightness,               // the model PSF's light relative to the display's
  stray_light,              // the stray-light ratio seen from the eye (a small render split into components)
  ghost_ratio,              // a path expression's light over the aerial image's, inside its outline, from the eye
  ghost_separation_arcmin,  // the angle between that light's centroid and the aerial image's, from the eye
  luminance_cd_m2,          // the aerial image's: the model PSF's brightness times the display's white
  contrast,                 // (aerial + background) / background of their mean luminances, from the eye
  legible_share,            // the share of the aerial image seen at the spec's legible_contrast or more
  char_height_mm,           // the smallest legible character on the aerial image (the spec's legibility)
  size_x_mm,                // the device's bounding box (display panel, half mirror, sheets) along x, y, z
  size_y_mm,
  size_z_mm,
  prop_cut_mm,  // the length of the lines where the display panel, the half mirror and the sheets cut props
};
inline constexpr int design_metric_count = int(design_metric::prop_cut_mm) + 1;
// The spec's name of a metric, and the metric a name stands for (empty for an unknown name).
const char* to_string(design_metric m);
std::optional<design_metric> design_metric_named(const std::string& name);
// Whether the metric depends on the eye (the others are the layout's alone).
bool metric_at_eye(design_metric m);
// The names, comma-separated (for error messages and help).
std::string design_metric_names();

struct design_variable {
  std::string key;  // a --set key, e.g. "half_mirror.pose.pitch_deg" or "floating_distance_mm"
  double min = 0, max = 0;
};

// Over several eyes, an eye metric is their mean, their minimum, or the share of them where it is
// at least a threshold (e.g. the part of a zone of eyes that sees 90% of the aerial image).
enum class over_eyes { mean, min, share_above };

// Whether the metric measures the paths of a path expression (the objective's "expression").
bool metric_takes_expression(design_metric m);

struct design_objective {
  design_metric metric = design_metric::visible_fraction;
  over_eyes over = over_eyes::mean;
  bool maximise = true;
  double weight = 1;
  double threshold = 0;      // for share_above
  std::string expression{};  // the ghost metrics' paths (docs/path-expressions.md)
};

struct design_constraint {
  design_metric metric = design_metric::visible_fraction;
  over_eyes over = over_eyes::mean;
  std::optional<double> min, max;
  double threshold = 0;      // for share_above
  std::string expression{};  // as the objective's
};

// An assembly tolerance: a scene value (by its --set key) off its nominal by a normal error of
// standard deviation `size`, or a uniform one within +-`size`; with `percent`, size is a
// percentage of the nominal value.
struct design_tolerance {
  std::string key;
  double size = 0;
  bool uniform = false;
  bool percent = false;
};

struct tolerance_settings {
  int samples = 1000;  // Monte Carlo layouts
  std::uint64_t seed = 1;
};

struct design_search {
  std::uint64_t seed = 1;
  int global_evaluations = 100;       // of the global search
  int local_evaluations = 60;         // of the local polish after it
  std::uint64_t psf_samples = 20000;  // per model PSF
};

// A Pareto front of the two objectives (points > 0): the best of each alone, then the first's best
// with the second held at least as good as each of `points` - 2 levels evenly between those ends.
struct design_front {
  int points = 0;
};

struct design_spec {
  std::string path;        // the spec's file
  std::string scene_path;  // the base scene, resolved
  scene base;              // read and checked
  std::vector<design_variable> variables;
  std::vector<glm::dvec3> eyes_mm;   // listed; the scene's observer when the spec gives no eyes at all
  std::optional<eye_grid> eye_zone;  // a grid of eyes besides, as `airr viewzone` places them
  std::vector<design_objective> objectives;
  std::vector<design_constraint> constraints;
  design_search search;
  design_front front;  // from "pareto"
  std::vector<design_tolerance> tolerances;
  tolerance_settings tolerance;
  double legible_contrast = 3;        // the contrast legible_share counts from
  legibility_criterion legibility{};  // what char_height_mm counts as legible
};

// Reads and checks a spec and its base scene; throws input_error "<file>: <field>: <problem>":
// unknown keys, empty or reversed ranges, values that are not finite, unknown metrics, variables
// the scene does not have, no objective.
design_spec load_design_spec(const std::string& path);
// The same read of spec text over a scene at hand (the designer's layout): a "scene" the text names
// is kept as scene_path but not read. Errors name `origin`.
design_spec parse_design_spec(const std::string& text, const std::string& origin, const scene& base);
// The spec as the text load_design_spec reads (its scene as scene_path says, when it says).
std::string design_spec_text(const design_spec& spec);

// Every eye the metrics are taken at: those listed, then the zone's row by row (placed about the
// base scene's aerial image).
std::vector<glm::dvec3> design_eyes(const design_spec& spec);

// The override setting `key` to exactly v (all 17 digits), as variables and tolerances set values.
scene_override design_override(const std::string& key, double v);

// The base scene with the variables set to x (one value per variable, in order); throws
// input_error naming the spec when a value makes no valid layout.
scene design_scene(const design_spec& spec, const std::vector<double>& x);

}  // namespace airr
