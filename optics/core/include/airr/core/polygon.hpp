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
// The convex hull of points, counter-clockwise (collinear points dropped; empty below 3 corners).
polygon2 convex_hull(polygon2 points);

}  // namespace airr
