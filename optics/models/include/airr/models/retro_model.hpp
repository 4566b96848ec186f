#pragma once
// The retroreflector model interface. Directions are in the sheet's local frame (normal +z) and
// point away from the surface: wi towards where the light came from, wo where it leaves.
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/random.hpp"
#include "airr/models/model_fields.hpp"
#include "airr/models/model_params.hpp"
#include "airr/models/polarization.hpp"

namespace airr {

// The random numbers of one interaction, each uniform in [0, 1). A caller may stratify the two
// named 2-D samples across a pixel's samples; each model documents what they drive. Anything
// further comes from `more`, in a fixed order; the model draws from its own copy, so a sample is
// a pure function of wi and these numbers.
struct retro_samples {
  glm::dvec2 lobe{0.5, 0.5};   // the model's main choice: where the light goes
  glm::dvec2 shift{0.5, 0.5};  // the second most important choice (the exit-point shift, ...)
  pcg32 more{0, 0};
};

struct retro_sample {
  glm::dvec3 wo{0, 0, 1};
  glm::dvec2 shift_mm{0, 0};  // exit point minus entry point, in the sheet plane (local x, y)
  double weight = 0;          // throughput; 0 means absorbed
  // False for light the sheet sends back some other way than by retroreflection (a surface
  // reflection, a diffuse lobe, stray paths through the structure): it lands wherever its direction
  // takes it, and is stray light, not part of the aerial image or its PSF.
  bool retroreflected = true;
  // What it carries of the tracer's R, G, B channels (1 each but for light drawn at one primary's
  // wavelength, diffraction.hpp); the model PSF and the model image take the mean, white.
  glm::dvec3 channels{1.0};
  // From sample_polarized, for models that follow polarization: the Mueller matrix of the light's
  // own path, which runs against the sample's (from the display's side in along -wo, out along wi
  // to the observer), between the frames sheet_light_frames gives, divided by its unpolarized
  // throughput, which `weight` carries. Empty: the sheet keeps the field as a perfect mirror
  // facing the light would (docs/polarization.md).
  std::optional<mueller> polarization{};
};

// The sheet-local frames retro_sample::polarization is written in: of the light arriving against
// wo, reversed(about(wo)), and of the light leaving along wi, reversed(about(-wi)).
struct sheet_light_frames {
  polarization_frame in, out;
};
inline sheet_light_frames light_frames_of(const glm::dvec3& wi, const glm::dvec3& wo) {
  return {reversed(polarization_frame::about(wo)), reversed(polarization_frame::about(-wi))};
}

// A model at one fixed incidence, for many samples there: sample(u) is the model's sample(wi, u)
// for that wi, with what depends on wi alone worked out once.
class retro_at_incidence {
 public:
  virtual ~retro_at_incidence() = default;
  virtual retro_sample sample(retro_samples u) const = 0;
  // For sample_at_each, called on at[0]: out[i] = at[i]->sample(u). A model may share the work
  // that does not depend on the incidence; the default samples each.
  virtual void sample_group(std::span<const retro_at_incidence* const> at, const retro_samples& u,
                            std::span<retro_sample> out) const;
};

// Samples at several incidences (of one model or several) from the same numbers: out[i] is
// at[i]->sample(u), with the work they share done once (the model image's bins).
inline void sample_at_each(std::span<const retro_at_incidence* const> at, const retro_samples& u,
                           std::span<retro_sample> out) {
  if (!at.empty()) at[0]->sample_group(at, u, out);
}

class retro_model {
 public:
  virtual ~retro_model() = default;
  virtual retro_sample sample(const glm::dvec3& wi, retro_samples u) const = 0;
  // sample with the polarization of its path, for the models that follow it; the others' (the
  // default) leave retro_sample::polarization empty.
  virtual retro_sample sample_polarized(const glm::dvec3& wi, retro_samples u) const { return sample(wi, u); }
  // The model prepared for incidence wi; the default calls sample(wi, u) each time. The model
  // outlives what this returns.
  virtual std::unique_ptr<const retro_at_incidence> at_incidence(const glm::dvec3& wi) const;
  // Density per steradian of sample's outgoing direction wo (absorbed samples included, so it
  // integrates to at most 1 over wo.z > 0); empty for a model without one (a delta, or no
  // closed form).
  virtual std::optional<double> pdf(const glm::dvec3& wi, const glm::dvec3& wo) const;
  // Throughput per steradian towards wo: the weight times pdf. Empty where pdf is.
  virtual std::optional<double> eval(const glm::dvec3& wi, const glm::dvec3& wo) const;
};

// Sends light exactly back where it came from (wo = wi), no shift, weight mu.
class ideal_retro final : public retro_model {
 public:
  explicit ideal_retro(double mu) : mu_(mu) {}
  retro_sample sample(const glm::dvec3& wi, retro_samples) const override {
    if (wi.z <= 0) return {};
    return {wi, {0, 0}, mu_};
  }

 private:
  double mu_;
};

// What building a model may need beyond its values: where its files (presets, tables) resolve,
// and the incidence angle of its sheet's chief ray (for parameters looked up once per render).
struct model_setting {
  std::string base_dir;
  double chief_incidence_deg = 0;
};

// A model as the scene file knows it: its name, its parameters and how to build it. A new model
// adds one of these in its own file and registers it in retro_model.cpp.
struct retro_model_kind {
  std::string name;
  std::string help;
  model_fields fields;
  // Errors name values.where().
  std::function<std::unique_ptr<retro_model>(const model_values& values, const model_setting& setting)> make;
  // What an unset optional number stands for at incidence angle theta (shown beside it), if known.
  std::function<std::optional<double>(const model_values& values, const std::string& key, const std::string& base_dir,
                                      double theta_deg)>
      derived;
};

const std::vector<const retro_model_kind*>& retro_model_kinds();
// Throws input_error "<where>.type: unknown model '...' (ideal, ...)".
const retro_model_kind& find_retro_model_kind(const std::string& name, const std::string& where = "model");

// The parameters with another type: values the new model shares keep, the others go.
retro_model_params with_model_type(const retro_model_params& p, const std::string& type);
// Sets one value through the model's field table (see set_model_value).
void set_model_value(retro_model_params& p, const std::string& key, std::optional<param_value> value);
// Reads values through the model's field table (defaults for absent keys).
model_values read_model_values(const retro_model_params& p, const std::string& where = "model");

const retro_model_kind& ideal_retro_kind();

// Builds a model from its parameters; errors name `where`, e.g. "retroreflectors[0].model".
// A scene's sheets are built with make_sheet_model (sheet_models.hpp), which knows their setting.
std::unique_ptr<retro_model> make_retro_model(const retro_model_params& p, const model_setting& setting = {},
                                              const std::string& where = "retroreflectors[0].model");

}  // namespace airr
