#pragma once
// What the sheet fit simulates a measurement as, from the model PSF alone: an MTF curve as the
// measurement saw it, and the image of a white square.
#include <opencv2/core.hpp>

#include "airr/analysis/psf_mtf.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"

namespace airr::analysis {

// psf_mtf as a measurement would report it: along its axis (y for a near-horizontal edge), with
// its Hamming window on the LSF (half-width in mm, centred on the windowed centroid; 0: none) and
// the pixel aperture of `params`.
psf_mtf_curve measured_like_mtf(const psf_samples& psf, const psf_mtf_params& params, double window_half_width_mm,
                                bool along_y);

// The image of a white square (width x height mm, centred on the source) shown at the source's
// intensity, through the PSF, as s's camera sees it: CV_64FC1, camera size, radiance units.
cv::Mat white_square_image(const scene& s, const psf_samples& psf, double width_mm, double height_mm);

}  // namespace airr::analysis
