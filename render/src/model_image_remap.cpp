// A model image moved to another placement of its layout: the pixels' new paths read the same
// bins' correlated grids.
#include <algorithm>
#include <cmath>

#include "airr/core/error.hpp"
#include "airr/layout/psf.hpp"
#include "airr/render/model_image.hpp"
#include "airr/render/parallel_rows.hpp"
#include "model_image_steps.hpp"

namespace airr {

using namespace model_image_steps;

namespace {

double frobenius(const glm::dmat2& m) {
  return std::sqrt(m[0][0] * m[0][0] + m[0][1] * m[0][1] + m[1][0] * m[1][0] + m[1][1] * m[1][1]);
}

// Whether a bin's PSF still serves in the moved layout: its pixel's path there keeps its angle,
// its length from the sheet to the display and its footprint on the display.
bool bin_still_holds(const scene& s, const ideal_parts& parts, const model_bin& b, std::size_t sheet,
                     const remap_limits& limits) {
  const auto centre = trace_ideal(parts, b.pixel.x, b.pixel.y);
  if (!centre || std::abs(centre->theta_deg - b.theta_deg) > limits.bin_shift_deg) return false;
  psf_chief_ray chief;
  try {
    chief = chief_ray_through(s, centre->aerial, sheet);
  } catch (const input_error&) {
    return false;  // the chief ray now grazes a part's edge
  }
  if (std::abs(chief.rr_distance_mm - b.chief.rr_distance_mm) > limits.distance_change * b.chief.rr_distance_mm) {
    return false;
  }
  const glm::dmat2 jitter = pixel_footprint(parts, b.pixel.x, b.pixel.y);
  return frobenius(jitter - b.jitter_mm) <= limits.footprint_change * frobenius(b.jitter_mm);
}

}  // namespace

image_rgb remap_model_image(const model_image& from, const scene& s, const model_image_params& p,
                            const std::atomic<bool>* cancel, const remap_limits& limits) {
  check_model_image_params(p);
  const model_correlations* kept = from.correlations.get();
  if (!kept || from.bins.empty() || from.sheet >= s.retroreflectors.size()) return {};
  const ideal_parts parts(s, from.sheet);
  const int w = parts.cam.width, h = parts.cam.height;
  if (w != from.image.width || h != from.image.height) return {};
  for (const model_bin& b : from.bins) {
    if (!bin_still_holds(s, parts, b, from.sheet, limits)) return {};
  }
  const std::shared_ptr<const emission_profile> emission = scene_emission_profile(s);
  std::vector<model_pixel> pixels = pixel_paths(parts, emission.get(), p, kept->maps, from.grids[model_tail], cancel);
  if (pixels.empty()) return {};
  // Farther beyond the bins, a pixel's PSF would be a guess (beyond the fine grid, as in
  // compute_model_image, the end bins' tails serve).
  const double first = from.bins.front().theta_deg, last = from.bins.back().theta_deg;
  const double spacing = from.bins.size() > 1 ? (last - first) / double(from.bins.size() - 1) : 0.0;
  const double margin = limits.beyond_bins * std::max(1.0, spacing);
  for (const model_pixel& px : pixels) {
    if (lands_on_fine_grid(px, from.grids[model_fine]) &&
        (px.theta_deg < first - margin || px.theta_deg > last + margin)) {
      return {};
    }
  }
  image_rgb out;
  out.width = w;
  out.height = h;
  out.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  // The same arithmetic as compute_model_image's: the lower bin's share plus the upper one's.
  detail::parallel_rows(h, row_workers_of(p), [&](int y0, int y1) {
    for (std::size_t i = std::size_t(y0) * w; i < std::size_t(y1) * w; ++i) {
      model_pixel& px = pixels[i];
      if (!px.ok) continue;
      assign_bin(from.bins, px);
      const glm::vec3 lower = gather(kept->bins[std::size_t(px.bin)], px) * float((1 - px.mix) * px.profile);
      glm::vec3 upper(0.0f);
      if (std::size_t(px.bin) + 1 < from.bins.size()) {
        upper = gather(kept->bins[std::size_t(px.bin) + 1], px) * float(px.mix * px.profile);
      }
      for (int c = 0; c < 3; ++c) out.rgb[3 * i + std::size_t(c)] = lower[c] + upper[c];
    }
  });
  return out;
}

}  // namespace airr
