#pragma once
// The viewing zone's full pass (spec section 8): for every eye of a grid, besides the geometric
// visible fraction, what the eye sees of the aerial image through the full model: its mean
// brightness (relative to the best eye), the mean MTF over (0, 1] lp/mm of the model PSF at that
// geometry, and the stray-light ratio, the display seen directly, the aerial image's luminance and
// its contrast against the rest (contrast.hpp), from a small render split into components, and the
// smallest legible character from both. Props block and scatter as everywhere.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/layout/legibility.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/measure/contrast.hpp"

namespace airr {

struct full_zone_params {
  int rows_per_eye = 64;             // the geometric pass's rows
  int render_size = 48;              // pixels per side of each eye's render of the aerial image
  std::uint64_t render_spp = 16;     // its samples per pixel
  std::uint64_t psf_samples = 4000;  // for the mean MTF
  std::vector<double> contrast_thresholds = default_contrast_thresholds;
  legibility_criterion legibility{};  // for the smallest legible character
};

struct full_zone_map {
  eye_grid grid;
  // ny rows of nx each; NaN where nothing of the aerial image is seen (and, for the MTF, where the
  // eye's chief ray through the aerial image's centre misses a part).
  std::vector<double> visible, brightness, mean_mtf, stray_ratio;
  // The display seen directly: the mean luminance of that component inside the aerial image's
  // outline, over the display's own face-on luminance (0 where it is hidden; NaN for a black display).
  std::vector<double> direct;
  // The aerial image's mean luminance inside its outline (the image's units: cd/m2 when the
  // display's luminance is given; 0 where none is seen), the contrast of the mean luminances (1
  // where none is seen), and for each of the params' contrast thresholds the share of the
  // outline's pixels whose contrast reaches it.
  std::vector<double> luminance, contrast;
  std::vector<double> thresholds;
  std::vector<std::vector<double>> contrast_share;
  // The smallest legible character on the aerial image from each eye, in mm and in arcmin
  // (legibility.hpp, with the eye's contrast; infinite where the contrast leaves too little, NaN
  // where nothing of the aerial image is seen).
  std::vector<double> char_height_mm, char_arcmin;
  double seconds = 0;
};

// The contrast map as a heatmap shows it: against a dark background the contrast is infinite, so
// the map tops out at its highest finite contrast or its highest threshold, whichever is more.
std::vector<double> contrast_shown(const full_zone_map& m, double& top);

// The legible share of the zone: the share of its eyes from which at least legible_image_share of
// the aerial image reaches threshold k's contrast.
double legible_share(const full_zone_map& m, std::size_t k);

// The stray-light ratio at `eye` (the observer there, looking at the aerial image's centre): in a
// small render (p's render size and samples), the light of every image component but the aerial
// image over the aerial image's own, inside the aerial image's outline; NaN when none of the
// aerial image's light is seen. The same number the full pass maps.
double stray_light_ratio(const scene& s, const glm::dvec3& eye, const full_zone_params& p = {});

// The light of the paths `expression` selects (docs/path-expressions.md) seen from `eye`, in the
// same small render: `ratio`, its mean luminance inside the aerial image's outline over the aerial
// image's (NaN when none of the aerial image's light is seen); `separation_arcmin`, the angle
// between its luminance centroid and the aerial image's over the whole render (NaN when either is
// dark). Throws input_error when the expression does not parse.
struct ghost_seen {
  double ratio = 0, separation_arcmin = 0;
};
ghost_seen ghost_from_eye(const scene& s, const glm::dvec3& eye, const std::string& expression,
                          const full_zone_params& p = {});

// All from one render: the stray-light ratio, each expression's ghost_seen, in their order, and the
// aerial image against the rest (its share_above for p's contrast thresholds).
struct eye_view_metrics {
  double stray_ratio = 0;
  std::vector<ghost_seen> ghosts;
  contrast_summary seen;
};
eye_view_metrics eye_view_from(const scene& s, const glm::dvec3& eye, const std::vector<std::string>& expressions,
                               const full_zone_params& p = {});

// Eyes run in parallel (each eye's render on one core; the maps do not depend on the number of
// cores), or as the items of `share` (an MPI job's ranks) when given; `progress(done, total)` after
// every eye this process measured, from one worker at a time. Empty maps when `cancel` was set
// (not heeded with `share`).
full_zone_map full_viewing_zone(const scene& s, const eye_grid& g, const full_zone_params& p = {},
                                const std::function<void(int, int)>& progress = {},
                                const std::atomic<bool>* cancel = nullptr, const item_share& share = {});

}  // namespace airr
