#pragma once
// A preset predicted from a sheet's geometry (spec section 9): the explicit sheet model is
// measured on a simulated bench (fit_synthesis.hpp) and the sinc-shift parameters are fitted to
// those measurements with the sheet fit, so a sheet nobody has measured gets a preset the fast
// model uses. The agreement check compares the explicit model's mean MTF with the predicted
// preset's, as the fit's measurement sees both.
#include <string>
#include <vector>

#include "airr/analysis/fit_synthesis.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/analysis/sheet_shift_table.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/preset.hpp"

namespace airr::analysis {

struct prediction_params {
  // The bench's measurements. The LSF window is the measurement's region of interest: a prism
  // sheet's front-surface reflection lands centimetres away and is not part of its blur.
  synthesis_params synthesis{.samples = 1000000, .seed = 7, .lsf_window_mm = 5.0};
  fit_params fit;
  // The sheet's own shift distributions, traced from its geometry (sheet_shift_table.hpp), for a
  // sheet that names a cube edge; false: the shipped corner cube's table, read inside the plate.
  bool sheet_shifts = true;
  sheet_shift_params shifts;
};

// Synthesises the bench's measurements of `sheet` into data_dir (kept: fit.json, the curves and
// images), fits them and returns the preset, named after the sheet, its provenance naming the sheet.
// The preset's shift table is the sheet's own (traced into data_dir as shift_table.json; save_preset
// puts a copy beside the preset); without one a prism sheet's preset reads the shipped table at
// the angle inside its plate (shift_index: its index). The preset's polarization is the sheet's
// mean Mueller matrix at each tilt (sheet_shift_table.hpp), for a sheet that changes it.
// Progress runs over both stages; returning false cancels (fit_cancelled). Their independent
// simulations run as items through `share` (an MPI job's ranks) when given.
fit_result predict_preset(const sheet_description& sheet, const scene& bench, const std::string& data_dir,
                          const prediction_params& p, const fit_progress_callback& progress,
                          const item_share& share = {});

struct prediction_agreement {
  double tilt_deg = 0;
  double explicit_mean_mtf = 0;   // over (0, 1] lp/mm, as the bench measures it
  double predicted_mean_mtf = 0;  // the preset's sinc-shift model, the same way
  double explicit_brightness = 0;
  double predicted_brightness = 0;
};

// The explicit sheet and the preset side by side on the bench at D 150 mm, at each tilt.
std::vector<prediction_agreement> compare_prediction(const sheet_description& sheet, const sheet_preset& preset,
                                                     const scene& bench, const std::vector<double>& tilts_deg,
                                                     const synthesis_params& p, const item_share& share = {});
// The same for several presets, the explicit sheet measured once for all: [k] is presets[k]'s.
std::vector<std::vector<prediction_agreement>> compare_predictions(
    const sheet_description& sheet, const std::vector<sheet_preset>& presets, const scene& bench,
    const std::vector<double>& tilts_deg, const synthesis_params& p, const item_share& share = {});

}  // namespace airr::analysis
