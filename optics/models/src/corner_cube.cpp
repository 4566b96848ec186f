#include "airr/models/corner_cube.hpp"

namespace airr {

triangle_mesh make_corner_cube() {
  triangle_mesh m;
  m.name = "corner_cube";
  m.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, {0.f, 0.f, 1.f}};
  m.indices = {0, 2, 3,   // x = 0
               0, 3, 1,   // y = 0
               0, 1, 2};  // z = 0
  return m;
}

}  // namespace airr
