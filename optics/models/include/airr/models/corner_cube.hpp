#pragma once
// The triangular cube corner of spec section 3: apex at the origin, mirror faces on the planes
// x = 0, y = 0, z = 0, cut by the aperture plane x + y + z = 1 (edge length 1.0).
#include "airr/core/mesh.hpp"

namespace airr {

// Three right-isosceles triangles, one per face, normals pointing into the corner.
triangle_mesh make_corner_cube();

}  // namespace airr
