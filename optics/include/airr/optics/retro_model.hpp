#pragma once
// The retroreflector model interface. Directions are in the sheet's local frame (normal +z) and
// point away from the surface: wi towards where the light came from, wo where it leaves.
#include <array>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "airr/optics/scene.hpp"

namespace airr {

// Random numbers a model may consume for one interaction, all uniform in [0, 1).
struct retro_randoms {
  std::array<double, 16> u{};
};

struct retro_sample {
  glm::dvec3 wo{0, 0, 1};
  glm::dvec2 shift_mm{0, 0};  // exit point minus entry point, in the sheet plane (local x, y)
  double weight = 0;          // throughput; 0 means absorbed
};

class retro_model {
 public:
  virtual ~retro_model() = default;
  virtual retro_sample sample(const glm::dvec3& wi, const retro_randoms& r) const = 0;
};

// Sends light exactly back where it came from (wo = wi), no shift, weight mu.
class ideal_retro final : public retro_model {
 public:
  explicit ideal_retro(double mu) : mu_(mu) {}
  retro_sample sample(const glm::dvec3& wi, const retro_randoms&) const override {
    if (wi.z <= 0) return {};
    return {wi, {0, 0}, mu_};
  }

 private:
  double mu_;
};

// Builds the model a scene names; files (presets, shift tables) resolve against base_dir.
std::unique_ptr<retro_model> make_retro_model(const retro_model_params& p, const std::string& base_dir = "");

}  // namespace airr
