#pragma once
// The two ways of measuring the aerial image's MTF on one scene: the model PSF (no tracer) and a
// slanted-edge chart rendered by the tracer. Both measure along x, as a near-vertical edge does,
// and include the camera pixel's aperture.
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "airr/layout/legibility.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

struct mtf_summary {
  double mean_mtf = 0;                    // over (0, 1] lp/mm
  std::optional<double> mtf50_lp_per_mm;  // empty when the MTF stays above 0.5 where measured
  double mm_per_pixel = 0;                // the pixel whose aperture is included; 0: none
};

// The model PSF of every sheet of the scene at the aerial-image centre (seeded by the scene; see
// sample_psf); the second form takes the sheets' models already built for the scene.
psf_samples scene_psf(const scene& s, std::uint64_t samples);
psf_samples scene_psf(const scene& s, const retro_model_list& models, std::uint64_t samples);

// MTF of a sampled PSF times a square pixel's aperture (pixel_mm = 0: the optics alone).
mtf_summary psf_route_mtf(const psf_samples& psf, double pixel_mm);

// The display's pixel pitch in mm (the coarser of its two axes; 0 for a uniform display).
double display_pixel_mm(const scene& s);
// The smallest legible character on the aerial image (spec section 11) seen from the scene's
// observer at `contrast`: the model PSF's MTF (the worse of x and y, searched to 20 lp/mm) and the
// display's pixels.
legible_character psf_legible_character(const scene& s, const psf_samples& psf, double contrast,
                                        const legibility_criterion& criterion);

// The scene with the source showing `chart_path` (an edge chart) instead of its image.
scene with_edge_chart(scene s, const std::string& chart_path);

// The pixels inside the aerial image of the source region [u0, u1] x [v0, v1] (fractions of its
// width and height, v down from the image's top), clipped to the frame; may be empty.
cv::Rect aerial_image_roi(const scene& s, double u0, double v0, double u1, double v1);

// The central `fraction` (per side) of the source's aerial image in camera pixels, clipped to
// the frame. Throws input_error when nothing of it is in view.
cv::Rect source_image_roi(const scene& s, double fraction);

// Rec.709 luminance of a render snapshot (CV_64FC1).
cv::Mat snapshot_luminance(const render_snapshot& snap);
// The same for another image of the snapshot's size (e.g. its even- or odd-sample half).
cv::Mat snapshot_luminance(const render_snapshot& snap, const std::vector<float>& rgb);

// Slanted-edge MTF of a render's Rec.709 luminance over source_image_roi(s, roi_fraction).
// Throws std::runtime_error when no usable edge is found.
mtf_summary edge_route_mtf(const scene& s, const render_snapshot& snap, double roi_fraction);

}  // namespace airr
