#pragma once
// The aerial image's outline as a camera sees it, for measures taken inside it (the stray-light
// ratio, the ghost table, the ghost metrics), and where in a camera's image light gathers.
#include <array>

#include <glm/glm.hpp>

#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// The aerial image's four corners projected into `cam`'s image (pixels from the top-left corner).
std::array<glm::dvec2, 4> aerial_outline(const scene& s, const pinhole_camera& cam);

// Whether image point (x, y) lies inside the convex quadrilateral q (either winding).
bool inside_quad(const std::array<glm::dvec2, 4>& q, double x, double y);

// An image's luminance-weighted centroid, in pixels (NaN when it is dark; negative values count 0).
glm::dvec2 luminance_centroid(const image_rgb& img);

// The angle between the directions `cam` sees at image points a and b, in arcmin.
double separation_arcmin(const pinhole_camera& cam, const glm::dvec2& a, const glm::dvec2& b);

}  // namespace airr
