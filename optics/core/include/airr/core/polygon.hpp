#pragma once
// Convex polygons in a plane, vertices counter-clockwise.
#include <vector>

#include <glm/glm.hpp>

namespace airr {

using polygon2 = std::vector<glm::dvec2>;

double polygon_area(const polygon2& p);
double polygon_perimeter(const polygon2& p);
// The part of convex `subject` inside convex `clip` (empty when they do not overlap).
polygon2 clip_convex_polygon(const polygon2& subject, const polygon2& clip);

}  // namespace airr
