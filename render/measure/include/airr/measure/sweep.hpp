#pragma once
// Sweeps of the floating distance and the retroreflector tilt (one of them or the grid of both):
// at each point the mean MTF over (0, 1] lp/mm, MTF50 and the PSF's 50%-energy radius.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/core/number_range.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// "key=start:end:step"; key floating_distance (scene.floating_distance_mm) or tilt
// (retroreflector.tilt_deg).
struct sweep_axis {
  std::string key;
  number_range range;
};
inline constexpr int max_sweep_points = 200;

// Throws input_error with one line naming the bad part.
sweep_axis parse_sweep_axis(const std::string& text);
std::vector<double> sweep_values(const sweep_axis& a);

struct sweep_params {
  std::vector<sweep_axis> axes;  // one or two distinct keys; two make a grid
  bool psf_route = false;        // false: render an edge chart and measure it
  std::uint64_t spp = 64;        // edge route: samples per pixel
  std::string chart;             // edge route: chart image; empty: the shipped slanted_edge.png
  double roi_fraction = 0.6;     // edge route: central part of the source's image measured
  std::uint64_t psf_samples = 100000;
  int threads = 0;  // 0: all cores
};

struct sweep_point {
  double floating_distance_mm = 0;
  double tilt_deg = 0;
  double mean_mtf = 0;                    // over (0, 1] lp/mm, with the camera pixel's aperture
  std::optional<double> mtf50_lp_per_mm;  // empty when not reached
  double r50_mm = 0;                      // 50%-energy radius of the model PSF (optics alone)
  double brightness = 0;                  // the model PSF's, every sheet together
  std::vector<double> sheet_brightness;   // each sheet's share (0 where its chief ray misses it)
  // Why the layout is no layout at this point (parts meeting, the camera ray missing a part, ...);
  // empty for a measured point. A point with a reason has no numbers (NaN).
  std::string reason;
  bool valid() const { return reason.empty(); }
};

// Least-squares slope of mean MTF against D, per mm, at one tilt.
struct sweep_slope {
  double tilt_deg = 0;
  double per_mm = 0;
};

struct sweep_result {
  std::vector<sweep_point> points;  // floating distance varies fastest
  std::vector<sweep_slope> slopes;  // one per tilt when D takes more than one value
  double mm_per_pixel = 0;
};

using sweep_progress = std::function<void(double fraction, const std::string& detail)>;

// Measures every point: on this machine's cores, or as the items of `share` (an MPI job's ranks;
// progress then counts this process's points). A point whose layout is no layout (it fails the
// scene's checks, or a camera ray misses a part) keeps its reason and the sweep goes on; slopes
// are fitted to the valid points. Throws input_error naming the first point's reason when no
// point is valid.
sweep_result run_sweep(const scene& s, const sweep_params& p, const sweep_progress& progress = {},
                       const item_share& share = {});

// Header "floating_distance_mm,tilt_deg,mean_mtf_0_1,mtf50_lp_per_mm,r50_mm,brightness" and a
// brightness per sheet; an MTF50 that was not reached is an empty field. When a point is no layout,
// a last column "reason": empty for measured points, the reason (quoted) for the others, whose
// numbers are empty.
std::string sweep_csv(const sweep_result& r);

}  // namespace airr
