#pragma once
// Fitting the sinc-shift model's a (per tilt), c and mu (per tilt) to measurements (spec
// section 5), simulating with the model PSF alone: the PSF is exactly the model's blur, so a
// simulated MTF is the PSF's MTF as the measurement would see it (its axis, LSF window and pixel
// aperture), and a white square's image is the square convolved with the PSF times brightness.
//
// - a per tilt: minimise the MSE between simulated and measured MTF over (0, 1] lp/mm: a scan of
//   log a over [a_min, a_max] (first fit) or downhill steps from a neighbouring solution, then
//   Brent's minimiser; the minimum is checked by the loss at a (1 -+ 2%) not being lower.
// - c at tilt 0: the root of d_sim(c) = d_real, d the least-squares slope of mean MTF over (0, 1]
//   lp/mm against floating distance, by a bracketing root finder (Illinois) on [0, c_max] with
//   a(0) refitted at every trial c. That root is the fixed point that alternating "a(0) given c"
//   and "c given a(0)" seeks; plain alternation oscillates on RF-Ay. The report gives the final
//   bracket and a(0) at both its ends.
// - mu per tilt: closed form, the image is linear in mu: mu = <I_real, I_1> / <I_1, I_1>, clamped
//   to [0, 1]. Without white squares mu is not fitted: fit.json's "mu", else 1.
// Every simulation uses the same seed (common random numbers), so the losses are smooth in a and c.
// The minimisers are minimise.hpp's, the report's types fit_report.hpp's.
#include <functional>
#include <stdexcept>
#include <string>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/fit_report.hpp"
#include "airr/analysis/fit_simulation.hpp"  // what the fit simulates, for callers synthesising data
#include "airr/core/item_share.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/preset.hpp"

namespace airr::analysis {

struct fit_progress {
  std::string stage;
  double fraction = 0;
  double eta_seconds = 0;
};

struct fit_result {
  sheet_preset preset;  // provenance: data dir, files, setup scene, settings and to_json(report)
  fit_report report;    // per fitted value: its loss, evaluations and inputs
};

// Thrown by fit_sheet when its progress callback returns false; nothing partial is returned.
struct fit_cancelled : std::runtime_error {
  fit_cancelled() : std::runtime_error("fit cancelled") {}
};

using fit_progress_callback = std::function<bool(const fit_progress&)>;

// `progress` may be empty. Throws input_error for data the model cannot simulate, fit_cancelled.
// Simulations that do not wait on each other (the a scan, the distance series at each trial c, the
// checks around a minimum, the white squares) run as items through `share` (an MPI job's ranks);
// the minimisers' steps run in turn. The result is the same with or without it.
fit_result fit_sheet(const fit_data& data, const fit_params& p, const fit_progress_callback& progress,
                     const item_share& share = {});

// The scene a measurement is simulated in: the setup at `tilt_deg` (the first sheet's) and
// `floating_distance_mm` with every sheet's model set to the sinc-shift model of scalar a, c, mu:
// a device's sheets are cut from the one material being fitted, each reached by its own path (the
// setup's shift table, R and each sheet's angle lookup are kept). A shift_table (a file) stands for
// the sheet's own shift distributions.
scene fit_scene(const scene& setup, double tilt_deg, double floating_distance_mm, double a_per_mm, double c_mm,
                double mu, double shift_index = 1.0, const std::string& shift_table = "");

}  // namespace airr::analysis
