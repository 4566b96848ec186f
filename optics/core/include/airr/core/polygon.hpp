#pragma once
// Convex polygons in a plane, vertices counter-clockwise.
#include <vector>

#include <glm/glm.hpp>

namespace airr {

using polygon2 = std::vector<glm::dvec2>;

double polygon_area(const polygon2& p);
double polygon_perimeter(const polygon2& p);
// A polygon's area, centroid and second moments about the centroid, the integral of (x - c)(x - c)^T
// over it (for a w x h rectangle, area w^2 / 12 and area h^2 / 12 on the diagonal).
struct polygon_moments {
  double area = 0;
  glm::dvec2 centroid{0};
  glm::dmat2 spread{0};
};
polygon_moments moments(const polygon2& p);
// The part of convex `subject` inside convex `clip` (empty when they do not overlap).
polygon2 clip_convex_polygon(const polygon2& subject, const polygon2& clip);
// The convex hull of points, counter-clockwise (collinear points dropped; empty below 3 corners).
polygon2 convex_hull(polygon2 points);

}  // namespace airr
