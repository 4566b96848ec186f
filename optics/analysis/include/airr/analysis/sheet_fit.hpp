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
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/optics/preset.hpp"
#include "airr/optics/psf.hpp"

namespace airr::analysis {

struct fit_params {
  // Enough for a within 5% on RF-Ay, whose blur at small tilts is mostly the corner shift so that
  // a hangs on c ten times over (with 20000 samples a is off by up to 14% there).
  std::uint64_t psf_samples = 200000;
  std::uint64_t seed = 1;
  int frequencies = 50;                 // compared on f_max * i / n, i = 1..n, f_max = min(1 lp/mm, the curve's end)
  double a_min_per_mm = 0.05;           // the a search bracket
  double a_max_per_mm = 100.0;
  int a_scan_points = 13;               // log-spaced scan over the bracket before Brent
  double a_tolerance = 2e-4;            // relative, Brent's stopping width
  double c_max_mm = 5.0;                // the c search bracket is [0, c_max]
  double c_tolerance_mm = 1e-4;         // the root finder's final bracket width
  double alternation_tolerance = 0.005; // converged: the final c bracket is narrower than this x c
};

struct fit_progress {
  std::string stage;
  double fraction = 0;
  double eta_seconds = 0;
};

struct fit_result {
  sheet_preset preset;   // provenance: data dir, files, setup scene, settings and the report
  nlohmann::json report; // per fitted value: its loss, evaluations and inputs
};

// Thrown by fit_sheet when its progress callback returns false; nothing partial is returned.
struct fit_cancelled : std::runtime_error {
  fit_cancelled() : std::runtime_error("fit cancelled") {}
};

using fit_progress_callback = std::function<bool(const fit_progress&)>;

// `progress` may be empty. Throws input_error for data the model cannot simulate, fit_cancelled.
fit_result fit_sheet(const fit_data& data, const fit_params& p, const fit_progress_callback& progress);

// The scene a measurement is simulated in: the setup at `tilt_deg` and `floating_distance_mm`
// with the sinc-shift model set to scalar a, c, mu (the setup's shift table and R are kept).
scene fit_scene(const scene& setup, double tilt_deg, double floating_distance_mm, double a_per_mm, double c_mm, double mu);

// psf_mtf as a measurement would report it: along its axis (y for a near-horizontal edge), with
// its Hamming window on the LSF (half-width in mm, centred on the windowed centroid; 0: none) and
// the pixel aperture of `params`.
psf_mtf_curve measured_like_mtf(const psf_samples& psf, const psf_mtf_params& params, double window_half_width_mm,
                                bool along_y);

// The image of a white square (width x height mm, centred on the source) shown at the source's
// intensity, through the PSF, as s's camera sees it: CV_64FC1, camera size, radiance units.
cv::Mat white_square_image(const scene& s, const psf_samples& psf, double width_mm, double height_mm);

}  // namespace airr::analysis
