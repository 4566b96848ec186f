// The pixels' ideal paths: camera, half mirror, a sheet straight back, display.
#include "model_image_steps.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "airr/core/cancel.hpp"
#include "airr/core/geometry.hpp"
#include "airr/render/parallel_rows.hpp"

namespace airr::model_image_steps {

std::optional<ideal_path> trace_ideal(const ideal_parts& parts, double px, double py) {
  const glm::dvec3 d = camera_direction(parts.cam, px, py);
  const ideal_return r = follow_ideal_return(parts.hm, parts.rr, parts.src, parts.cam.position, d, parts.by_reflection);
  if (r.failed != ideal_return::step::none) return std::nullopt;
  if (glm::dot(r.towards_display, parts.src.n) >= 0) return std::nullopt;  // the display's back
  const auto p = hit_part(parts.aerial, parts.cam.position, d, false);
  if (!p) return std::nullopt;
  const glm::dvec3 wi = -to_local(parts.rr, r.towards_sheet);
  return ideal_path{part_local(parts.src, r.landing), *p, r.towards_display, wi, polar_angle_deg(wi)};
}

// The display-plane step across one pixel along `step`: from the paths half a pixel either side,
// or, where one of them misses (a pixel at the region of paths' edge), from the other and the
// pixel's own; nullopt when both miss.
static std::optional<glm::dvec2> footprint_column(const ideal_parts& parts, const std::optional<ideal_path>& centre,
                                                  double px, double py, const glm::dvec2& step) {
  const auto ahead = trace_ideal(parts, px + 0.5 * step.x, py + 0.5 * step.y);
  const auto behind = trace_ideal(parts, px - 0.5 * step.x, py - 0.5 * step.y);
  if (ahead && behind) return ahead->display - behind->display;
  if (!centre) return std::nullopt;
  if (ahead) return 2.0 * (ahead->display - centre->display);
  if (behind) return 2.0 * (centre->display - behind->display);
  return std::nullopt;
}

glm::dmat2 pixel_footprint(const ideal_parts& parts, double px, double py) {
  const auto centre = trace_ideal(parts, px, py);
  const auto x = footprint_column(parts, centre, px, py, {1, 0}), y = footprint_column(parts, centre, px, py, {0, 1});
  if (!(x && y)) return glm::dmat2(0.0);
  return glm::dmat2(*x, *y);
}

static pixel_path pixel_ideal(const ideal_parts& parts, const emission_profile* emission, double x, double y) {
  const auto path = trace_ideal(parts, x, y);
  if (!path) return {};
  pixel_path out{true, path->display, path->wi, 1.0};
  out.profile = emission_at(emission, parts.src, path->towards_display);
  return out;
}

// A pixel's path on the grids.
static model_pixel mapped(const pixel_path& path, const grid_mapping (&maps)[2], const model_grid& tail) {
  model_pixel px;
  if (!path.ok) return px;
  for (int g : {model_fine, model_tail}) px.node[g] = glm::vec2(maps[g].node(path.display));
  // Landing outside the tail's padded grid, it is farther from the display than any kernel
  // offset. (Outside the fine grid, only the fine part sees nothing, in both uses alike.)
  const glm::dvec2 t = px.node[model_tail];
  px.ok = t.x >= 0 && t.y >= 0 && t.x < tail.padded.width - 1 && t.y < tail.padded.height - 1;
  px.theta_deg = float(polar_angle_deg(glm::normalize(path.wi)));
  px.profile = float(path.profile);
  return px;
}

model_pixel pixel_path_at(const ideal_parts& parts, const emission_profile* emission, const grid_mapping (&maps)[2],
                          const model_grid& tail, int x, int y) {
  return mapped(pixel_ideal(parts, emission, x + 0.5, y + 0.5), maps, tail);
}

pixel_angle_map pixel_angles(const ideal_parts& parts, const emission_profile* emission, const model_image_params& p,
                             const grid_mapping (&maps)[2], const model_grid& fine, const model_grid& tail,
                             const std::atomic<bool>* cancel) {
  const int w = parts.cam.width, h = parts.cam.height;
  pixel_angle_map out;
  out.theta_deg.resize(std::size_t(w) * h);
  out.on_fine_grid.resize(std::size_t(w) * h);
  detail::parallel_rows(h, row_workers_of(p), [&](int y0, int y1) {
    for (int y = y0; y < y1 && !cancel_requested(cancel); ++y) {
      for (int x = 0; x < w; ++x) {
        const model_pixel px = pixel_path_at(parts, emission, maps, tail, x, y);
        out.theta_deg[std::size_t(y) * w + x] = px.ok ? px.theta_deg : std::numeric_limits<float>::quiet_NaN();
        out.on_fine_grid[std::size_t(y) * w + x] = lands_on_fine_grid(px, fine);
      }
    }
  });
  if (cancel_requested(cancel)) return {};
  return out;
}

std::vector<model_pixel> pixel_paths(const ideal_parts& parts, const emission_profile* emission,
                                     const model_image_params& p, const grid_mapping (&maps)[2], const model_grid& tail,
                                     const std::atomic<bool>* cancel) {
  const int w = parts.cam.width, h = parts.cam.height;
  const int n =
      p.least_paths > 0 ? std::min(p.path_stride, std::max(1, std::min(w, h) / p.least_paths)) : p.path_stride;
  std::vector<model_pixel> out(std::size_t(w) * h);
  if (n <= 1) {
    detail::parallel_rows(h, row_workers_of(p), [&](int y0, int y1) {
      for (int y = y0; y < y1 && !cancel_requested(cancel); ++y) {
        for (int x = 0; x < w; ++x) out[std::size_t(y) * w + x] = pixel_path_at(parts, emission, maps, tail, x, y);
      }
    });
    if (cancel_requested(cancel)) return {};
    return out;  // moved (a conditional expression would copy it)
  }
  // Lattice node i sits on pixel min(i n, size - 1).
  const int lw = (w - 1 + n - 1) / n + 1, lh = (h - 1 + n - 1) / n + 1;
  auto at = [n](int i, int size) { return std::min(i * n, size - 1); };
  std::vector<pixel_path> lattice(std::size_t(lw) * lh);
  detail::parallel_rows(lh, row_workers_of(p), [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j) {
      for (int i = 0; i < lw; ++i) {
        lattice[std::size_t(j) * lw + i] = pixel_ideal(parts, emission, at(i, w) + 0.5, at(j, h) + 0.5);
      }
    }
  });
  // A cell whose corners and their neighbours all miss lies outside the region of paths: paths are
  // projective, and a region reaching into such a cell would reach past a neighbour too.
  auto node_ok = [&](int i, int j) {
    return lattice[std::size_t(std::clamp(j, 0, lh - 1)) * lw + std::clamp(i, 0, lw - 1)].ok;
  };
  std::vector<char> near_paths(std::size_t(lw) * lh, 0);
  for (int j = 0; j < lh; ++j) {
    for (int i = 0; i < lw; ++i) {
      for (int dj = -1; dj <= 2 && !near_paths[std::size_t(j) * lw + i]; ++dj) {
        for (int di = -1; di <= 2; ++di) near_paths[std::size_t(j) * lw + i] |= node_ok(i + di, j + dj);
      }
    }
  }
  detail::parallel_rows(h, row_workers_of(p), [&](int y0, int y1) {
    for (int y = y0; y < y1 && !cancel_requested(cancel); ++y) {
      const int j = std::min(y / n, std::max(0, lh - 2)), ya = at(j, h), yb = at(j + 1, h);
      const double fy = yb > ya ? double(y - ya) / (yb - ya) : 0.0;
      for (int x = 0; x < w; ++x) {
        const int i = std::min(x / n, std::max(0, lw - 2)), xa = at(i, w), xb = at(i + 1, w);
        const double fx = xb > xa ? double(x - xa) / (xb - xa) : 0.0;
        const int i1 = std::min(i + 1, lw - 1), j1 = std::min(j + 1, lh - 1);
        const pixel_path* c[4] = {&lattice[std::size_t(j) * lw + i], &lattice[std::size_t(j) * lw + i1],
                                  &lattice[std::size_t(j1) * lw + i], &lattice[std::size_t(j1) * lw + i1]};
        model_pixel& out_px = out[std::size_t(y) * w + x];
        if (!(c[0]->ok && c[1]->ok && c[2]->ok && c[3]->ok)) {
          if (near_paths[std::size_t(j) * lw + i])
            out_px = mapped(pixel_ideal(parts, emission, x + 0.5, y + 0.5), maps, tail);
          continue;
        }
        const double cw[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        pixel_path px;
        px.ok = true;
        px.display = glm::dvec2(0);
        px.wi = glm::dvec3(0);
        px.profile = 0;
        for (int k = 0; k < 4; ++k) {
          px.display += cw[k] * c[k]->display;
          px.wi += cw[k] * c[k]->wi;
          px.profile += cw[k] * c[k]->profile;
        }
        out_px = mapped(px, maps, tail);
      }
    }
  });
  if (cancel_requested(cancel)) return {};
  return out;  // moved (a conditional expression would copy it)
}

}  // namespace airr::model_image_steps
