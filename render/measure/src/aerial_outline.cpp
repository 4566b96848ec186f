#include "airr/measure/aerial_outline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "airr/core/color.hpp"

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

glm::dvec2 luminance_centroid(const image_rgb& img) {
  double sum = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float* v = img.at(x, y);
      const double l = std::max(0.0, rec709_luminance(v[0], v[1], v[2]));
      sum += l;
      sx += l * (x + 0.5);
      sy += l * (y + 0.5);
    }
  }
  return sum > 0 ? glm::dvec2(sx / sum, sy / sum) : glm::dvec2(std::numeric_limits<double>::quiet_NaN());
}

double separation_arcmin(const pinhole_camera& cam, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec3 u = camera_direction(cam, a.x, a.y), v = camera_direction(cam, b.x, b.y);
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v)) * 180 / M_PI * 60;
}

}  // namespace airr
