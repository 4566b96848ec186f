#include "airr/core/polygon.hpp"

#include <algorithm>
#include <cmath>

namespace airr {

double polygon_area(const polygon2& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const glm::dvec2 &u = p[i], &v = p[i + 1 < p.size() ? i + 1 : 0];
    a += u.x * v.y - u.y * v.x;
  }
  return 0.5 * std::abs(a);
}

double polygon_perimeter(const polygon2& p) {
  double l = 0;
  for (std::size_t i = 0; i < p.size(); ++i) l += glm::length(p[i + 1 < p.size() ? i + 1 : 0] - p[i]);
  return l;
}

polygon_moments moments(const polygon2& p) {
  // Green's theorem over the edges, about the first corner (no cancellation far from the origin).
  polygon_moments m;
  if (p.empty()) return m;
  const glm::dvec2 o = p[0];
  double a = 0, sx = 0, sy = 0, ixx = 0, iyy = 0, ixy = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const glm::dvec2 u = p[i] - o, v = p[i + 1 < p.size() ? i + 1 : 0] - o;
    const double c = u.x * v.y - v.x * u.y;
    a += c;
    sx += (u.x + v.x) * c;
    sy += (u.y + v.y) * c;
    ixx += (u.x * u.x + u.x * v.x + v.x * v.x) * c;
    iyy += (u.y * u.y + u.y * v.y + v.y * v.y) * c;
    ixy += (u.x * v.y + 2 * u.x * u.y + 2 * v.x * v.y + v.x * u.y) * c;
  }
  a /= 2;
  if (a == 0) return m;
  const glm::dvec2 c(sx / (6 * a), sy / (6 * a));  // about o
  m.area = std::abs(a);
  m.centroid = o + c;
  const double sign = a > 0 ? 1 : -1;
  const double jxx = sign * ixx / 12 - m.area * c.x * c.x, jyy = sign * iyy / 12 - m.area * c.y * c.y;
  const double jxy = sign * ixy / 24 - m.area * c.x * c.y;
  m.spread = glm::dmat2(jxx, jxy, jxy, jyy);
  return m;
}

polygon2 clip_convex_polygon(const polygon2& subject, const polygon2& clip) {
  // Each clip edge adds at most one vertex: two buffers of that size, swapped (the second kept per
  // thread: sheets clip apertures once or twice per path).
  thread_local polygon2 next;
  polygon2 out;
  out.reserve(subject.size() + clip.size());
  next.reserve(subject.size() + clip.size());
  out = subject;
  for (std::size_t i = 0; i < clip.size() && !out.empty(); ++i) {
    const glm::dvec2 a = clip[i], b = clip[i + 1 < clip.size() ? i + 1 : 0];
    auto side = [&](const glm::dvec2& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    next.clear();
    for (std::size_t j = 0; j < out.size(); ++j) {
      const glm::dvec2 p = out[j], q = out[j + 1 < out.size() ? j + 1 : 0];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) next.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    std::swap(out, next);
  }
  if (out.size() < 3) out.clear();
  return out;
}

polygon2 convex_hull(polygon2 points) {
  // Andrew's monotone chain.
  std::sort(points.begin(), points.end(),
            [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3) return {};
  auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  polygon2 hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  if (hull.size() < 3) hull.clear();
  return hull;
}

}  // namespace airr
