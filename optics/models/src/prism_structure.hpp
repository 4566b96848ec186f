#pragma once
// The prism sheet's grooved back, as its tracer walks it (prism_sheet.cpp: triangular cube
// corners; prism_full_cube.cpp: full cubes).
#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "airr/core/polygon.hpp"
#include "airr/models/prism_sheet.hpp"
#include "plate_walk.hpp"

namespace airr {

// Full cubes: the glass is the union of the cube lattice's cells (edge: the cube edge, axes the
// three cube axes, whose sum is the sheet normal) with index sum i + j + k >= 0, so every lattice
// point of sum 0 is the apex of a cube corner of three square faces, seen from the glass. The ray
// from p along d walks the lattice's cells (their index sum changes by one at each step) until it
// crosses from glass into air or back, or leaves the slab (sum 2 at the ridges, 0 at the apexes).
stretch_end follow_full_cubes(const prism_sheet_geometry& g, const glm::dvec3& p, const glm::dvec3& d, bool in_plate);

// A cube corner seen along d (inside, d.z < 0), in the plane its aperture is measured in: where
// the line through its apex along d meets that plane, and the ends of its three edges there (the
// aperture triangle's vertices; a full cube's projected edges). Triangular: about the triangle's
// centroid at the ridges; full cubes: about the apex, in its plane.
struct corner_view {
  glm::dvec2 apex{0};
  std::array<glm::dvec2, 3> edge_ends{};
};
corner_view full_cube_corner_view(const prism_sheet_geometry& g, const glm::dvec3& d);
corner_view triangular_corner_view(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing);

// The part of a cube corner's effective aperture whose light meets the faces in the same order as
// light entering at `entry` (same plane and origin as `view`): the six face orders divide the
// aperture along its edges' lines through the apex, each part a quadrilateral at normal incidence.
polygon2 face_order_aperture(const polygon2& effective, const corner_view& view, const glm::dvec2& entry);

}  // namespace airr
