#include "airr/measure/aerial_outline.hpp"

#include <utility>

namespace airr {

std::array<glm::dvec2, 4> aerial_outline(const scene& s, const pinhole_camera& cam) {
  const part_frame a = aerial_image_frame(s);
  std::array<glm::dvec2, 4> outline;
  int k = 0;
  for (const auto& [x, y] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
    outline[std::size_t(k++)] = camera_project(cam, part_point(a, x * a.width, y * a.height));
  }
  return outline;
}

bool inside_quad(const std::array<glm::dvec2, 4>& q, double x, double y) {
  int sign = 0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec2 a = q[std::size_t(i)], b = q[std::size_t((i + 1) % 4)];
    const double c = (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
    const int s = c > 0 ? 1 : c < 0 ? -1 : 0;
    if (s != 0 && sign != 0 && s != sign) return false;
    if (s != 0) sign = s;
  }
  return true;
}

}  // namespace airr
