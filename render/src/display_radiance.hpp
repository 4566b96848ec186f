#pragma once
// The display's radiance at a point of its emitting area: one home for the tracer's texture read
// and the model image's display parts.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/formats/image.hpp"

namespace airr {

// Bilinear between texel centres (edges clamped) of `texels` (null: uniform), times `scale`;
// local (x, y) in mm from the emitting area's centre, image top towards +v. The bezel around the
// emitting area is black.
inline glm::vec3 display_radiance(const part_frame& area, const image_rgb* texels, float scale,
                                  const glm::dvec2& local) {
  if (!inside_part(area, local)) return glm::vec3(0.0f);
  if (!texels) return glm::vec3(scale);
  const image_rgb& img = *texels;
  const double s = (local.x / area.width + 0.5) * img.width - 0.5;
  const double t = (0.5 - local.y / area.height) * img.height - 0.5;
  const int x0 = int(std::floor(s)), y0 = int(std::floor(t));
  const float fx = float(s - x0), fy = float(t - y0);
  auto texel = [&](int x, int y) {
    x = std::clamp(x, 0, img.width - 1);
    y = std::clamp(y, 0, img.height - 1);
    const float* p = img.at(x, y);
    return glm::vec3(p[0], p[1], p[2]);
  };
  const glm::vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx);
  const glm::vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx);
  return glm::mix(top, bottom, fy) * scale;
}

}  // namespace airr
