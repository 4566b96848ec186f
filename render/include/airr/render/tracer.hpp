#pragma once
// Backward path tracing through an AIRR layout: camera -> half mirror -> retroreflector ->
// half mirror -> source, with every other branch followed as ordinary light transport.
#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/emission_profile.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/ambient_lights.hpp"
#include "airr/render/embree_scene.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/path_expression.hpp"

namespace airr {

// Everything a render needs, built from a scene; cheap to update when only parts move.
struct tracer_scene {
  scene layout;
  std::vector<part_frame> frames;  // by part_id: the display's whole panel, the half mirror, the sheets
  part_frame source_area;          // the display's emitting area
  pinhole_camera camera;
  std::shared_ptr<const image_rgb> texture;          // null: uniform white source
  std::shared_ptr<const emission_profile> emission;  // null: Lambertian
  retro_model_list retro;                            // one per sheet
  // The visible props, instanced after the sheets from instance id first_prop on.
  struct prop {
    prop_params params;
    std::shared_ptr<const triangle_mesh> mesh;
    glm::dmat3 rotation{1.0};  // turns the mesh's normals into the world's
    std::uint16_t index = 0;   // among the scene's props (hidden ones included): its path events'
  };
  std::vector<prop> props;
  unsigned first_prop = part_first_sheet;
  std::unique_ptr<embree_instanced_scene> embree;
  ambient_lights ambient;  // the layout's room, sun and luminaires
  // The model image, the control variate of every pixel's estimate (null: none, the plain
  // estimator); see update_model_image.
  bool use_model_image = true;
  std::shared_ptr<const layout_model_image> model;
  // The model image keeps its pixels' ideal paths (model_image_params::keep_pixels); off for a
  // render that predicts its samples once at its end (predict_pixel), which traces them anew.
  bool model_pixels_kept = true;
  // Paths carry their polarization when the scene polarizes (scene_polarizes), or always when
  // forced (a test of the polarized tracer on scenes that do not).
  bool polarized = false;
  bool force_polarized = false;
  // -1: what the observer sees (through its polarizer if any). 0 to 3: the Stokes parameter S_i of
  // the light reaching the observer, before its polarizer, in the image's frame (x its right, y
  // its up); traced with polarization and without the control variate.
  int stokes = -1;
  // The layers trace_rows keeps apart when asked (null: none), bound to the layout's props on
  // every build.
  std::shared_ptr<const path_layers> layers;
};

// Builds (or, given the previous state, updates in place: meshes and textures are reused when
// their files did not change, and moved parts only get new instance transforms). `models`, when
// given, are the sheets' retroreflector models already built; otherwise they are built here.
void build_tracer_scene(tracer_scene& ts, const embree_device& device, const scene& s, retro_model_list models = {});

// Computes the model image of every sheet of the built layout (or leaves none when
// use_model_image is off or no pixel sees a sheet, or `cancel` is set while it runs), at
// model_image_params::for_image(width, height, quick). Building clears it: it takes longer than
// the rest (about 0.75 s at 512 x 512, 0.27 s quick), so the session traces meanwhile
// (control_variate_job, add_predictions).
void update_model_image(tracer_scene& ts, const std::atomic<bool>* cancel = nullptr, bool quick = false);

// What the control variate's model image needs of a built scene, copied: it can be computed on
// another thread while the scene is traced (and rebuilt) meanwhile.
struct model_image_job {
  scene layout;
  retro_model_list retro;
  std::shared_ptr<const image_rgb> texture;
  model_image_params params;
  bool wanted = false;  // use_model_image is on and there are sheets
  // The model image (null: not wanted, no pixel sees a sheet, or cancelled).
  std::shared_ptr<const layout_model_image> run(const std::atomic<bool>* cancel = nullptr) const;
};
model_image_job control_variate_job(const tracer_scene& ts, bool quick = false);

// The components of an image (spec section 8), by what a path met before the display: the aerial
// image (at least one retroreflection), the display seen directly (no half-mirror reflection, no
// prop), its plain reflection in the half mirror (one, no prop), and the rest (more, or light a
// prop scattered or a sheet sent back without retroreflecting it); and ambient light (spec section
// 11) by any path: the room's, the sun's and the luminaires'. They add up to the image.
enum image_component {
  component_aerial,
  component_direct,
  component_reflection,
  component_rest,
  component_room,
  component_sun,
  component_luminaires
};
inline constexpr int component_count = 7;
inline constexpr const char* component_names[component_count] = {"aerial", "direct", "reflection", "rest",
                                                                 "room",   "sun",    "luminaires"};
// A sample's light by component. With `each_luminaire`, luminaire k's share of the luminaires'
// component is also added at each_luminaire[k].
struct component_radiance : std::array<glm::vec3, component_count> {
  glm::vec3* each_luminaire = nullptr;
};

// Where a pixel's component sums hold each component: `count` RGB triples a pixel, component k at
// slot[k], or nowhere (-1) for one the scene cannot have (zero everywhere); and each luminaire's
// share of the luminaires' component, `luminaires` of them from slot `first_luminaire`.
struct component_slots {
  std::array<int, component_count> slot{0, 1, 2, 3, 4, 5, 6};
  int count = component_count;
  int first_luminaire = -1;
  int luminaires = 0;
};
// Only the components the scene's light can make: the room's, the sun's and the luminaires' only
// with such light (a render's sums then take 48 bytes a pixel, not 84, in a dark room), and each
// luminaire's own (luminaire_component_name).
component_slots possible_component_slots(const ambient_lights& a);
// Every component at its own index (slot[k] = k), then each luminaire's: the designer's views.
component_slots all_component_slots(const ambient_lights& a);
// The name of luminaire k's own component: "luminaire0", "luminaire1", ... as its path event's.
std::string luminaire_component_name(int k);
// A render's components by name, as its layers: component_names, then each of `luminaires`
// luminaires' own.
std::vector<std::string> component_layer_names(int luminaires);
// Whether `name` is a component's (component_names, or luminaire_component_name of any k < max_luminaires).
bool is_component_name(const std::string& name);

// The pixel's random rotation of the low-discrepancy sequence its samples share.
std::array<double, 6> pixel_sequence_rotation(const tracer_scene& ts, int px, int py);

// Radiance along one camera sample of pixel (px, py); `rays` counts intersection queries.
glm::vec3 trace_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                       const std::array<double, 6>& rotation, std::uint64_t& rays);
glm::vec3 trace_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index, std::uint64_t& rays);

// One sample of the pixel's estimator: its radiance minus the model image's prediction for the
// same random numbers. The pixel's estimate is the model image's value plus the mean of these.
glm::vec3 estimate_sample(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                          const std::array<double, 6>& rotation, std::uint64_t& rays);
// The same sample split into components; the model image's prediction is the aerial image's.
component_radiance estimate_components(const tracer_scene& ts, int px, int py, std::uint64_t sample_index,
                                       const std::array<double, 6>& rotation, std::uint64_t& rays);

// The layers (bit k: ts.layers' layer k, as path_layers::select) that carry the control variate:
// those selecting every sheet's modelled path (display, half mirror, the sheet's retroreflection,
// half mirror, eye), the unmatched layer when none does; 0 without layers or a model image. Each
// layer stays an unbiased estimate of its own paths, and a partition of the paths keeps adding up.
std::uint64_t model_layers(const tracer_scene& ts);

// The part of the pixel's estimate that needs no samples: the model image's value (0 without one).
glm::vec3 model_value(const tracer_scene& ts, int px, int py);

// The model image's predictions of a render's samples, summed apart from what the samples traced
// (RGB per pixel; the odd-numbered samples also alone), so that the predictions of samples traced
// before the model image arrived can be added when it does, in the same order: the estimate
// comes out the same to the bit, whenever it arrived. Empty vectors keep nothing: the predictions
// are then made when the image is (predict_pixel), as a render that publishes only at its target does.
struct prediction_sums {
  std::vector<float> all, odd;
};

// Accumulates estimate_sample for samples [first, first + count) of every pixel in rows [y0, y1) into `sums`
// (single-precision RGB per pixel, added in sample order so that splitting into waves changes
// nothing), and the odd-numbered samples also into `odd_sums` when given (two independent half
// estimates, whose difference measures the noise), and by component into `component_sums` when given
// (laid out as `slots` says, all component_count of them by default). With `predictions`, the sums are of the traced
// radiance alone and the model image's predictions go there (the estimate: model_value plus the mean of the sums less
// the predictions). With ts.layers and `layer_sums`, also by layer (ts.layers->count() RGB triples per pixel; the
// model's predictions, unless apart, taken from model_layers' layers). Stops early (returns false) when `cancel`
// becomes true.
bool trace_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                std::vector<float>& sums, const std::atomic<bool>& cancel, std::uint64_t& rays,
                std::vector<float>* odd_sums = nullptr, std::vector<float>* component_sums = nullptr,
                prediction_sums* predictions = nullptr, std::vector<float>* layer_sums = nullptr,
                const component_slots& slots = {});

// One class of a census: a path label and the light (RGB, summed over the samples) that met it.
struct census_class {
  path_label label;
  glm::dvec3 light{0.0};
};
// Every distinct path label that samples [first, first + count) of rows [y0, y1) met, keyed by
// label_text (a path expression selecting exactly that label), with its light: a census of the
// light paths, without the control variate.
void census_rows(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                 std::map<std::string, census_class>& classes, const std::atomic<bool>& cancel, std::uint64_t& rays);

// Adds the model image's predictions of samples [first, first + count) of rows [y0, y1): those
// traced before ts.model arrived. Stops early (returns false, the sums half done) when `cancel`
// becomes true.
bool add_predictions(const tracer_scene& ts, int y0, int y1, std::uint64_t first, std::uint64_t count,
                     prediction_sums& predictions, const std::atomic<bool>& cancel);

// The model image's predictions of samples [first, first + count) of pixel (px, py), each summed
// in sample order in double precision: all of them and the odd-numbered alone. Zero without ts.model.
struct pixel_predictions {
  glm::dvec3 all{0.0}, odd{0.0};
};
pixel_predictions predict_pixel(const tracer_scene& ts, int px, int py, std::uint64_t first, std::uint64_t count);

}  // namespace airr
