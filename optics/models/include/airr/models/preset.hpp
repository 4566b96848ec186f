#pragma once
// Fitted parameters of a real retroreflective sheet for the sinc-shift model: a and mu per
// incidence angle (or one value for all), corner size c and reference distance R.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/models/polarization.hpp"

namespace airr {

struct sheet_preset {
  std::string name;
  std::vector<double> theta_deg;  // tabulated incidence angles, ascending; empty: scalars
  std::vector<double> a_per_mm;   // one per angle, or a single value
  std::vector<double> mu;         // one per angle, or a single value
  double c_mm = 0.0;
  double reference_distance_mm = 300.0;
  // Refractive index in front of the cube corners: the shift distribution is the corner-cube
  // table's at the angle inside, asin(sin theta / n). 1 (every shipped preset): at theta itself.
  double shift_index = 1.0;
  // The sheet's own shift distributions (shift_table.hpp; a predicted preset's, traced from the
  // sheet's geometry), absolute once loaded; the file names it relative to itself. Empty: the
  // shipped corner cube's.
  std::string shift_table;
  // The sheet's Mueller matrix (retro_sample::polarization: relative to the weight) per tilt_deg entry,
  // or one for all; empty: the identity (the sheet keeps the field as a mirror facing the light).
  // A predicted preset's is the mean over the explicit sheet's retroreflected paths.
  std::vector<mueller> polarization;
  nlohmann::json provenance;  // where the values come from (a table, a fit with its inputs and losses)
};

// A name ("rf-ay") is looked up in assets/presets; anything with a '/' or ending in ".json" is a
// path, relative to base_dir. Throws input_error naming the file and the field. A preset's
// shift_table is resolved against the preset's folder (`origin`'s for preset_from_json);
// save_preset writes it beside the preset as <stem>_shifts.json (copying it there) and names it.
bool is_preset_path(const std::string& name_or_path);
std::string resolve_preset_path(const std::string& name_or_path, const std::string& base_dir);
sheet_preset load_preset(const std::string& name_or_path, const std::string& base_dir = "");
sheet_preset preset_from_json(const nlohmann::json& j, const std::string& origin);
nlohmann::json preset_to_json(const sheet_preset& p);
void save_preset(const sheet_preset& p, const std::string& path);

// Linear interpolation of values over ascending angles, clamped outside; one value is constant.
double interpolate_by_angle(const std::vector<double>& theta_deg, const std::vector<double>& values, double theta);
// The same for Mueller matrices, element by element (a mixture of the two neighbours' light).
mueller interpolate_by_angle(const std::vector<double>& theta_deg, const std::vector<mueller>& values, double theta);

}  // namespace airr
