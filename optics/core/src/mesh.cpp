#include "airr/core/mesh.hpp"

namespace airr {

triangle_mesh make_unit_panel() {
  triangle_mesh m;
  m.name = "panel";
  m.positions = {{-0.5f, -0.5f, 0.f}, {0.5f, -0.5f, 0.f}, {0.5f, 0.5f, 0.f}, {-0.5f, 0.5f, 0.f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

mesh_bounds bounds_of(const triangle_mesh& mesh) {
  if (mesh.positions.empty()) return {};
  mesh_bounds b{mesh.positions.front(), mesh.positions.front()};
  for (const auto& p : mesh.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

}  // namespace airr
