#pragma once
// An independent visible fraction for tests: the aerial-image rectangle clipped by the central
// projections, from the eye, of the half mirror's and the first sheet's rectangles onto the
// aerial-image plane (convex polygon clipping, no ray following). It holds while the display and
// the parts' other apertures do not cut the view.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "airr/layout/layout.hpp"

namespace airr::test {

using polygon = std::vector<glm::dvec2>;

inline double signed_area(const polygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const glm::dvec2 &u = p[i], &v = p[(i + 1) % p.size()];
    a += u.x * v.y - v.x * u.y;
  }
  return 0.5 * a;
}

// Sutherland-Hodgman: `subject` clipped by the convex, counter-clockwise `clip`.
inline polygon clip_convex(const polygon& subject, const polygon& clip) {
  polygon out = subject;
  for (std::size_t e = 0; e < clip.size() && !out.empty(); ++e) {
    const glm::dvec2 a = clip[e], b = clip[(e + 1) % clip.size()];
    auto side = [&](const glm::dvec2& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    const polygon in = out;
    out.clear();
    for (std::size_t i = 0; i < in.size(); ++i) {
      const glm::dvec2 p = in[i], q = in[(i + 1) % in.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
  }
  return out;
}

// A part's corners seen from the eye, on the aerial-image plane, in its local coordinates.
inline polygon projected(const part_frame& part, const part_frame& plane, const glm::dvec3& eye) {
  polygon p;
  for (const auto& [x, y] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
    const glm::dvec3 c = part.center + x * part.width * part.u + y * part.height * part.v;
    const glm::dvec3 d = c - eye;
    const double t = glm::dot(plane.center - eye, plane.n) / glm::dot(d, plane.n);
    p.push_back(part_local(plane, eye + t * d));
  }
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

inline double polygon_visible_fraction(const scene& s, const glm::dvec3& eye) {
  const part_frame aerial = aerial_image_frame(s);
  const double w = 0.5 * aerial.width, h = 0.5 * aerial.height;
  polygon region = {{-w, -h}, {w, -h}, {w, h}, {-w, h}};
  region = clip_convex(region, projected(half_mirror_frame(s), aerial, eye));
  region = clip_convex(region, projected(retroreflector_frame(s), aerial, eye));
  return region.size() < 3 ? 0.0 : std::abs(signed_area(region)) / (aerial.width * aerial.height);
}

}  // namespace airr::test
