#include "airr/render/model_image.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "airr/optics/emission_profile.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/geometry.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/low_discrepancy.hpp"
#include "airr/optics/random.hpp"
#include "airr/render/parallel_rows.hpp"

namespace airr {

namespace {

// The parts an ideal path meets, built once per image.
struct ideal_parts {
  part_frame hm, rr, src, aerial;
  pinhole_camera cam;
  explicit ideal_parts(const scene& s)
      : hm(half_mirror_frame(s)),
        rr(retroreflector_frame(s)),
        src(source_frame(s)),
        aerial(aerial_image_frame(s)),
        cam(make_camera(s)) {}
};

struct ideal_path {
  glm::dvec2 display{0};  // display-local mm
  glm::dvec3 aerial{0};   // where the camera ray crosses the aerial-image plane
  glm::dvec3 towards_display{0};
  glm::dvec3 wi{0, 0, 1};  // incidence on the sheet, sheet-local
  double theta_deg = 0;
};

std::optional<ideal_path> trace_ideal(const ideal_parts& parts, double px, double py) {
  const glm::dvec3 d = camera_direction(parts.cam, px, py);
  const ideal_return r = follow_ideal_return(parts.hm, parts.rr, parts.src, parts.cam.position, d);
  if (r.failed != ideal_return::step::none) return std::nullopt;
  if (glm::dot(r.towards_display, parts.src.n) >= 0) return std::nullopt;  // the display's back
  const auto p = hit_part(parts.aerial, parts.cam.position, d, false);
  if (!p) return std::nullopt;
  const glm::dvec3 wi = -to_local(parts.rr, d);
  return ideal_path{part_local(parts.src, r.landing), *p, r.towards_display, wi, polar_angle_deg(wi)};
}

// What a pixel needs of its ideal path.
struct pixel_path {
  bool ok = false;
  glm::dvec2 display{0};   // display-local mm
  glm::dvec3 wi{0, 0, 1};  // incidence on the sheet (its polar angle is not smooth at 0: not interpolated)
  double profile = 1;      // the display's relative luminance towards the half mirror
};

pixel_path pixel_ideal(const ideal_parts& parts, const emission_profile* emission, double x, double y) {
  const auto path = trace_ideal(parts, x, y);
  if (!path) return {};
  pixel_path out{true, path->display, path->wi, 1.0};
  if (emission) {
    out.profile = emission->at(degrees(std::acos(std::min(1.0, -glm::dot(path->towards_display, parts.src.n)))));
  }
  return out;
}

// Every pixel's ideal path (empty when cancelled). With a stride, paths are traced on a lattice of
// pixels and interpolated inside each cell whose four corners all have one; other cells are traced
// pixel by pixel.
std::vector<pixel_path> pixel_paths(const ideal_parts& parts, const emission_profile* emission,
                                    const model_image_params& p, const std::atomic<bool>* cancel) {
  const int w = parts.cam.width, h = parts.cam.height, n = p.path_stride;
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  std::vector<pixel_path> out(std::size_t(w) * h);
  if (n <= 1) {
    detail::parallel_rows(h, p.threads, [&](int y0, int y1) {
      for (int y = y0; y < y1 && !cancelled(); ++y) {
        for (int x = 0; x < w; ++x) out[std::size_t(y) * w + x] = pixel_ideal(parts, emission, x + 0.5, y + 0.5);
      }
    });
    return cancelled() ? std::vector<pixel_path>{} : out;
  }
  // Lattice node i sits on pixel min(i n, size - 1).
  const int lw = (w - 1 + n - 1) / n + 1, lh = (h - 1 + n - 1) / n + 1;
  auto at = [n](int i, int size) { return std::min(i * n, size - 1); };
  std::vector<pixel_path> lattice(std::size_t(lw) * lh);
  detail::parallel_rows(lh, p.threads, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j) {
      for (int i = 0; i < lw; ++i) {
        lattice[std::size_t(j) * lw + i] = pixel_ideal(parts, emission, at(i, w) + 0.5, at(j, h) + 0.5);
      }
    }
  });
  detail::parallel_rows(h, p.threads, [&](int y0, int y1) {
    for (int y = y0; y < y1 && !cancelled(); ++y) {
      const int j = std::min(y / n, std::max(0, lh - 2)), ya = at(j, h), yb = at(j + 1, h);
      const double fy = yb > ya ? double(y - ya) / (yb - ya) : 0.0;
      for (int x = 0; x < w; ++x) {
        const int i = std::min(x / n, std::max(0, lw - 2)), xa = at(i, w), xb = at(i + 1, w);
        const double fx = xb > xa ? double(x - xa) / (xb - xa) : 0.0;
        const int i1 = std::min(i + 1, lw - 1), j1 = std::min(j + 1, lh - 1);
        const pixel_path* c[4] = {&lattice[std::size_t(j) * lw + i], &lattice[std::size_t(j) * lw + i1],
                                  &lattice[std::size_t(j1) * lw + i], &lattice[std::size_t(j1) * lw + i1]};
        pixel_path& px = out[std::size_t(y) * w + x];
        if (!(c[0]->ok && c[1]->ok && c[2]->ok && c[3]->ok)) {
          px = pixel_ideal(parts, emission, x + 0.5, y + 0.5);
          continue;
        }
        const double cw[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        px.ok = true;
        px.display = glm::dvec2(0);
        px.wi = glm::dvec3(0);
        px.profile = 0;
        for (int k = 0; k < 4; ++k) {
          px.display += cw[k] * c[k]->display;
          px.wi += cw[k] * c[k]->wi;
          px.profile += cw[k] * c[k]->profile;
        }
      }
    }
  });
  return cancelled() ? std::vector<pixel_path>{} : out;
}

// The display's radiance on a grid of at most max_texels on its longer side (area-averaged down
// from the texture; uniform: a grid of that size).
cv::Mat display_texels(const scene& s, const image_rgb* display, int max_texels) {
  cv::Mat m;
  if (display) {
    m = cv::Mat(display->height, display->width, CV_32FC3, const_cast<float*>(display->rgb.data()));
  } else {
    const part_frame src = source_frame(s);
    const double longer = std::max(src.width, src.height);
    m = cv::Mat(std::max(1, int(std::lround(max_texels * src.height / longer))),
                std::max(1, int(std::lround(max_texels * src.width / longer))), CV_32FC3,
                cv::Scalar::all(s.source.intensity));
  }
  const int longer = std::max(m.cols, m.rows);
  if (longer > max_texels) {
    const double f = double(max_texels) / longer;
    cv::Mat small;
    cv::resize(m, small, cv::Size(std::max(1, int(std::lround(m.cols * f))), std::max(1, int(std::lround(m.rows * f)))),
               0, 0, cv::INTER_AREA);
    m = small;
  }
  if (display) {
    // Into a new matrix: `m` may still be the caller's texture itself.
    cv::Mat scaled;
    m.convertTo(scaled, CV_32F, s.source.intensity);
    return scaled;
  }
  return m;
}

// The texels' bilinear surface (edges clamped, as the tracer reads its texture) sampled `refine`
// times more densely: nodes at texel coordinates origin + j / refine. With an even `refine` the
// nodes start half a texel out and include every texel centre, so the refined grid's bilinear
// surface is the texels' own, exactly.
image_rgb refined_grid(const cv::Mat& texels, int refine, double& origin) {
  origin = refine % 2 == 0 ? -0.5 : 0.0;
  image_rgb out;
  out.width = int(std::lround((texels.cols - 1 - 2 * origin) * refine)) + 1;
  out.height = int(std::lround((texels.rows - 1 - 2 * origin) * refine)) + 1;
  out.rgb.resize(std::size_t(out.width) * out.height * 3);
  auto texel = [&](int x, int y) {
    const cv::Vec3f& v = texels.at<cv::Vec3f>(std::clamp(y, 0, texels.rows - 1), std::clamp(x, 0, texels.cols - 1));
    return glm::vec3(v[0], v[1], v[2]);
  };
  for (int j = 0; j < out.height; ++j) {
    const double ty = origin + double(j) / refine;
    const int y0 = int(std::floor(ty));
    const float fy = float(ty - y0);
    for (int i = 0; i < out.width; ++i) {
      const double tx = origin + double(i) / refine;
      const int x0 = int(std::floor(tx));
      const float fx = float(tx - x0);
      const glm::vec3 v = glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                                   glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
      std::copy_n(&v.x, 3, out.at(i, j));
    }
  }
  return out;
}

image_rgb pad(const image_rgb& img, int radius) {
  image_rgb out;
  out.width = img.width + 2 * radius;
  out.height = img.height + 2 * radius;
  out.rgb.assign(std::size_t(out.width) * out.height * 3, 0.0f);
  for (int y = 0; y < img.height; ++y) std::copy_n(img.at(0, y), 3 * img.width, out.at(radius, y + radius));
  return out;
}

glm::vec3 bilinear(const image_rgb& m, const glm::dvec2& t) {
  const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= m.width || y0 + 1 >= m.height) return glm::vec3(0.0f);
  const float fx = float(t.x - x0), fy = float(t.y - y0);
  auto texel = [&](int x, int y) {
    const float* p = m.at(x, y);
    return glm::vec3(p[0], p[1], p[2]);
  };
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                  glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

// Where the model sends one sample: the grid and the offset in its nodes from the ideal point (the
// pixel jitter included), and its throughput; empty when it is absorbed, misses the half mirror or
// lands beyond the kernels. Both the kernels and the predictions go through here.
struct grid_offset {
  int grid;
  glm::dvec2 nodes;
};
std::optional<grid_offset> sample_offset(const model_image& m, const model_bin& b, const glm::dvec2& jitter,
                                         const retro_samples& u, double& weight) {
  const retro_sample rs = b.sampler->sample(u);
  if (!(rs.weight > 0)) return std::nullopt;
  const auto delta = psf_landing_offset(b.chief, rs);
  if (!delta) return std::nullopt;
  const glm::dvec2 mm =
      glm::dvec2(glm::dot(*delta, b.chief.src.u), glm::dot(*delta, b.chief.src.v)) + b.jitter_mm * (jitter - 0.5);
  weight = rs.weight * m.hm_factor;
  for (int g : {model_fine, model_tail}) {
    const model_grid& grid = m.grids[g];
    const glm::dvec2 t(mm.x / grid.node_w, -mm.y / grid.node_h);  // node rows run down the display
    if (std::abs(t.x) < grid.radius - 1 && std::abs(t.y) < grid.radius - 1) return grid_offset{g, t};
  }
  return std::nullopt;
}

// An offset between whole nodes spreads over the four around it with bilinear weights, in the
// kernels and in the predictions alike, so that the kernels' mean is exactly the predictions'.
template <typename F>
void for_each_corner(const glm::dvec2& t, F&& f) {
  const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
  const double fx = t.x - x0, fy = t.y - y0;
  f(x0, y0, (1 - fx) * (1 - fy));
  f(x0 + 1, y0, fx * (1 - fy));
  f(x0, y0 + 1, (1 - fx) * fy);
  f(x0 + 1, y0 + 1, fx * fy);
}

// The grid's bilinear surface at `base` plus the offset `t`, spread over the four nodes around it
// as for_each_corner does: four bilinear reads, which together are one 3 x 3 stencil of nodes.
glm::vec3 spread_bilinear(const image_rgb& grid, const glm::dvec2& base, const glm::dvec2& t) {
  const glm::dvec2 b = glm::floor(base), n = glm::floor(t);
  const int x0 = int(b.x + n.x), y0 = int(b.y + n.y);
  if (x0 < 0 || y0 < 0 || x0 + 2 >= grid.width || y0 + 2 >= grid.height) {
    glm::vec3 sum(0.0f);
    for_each_corner(t, [&](int x, int y, double c) { sum += bilinear(grid, base + glm::dvec2(x, y)) * float(c); });
    return sum;
  }
  auto weights = [](double f_base, double f_node) {
    return std::array<float, 3>{float((1 - f_node) * (1 - f_base)),
                                float((1 - f_node) * f_base + f_node * (1 - f_base)), float(f_node * f_base)};
  };
  const auto wx = weights(base.x - b.x, t.x - n.x), wy = weights(base.y - b.y, t.y - n.y);
  glm::vec3 sum(0.0f);
  for (int j = 0; j < 3; ++j) {
    glm::vec3 row(0.0f);
    for (int i = 0; i < 3; ++i) {
      const float* v = grid.at(x0 + i, y0 + j);
      row += glm::vec3(v[0], v[1], v[2]) * wx[std::size_t(i)];
    }
    sum += row * wy[std::size_t(j)];
  }
  return sum;
}

// The bin's kernels from its samples (a rotated R6 sequence for jitter, lobe and shift, as the
// tracer's pixels use); blocks run in parallel and are summed in order, so the result does not
// depend on the number of threads.
std::array<cv::Mat, 2> bin_kernels(const model_image& m, const model_bin& b, std::size_t bin, std::uint64_t samples,
                                   std::uint64_t seed, int threads, const std::atomic<bool>* cancel) {
  std::array<double, 6> rotation;
  pcg32 rotation_rng = sample_rng(bin, 0, seed ^ 0x6b65726eu);
  for (double& r : rotation) r = rotation_rng.next_double();
  auto zero = [&] {
    std::array<cv::Mat, 2> k;
    for (int g : {model_fine, model_tail}) {
      const int n = 2 * m.grids[g].radius + 1;
      k[std::size_t(g)] = cv::Mat(n, n, CV_64F, cv::Scalar(0));
    }
    return k;
  };
  constexpr std::uint64_t block = 65536;  // few partial kernels: each is as large as the kernel
  const std::size_t blocks = std::size_t((samples + block - 1) / block);
  std::vector<std::array<cv::Mat, 2>> parts(blocks);
  auto block_kernels = [&](std::size_t k) {
    std::array<cv::Mat, 2> part = zero();
    const std::uint64_t end = std::min<std::uint64_t>(samples, (k + 1) * block);
    for (std::uint64_t i = k * block; i < end; ++i) {
      const std::array<double, 6> q = r6_point(i, rotation);
      retro_samples u;
      u.lobe = {q[2], q[3]};
      u.shift = {q[4], q[5]};
      u.more = sample_rng(i, bin, seed ^ 0x6d6f7265u);
      double w = 0;
      const auto o = sample_offset(m, b, {q[0], q[1]}, u, w);
      if (!o) continue;
      cv::Mat& kernel = part[std::size_t(o->grid)];
      const int r = m.grids[o->grid].radius;
      for_each_corner(o->nodes, [&](int x, int y, double c) { kernel.at<double>(y + r, x + r) += w * c; });
    }
    return part;
  };
  detail::parallel_rows(int(blocks), threads, [&](int b0, int b1) {
    for (int k = b0; k < b1 && !(cancel && cancel->load(std::memory_order_relaxed)); ++k) {
      parts[std::size_t(k)] = block_kernels(std::size_t(k));
    }
  });
  std::array<cv::Mat, 2> sum = zero(), out;
  for (const auto& part : parts) {
    if (part[0].empty()) continue;  // cancelled
    for (std::size_t g = 0; g < 2; ++g) sum[g] += part[g];
  }
  for (std::size_t g = 0; g < 2; ++g) sum[g].convertTo(out[g], CV_32F, 1.0 / double(samples));
  return out;
}

bool is_grey(const image_rgb& img) {
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
    if (img.rgb[i] != img.rgb[i + 1] || img.rgb[i] != img.rgb[i + 2]) return false;
  }
  return true;
}

// A padded grid's spectrum, computed once and correlated with every bin's kernel. The grid's
// margins are black and as wide as the kernels reach, so a DFT the grid's own size suffices:
// what wraps around lands on black.
struct grid_spectrum {
  int width = 0, height = 0;      // the padded grid's
  std::vector<cv::Mat> channels;  // one spectrum per distinct channel (one for a grey display)
};

grid_spectrum spectrum_of(const image_rgb& padded) {
  grid_spectrum out;
  out.width = padded.width;
  out.height = padded.height;
  const cv::Mat src(padded.height, padded.width, CV_32FC3, const_cast<float*>(padded.rgb.data()));
  const int n = is_grey(padded) ? 1 : 3;
  const cv::Size size(cv::getOptimalDFTSize(padded.width), cv::getOptimalDFTSize(padded.height));
  for (int c = 0; c < n; ++c) {
    cv::Mat channel = cv::Mat::zeros(size, CV_32F);
    cv::extractChannel(src, channel(cv::Rect(0, 0, padded.width, padded.height)), c);
    cv::Mat spectrum;
    cv::dft(channel, spectrum, 0, padded.height);
    out.channels.push_back(std::move(spectrum));
  }
  return out;
}

// out(x) = sum over offsets o of kernel(o) grid(x + o), the kernel's centre at offset 0 (the
// prediction's sum, for every node at once); one matrix per distinct channel, as the spectrum.
struct correlated_grid {
  std::vector<cv::Mat> channels;
  glm::vec3 at(const glm::dvec2& t) const {
    const cv::Mat& first = channels.front();
    const int x0 = int(std::floor(t.x)), y0 = int(std::floor(t.y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= first.cols || y0 + 1 >= first.rows) return glm::vec3(0.0f);
    const float fx = float(t.x - x0), fy = float(t.y - y0);
    glm::vec3 v(0.0f);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const float* r0 = channels[c].ptr<float>(y0);
      const float* r1 = channels[c].ptr<float>(y0 + 1);
      v[int(c)] = (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
    }
    return channels.size() == 1 ? glm::vec3(v[0]) : v;
  }
};

correlated_grid correlate(const grid_spectrum& grid, const cv::Mat& kernel) {
  const cv::Size size = grid.channels.front().size();
  const int r = kernel.rows / 2;
  cv::Mat kernel_spectrum;
  {
    // The kernel with offset o at index o modulo the DFT's size.
    cv::Mat wrapped = cv::Mat::zeros(size, CV_32F);
    for (int y = -r; y <= r; ++y) {
      const float* row = kernel.ptr<float>(y + r);
      float* dst = wrapped.ptr<float>((y + size.height) % size.height);
      for (int x = -r; x <= r; ++x) dst[(x + size.width) % size.width] = row[x + r];
    }
    cv::dft(wrapped, kernel_spectrum);
  }
  correlated_grid out;
  for (const cv::Mat& channel : grid.channels) {
    cv::Mat product, values;
    cv::mulSpectrums(channel, kernel_spectrum, product, 0, true);
    cv::dft(product, values, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT, grid.height);
    out.channels.push_back(values(cv::Rect(0, 0, grid.width, grid.height)));
  }
  return out;
}

// One grid over the display's texels (`refine` nodes per texel) and where display-local points
// fall on it.
struct grid_mapping {
  double cols = 1, rows = 1, width = 1, height = 1, origin = 0, refine = 1, radius = 0;
  glm::dvec2 node(const glm::dvec2& local) const {
    const glm::dvec2 texel((local.x / width + 0.5) * cols - 0.5, (0.5 - local.y / height) * rows - 0.5);
    return (texel - origin) * refine + radius;
  }
};

grid_mapping make_grid(model_grid& grid, const cv::Mat& texels, int refine, double reach_mm, const part_frame& src) {
  grid_mapping map;
  const image_rgb nodes = refined_grid(texels, refine, map.origin);
  grid.node_w = src.width / texels.cols / refine;
  grid.node_h = src.height / texels.rows / refine;
  grid.radius = std::clamp(int(std::ceil(reach_mm / std::min(grid.node_w, grid.node_h))) + 1, 2, 2048);
  grid.padded = pad(nodes, grid.radius);
  map.cols = texels.cols;
  map.rows = texels.rows;
  map.width = src.width;
  map.height = src.height;
  map.refine = refine;
  map.radius = grid.radius;
  return map;
}

// The two bins around a pixel's angle (bin angles ascend) and its weight on the upper one.
void assign_bin(const std::vector<model_bin>& bins, model_pixel& px) {
  if (!px.ok) return;
  const int n = int(bins.size());
  int k = 0;
  while (k + 1 < n && bins[std::size_t(k + 1)].theta_deg < px.theta_deg) ++k;
  px.bin = k;
  if (k + 1 < n) {
    const double a0 = bins[std::size_t(k)].theta_deg, a1 = bins[std::size_t(k + 1)].theta_deg;
    px.mix = a1 > a0 ? std::clamp((px.theta_deg - a0) / (a1 - a0), 0.0, 1.0) : 0.0;
  }
}

}  // namespace

model_image_params model_image_params::for_image(int width, int height, bool quick) {
  model_image_params p;
  if (quick || std::int64_t(width) * height < 256 * 256) {
    p.texel_refine = 2;
    p.core_radius_mm = 4;
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
  return p;
}

std::shared_ptr<const model_image> compute_model_image(const scene& s, std::shared_ptr<const retro_model> model,
                                                       const image_rgb* display, const model_image_params& p,
                                                       const std::atomic<bool>* cancel) {
  if (p.angle_bins < 1 || p.angle_bins > 64 || p.psf_samples < 1000 || p.max_texels < 16 || p.max_texels > 4096 ||
      p.texel_refine < 1 || p.texel_refine > 4 || !(p.core_radius_mm > 0) || p.tail_texels < 4 ||
      !(p.kernel_radius_mm >= p.core_radius_mm) || p.path_stride < 1 || p.path_stride > 64 || p.threads < 0) {
    throw input_error("model image: parameters out of range");
  }
  if (s.retroreflectors.empty() || !model) return nullptr;
  const auto t0 = std::chrono::steady_clock::now();
  const ideal_parts parts(s);
  const int w = parts.cam.width, h = parts.cam.height;
  std::shared_ptr<const emission_profile> emission;
  if (!s.source.emission_profile.empty()) {
    emission = load_emission_profile(resolve_scene_path(s, s.source.emission_profile));
  }

  auto m = std::make_shared<model_image>();
  m->model = std::move(model);
  m->hm_factor = s.half_mirror.reflectance * s.half_mirror.transmittance;
  // The grids' kernels stay within about 384 (fine) and 320 (tail) nodes of reach, however small
  // the display: no finer grid than that pays.
  const double longer_mm = std::max(parts.src.width, parts.src.height);
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
  const grid_mapping maps[2] = {make_grid(m->grids[model_fine], texels, p.texel_refine, p.core_radius_mm, parts.src),
                                make_grid(m->grids[model_tail], tail_texels, 1, p.kernel_radius_mm, parts.src)};

  const std::vector<pixel_path> paths = pixel_paths(parts, emission.get(), p, cancel);
  if (paths.empty()) return nullptr;
  m->pixels.resize(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (!paths[i].ok) continue;
    model_pixel& px = m->pixels[i];
    for (int g : {model_fine, model_tail}) px.node[g] = maps[g].node(paths[i].display);
    // Landing outside the tail's padded grid, it is farther from the display than any kernel
    // offset. (Outside the fine grid, only the fine part sees nothing, in both uses alike.)
    const glm::dvec2 t = px.node[model_tail];
    const image_rgb& padded = m->grids[model_tail].padded;
    px.ok = t.x >= 0 && t.y >= 0 && t.x < padded.width - 1 && t.y < padded.height - 1;
    px.theta_deg = polar_angle_deg(glm::normalize(paths[i].wi));
    px.profile = paths[i].profile;
  }
  m->paths_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double lo = INFINITY, hi = -INFINITY;
  for (const model_pixel& px : m->pixels) {
    if (px.ok) lo = std::min(lo, px.theta_deg), hi = std::max(hi, px.theta_deg);
  }
  if (!(lo <= hi)) return nullptr;

  // One PSF per bin, at the pixel whose angle is nearest the bin's.
  const int bins = hi - lo < 0.1 ? 1 : p.angle_bins;
  for (int k = 0; k < bins; ++k) {
    const double want = bins == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * k / (bins - 1);
    std::size_t best = 0;
    bool found = false;
    for (std::size_t i = 0; i < m->pixels.size(); ++i) {
      const model_pixel& px = m->pixels[i];
      if (px.ok && (!found || std::abs(px.theta_deg - want) < std::abs(m->pixels[best].theta_deg - want))) {
        best = i;
        found = true;
      }
    }
    const double bx = double(best % std::size_t(w)) + 0.5, by = double(best / std::size_t(w)) + 0.5;
    const auto centre = trace_ideal(parts, bx, by);
    const auto right = trace_ideal(parts, bx + 0.5, by), left = trace_ideal(parts, bx - 0.5, by);
    const auto down = trace_ideal(parts, bx, by + 0.5), up = trace_ideal(parts, bx, by - 0.5);
    model_bin b;
    b.theta_deg = centre->theta_deg;
    b.chief = chief_ray_through(s, centre->aerial);
    b.sampler = m->model->at_incidence(b.chief.wi);
    if (right && left && down && up) {
      b.jitter_mm = glm::dmat2(right->display - left->display, down->display - up->display);
    }
    m->bins.push_back(std::move(b));
  }
  auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
  const grid_spectrum spectra[2] = {spectrum_of(m->grids[model_fine].padded), spectrum_of(m->grids[model_tail].padded)};
  for (model_pixel& px : m->pixels) assign_bin(m->bins, px);
  // Each bin adds its share to the pixels it is the lower bin of, or the upper: no pixel is
  // written by two bins at once, and a bin's correlated grids are dropped as soon as it is done.
  image_rgb shares[2];
  for (image_rgb& share : shares) {
    share.width = w;
    share.height = h;
    share.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  }
  detail::parallel_rows(bins, p.threads, [&](int k0, int k1) {
    for (int k = k0; k < k1 && !cancelled(); ++k) {
      const std::array<cv::Mat, 2> kernels =
          bin_kernels(*m, m->bins[std::size_t(k)], std::size_t(k), p.psf_samples, s.seed, p.threads, cancel);
      const correlated_grid correlated[2] = {correlate(spectra[model_fine], kernels[model_fine]),
                                             correlate(spectra[model_tail], kernels[model_tail])};
      for (std::size_t i = 0; i < m->pixels.size(); ++i) {
        const model_pixel& px = m->pixels[i];
        if (!px.ok || (px.bin != k && px.bin + 1 != k)) continue;
        const bool upper = px.bin + 1 == k;
        const float weight = float((upper ? px.mix : 1 - px.mix) * px.profile);
        glm::vec3 v(0.0f);
        for (int g : {model_fine, model_tail}) v += correlated[g].at(px.node[g]);
        float* out = shares[upper ? 1 : 0].rgb.data() + 3 * i;
        for (int c = 0; c < 3; ++c) out[c] = v[c] * weight;
      }
    }
  });
  if (cancelled()) return nullptr;
  m->image = std::move(shares[0]);
  for (std::size_t i = 0; i < m->image.rgb.size(); ++i) m->image.rgb[i] += shares[1].rgb[i];
  m->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m;
}

image_rgb model_image_first_look(const scene& s, std::shared_ptr<const retro_model> model, const image_rgb* display,
                                 const std::atomic<bool>* cancel) {
  const int w = s.observer.width, h = s.observer.height;
  int f = 4;
  while (f > 1 && (w % f != 0 || h % f != 0 || std::min(w, h) / f < 128)) f /= 2;
  scene small = s;
  small.observer.width = w / f;
  small.observer.height = h / f;
  const auto m = compute_model_image(small, std::move(model), display, model_image_params::first_look(), cancel);
  if (!m) return {};
  if (f == 1) return m->image;
  image_rgb out;
  out.width = w;
  out.height = h;
  out.rgb.resize(std::size_t(w) * h * 3);
  const cv::Mat src(m->image.height, m->image.width, CV_32FC3, const_cast<float*>(m->image.rgb.data()));
  cv::Mat dst(h, w, CV_32FC3, out.rgb.data());  // resized straight into the result
  cv::resize(src, dst, dst.size(), 0, 0, cv::INTER_LINEAR);
  return out;
}

glm::vec3 model_prediction(const model_image& m, int px, int py, const glm::dvec2& jitter, const retro_samples& u) {
  const model_pixel& p = m.pixels[std::size_t(py) * m.image.width + px];
  if (!p.ok) return glm::vec3(0.0f);
  auto one = [&](int k) {
    double weight = 0;
    const auto o = sample_offset(m, m.bins[std::size_t(k)], jitter, u, weight);
    if (!o) return glm::vec3(0.0f);
    return spread_bilinear(m.grids[o->grid].padded, p.node[o->grid], o->nodes) * float(weight * p.profile);
  };
  glm::vec3 v = one(p.bin) * float(1 - p.mix);
  if (p.mix > 0) v += one(p.bin + 1) * float(p.mix);
  return v;
}

}  // namespace airr
