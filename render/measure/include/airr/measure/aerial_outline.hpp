#pragma once
// The aerial image's outline as a camera sees it, for measures taken inside it (the stray-light
// ratio, the ghost table).
#include <array>

#include <glm/glm.hpp>

#include "airr/layout/layout.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// The aerial image's four corners projected into `cam`'s image (pixels from the top-left corner).
std::array<glm::dvec2, 4> aerial_outline(const scene& s, const pinhole_camera& cam);

// Whether image point (x, y) lies inside the convex quadrilateral q (either winding).
bool inside_quad(const std::array<glm::dvec2, 4>& q, double x, double y);

}  // namespace airr
