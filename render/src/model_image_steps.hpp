#pragma once
// The steps of computing a model image (model_image.cpp): the pixels' ideal paths
// (model_image_paths.cpp), the display's grids and their correlation with a kernel
// (model_image_grids.cpp), and the bins' kernels from the model's samples (model_image_samples.cpp).
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "airr/render/model_image.hpp"
#include "airr/render/parallel_rows.hpp"
#include "real_fft.hpp"

namespace airr::model_image_steps {

// The parts an ideal path to one sheet meets, built once per image.
struct ideal_parts {
  part_frame hm, rr, src, aerial;
  pinhole_camera cam;
  bool by_reflection;  // the sheet is reached by reflection in the half mirror
  ideal_parts(const scene& s, std::size_t sheet)
      : hm(half_mirror_frame(s)),
        rr(retroreflector_frame(s, sheet)),
        src(source_frame(s)),
        aerial(aerial_image_frame(s)),
        cam(make_camera(s)),
        by_reflection(sheet_seen_by_reflection(s, sheet)) {}
};

struct ideal_path {
  glm::dvec2 display{0};  // display-local mm
  glm::dvec3 aerial{0};   // where the camera ray crosses the aerial-image plane
  glm::dvec3 towards_display{0};
  glm::dvec3 wi{0, 0, 1};  // incidence on the sheet, sheet-local
  double theta_deg = 0;
};

std::optional<ideal_path> trace_ideal(const ideal_parts& parts, double px, double py);

// The display-plane offset (u, v) per unit of pixel jitter at pixel point (px, py) (columns: x, y),
// from the ideal paths half a pixel either side (one side and the pixel's own where the other
// misses); zero where neither side has a path.
glm::dmat2 pixel_footprint(const ideal_parts& parts, double px, double py);

// What a pixel needs of its ideal path.
struct pixel_path {
  bool ok = false;
  glm::dvec2 display{0};   // display-local mm
  glm::dvec3 wi{0, 0, 1};  // incidence on the sheet (its polar angle is not smooth at 0: not interpolated)
  double profile = 1;      // the display's relative luminance towards the half mirror
};

// The display's radiance on a grid of at most max_texels on its longer side (area-averaged down
// from the texture; uniform: a grid of that size).
cv::Mat display_texels(const scene& s, const image_rgb* display, int max_texels);

// A padded grid's spectrum, computed once and correlated with every bin's kernel. The grid's
// margins are black and as wide as the kernels reach, so a DFT the grid's own size suffices:
// what wraps around lands on black.
struct grid_spectrum {
  int width = 0, height = 0;          // the padded grid's
  int fft_width = 0, fft_height = 0;  // the transform's (the grid zero-padded to sizes of small factors)
  std::vector<fft_buffer<std::complex<float>>> channels;  // per distinct channel (one for a grey display)
};

// Empty (no channels) when `cancel` is set before it is done: it is checked between channels.
grid_spectrum spectrum_of(const image_rgb& padded, const std::atomic<bool>* cancel = nullptr);

// out(x) = sum over offsets o of kernel(o) grid(x + o), the kernel's centre at offset 0 (the
// prediction's sum, for every node at once); one matrix per distinct channel, as the spectrum.
struct correlated_grid {
  std::vector<fft_buffer<float>> channels;  // rows of `stride` values, the first `cols` of `rows` rows used
  int cols = 0, rows = 0, stride = 0;
  glm::vec3 at(const glm::dvec2& t) const {
    const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= cols || y0 + 1 >= rows) return glm::vec3(0.0f);
    const float fx = float(t.x - x0), fy = float(t.y - y0);
    glm::vec3 v(0.0f);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const float* r0 = channels[c].data.get() + std::size_t(y0) * stride;
      const float* r1 = r0 + stride;
      v[int(c)] = (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
    }
    return channels.size() == 1 ? glm::vec3(v[0]) : v;
  }
};

// What one worker's correlations of one grid reuse from bin to bin: fresh buffers of a grid's size
// cost their pages' faults and zeroing. A bin's correlated grid given back lends its buffers to the
// next.
struct correlate_scratch {
  fft_buffer<float> rows;
  fft_buffer<std::complex<float>> kernel_spectrum, product;
  std::vector<fft_buffer<float>> spare_values;
  void take_back(correlated_grid&& done);
};

// Empty (no channels) when `cancel` is set before it is done: it is checked between channels.
correlated_grid correlate(const grid_spectrum& grid, const cv::Mat& kernel, correlate_scratch& scratch,
                          const std::atomic<bool>* cancel = nullptr);

// One grid over the display's texels (`refine` nodes per texel) and where display-local points
// fall on it.
struct grid_mapping {
  double cols = 1, rows = 1, width = 1, height = 1, origin = 0, refine = 1, radius = 0;
  glm::dvec2 node(const glm::dvec2& local) const {
    const glm::dvec2 texel((local.x / width + 0.5) * cols - 0.5, (0.5 - local.y / height) * rows - 0.5);
    return (texel - origin) * refine + radius;
  }
};

// Pixel (x, y)'s ideal path on the grids, as pixel_paths finds it at path stride 1 (before its bins).
model_pixel pixel_path_at(const ideal_parts& parts, const emission_profile* emission, const grid_mapping (&maps)[2],
                          const model_grid& tail, int x, int y);

// Every pixel's ideal path, mapped onto the display's grids as it is traced: where it lands, its
// angle and profile (not yet its bins); a pixel landing beyond the tail's padded grid is not ok.
// Empty when cancelled. With a stride, paths are traced on a lattice of pixels and interpolated
// inside each cell whose four corners all have one; other cells are traced pixel by pixel. (The
// paths themselves are not kept: at 56 bytes a pixel they made a large render's peak.)
std::vector<model_pixel> pixel_paths(const ideal_parts& parts, const emission_profile* emission,
                                     const model_image_params& p, const grid_mapping (&maps)[2], const model_grid& tail,
                                     const std::atomic<bool>* cancel);

// Whether a pixel's ideal point lands on the fine grid: on the display or within the core's reach
// of it, where the model's light is more than the PSF's tail. The bins' angles are chosen among
// these pixels (the region of paths reaches far beyond the display, where the image is dark).
inline bool lands_on_fine_grid(const model_pixel& px, const model_grid& fine) {
  const glm::vec2 t = px.node[model_fine];
  return px.ok && t.x >= 0 && t.y >= 0 && t.x < float(fine.padded.width - 1) && t.y < float(fine.padded.height - 1);
}

// Every pixel's angle of incidence on the sheet alone (path stride 1; NaN where pixel_paths' pixel is
// not ok) and whether it lands on the fine grid: 5 bytes a pixel where the paths take 36, for a
// model image that does not keep them.
struct pixel_angle_map {
  std::vector<float> theta_deg;
  std::vector<char> on_fine_grid;  // bytes: rows written in parallel would share a bit vector's words
};
pixel_angle_map pixel_angles(const ideal_parts& parts, const emission_profile* emission, const model_image_params& p,
                             const grid_mapping (&maps)[2], const model_grid& fine, const model_grid& tail,
                             const std::atomic<bool>* cancel);

// `grid` is left without its padded nodes when `cancel` is set while they are made.
grid_mapping make_grid(model_grid& grid, const cv::Mat& texels, int refine, double reach_mm, const part_frame& src,
                       const std::atomic<bool>* cancel = nullptr);

// The two bins around the pixel's angle (bin angles ascend) and its weight on the upper one.
void assign_bin(const std::vector<model_bin>& bins, model_pixel& px);

// One bin's correlated grids, read at a pixel's nodes.
inline glm::vec3 gather(const std::array<correlated_grid, 2>& bin, const model_pixel& px) {
  glm::vec3 v(0.0f);
  for (int g : {model_fine, model_tail}) v += bin[g].at(px.node[g]);
  return v;
}

// A bin sample that landed on the fine grid: its offset in nodes from the pixel's ideal point, and
// its weight.
struct fine_sample {
  glm::dvec2 t;
  double w;
};

// Where one bin sample lands: the grid (-1: absorbed, off the half mirror or beyond the kernels)
// and its offset in that grid's nodes from the pixel's ideal point (its jitter included), and its
// throughput.
struct bin_landing {
  glm::dvec2 nodes{0.0};
  double w = 0;
  int grid = -1;
};

// Every bin's samples: the same numbers (kernel_sequence) sent through each bin, sampled together
// (sample_at_each), so that a model works out once what does not depend on the incidence.
// landings[k][i] is bin k's sample i; empty when `cancel` is set.
std::vector<std::vector<bin_landing>> bin_landings(const model_image& m, std::uint64_t samples, std::uint64_t seed,
                                                   detail::row_workers threads, const std::atomic<bool>* cancel);

// The bin's kernels from its samples' landings; blocks run in parallel and are summed in order, so
// the result does not depend on the number of threads. `fine`, when given, receives those of the
// first `fine_count` samples that landed on the fine grid, in order (for the display's edges).
std::array<cv::Mat, 2> bin_kernels(const model_image& m, const std::vector<bin_landing>& landed,
                                   detail::row_workers threads, const std::atomic<bool>* cancel,
                                   std::vector<fine_sample>* fine = nullptr, std::uint64_t fine_count = 0);

// The grid's bilinear surface at node point `t` (black beyond the grid).
glm::vec3 bilinear(const image_rgb& m, const glm::dvec2& t);

// The grid's bilinear surface at `base` plus the offset `t`, spread over the four nodes around it
// as the kernels are: four bilinear reads, which together are one 3 x 3 stencil of nodes.
glm::vec3 spread_bilinear(const image_rgb& grid, const glm::dvec2& base, const glm::dvec2& t);
// The same on a grid's nodes, from its one channel when the display is grey.
glm::vec3 spread_bilinear(const model_grid& grid, const glm::dvec2& base, const glm::dvec2& t);

// What a prediction reads on a grid for the offset `t` from `base`: spread_bilinear, except where
// the offset's cell of nodes reaches beyond the display's edge on a grid whose edges lie on nodes:
// there the display itself (black beyond the edge), read at the landing point (model_image_edges.cpp).
glm::vec3 grid_value(const model_grid& grid, const glm::dvec2& base, const glm::dvec2& t);

// A bin's fine-grid samples sorted by their cells' columns and, apart, by their rows, for
// edge_correction.
struct edge_samples {
  std::vector<fine_sample> by_column, by_row;
  std::vector<std::uint32_t> column_start, row_start;  // cell c's samples from [c + radius] to [c + radius + 1]
  int radius = 0;
  std::uint64_t drawn = 0;  // the samples these are of (their divisor)
};
edge_samples sort_edge_samples(const std::vector<fine_sample>& fine, int radius, std::uint64_t drawn);

// What grid_value adds over spread_bilinear at the display's edges, averaged over a bin's samples
// for a pixel whose ideal point is `base`: the correlated fine grid at `base` plus this is the mean
// of the pixel's predictions from that bin's samples.
glm::vec3 edge_correction(const model_grid& fine, const edge_samples& samples, const glm::dvec2& base);

// The workers a model image's loops run on.
inline detail::row_workers row_workers_of(const model_image_params& p) { return {p.threads, p.own_threads}; }

}  // namespace airr::model_image_steps

namespace airr {

struct display_grids {
  model_grid grids[2];
  model_image_steps::grid_mapping maps[2];
  model_image_steps::grid_spectrum spectra[2];
  double grids_seconds = 0, spectra_seconds = 0;  // to compute them
};

struct model_correlations {
  model_image_steps::grid_mapping maps[2];
  std::vector<std::array<model_image_steps::correlated_grid, 2>> bins;
};

struct model_pixel_recipe {
  model_image_steps::ideal_parts parts;
  std::shared_ptr<const emission_profile> emission;
};

}  // namespace airr
