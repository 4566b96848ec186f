#pragma once
// The noise-free model image (spec section 8) and its use as the tracer's control variate.
//
// Where no aperture cuts the light, one sheet's share of the aerial image is the mirrored display
// seen through that sheet's PSF at the incidence angle of each image point (layout_model_image.hpp
// adds the sheets up). The PSF is sampled at a few
// incidence angles across the image (angle bins) as offsets on the display's texel grid (the pixel's
// own extent included), the display's radiance is convolved with each, and every pixel mixes the
// two bins around its own angle.
//
// The same definition predicts single tracer samples: given a sample's pixel jitter and its first
// retroreflection's random numbers, where the model sends it on the display and what it sees there.
// Averaged over the samples, the prediction is the model image (up to the PSF's own sampling, drawn
// from the scene's seed), so the tracer estimates only the difference between each true path and
// its prediction, which is small wherever the model holds.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "airr/formats/image.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct model_image_params {
  int angle_bins = 8;                  // PSFs across the image's range of incidence angles
  std::uint64_t psf_samples = 200000;  // per bin
  // Where the fine grid's nodes put the display's edges (an even texel_refine), a prediction steps
  // at the edge as the display does; the image's share of that step is summed over the first this
  // many of a bin's samples, at most psf_samples (its cost grows with them, its error is theirs).
  std::uint64_t edge_samples = 16384;
  int max_texels = 512;          // the display's texels, on its longer side
  int texel_refine = 4;          // fine grid nodes per texel and direction
  double core_radius_mm = 8;     // offsets up to this go to the fine grid ...
  int tail_texels = 256;         // ... the rest to a coarse grid this size (longer side)
  double kernel_radius_mm = 64;  // ... up to this; farther ones are left out (of both uses)
  // Ideal paths traced on every n-th pixel and interpolated between where all four neighbours
  // have one (1: every pixel); the path from a pixel to the display is smooth (projective).
  int path_stride = 1;
  // The stride is lowered so that an image keeps at least this many paths a side (0: none).
  int least_paths = 0;
  int threads = 0;  // 0: all cores; 1: the calling thread alone
  // Run on threads of its own at the caller's priority, not the shared pool's (row_workers): the
  // designer's model images beside a render whose pool threads are lowered.
  bool own_threads = false;
  // Keep every bin's correlated grids, so that the image can be moved to other placements of its
  // layout (remap_model_image); they take the display's texels times 12 bytes per bin and channel.
  bool keep_correlations = false;
  // Keep each pixel's ideal path (model_pixel, 36 bytes a pixel) beside the image. Without them
  // (path_stride 1 only), the image is made holding the pixels' angles alone (4 bytes a pixel) and
  // tracing a pixel's path anew for each of its two bins, and model_pixel_at traces it anew, to the
  // same numbers: a render that predicts its samples once per pixel at its end (predict_pixel)
  // saves that memory (a 4096 x 4096 render's peak without components: 30 bytes a pixel, not 53).
  bool keep_pixels = true;
  // Add the display seen directly and in the half mirror (display_parts_image.hpp), from this many
  // points per pixel side: images the designer is shown. 0: the aerial image alone, as a control
  // variate needs (its predictions are of the aerial image).
  int display_samples = 0;

  // The tracer's control variate for an image of this size. `quick`, or below 256 x 256 pixels:
  // the fine grid is twice the texels and reaches 4 mm, its edges' share from 2048 samples (a
  // third of the time; RF-AN's variance per sample 1.6 times as high), since the finer grid's
  // fixed cost (about 3 s more on two cores) would outweigh the variance it saves over a small
  // image's samples, or delay an interactive session's first traced image after every edit.
  // Otherwise 16 angle bins: a pixel's prediction mixes its two bins' landings, and with 8 the
  // default scene's variance per sample at 512 x 512 was 1.8 times as high, for about 1 s less;
  // the edges' share from 16384 samples at 512 x 512, fewer in proportion above (2048 at least).
  // Either way 65536 samples a bin: at 512 x 512 the image of one seed differs from another's by
  // 0.10% RMS of the mean (RF-AN; 0.07% with 200000), and a 16 spp render's noise is the same.
  static model_image_params for_image(int width, int height, bool quick = false);

  // The designer's first look after an edit: a few milliseconds on one thread, coarser (texels of
  // the display at most 128 on its longer side, two bins, fewer PSF samples).
  static model_image_params first_look();

  // The model image the designer is shown after the first look, until traced samples replace it:
  // as close to the tracer's converged image as the control variate's (airr bench --model-error),
  // in about a tenth of its time. Its fine grid is the display's own texels and each bin has 32768
  // samples; a control variate needs finer nodes (the predictions' texel-sized blur would double
  // the tracer's noise), so this one is shown, never subtracted. It keeps its correlations.
  static model_image_params for_view();
};

// The display's radiance on one grid, with a black margin as wide as the grid's kernel reaches.
struct model_grid {
  image_rgb padded;
  // padded's one channel when the display is grey (R = G = B at every node), else empty: what a
  // prediction reads, in a third of the memory.
  std::vector<float> grey;
  double node_w = 0, node_h = 0;  // mm between nodes
  int radius = 0;                 // the kernel's reach, in nodes
  // The display's edges lie on node lines (an even refine), so that a prediction can step to black
  // at the edge as the tracer's display does, not ramp over a node (model_image_edges.cpp).
  bool edges_on_nodes = false;
};

// The two grids: near the ideal point the fine one, which follows the display's texels exactly;
// the PSF's tail on a coarse one, so that its wide kernel stays cheap.
inline constexpr int model_fine = 0, model_tail = 1;

// One angle bin: the model's PSF at the incidence angle of one representative pixel.
struct model_bin {
  glm::dvec2 pixel{0};  // the representative pixel's centre
  double theta_deg = 0;
  psf_chief_ray chief;
  std::shared_ptr<const retro_at_incidence> sampler;  // the model at the chief ray's incidence
  glm::dmat2 jitter_mm{0.0};  // display-plane offset (u, v) per unit of pixel jitter (columns: x, y)
};

// A pixel's ideal path: camera -> half mirror -> the sheet -> straight back -> display. Single
// precision, as its image is (36 bytes a pixel, held for as long as the model image is).
struct model_pixel {
  glm::vec2 node[2]{};  // where it lands, in each padded grid's node coordinates
  float profile = 1;    // the display's relative luminance towards the half mirror
  float theta_deg = 0;  // incidence on the sheet
  float mix = 0;        // between bins `bin` and `bin + 1`, the latter with weight `mix`
  int bin = 0;
  bool ok = false;  // false: the ideal path misses a part; the model predicts nothing here
};

// The bins' correlated grids and the grids' mappings (kept with keep_correlations).
struct model_correlations;

// The display on the two grids, where display points fall on them, and their spectra: the same for
// every sheet of a layout, so computed once per layout (compute_display_grids) and shared by every
// sheet's model image.
struct display_grids;

// What model_pixel_at needs to trace a pixel's ideal path anew (kept without keep_pixels).
struct model_pixel_recipe;

struct model_image {
  image_rgb image;                                   // the model image itself
  std::vector<model_pixel> pixels;                   // empty without keep_pixels ...
  std::shared_ptr<const model_pixel_recipe> recipe;  // ... which keeps this instead
  std::vector<model_bin> bins;
  const model_grid* grids = nullptr;                       // the display's two grids, held by `display`
  std::shared_ptr<const display_grids> display;            // shared with the layout's other sheets
  double hm_factor = 0;                                    // R x T of the half mirror, once each way
  std::shared_ptr<const model_correlations> correlations;  // null unless kept
  std::shared_ptr<const retro_model> model;
  std::size_t sheet = 0;     // the scene's sheet this is the share of
  double seconds = 0;        // to compute
  double paths_seconds = 0;  // of which: the pixels' ideal paths (and, before them, the display's grids)
  // Where the rest went (airr bench --model-image): the bins' chief rays, the grids' spectra, the
  // bins' samples (sampled together, bin_landings), and the per-bin loop (wall times); within the
  // loop, summed over the bins that run side by side, each bin's kernels from its samples,
  // correlating the grids with them, and gathering the pixels.
  double bins_seconds = 0, spectra_seconds = 0, landings_seconds = 0, loop_seconds = 0;
  double kernels_seconds = 0, correlate_seconds = 0, gather_seconds = 0;
};

// Pixel (px, py)'s ideal path on the grids and its bins: kept, or traced anew (keep_pixels).
model_pixel model_pixel_at(const model_image& m, int px, int py);

// Throws input_error when a parameter is out of range.
void check_model_image_params(const model_image_params& p);

// The display's grids and their spectra for a layout's model images (`display` is the display's
// texture, null: uniform; the display white's radiance (white_radiance) is applied here). Null when `cancel` is set
// while it runs. Throws input_error for parameters out of range.
std::shared_ptr<const display_grids> compute_display_grids(const scene& s, const image_rgb* display,
                                                           const model_image_params& p = {},
                                                           const std::atomic<bool>* cancel = nullptr);

// Sheet `sheet`'s model image (`model` is that sheet's). Null when no pixel has an ideal path to
// the sheet (or there is no such sheet), or when `cancel` is set while it runs. `display` is the
// display's texture (null: uniform); the display white's radiance (white_radiance) is applied here. `grids`, when
// given, are the layout's (compute_display_grids with the same scene, display and `p`); else they are computed. Throws
// input_error for parameters out of range, or when a bin's chief ray grazes a part's edge.
std::shared_ptr<model_image> compute_model_image(const scene& s, std::shared_ptr<const retro_model> model,
                                                 const image_rgb* display, const model_image_params& p = {},
                                                 const std::atomic<bool>* cancel = nullptr, std::size_t sheet = 0,
                                                 std::shared_ptr<const display_grids> grids = nullptr);

// Sheet `sheet`'s model image `from`, moved to `s`, a placement of the layout it was computed for
// (differ_in_placement_alone): the pixels' ideal paths are traced anew (`p`'s path stride and
// threads) and read the same bins' correlated grids at their new landing points and angles. For a
// small move (a drag's step), this is the new placement's model image up to the PSFs' change with
// it. Empty when `from` kept no correlations, when cancelled, or when the move took a pixel's angle
// beyond the bins, or changed a bin's angle by more than 1 deg, its path from the sheet to the
// display by more than 2% or its pixel's footprint on the display by more than 10%.
// `limits` are those of a move; farther moves are refused.
struct remap_limits {
  double bin_shift_deg = 1.0, distance_change = 0.02, footprint_change = 0.1;
  // A pixel's angle may lie beyond the bins by this share of their spacing (and as many degrees).
  double beyond_bins = 0.5;
  // Six times as far: what a first look may still move when no closer view image is done (a drag
  // faster than view images are made, as on a loaded machine), rather than fall back to the coarse
  // first look (at 256 x 256, tilt 10: moved 6 deg, 1.4% from the moved layout's own view image;
  // the coarse look 10%). Beyond the bins as far as a bin's own pixel may move: the bins span
  // the angles of the pixels near the display alone, so their spacing is small.
  static remap_limits lenient() { return {6.0, 0.12, 0.6, 6.0}; }
};
image_rgb remap_model_image(const model_image& from, const scene& s, const model_image_params& p,
                            const std::atomic<bool>* cancel = nullptr, const remap_limits& limits = {});

// The pixel jitters and first-retroreflection samples the bins' kernels are made of (a rotated R6
// sequence, as the tracer's pixels use): every bin's kernels are samples 0 .. psf_samples - 1 of
// the same numbers, so that the bins sample them together.
class kernel_sequence {
 public:
  explicit kernel_sequence(std::uint64_t seed);
  void at(std::uint64_t i, glm::dvec2& jitter, retro_samples& u) const;

 private:
  std::array<double, 6> rotation_{};
  std::uint64_t seed_;
};

// The model's prediction for one tracer sample of pixel (px, py), from its pixel jitter in
// [0, 1)^2 and its first retroreflection's samples: the same numbers sent through both of the
// pixel's bins, mixed with the pixel's weights (closer to the true path, at the pixel's own angle,
// than either bin alone).
glm::vec3 model_prediction(const model_image& m, int px, int py, const glm::dvec2& jitter, const retro_samples& u);
// The same for a pixel whose model_pixel_at is `p`.
glm::vec3 model_prediction(const model_image& m, const model_pixel& p, const glm::dvec2& jitter,
                           const retro_samples& u);

}  // namespace airr
