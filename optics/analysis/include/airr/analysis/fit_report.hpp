#pragma once
// What a sheet fit (sheet_fit.hpp) reports: its settings, and per fitted value its loss,
// evaluations and inputs. `airr fit` prints it, the designer shows it, and to_json writes it into
// the fitted preset's provenance.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/analysis/minimise.hpp"

namespace airr::analysis {

// The fit's settings; the report keeps the ones it ran with.
struct fit_params {
  // Enough for a within 5% on RF-Ay, whose blur at small tilts is mostly the corner shift so that
  // a hangs on c ten times over (with 20000 samples a is off by up to 14% there).
  std::uint64_t psf_samples = 200000;
  std::uint64_t seed = 1;
  int frequencies = 50;        // compared on f_max * i / n, i = 1..n, f_max = min(1 lp/mm, the curve's end)
  double a_min_per_mm = 0.05;  // the a search bracket
  double a_max_per_mm = 100.0;
  int a_scan_points = 13;                // log-spaced scan over the bracket before Brent
  double a_tolerance = 2e-4;             // relative, Brent's stopping width
  double c_max_mm = 5.0;                 // the c search bracket is [0, c_max]
  double c_tolerance_mm = 1e-4;          // the root finder's final bracket width
  double alternation_tolerance = 0.005;  // converged: the final c bracket is narrower than this x c
  double shift_index = 1.0;              // of the simulated sheet (preset.hpp); 1: as the shipped presets
  // a per tilt matches the measured mean MTF over the compared frequencies (the squared difference
  // of the means is its loss) instead of the whole curve (the mean squared difference): for a
  // sheet whose curve the sinc-shift lobe cannot take the shape of (predicted presets).
  bool a_by_mean_mtf = false;
};

// A measured MTF curve as the fit compared with it.
struct fit_input {
  std::string file;
  std::string kind;  // "mtf_csv" or "edge_image"
  double tilt_deg = 0;
  double floating_distance_mm = 0;
  double pixel_mm = 0;
  double lsf_window_half_width_mm = 0;
  bool along_y = false;  // the axis the blur is measured along: y, else x
  double compared_up_to_lp_per_mm = 0;
  double measured_mean_mtf = 0;  // over the compared frequencies
};

// a at one tilt.
struct fit_a_entry {
  double tilt_deg = 0;
  double a_per_mm = 0;
  double loss = 0;  // MSE of the simulated against the measured MTF
  int evaluations = 0;
  double loss_at_a_minus_2_percent = 0;
  double loss_at_a_plus_2_percent = 0;
  bool minimum_checked = false;  // neither a (1 -+ 2%) has a lower loss
  bool at_bracket_end = false;   // a lies within 2 tolerances of a_min or a_max
  std::optional<std::string> note;
  fit_input input;
};

// One trial c of the root finder, with a(0) refitted there.
struct fit_c_trial {
  double c_mm = 0;
  double a0_per_mm = 0;
  double slope_simulated_per_mm = 0;
};

// Mean MTF at one floating distance, measured and simulated with the fitted a(0) and c.
struct fit_mean_mtf {
  double floating_distance_mm = 0;
  double measured_mean_mtf = 0;
  double simulated_mean_mtf = 0;
  fit_input input;
};

// c: the root of d_sim(c) = d_real, d the slope of mean MTF against floating distance.
struct fit_c_entry {
  double c_mm = 0;
  double loss = 0;  // (d_sim - d_real)^2
  double slope_measured_per_mm = 0;
  double slope_simulated_per_mm = 0;
  double a0_per_mm = 0;
  int trial_c_values = 0;
  root_bound bound = root_bound::none;  // lower, upper: the slope matches only beyond [0, c_max]
  std::array<double, 2> bracket_mm{};   // the root finder's final bracket
  std::array<double, 2> a0_at_bracket_ends_per_mm{};
  std::array<double, 2> slope_mismatch_at_bracket_ends_per_mm{};
  bool converged = false;  // the bracket is narrower than alternation_tolerance x c
  std::vector<fit_c_trial> history;
  std::vector<fit_mean_mtf> mean_mtf;
};

// mu at one tilt, from a white square's image.
struct fit_mu_entry {
  double tilt_deg = 0;
  double mu = 0;
  double loss = 0;          // mean squared residual per pixel
  double relative_rms = 0;  // its root over the mean measured luminance
  double unclamped_mu = 0;
  bool clamped = false;  // mu was clamped to [0, 1]
  int evaluations = 1;   // closed form: one simulation
  double brightness_at_mu_1 = 0;
  std::string image;
  double floating_distance_mm = 0;
  std::array<double, 2> square_mm{};  // width, height
};

struct fit_report {
  std::string data_dir;
  std::string fit_json;
  std::string setup_scene;
  std::vector<std::string> files;
  fit_params settings;
  std::vector<fit_a_entry> a;  // one per tilt, ascending
  fit_c_entry c;
  std::vector<fit_mu_entry> mu;  // one per white square; empty when mu is not fitted
  std::optional<std::string> mu_note;
  std::uint64_t simulations = 0;  // PSF simulations
  double seconds = 0;
};

// The report as the preset's provenance records it ("fit"), with the methods spelled out.
nlohmann::json to_json(const fit_report& r);

}  // namespace airr::analysis
