#pragma once
// The display seen directly and in the half mirror (spec section 8's direct and reflection
// components) as the designer's model images show them beside the aerial image: projections of
// the display through the planar parts, times the half mirror's transmittance or reflectance, the
// emission profile, the bezel black. Each pixel is the mean over a stratified set of points in the
// pixel and on the lens, followed as the tracer's paths go (the sheets block, the half mirror
// passes and reflects once) about one a texel, on the display's texels (area-averaged where a pixel
// would span more than it takes points); where a thin lens spreads them farther than a few of their
// spacings, low-discrepancy points over the footprint widened by the blur; docs/model-image.md.
// Props are not met, and a scene that polarizes has none (its half mirror's light depends on the
// state).
#include <atomic>
#include <vector>

#include "airr/formats/image.hpp"
#include "airr/layout/scene.hpp"
#include "airr/render/model_image.hpp"

namespace airr {

// The display's radiance area-averaged to about an (8 samples_per_side)-th of the smallest
// footprint a pixel of the observer has on it, directly or in the half mirror (the texture's own
// texels when they are coarser; `display` null: uniform), and again at each half the resolution
// down to 2 texels: a pixel reads the level as fine as its points are dense. Empty when the scene
// polarizes or no pixel sees the display either way.
std::vector<image_rgb> display_parts_texels(const scene& s, const image_rgb* display, int samples_per_side);

// Each pixel's light of the display seen directly and in the half mirror, the mean over at least
// p.display_samples squared points in the pixel and on the lens; `texels` from
// display_parts_texels (for this scene, or one differing in placement alone). Empty when `texels`
// is, or `cancel` was set.
image_rgb display_parts_image(const scene& s, const std::vector<image_rgb>& texels, const model_image_params& p,
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace airr
