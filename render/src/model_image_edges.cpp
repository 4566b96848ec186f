// The display's edges on a grid whose edges lie on node lines: there a prediction steps to black as
// the tracer's display does, where the grid's bilinear surface would ramp to black over a node (a
// bright edge's samples then differed from their predictions by up to the edge's radiance, two
// thirds of the default scene's noise).
#include <algorithm>
#include <array>
#include <cmath>

#include "model_image_steps.hpp"

namespace airr::model_image_steps {

namespace {

// The display's extent in the padded grid's node coordinates.
struct node_box {
  double x0, y0, x1, y1;
  explicit node_box(const model_grid& g)
      : x0(g.radius), y0(g.radius), x1(g.padded.width - 1 - g.radius), y1(g.padded.height - 1 - g.radius) {}
  bool holds(const glm::dvec2& p) const { return p.x >= x0 && p.y >= y0 && p.x <= x1 && p.y <= y1; }
};

// Whether the cell of nodes with first corner `c` reaches beyond the display and comes within a
// node of it: there the bilinear surface ramps where the display steps.
bool edge_cell(const node_box& d, const glm::dvec2& c) {
  const bool beyond = c.x < d.x0 || c.y < d.y0 || c.x + 1 > d.x1 || c.y + 1 > d.y1;
  const bool near = c.x > d.x0 - 2 && c.y > d.y0 - 2 && c.x < d.x1 + 1 && c.y < d.y1 + 1;
  return beyond && near;
}

int cell_of(double t, int radius) { return std::clamp(int(std::floor(t)), -radius, radius - 1); }

// The cells (offsets from a pixel's ideal point `b`) whose first corner lies within two nodes before
// the edge at `lo` or one node either side of the edge at `hi` along one axis (edge_cell's bounds:
// the sums are exact in double), in ascending order: at most two of each.
struct cell_list {
  std::array<int, 4> at{};
  int count = 0;
  const int* begin() const { return at.data(); }
  const int* end() const { return at.data() + count; }
};
cell_list edge_cells(double b, double lo, double hi, int radius) {
  cell_list out;
  for (const auto& [from, to] : {std::pair{lo - 2, lo}, std::pair{hi - 1, hi + 1}}) {
    for (int n = int(std::floor(from - b)) + 1; n < to - b; ++n) {
      if (n >= -radius && n < radius && (out.count == 0 || n > out.at[std::size_t(out.count - 1)]) && out.count < 4)
        out.at[std::size_t(out.count++)] = n;
    }
  }
  return out;
}

// The display itself at node point `p`: black beyond its edges.
glm::vec3 display_at(const model_grid& grid, const node_box& d, const glm::dvec2& p) {
  return d.holds(p) ? bilinear(grid.padded, p) : glm::vec3(0.0f);
}

}  // namespace

glm::vec3 grid_value(const model_grid& grid, const glm::dvec2& base, const glm::dvec2& t) {
  if (grid.edges_on_nodes) {
    const node_box d(grid);
    if (edge_cell(d, base + glm::floor(t))) return display_at(grid, d, base + t);
  }
  return spread_bilinear(grid, base, t);
}

edge_samples sort_edge_samples(const std::vector<fine_sample>& fine, int radius, std::uint64_t drawn) {
  edge_samples out;
  out.radius = radius;
  out.drawn = drawn;
  auto sort_by = [&](auto key, std::vector<fine_sample>& sorted, std::vector<std::uint32_t>& start) {
    start.assign(std::size_t(2 * radius + 2), 0);
    for (const fine_sample& f : fine) ++start[std::size_t(key(f) + radius + 1)];
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    sorted.resize(fine.size());
    for (const fine_sample& f : fine) sorted[next[std::size_t(key(f) + radius)]++] = f;
  };
  sort_by([&](const fine_sample& f) { return cell_of(f.t.x, radius); }, out.by_column, out.column_start);
  sort_by([&](const fine_sample& f) { return cell_of(f.t.y, radius); }, out.by_row, out.row_start);
  return out;
}

glm::vec3 edge_correction(const model_grid& fine, const edge_samples& s, const glm::dvec2& base) {
  const node_box d(fine);
  glm::dvec3 sum(0.0);
  auto add = [&](const fine_sample& f) {
    if (!edge_cell(d, base + glm::floor(f.t))) return;  // grid_value is spread_bilinear there
    sum += glm::dvec3(display_at(fine, d, base + f.t) - spread_bilinear(fine.padded, base, f.t)) * f.w;
  };
  // Samples of cells reaching beyond a left or right edge by column, then the others beyond the
  // top or bottom by row; elsewhere grid_value is spread_bilinear and adds nothing.
  const cell_list columns = edge_cells(base.x, d.x0, d.x1, s.radius);
  for (int c : columns) {
    const std::size_t i = std::size_t(c + s.radius);
    for (std::uint32_t k = s.column_start[i]; k < s.column_start[i + 1]; ++k) add(s.by_column[k]);
  }
  for (int c : edge_cells(base.y, d.y0, d.y1, s.radius)) {
    const std::size_t i = std::size_t(c + s.radius);
    for (std::uint32_t k = s.row_start[i]; k < s.row_start[i + 1]; ++k) {
      const fine_sample& f = s.by_row[k];
      if (!std::binary_search(columns.begin(), columns.end(), cell_of(f.t.x, s.radius))) add(f);
    }
  }
  return glm::vec3(sum / double(s.drawn));
}

}  // namespace airr::model_image_steps
