// The display seen directly and in the half mirror: each pixel's points followed through the
// planar parts as the tracer's paths go (tracer.cpp), without its randomness.
#include "airr/render/display_parts_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "airr/core/cancel.hpp"
#include "airr/core/geometry.hpp"
#include "airr/core/low_discrepancy.hpp"
#include "airr/layout/layout.hpp"
#include "display_radiance.hpp"
#include "model_image_steps.hpp"

namespace airr {
namespace {

struct planar_parts {
  part_frame panel, area, hm;  // the display's panel (bezel included) and emitting area
  std::vector<part_frame> sheets;
  double reflectance = 0, transmittance = 0;
  pinhole_camera cam;
  std::shared_ptr<const emission_profile> emission;

  explicit planar_parts(const scene& s)
      : panel(source_panel_frame(s)), area(source_frame(s)), hm(half_mirror_frame(s)), cam(make_camera(s)) {
    half_mirror_params light = s.half_mirror;
    derive_half_mirror_light(light);
    reflectance = light.reflectance;
    transmittance = light.transmittance;
    for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) sheets.push_back(retroreflector_frame(s, i));
    emission = scene_emission_profile(s);
  }
};

// Where a ray reaches the display's front: seen directly (reflections 0) or in the half mirror (1).
struct landing {
  glm::dvec2 local{0};  // on the emitting area's plane, mm
  glm::dvec3 dir{0};
  double weight = 0;
  int reflections = 0;
};

enum part_met { met_none, met_panel, met_half_mirror, met_sheet };

part_met nearest_part(const planar_parts& d, const glm::dvec3& o, const glm::dvec3& dir, bool leaving_hm,
                      glm::dvec3& hit) {
  double best = std::numeric_limits<double>::infinity();
  part_met met = met_none;
  auto consider = [&](const part_frame& f, part_met kind) {
    const auto p = hit_part(f, o, dir);
    if (!p) return;
    const double t = glm::dot(*p - o, dir);
    if (t < best) {
      best = t;
      met = kind;
      hit = *p;
    }
  };
  consider(d.panel, met_panel);
  if (!leaving_hm) consider(d.hm, met_half_mirror);
  for (const part_frame& f : d.sheets) consider(f, met_sheet);
  return met;
}

// The ray's landings (at most two): the half mirror passes it (its transmittance) and reflects it
// once (its reflectance; a second reflection is the rest's); a sheet or the display's back stops it.
int follow(const planar_parts& d, const glm::dvec3& origin, const glm::dvec3& direction, landing (&out)[2]) {
  struct branch {
    glm::dvec3 o, dir;
    double weight;
    int reflections;
    bool leaving_hm;
  };
  branch pending[2];
  int n_pending = 0, n_out = 0;
  pending[n_pending++] = {origin, direction, 1.0, 0, false};
  while (n_pending > 0) {
    branch b = pending[--n_pending];
    for (int step = 0; step < 3; ++step) {
      glm::dvec3 hit(0.0);
      const part_met met = nearest_part(d, b.o, b.dir, b.leaving_hm, hit);
      if (met == met_panel) {
        if (glm::dot(b.dir, d.panel.n) < 0) out[n_out++] = {part_local(d.area, hit), b.dir, b.weight, b.reflections};
        break;
      }
      if (met != met_half_mirror) break;
      if (b.reflections == 0 && d.reflectance > 0)
        pending[n_pending++] = {hit, reflect(b.dir, d.hm.n), b.weight * d.reflectance, 1, true};
      b = {hit, b.dir, b.weight * d.transmittance, b.reflections, true};
      if (!(b.weight > 0)) break;
    }
  }
  return n_out;
}

// The landings of the pinhole ray through pixel point (x, y).
struct corner {
  landing l[2];
  int n = 0;
  // Where the ray meets the display's plane, directly and reflected in the half mirror's plane
  // (mm, both unbounded; `on` says which exist): the footprint's size even where a pixel's corners
  // miss the display.
  glm::dvec2 plane[2];
  bool on[2] = {false, false};
  // Whether the display's emitting area lies within the lens's blur of where the ray meets its
  // plane, either way (a thin lens shows the display in pixels whose corners miss it).
  bool near = false;
  glm::dvec2 blur{0};  // the lens's blur there (mm along the display's x and y), the larger way
};

// The lens's blur (mm along the display's x and y) on the display's plane for a ray leaving the
// observer along `dir` and meeting the plane `travelled` mm later, arriving along `arrival`: the
// aperture's cone around the point in focus cut by the plane, an ellipse drawn out along the
// arrival's slant.
glm::dvec2 blur_on_display(const planar_parts& d, const glm::dvec3& dir, double travelled, const glm::dvec3& arrival) {
  if (!(d.cam.aperture_mm > 0)) return glm::dvec2(0.0);
  const double in_focus = d.cam.focus_distance / glm::dot(dir, d.cam.forward);
  const double across = d.cam.aperture_mm * std::abs(1 - travelled / in_focus);
  const glm::dvec2 slant(glm::dot(arrival, d.area.u), glm::dot(arrival, d.area.v));
  const double along = across / std::max(0.05, std::abs(glm::dot(arrival, d.area.n)));
  const double l = glm::length(slant);
  const glm::dvec2 e = l > 1e-12 ? slant / l : glm::dvec2(1, 0);
  return {std::sqrt(along * along * e.x * e.x + across * across * e.y * e.y),
          std::sqrt(along * along * e.y * e.y + across * across * e.x * e.x)};
}

corner corner_at(const planar_parts& d, double x, double y) {
  corner c;
  const glm::dvec3 dir = camera_direction(d.cam, x, y);
  c.n = follow(d, d.cam.position, dir, c.l);
  if (const auto p = hit_part(d.area, d.cam.position, dir, false)) {
    c.plane[0] = part_local(d.area, *p);
    c.on[0] = true;
    c.blur = blur_on_display(d, dir, glm::length(*p - d.cam.position), dir);
    c.near = inside_part(d.area, c.plane[0], 0.5 * c.blur);
  }
  if (const auto m = hit_part(d.hm, d.cam.position, dir, false)) {
    const glm::dvec3 mirrored = reflect(dir, d.hm.n);
    if (const auto p = hit_part(d.area, *m, mirrored, false)) {
      c.plane[1] = part_local(d.area, *p);
      c.on[1] = true;
      const double travelled = glm::length(*m - d.cam.position) + glm::length(*p - *m);
      const glm::dvec2 blur = blur_on_display(d, dir, travelled, mirrored);
      c.near = c.near || inside_part(d.area, c.plane[1], 0.5 * blur);
      c.blur = glm::max(c.blur, blur);
    }
  }
  return c;
}

// How far apart (mm) two points meet the display's plane, the larger of the direct and the
// mirrored way; 0 when neither way both do.
double apart(const corner& a, const corner& b) {
  double most = 0;
  for (int i = 0; i < 2; ++i) {
    if (a.on[i] && b.on[i]) most = std::max(most, glm::length(a.plane[i] - b.plane[i]));
  }
  return most;
}

// A lower bound on the shortest side (mm) of a pixel's footprint on the display, directly or in the
// half mirror: the pixel's angle times the display's nearest distance from the observer or from its
// mirror image (a slanted view only draws the footprint out).
double shortest_footprint(const planar_parts& d) {
  const double pixel_angle = 2 * d.cam.tan_half_fov / d.cam.height;
  const glm::dvec3 mirrored = mirror_point(d.cam.position, d.hm.center, d.hm.n);
  double nearest = std::numeric_limits<double>::infinity();
  for (const glm::dvec3& eye : {d.cam.position, mirrored}) {
    const glm::dvec2 l = part_local(d.area, eye);
    const glm::dvec2 on(std::clamp(l.x, -0.5 * d.area.width, 0.5 * d.area.width),
                        std::clamp(l.y, -0.5 * d.area.height, 0.5 * d.area.height));
    nearest = std::min(nearest, glm::length(part_point(d.area, on.x, on.y) - eye));
  }
  return nearest * pixel_angle;
}

// Whether two points see the display alike: the same landings, each on the emitting area or off it.
bool alike(const planar_parts& d, const corner& a, const corner& b) {
  if (a.n != b.n) return false;
  for (int i = 0; i < a.n; ++i) {
    if (a.l[i].reflections != b.l[i].reflections || a.l[i].weight != b.l[i].weight ||
        inside_part(d.area, a.l[i].local) != inside_part(d.area, b.l[i].local)) {
      return false;
    }
  }
  return true;
}

// How far apart (mm) a pixel's corners meet the display's plane along x and along y, the larger of
// its two edges each way.
glm::dvec2 footprint_of(const corner (&c)[4]) {
  return {std::max(apart(c[0], c[1]), apart(c[2], c[3])), std::max(apart(c[0], c[2]), apart(c[1], c[3]))};
}

// The points a pixel is sampled at along x and y: at least `k` each, and about one per texel its
// footprint spans (a fine pattern the pixel holds a few periods of leaves a moire that only points
// as dense as its texels catch; a footprint drawn out by a grazing view needs more along its
// length), at most 64 k^2 in all; 16 each where an edge (of the display, its bezel, the half
// mirror, a sheet in the way) crosses the pixel, whose share of it is the pixel's value there.
glm::ivec2 points_per_pixel(const planar_parts& d, const corner (&c)[4], const glm::dvec2& footprint, double texel_mm,
                            int k) {
  const glm::dvec2 along = footprint / texel_mm;
  const bool edge = !alike(d, c[0], c[1]) || !alike(d, c[0], c[2]) || !alike(d, c[0], c[3]);
  const int least = edge ? std::max(k, 16) : k;
  glm::dvec2 wanted = glm::ceil(glm::min(along, glm::dvec2(4096.0)));
  // Over the cap, both ways thinned alike, so the points stay as far apart along the footprint as
  // across it and the texels' level read (level_for) suits both.
  const double cap = 64.0 * k * k;
  if (wanted.x * wanted.y > cap) wanted = glm::floor(wanted * std::sqrt(cap / (wanted.x * wanted.y)));
  return {std::clamp(int(wanted.x), least, 64), std::clamp(int(wanted.y), least, 64)};
}

// The texels' level whose spacing is nearest the pixel's points' (level 0 the finest, each next
// one half as fine): points farther apart than the texels would alias a fine pattern.
std::size_t level_for(double spacing_mm, double texel_mm, std::size_t levels) {
  const double spacing = spacing_mm / texel_mm;
  if (!(spacing > 1)) return 0;
  return std::min(levels - 1, std::size_t(std::lround(std::log2(spacing))));
}

// The display's light along ray r (both landings), on texel level `level`.
glm::dvec3 light_along(const planar_parts& d, const image_rgb& level, const camera_ray& r) {
  landing l[2];
  const int m = follow(d, r.origin, r.dir, l);
  glm::dvec3 sum(0.0);
  for (int a = 0; a < m; ++a) {
    const double profile = emission_at(d.emission.get(), d.area, l[a].dir);
    sum += glm::dvec3(display_radiance(d.area, &level, 1.0f, l[a].local)) * (l[a].weight * profile);
  }
  return sum;
}

// Points on the lens for a pixel's n points: a rank-1 lattice (stratified in both directions)
// visited in a scrambled order, so that the pixel's rows do not share a lens sector. One point
// alone looks through the lens's centre.
struct lens_lattice {
  explicit lens_lattice(int points) : n(points), g(int(0.618 * points) | 1) {
    while (n > 1 && std::gcd(g, n) != 1) ++g;
  }
  glm::dvec2 point(int s) const {
    if (n == 1) return glm::dvec2(0.0);
    const int t = int((std::int64_t(s) * g) % n);
    const double u = (t + 0.5) / n, v = (t + 0.5) * 0.6180339887498949;
    return {u, v - std::floor(v)};
  }
  int n, g;
};

// Pixel (x, y)'s mean light from n points on a grid in the pixel, each with its own lens point
// (the lens moves them by a few of the grid's spacings at most), on the level their spacing suits.
glm::dvec3 grid_mean(const planar_parts& d, const std::vector<image_rgb>& texels, int x, int y,
                     const glm::dvec2& footprint, const glm::ivec2& n, double texel_mm) {
  const image_rgb& level = texels[level_for(std::max(footprint.x / n.x, footprint.y / n.y), texel_mm, texels.size())];
  const lens_lattice lens(n.x * n.y);
  glm::dvec3 sum(0.0);
  for (int j = 0; j < n.y; ++j) {
    for (int i = 0; i < n.x; ++i) {
      // Each point within its own cell, shifted along x by its row and along y by its column: an
      // edge along the pixel's rows or columns then crosses the points one at a time, not a whole
      // row at once, and the pixel's share on either side is found to a point, not to a row.
      const double ox = glm::fract((j + 0.5) * 0.6180339887498949), oy = glm::fract((i + 0.5) * 0.7548776662466927);
      sum += light_along(d, level,
                         make_camera_ray(d.cam, x + (i + ox) / n.x, y + (j + oy) / n.y, lens.point(j * n.x + i)));
    }
  }
  return sum / double(n.x * n.y);
}

// Pixel (x, y)'s mean light where the lens moves a point farther than a few of the grid's
// spacings: points on a grid, each with its own lens point, would land on the display as if at
// random. Points low-discrepancy in the pixel and on the lens together land evenly over the
// footprint widened by the blur, dense enough for a k-th of the blur (at least the grid's n, at
// most 64 k^2 unless the grid has more); off a grid they alias more, so they read the level one
// coarser than their spacing. The kiosk's display seen at a grazing angle (128 x 128, its
// observer's 4 mm pupil): 1.2% RMS of the whole image's mean from the converged parts, against
// 2.5% with the grid.
glm::dvec3 spread_mean(const planar_parts& d, const std::vector<image_rgb>& texels, int x, int y,
                       const glm::dvec2& footprint, const glm::dvec2& blur, const glm::ivec2& n, double texel_mm,
                       int k) {
  const glm::dvec2 reach = footprint + blur;
  const double spacing = std::max(texel_mm, std::min(blur.x, blur.y) / k);
  const double wanted = std::ceil(reach.x / spacing) * std::ceil(reach.y / spacing);
  const double least = double(n.x) * n.y;
  const int count = int(std::clamp(wanted, least, std::max(least, 64.0 * k * k)));
  const std::size_t level =
      std::min(level_for(std::sqrt(reach.x * reach.y / count), texel_mm, texels.size()) + 1, texels.size() - 1);
  glm::dvec3 sum(0.0);
  r4_walk q;
  for (int s = 0; s < count; ++s, q.next()) {
    sum += light_along(d, texels[level], make_camera_ray(d.cam, x + q.u[0], y + q.u[1], {q.u[2], q.u[3]}));
  }
  return sum / double(count);
}

}  // namespace

std::vector<image_rgb> display_parts_texels(const scene& s, const image_rgb* display, int samples_per_side) {
  if (scene_polarizes(s) || samples_per_side < 1) return {};
  const planar_parts d(s);
  const double footprint = shortest_footprint(d);
  if (!(footprint > 0)) return {};
  const double longer_mm = std::max(d.area.width, d.area.height);
  const int longest = display ? std::max(display->width, display->height) : 2;
  const double wanted = std::ceil(longer_mm / (footprint / (8 * samples_per_side)));
  const int texels = int(std::clamp(wanted, 2.0, double(std::min(longest, 4096))));
  cv::Mat m = model_image_steps::display_texels(s, display, texels);
  std::vector<image_rgb> levels;
  for (;;) {
    image_rgb level;
    level.width = m.cols;
    level.height = m.rows;
    level.rgb.assign(m.ptr<float>(0), m.ptr<float>(0) + std::size_t(m.cols) * m.rows * 3);
    levels.push_back(std::move(level));
    if (std::max(m.cols, m.rows) <= 2) break;
    cv::Mat half;
    cv::resize(m, half, cv::Size(std::max(1, m.cols / 2), std::max(1, m.rows / 2)), 0, 0, cv::INTER_AREA);
    m = half;
  }
  return levels;
}

namespace {

// The pixels [x0, x1) x [y0, y1) whose corners the observer may see the display's emitting area
// from, directly or mirrored in the half mirror's plane: those around the projections of its
// corners and of their mirror images (a ray meeting the area either way passes within them), the
// ways from which its front faces the observer. Through a thin lens, a ray from a lens point a
// (|a| <= A / 2) reaches a point at depth z from the pixel a |1 / z - 1 / z_focus| (in tangent)
// from the point's own projection: the box widens by that at the corners' depths (its extremes),
// half as much again for the pixels' points spread over the blur. The whole image when a corner
// lies behind the observer.
struct pixel_box {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
pixel_box pixels_seeing_display(const planar_parts& d) {
  const int w = d.cam.width, h = d.cam.height;
  const pixel_box whole{0, 0, w, h};
  const double lens_radius = 0.5 * d.cam.aperture_mm;
  if (lens_radius > 0 && !(d.cam.focus_distance > 0)) return whole;
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  double defocus = 0;  // the largest |1 / z - 1 / z_focus| at the corners
  for (const bool mirrored : {false, true}) {
    // An observer (or its mirror image) behind the display's plane, its whole lens, sees only the
    // display's back that way.
    const glm::dvec3 eye = mirrored ? mirror_point(d.cam.position, d.hm.center, d.hm.n) : d.cam.position;
    if (!(glm::dot(eye - d.area.center, d.area.n) > -lens_radius)) continue;
    for (const glm::dvec3& c : corners(d.area)) {
      const glm::dvec3 point = mirrored ? mirror_point(c, d.hm.center, d.hm.n) : c;
      const double depth = glm::dot(point - d.cam.position, d.cam.forward);
      if (!(depth > 1e-9)) return whole;
      const glm::dvec2 q = camera_project(d.cam, point);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
      if (lens_radius > 0) defocus = std::max(defocus, std::abs(1 / depth - 1 / d.cam.focus_distance));
    }
  }
  if (!(lo.x <= hi.x)) return {};  // seen from behind both ways
  // A pixel's corners lie at its integer points: a pixel is kept when one of them may lie within,
  // two pixels' margin for rounding.
  const double margin = 2 + 1.5 * lens_radius * defocus * 0.5 * h / d.cam.tan_half_fov;
  auto clamp_to = [](double v, int size) { return int(std::clamp(v, 0.0, double(size))); };
  const pixel_box box{clamp_to(std::floor(lo.x - margin), w), clamp_to(std::floor(lo.y - margin), h),
                      clamp_to(std::ceil(hi.x + margin), w), clamp_to(std::ceil(hi.y + margin), h)};
  return box;
}

}  // namespace

image_rgb display_parts_image(const scene& s, const std::vector<image_rgb>& texels, const model_image_params& p,
                              const std::atomic<bool>* cancel) {
  check_model_image_params(p);
  if (texels.empty() || p.display_samples < 1) return {};
  const planar_parts d(s);
  const int w = d.cam.width, h = d.cam.height, k = p.display_samples;
  image_rgb out;
  out.width = w;
  out.height = h;
  out.rgb.assign(std::size_t(w) * h * 3, 0.0f);
  const double texel_mm = std::min(d.area.width / texels[0].width, d.area.height / texels[0].height);
  const pixel_box box = pixels_seeing_display(d);
  if (box.x1 <= box.x0 || box.y1 <= box.y0) return cancel_requested(cancel) ? image_rgb{} : out;
  const std::size_t columns = std::size_t(box.x1 - box.x0);
  detail::parallel_rows(box.y1 - box.y0, model_image_steps::row_workers_of(p), [&](int r0, int r1) {
    std::vector<corner> top(columns + 1), bottom(columns + 1);
    const int y0 = box.y0 + r0, y1 = box.y0 + r1;
    for (int y = y0; y < y1 && !cancel_requested(cancel); ++y) {
      for (int x = box.x0; x <= box.x1; ++x) {
        if (y == y0) top[std::size_t(x - box.x0)] = corner_at(d, x, y);
        bottom[std::size_t(x - box.x0)] = corner_at(d, x, y + 1);
      }
      for (int x = box.x0; x < box.x1; ++x) {
        const std::size_t i = std::size_t(x - box.x0);
        const corner c[4] = {top[i], top[i + 1], bottom[i], bottom[i + 1]};
        // A pixel whose corners see no display, nor come within the lens's blur of it, is taken to
        // see none (a display smaller than a pixel, or a corner of it between pixel corners, is
        // missed).
        if (c[0].n == 0 && c[1].n == 0 && c[2].n == 0 && c[3].n == 0 && !c[0].near && !c[1].near && !c[2].near &&
            !c[3].near) {
          continue;
        }
        const glm::dvec2 footprint = footprint_of(c);
        const glm::ivec2 n = points_per_pixel(d, c, footprint, texel_mm, k);
        const glm::dvec2 blur = glm::max(glm::max(c[0].blur, c[1].blur), glm::max(c[2].blur, c[3].blur));
        // A lens moving points by up to a few of the grid's spacings only jitters the grid.
        const bool spread = blur.x > 4 * footprint.x / n.x || blur.y > 4 * footprint.y / n.y;
        const glm::dvec3 mean = spread ? spread_mean(d, texels, x, y, footprint, blur, n, texel_mm, k)
                                       : grid_mean(d, texels, x, y, footprint, n, texel_mm);
        float* o = out.rgb.data() + 3 * (std::size_t(y) * w + x);
        for (int c3 = 0; c3 < 3; ++c3) o[c3] = float(mean[c3]);
      }
      std::swap(top, bottom);
    }
  });
  if (cancel_requested(cancel)) return {};
  return out;
}

}  // namespace airr
