#include "airr/render/model_image.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "airr/core/cancel.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/render/parallel_rows.hpp"
#include "model_image_steps.hpp"

namespace airr {

using namespace model_image_steps;

void model_image_steps::assign_bin(const std::vector<model_bin>& bins, model_pixel& px) {
  if (!px.ok) return;
  const int n = int(bins.size());
  int k = 0;
  while (k + 1 < n && bins[std::size_t(k + 1)].theta_deg < px.theta_deg) ++k;
  px.bin = k;
  if (k + 1 < n) {
    const double a0 = bins[std::size_t(k)].theta_deg, a1 = bins[std::size_t(k + 1)].theta_deg;
    px.mix = a1 > a0 ? float(std::clamp((px.theta_deg - a0) / (a1 - a0), 0.0, 1.0)) : 0.0f;
  }
}

model_image_params model_image_params::for_image(int width, int height, bool quick) {
  model_image_params p;
  p.psf_samples = 65536;
  if (quick || std::int64_t(width) * height < 256 * 256) {
    p.texel_refine = 2;
    p.core_radius_mm = 4;
    p.edge_samples = 2048;
  } else {
    p.angle_bins = 16;
    // The edges' share costs as many samples a pixel near an edge: a large image takes fewer.
    const double pixels = double(width) * double(height);
    p.edge_samples = std::uint64_t(std::clamp(16384.0 * (512.0 * 512.0) / pixels, 2048.0, 16384.0));
  }
  return p;
}

model_image_params model_image_params::first_look() {
  model_image_params p;
  p.angle_bins = 2;
  p.psf_samples = 2048;
  p.max_texels = 128;
  p.texel_refine = 1;
  p.core_radius_mm = 3;
  p.kernel_radius_mm = 16;
  p.tail_texels = 32;
  p.path_stride = 8;
  p.threads = 1;
  p.display_samples = 4;
  return p;
}

model_image_params model_image_params::for_view() {
  model_image_params p;
  p.texel_refine = 1;
  p.psf_samples = 32768;
  p.tail_texels = 64;
  p.path_stride = 4;
  // At least 128 paths a side: in a small image the cells the region of paths only partly covers
  // (its edges, the display's and bezel's outlines) are a large share of the aerial image (the
  // kiosk's own view at 128 x 128: 3.7% RMS from the tracer, noise taken out, with every pixel's
  // path; 4.2% with every fourth's).
  p.least_paths = 128;
  p.keep_correlations = true;
  p.own_threads = true;
  p.display_samples = 4;
  return p;
}

void check_model_image_params(const model_image_params& p) {
  if (p.angle_bins < 1 || p.angle_bins > 64 || p.psf_samples < 1000 || p.max_texels < 16 || p.max_texels > 4096 ||
      p.texel_refine < 1 || p.texel_refine > 4 || !(p.core_radius_mm > 0) || p.tail_texels < 4 ||
      !(p.kernel_radius_mm >= p.core_radius_mm) || p.path_stride < 1 || p.path_stride > 64 || p.least_paths < 0 ||
      p.threads < 0 || (!p.keep_pixels && p.path_stride != 1) || p.edge_samples < 1 || p.display_samples < 0 ||
      p.display_samples > 16) {
    throw input_error("model image: parameters out of range");
  }
}

std::shared_ptr<const display_grids> compute_display_grids(const scene& s, const image_rgb* display,
                                                           const model_image_params& p,
                                                           const std::atomic<bool>* cancel) {
  check_model_image_params(p);
  using clock_type = std::chrono::steady_clock;
  const auto t0 = clock_type::now();
  auto g = std::make_shared<display_grids>();
  const part_frame src = source_frame(s);
  // The grids' kernels stay within about 384 (fine) and 320 (tail) nodes of reach, however small
  // the display: no finer grid than that pays.
  const double longer_mm = std::max(src.width, src.height);
  const int fine_texels = std::clamp(int(longer_mm / (p.core_radius_mm / 384) / p.texel_refine), 8, p.max_texels);
  const int coarse_texels = std::clamp(int(longer_mm / (p.kernel_radius_mm / 320)), 4, p.tail_texels);
  const cv::Mat texels = display_texels(s, display, fine_texels);
  cv::Mat tail_texels = texels;
  if (std::max(texels.cols, texels.rows) > coarse_texels) {
    const double f = double(coarse_texels) / std::max(texels.cols, texels.rows);
    cv::resize(texels, tail_texels,
               cv::Size(std::max(1, int(std::lround(texels.cols * f))), std::max(1, int(std::lround(texels.rows * f)))),
               0, 0, cv::INTER_AREA);
  }
  g->maps[model_fine] = make_grid(g->grids[model_fine], texels, p.texel_refine, p.core_radius_mm, src, cancel);
  if (cancel_requested(cancel)) return nullptr;
  g->maps[model_tail] = make_grid(g->grids[model_tail], tail_texels, 1, p.kernel_radius_mm, src, cancel);
  if (cancel_requested(cancel)) return nullptr;
  const auto t1 = clock_type::now();
  g->grids_seconds = std::chrono::duration<double>(t1 - t0).count();
  g->spectra[model_fine] = spectrum_of(g->grids[model_fine].padded, cancel);
  g->spectra[model_tail] = spectrum_of(g->grids[model_tail].padded, cancel);
  if (cancel_requested(cancel)) return nullptr;
  g->spectra_seconds = std::chrono::duration<double>(clock_type::now() - t1).count();
  return g;
}

std::shared_ptr<model_image> compute_model_image(const scene& s, std::shared_ptr<const retro_model> model,
                                                 const image_rgb* display, const model_image_params& p,
                                                 const std::atomic<bool>* cancel, std::size_t sheet,
                                                 std::shared_ptr<const display_grids> grids) {
  check_model_image_params(p);
  if (sheet >= s.retroreflectors.size() || !model) return nullptr;
  const auto t0 = std::chrono::steady_clock::now();
  const ideal_parts parts(s, sheet);
  const int w = parts.cam.width, h = parts.cam.height;
  const std::shared_ptr<const emission_profile> emission = scene_emission_profile(s);

  auto m = std::make_shared<model_image>();
  m->model = std::move(model);
  m->sheet = sheet;
  m->hm_factor = s.half_mirror.reflectance * s.half_mirror.transmittance;
  const bool own_grids = !grids;
  m->display = own_grids ? compute_display_grids(s, display, p, cancel) : std::move(grids);
  if (!m->display) return nullptr;  // cancelled
  m->grids = m->display->grids;
  const grid_mapping(&maps)[2] = m->display->maps;

  // Without keep_pixels only the angles are held while the image is made (5 bytes a pixel, not 36:
  // a large render's peak); a bin's gather traces its pixels' paths anew, to the same numbers.
  pixel_angle_map angles;
  if (p.keep_pixels) {
    m->pixels = pixel_paths(parts, emission.get(), p, maps, m->grids[model_tail], cancel);
  } else {
    angles = pixel_angles(parts, emission.get(), p, maps, m->grids[model_fine], m->grids[model_tail], cancel);
  }
  const std::size_t count = std::size_t(w) * h;
  if (m->pixels.size() != count && angles.theta_deg.size() != count) return nullptr;  // cancelled
  auto on_fine_grid = [&](std::size_t i) {
    return p.keep_pixels ? lands_on_fine_grid(m->pixels[i], m->grids[model_fine]) : angles.on_fine_grid[i] != 0;
  };
  // The bins' angles span the pixels that land on the fine grid (or, when none does, every pixel
  // with a path): the kiosk's region of paths is twice the aerial image's width, and bins spread
  // over it gave the image's pixels the footprints of pixels far from them, several percent apart
  // (the aerial image 2.75% RMS of the image's mean from the tracer; 1.56% with the bins within
  // the fine grid).
  bool any_on_fine_grid = false;
  for (std::size_t i = 0; i < count && !any_on_fine_grid; ++i) any_on_fine_grid = on_fine_grid(i);
  auto angle = [&](std::size_t i) {
    constexpr float none = std::numeric_limits<float>::quiet_NaN();
    if (any_on_fine_grid && !on_fine_grid(i)) return none;
    if (!p.keep_pixels) return angles.theta_deg[i];
    return m->pixels[i].ok ? m->pixels[i].theta_deg : none;
  };
  m->paths_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() -
                     (own_grids ? m->display->spectra_seconds : 0.0);
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < count; ++i) {
    if (const float a = angle(i); !std::isnan(a)) lo = std::min(lo, double(a)), hi = std::max(hi, double(a));
  }
  if (!(lo <= hi)) return nullptr;

  // One PSF per bin, at the pixel whose angle is nearest the bin's (bin angles are evenly spaced:
  // each pixel is a candidate for the bin nearest it alone, and the first of equals wins).
  const int bins = hi - lo < 0.1 ? 1 : p.angle_bins;
  auto want = [&](int k) { return bins == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * k / (bins - 1); };
  std::vector<std::size_t> nearest(std::size_t(bins), count);
  for (std::size_t i = 0; i < count; ++i) {
    const float a = angle(i);
    if (std::isnan(a)) continue;
    const int k = bins == 1 ? 0 : std::clamp(int(std::lround((a - lo) / (hi - lo) * (bins - 1))), 0, bins - 1);
    std::size_t& best = nearest[std::size_t(k)];
    if (best == count || std::abs(a - want(k)) < std::abs(angle(best) - want(k))) best = i;
  }
  for (int k = 0; k < bins; ++k) {
    // A bin no pixel is nearest to (none within half a spacing of it): the nearest pixel overall.
    std::size_t best = nearest[std::size_t(k)];
    if (best == count) {
      for (std::size_t i = 0; i < count; ++i) {
        const float a = angle(i);
        if (!std::isnan(a) && (best == count || std::abs(a - want(k)) < std::abs(angle(best) - want(k)))) best = i;
      }
    }
    const double bx = double(best % std::size_t(w)) + 0.5, by = double(best / std::size_t(w)) + 0.5;
    const auto centre = trace_ideal(parts, bx, by);
    model_bin b;
    b.pixel = {bx, by};
    b.theta_deg = centre->theta_deg;
    b.chief = chief_ray_through(s, centre->aerial, sheet);
    b.sampler = m->model->at_incidence(b.chief.wi);
    b.jitter_mm = pixel_footprint(parts, bx, by);
    m->bins.push_back(std::move(b));
  }
  using clock_type = std::chrono::steady_clock;
  auto since = [](clock_type::time_point t) { return std::chrono::duration<double>(clock_type::now() - t).count(); };
  m->spectra_seconds = own_grids ? m->display->spectra_seconds : 0.0;
  m->bins_seconds = since(t0) - m->paths_seconds - m->spectra_seconds;
  const grid_spectrum(&spectra)[2] = m->display->spectra;
  if (cancel_requested(cancel)) return nullptr;
  for (model_pixel& px : m->pixels) assign_bin(m->bins, px);
  // Each bin adds its share to the pixels it is the lower bin of, or the upper: the even bins side
  // by side, then the odd ones, so that no pixel is written by two bins at once (its two bins are
  // neighbours); a bin's correlated grids are dropped as soon as it is done.
  m->image.width = w;
  m->image.height = h;
  m->image.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  std::shared_ptr<model_correlations> kept;
  if (p.keep_correlations) {
    kept = std::make_shared<model_correlations>();
    kept->maps[model_fine] = maps[model_fine];
    kept->maps[model_tail] = maps[model_tail];
    kept->bins.resize(std::size_t(bins));
  }
  // Whether a pixel at this angle is bin k's lower or upper bin's (assign_bin gives k or k - 1):
  // two comparisons, where assign_bin walks the bins, for every pixel in every bin's pass.
  auto in_gather = [&](float theta, int k) {
    if (std::isnan(theta)) return false;
    const bool from_below = k - 1 <= 0 || m->bins[std::size_t(k - 1)].theta_deg < theta;
    const bool from_above = k + 1 >= bins || !(m->bins[std::size_t(k + 1)].theta_deg < theta);
    return from_below && from_above;
  };
  std::vector<std::array<double, 3>> bin_seconds(std::size_t(bins), {0.0, 0.0, 0.0});
  const std::uint64_t edge_count = std::min(p.edge_samples, p.psf_samples);
  const auto t_landings = clock_type::now();
  const std::vector<std::vector<bin_landing>> landings =
      bin_landings(*m, p.psf_samples, s.seed, row_workers_of(p), cancel);
  if (cancel_requested(cancel)) return nullptr;
  m->landings_seconds = since(t_landings);
  const auto t_loop = clock_type::now();
  for (const int parity : {0, 1}) {
    detail::parallel_rows((bins + 1 - parity) / 2, row_workers_of(p), [&](int j0, int j1) {
      correlate_scratch scratch[2];
      for (int k = 2 * j0 + parity; k < 2 * j1 + parity && !cancel_requested(cancel); k += 2) {
        auto t = clock_type::now();
        const model_grid& fine_grid = m->grids[model_fine];
        std::vector<fine_sample> landed;
        const std::array<cv::Mat, 2> kernels = bin_kernels(*m, landings[std::size_t(k)], row_workers_of(p), cancel,
                                                           fine_grid.edges_on_nodes ? &landed : nullptr, edge_count);
        const edge_samples edges =
            fine_grid.edges_on_nodes ? sort_edge_samples(landed, fine_grid.radius, edge_count) : edge_samples{};
        landed = {};
        bin_seconds[std::size_t(k)][0] = since(t);
        if (cancel_requested(cancel)) break;
        t = clock_type::now();
        correlated_grid fine = correlate(spectra[model_fine], kernels[model_fine], scratch[model_fine], cancel);
        if (cancel_requested(cancel)) break;
        std::array<correlated_grid, 2> correlated = {
            std::move(fine), correlate(spectra[model_tail], kernels[model_tail], scratch[model_tail], cancel)};
        if (cancel_requested(cancel)) break;
        bin_seconds[std::size_t(k)][1] = since(t);
        t = clock_type::now();
        for (std::size_t i = 0; i < count; ++i) {
          model_pixel traced;
          if (!p.keep_pixels) {
            if (!in_gather(angles.theta_deg[i], k)) continue;
            traced = pixel_path_at(parts, emission.get(), maps, m->grids[model_tail], int(i % std::size_t(w)),
                                   int(i / std::size_t(w)));
            assign_bin(m->bins, traced);
          }
          const model_pixel& px = p.keep_pixels ? m->pixels[i] : traced;
          if (!px.ok || (px.bin != k && px.bin + 1 != k)) continue;
          const bool upper = px.bin + 1 == k;
          const float weight = float((upper ? px.mix : 1 - px.mix) * px.profile);
          glm::vec3 v = gather(correlated, px);
          if (fine_grid.edges_on_nodes) v += edge_correction(fine_grid, edges, px.node[model_fine]);
          float* out = m->image.rgb.data() + 3 * i;
          for (int c = 0; c < 3; ++c) out[c] += v[c] * weight;
        }
        bin_seconds[std::size_t(k)][2] = since(t);
        if (kept) {
          kept->bins[std::size_t(k)] = std::move(correlated);
        } else {
          for (int g : {model_fine, model_tail}) scratch[g].take_back(std::move(correlated[std::size_t(g)]));
        }
      }
    });
  }
  if (cancel_requested(cancel)) return nullptr;
  m->loop_seconds = since(t_loop);
  for (const auto& b : bin_seconds) {
    m->kernels_seconds += b[0];
    m->correlate_seconds += b[1];
    m->gather_seconds += b[2];
  }
  m->correlations = std::move(kept);
  if (!p.keep_pixels) m->recipe = std::make_shared<const model_pixel_recipe>(model_pixel_recipe{parts, emission});
  m->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m;
}

model_pixel model_pixel_at(const model_image& m, int px, int py) {
  if (!m.pixels.empty()) return m.pixels[std::size_t(py) * m.image.width + px];
  model_pixel out =
      pixel_path_at(m.recipe->parts, m.recipe->emission.get(), m.display->maps, m.grids[model_tail], px, py);
  assign_bin(m.bins, out);
  return out;
}

}  // namespace airr
