#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/models/tile_sheet.hpp"

namespace airr {

namespace {

// Union-find over triangles.
int root_of(std::vector<int>& parent, int i) {
  while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
  return i;
}

}  // namespace

tile_structure::tile_structure(const tile_sheet_geometry& g) {
  const std::string& file = g.tile_file;
  if (!g.tile || g.tile->indices.empty()) throw input_error(file + ": the tile has no triangles");
  const triangle_mesh& m = *g.tile;
  for (const glm::vec3& p : m.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw input_error(file + ": the tile has a vertex that is not a finite number");
  if (!(g.period_mm.x > 0 && g.period_mm.y > 0)) throw input_error(file + ": the tile's period must be positive");
  const mesh_bounds b = bounds_of(m);
  const double reach = 1e-6 * std::max(g.period_mm.x, g.period_mm.y);
  for (int k = 0; k < 2; ++k) {
    const double p = g.period_mm[k];
    if (b.lo[k] < -p + reach || b.hi[k] > 2 * p - reach)
      throw input_error(file + ": the tile reaches " + std::string(k ? "y" : "x") + " from " + number_text(b.lo[k]) +
                        " to " + number_text(b.hi[k]) + " mm, more than a period (" + number_text(p) +
                        " mm) beyond its cell [0, " + number_text(p) + ")");
  }
  top_ = b.hi.z;
  bottom_ = b.lo.z;
  if (!(top_ - bottom_ > reach)) throw input_error(file + ": the tile is flat (no depth to reflect in)");

  // Faces: coplanar triangles sharing an edge.
  const std::size_t n = m.indices.size() / 3;
  std::vector<glm::dvec3> normal(n);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto vertex = [&](std::size_t t, int k) { return glm::dvec3(m.positions[m.indices[3 * t + std::size_t(k)]]); };
  auto key = [&](const glm::dvec3& v) {
    return std::make_tuple(std::llround(v.x / reach), std::llround(v.y / reach), std::llround(v.z / reach));
  };
  using vertex_key = decltype(key(glm::dvec3(0)));
  std::map<std::pair<vertex_key, vertex_key>, int> edges;
  triangle_mesh kept;
  std::vector<std::size_t> kept_triangle;  // Embree's triangle -> the mesh's
  for (std::size_t t = 0; t < n; ++t) {
    const glm::dvec3 c = glm::cross(vertex(t, 1) - vertex(t, 0), vertex(t, 2) - vertex(t, 0));
    if (glm::length(c) <= reach * reach) {
      parent[t] = -1;  // degenerate: not traced
      continue;
    }
    normal[t] = glm::normalize(c);
    for (int k = 0; k < 3; ++k) {
      auto a = key(vertex(t, k)), z = key(vertex(t, (k + 1) % 3));
      if (z < a) std::swap(a, z);
      const auto [it, fresh] = edges.emplace(std::make_pair(a, z), int(t));
      if (fresh) continue;
      const std::size_t other = std::size_t(it->second);
      const bool coplanar = std::abs(glm::dot(normal[t], normal[other])) > 1 - 1e-6 &&
                            std::abs(glm::dot(normal[other], vertex(t, 0) - vertex(other, 0))) < reach;
      if (coplanar) parent[std::size_t(root_of(parent, int(t)))] = root_of(parent, int(other));
    }
    for (int k = 0; k < 3; ++k) kept.positions.push_back(m.positions[m.indices[3 * t + std::size_t(k)]]);
    for (std::uint32_t k = 0; k < 3; ++k) kept.indices.push_back(std::uint32_t(3 * kept_triangle.size()) + k);
    kept_triangle.push_back(t);
  }
  if (kept_triangle.empty()) throw input_error(file + ": every triangle of the tile is degenerate");

  std::map<int, int> face_of_root;
  std::vector<std::vector<std::size_t>> members;
  for (std::size_t t : kept_triangle) {
    const int r = root_of(parent, int(t));
    const auto [it, fresh] = face_of_root.emplace(r, int(members.size()));
    if (fresh) members.emplace_back();
    members[std::size_t(it->second)].push_back(t);
  }
  for (const auto& group : members) {
    face f;
    glm::dvec3 sum(0);
    for (std::size_t t : group)
      sum += normal[t] * (glm::dot(normal[t], normal[group.front()]) < 0 ? -1.0 : 1.0) *
             glm::length(glm::cross(vertex(t, 1) - vertex(t, 0), vertex(t, 2) - vertex(t, 0)));
    f.normal = glm::normalize(sum);
    const basis plane = make_basis(f.normal);
    polygon2 in_plane;
    double offset = 0;
    for (std::size_t t : group)
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 v = vertex(t, k);
        in_plane.emplace_back(glm::dot(v, plane.t), glm::dot(v, plane.b));
        offset += glm::dot(v, f.normal);
      }
    f.offset = offset / double(3 * group.size());
    for (const glm::dvec2& q : convex_hull(in_plane))
      f.outline.push_back(q.x * plane.t + q.y * plane.b + f.offset * f.normal);
    const std::size_t t0 = group.front();
    if (t0 < m.triangle_materials.size() && m.triangle_materials[t0] < m.materials.size()) {
      const mesh_material& mat = m.materials[m.triangle_materials[t0]];
      if (mat.metallic >= 0.5f) f.metal_reflectance = (mat.base_color.r + mat.base_color.g + mat.base_color.b) / 3.0;
    }
    faces_.push_back(f);
  }
  triangle_face_.assign(kept_triangle.size(), -1);
  for (std::size_t k = 0; k < kept_triangle.size(); ++k)
    triangle_face_[k] = face_of_root.at(root_of(parent, int(kept_triangle[k])));

  // The tile over its cell and the eight around it: a ray crossing the cell meets every triangle
  // that reaches into it.
  auto shared = std::make_shared<const triangle_mesh>(std::move(kept));
  std::vector<instance_mesh> instances(9, instance_mesh{"tile", shared});
  instanced_ = std::make_unique<embree_instanced_scene>(device_, instances);
  std::vector<glm::dmat4> moves;
  for (unsigned i = 0; i < 9; ++i) {
    const glm::dvec2 o = instance_offset(i) * g.period_mm;
    glm::dmat4 t(1.0);
    t[3] = glm::dvec4(o, 0, 1);
    moves.push_back(t);
  }
  instanced_->set_transforms(moves);
}

tile_structure::~tile_structure() = default;

RTCScene tile_structure::scene() const { return instanced_->get(); }

std::size_t tile_structure::memory_bytes() const { return device_.bytes_in_use(); }

int tile_structure::face_of(unsigned triangle) const { return triangle_face_.at(triangle); }

glm::dvec2 tile_structure::instance_offset(unsigned instance) const {
  return {double(int(instance % 3) - 1), double(int(instance / 3) - 1)};
}

}  // namespace airr
