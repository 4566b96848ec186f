#pragma once
// A flat rectangular prop for tests: where it stands, whether a segment crosses it, and the glTF
// file a modeller would export of it.
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "gltf_builder.hpp"

namespace airr::test {

// An axis-aligned rectangle in world millimetres: `axis` is the coordinate it is constant in.
struct plate {
  int axis = 1;
  double at = 0;
  double lo[2] = {0, 0}, hi[2] = {0, 0};  // the other two coordinates, in x, y, z order

  plate(int axis_, double at_, double lo0, double hi0, double lo1, double hi1) : axis(axis_), at(at_) {
    lo[0] = lo0, hi[0] = hi0, lo[1] = lo1, hi[1] = hi1;
  }

  // Whether the segment a -> b crosses the plate grown by `grow` mm on every side.
  bool crossed_by(const glm::dvec3& a, const glm::dvec3& b, double grow) const {
    if ((a[axis] - at) * (b[axis] - at) >= 0) return false;
    const glm::dvec3 p = a + (at - a[axis]) / (b[axis] - a[axis]) * (b - a);
    int k = 0;
    for (int i = 0; i < 3; ++i) {
      if (i == axis) continue;
      if (p[i] < lo[k] - grow || p[i] > hi[k] + grow) return false;
      ++k;
    }
    return true;
  }
};

// Writes the plate as a glTF file the way a modeller exports it: metres, the quad in a child
// node's own coordinates under a translated parent.
inline void write_plate(const plate& pl, const std::string& path) {
  test::gltf_builder b;
  const int u = pl.axis == 0 ? 1 : 0, v = pl.axis == 2 ? 1 : 2;
  std::vector<float> xyz;
  for (const auto& [i, j] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
    glm::dvec3 p(0.0);
    p[u] = (i ? pl.hi[0] : pl.lo[0]) / 1000;
    p[v] = (j ? pl.hi[1] : pl.lo[1]) / 1000;
    for (int c = 0; c < 3; ++c) xyz.push_back(float(p[c]));
  }
  const int mesh = b.add_mesh({{b.add_positions(xyz), b.add_indices({0, 1, 2, 0, 2, 3}, 5121), -1}});
  glm::dvec3 offset(0.0);
  offset[pl.axis] = pl.at / 1000;
  const int parent = b.add_node({{"name", "housing"}, {"translation", {offset.x, offset.y, offset.z}}});
  b.add_node({{"name", "hood"}, {"mesh", mesh}}, parent);
  b.write(path, test::gltf_builder::storage::glb);
}

}  // namespace airr::test
