#pragma once
// The triangular cube corner of spec section 3: apex at the origin, mirror faces on the planes
// x = 0, y = 0, z = 0, cut by the aperture plane x + y + z = 1 (edge length 1.0).
#include <array>
#include <complex>

#include "airr/core/mesh.hpp"
#include "airr/models/polarization.hpp"

namespace airr {

// Three right-isosceles triangles, one per face, normals pointing into the corner.
triangle_mesh make_corner_cube();

// The tile sheet's shipped tile (tile_sheet.hpp), in metres as glTF files are: the prism sheet's
// triangular cube corners at `pitch_mm`, azimuth 0 (ridges at z = 0, apexes below), over the
// cell [0, 2 pitch / sqrt 3) x [0, 2 pitch): the four cube corners whose apexes lie in it, each of
// three triangular faces.
triangle_mesh make_corner_cube_tile(double pitch_mm);

// Polarized light along in.k reflected by a cube corner's three faces (unit normals) in the order
// given, each with the Fresnel amplitudes of relative index `eta` (1 / index for total internal
// reflection, the coat's index / the prism's for a metal coat): the Mueller matrix from frame `in`
// to the returned frame of the light leaving.
polarized_step cube_corner_polarized(const polarization_frame& in, const std::array<glm::dvec3, 3>& faces,
                                     std::complex<double> eta);

}  // namespace airr
