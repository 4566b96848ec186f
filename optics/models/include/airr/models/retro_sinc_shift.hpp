#pragma once
// The sinc-shift retroreflector (the default model): a sinc^2 angular spread whose blur grows
// with the distance to the aerial image, an exit-point shift drawn from the corner-cube shift
// distribution for the ray's incidence angle, and weight mu; a and mu follow the incidence angle
// (or, with the "per_render" lookup, the incidence angle of the sheet's chief ray).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "airr/core/geometry.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/models/shift_table.hpp"

namespace airr {

// Concrete parameters: a(theta), mu(theta) over tabulated angles (or single values), c, R.
struct sinc_shift_params {
  std::vector<double> theta_deg;
  std::vector<double> a_per_mm{2.0};
  std::vector<double> mu{1.0};
  double c_mm = 0.0;
  double reference_distance_mm = 300.0;
  double shift_index = 1.0;           // the shift table is read at the angle inside this index (preset.hpp)
  std::string shift_table;            // resolved path: the scene's, else the preset's; empty: the shipped table
  std::vector<mueller> polarization;  // the preset's, over theta_deg (preset.hpp); empty: the identity
  // Lookup "per_render": a, mu and the shift distribution at this one angle (the sheet's chief
  // ray) for every ray; unset ("per_ray"): at each ray's own incidence angle.
  std::optional<double> lookup_angle_deg{};
};

// Combines an optional preset with the scene's overrides (a set value applies at every angle).
// Throws input_error when a needed value has no source.
sinc_shift_params resolve_sinc_shift_params(const model_values& v, const model_setting& setting);
sinc_shift_params resolve_sinc_shift_params(const retro_model_params& p, const model_setting& setting);

// The model's scene-file entry ("sinc_shift").
const retro_model_kind& sinc_shift_retro_kind();

class sinc_shift_retro final : public retro_model {
 public:
  // `shifts` may be null when c is 0.
  sinc_shift_retro(sinc_shift_params p, std::shared_ptr<const shift_table> shifts);
  // lobe: the deviation's table cell and its azimuth; shift: the shift's bin and direction;
  // more: the jitter inside the lobe cell, the choice between angle tables, the jitter in the bin.
  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override;
  // With the preset's Mueller matrix at the lookup angle (none without one).
  retro_sample sample_polarized(const glm::dvec3& wi, retro_samples u) const override;
  std::unique_ptr<const retro_at_incidence> at_incidence(const glm::dvec3& wi) const override;
  // The lobe's density about the retro direction; the shift does not change directions.
  std::optional<double> pdf(const glm::dvec3& wi, const glm::dvec3& wo) const override;
  std::optional<double> eval(const glm::dvec3& wi, const glm::dvec3& wo) const override;

  // At a ray's incidence angle, or at the lookup angle when there is one.
  double a_at(double theta_deg) const;
  double mu_at(double theta_deg) const;
  const sinc_shift_params& params() const { return p_; }

  // What a sample needs of its incidence: sample(wi, u) is sample(prepare(wi), u).
  struct incidence {
    bool lit = false;  // wi above the sheet
    basis frame;       // around wi
    double k = 0, mu = 0;
    shift_rows rows;
  };
  incidence prepare(const glm::dvec3& wi) const;
  retro_sample sample(const incidence& in, retro_samples u) const;

  // What a sample draws before it knows its incidence: sample(in, u) is sample(in, draw_of(u)),
  // and samples at several incidences from the same numbers share it (sample_at_each).
  struct draw {
    double k_tan_delta = 0;                    // k tan(delta): the deviation for every k
    double cos_phi = 1, sin_phi = 0;           // its azimuth
    double pick = 0, u_bin = 0, u_jitter = 0;  // the shift's table, bin and place in the bin
    double cos_psi = 1, sin_psi = 0;           // the shift's direction
  };
  // The shifts already drawn from table rows by one draw, for its other incidences.
  struct row_shifts {
    std::size_t count = 0;
    std::array<std::pair<std::size_t, double>, 4> known{};
  };
  draw draw_of(retro_samples u) const;
  retro_sample sample(const incidence& in, const draw& d, row_shifts& rows) const;

 private:
  sinc_shift_params p_;
  std::shared_ptr<const shift_table> shifts_;
};

}  // namespace airr
