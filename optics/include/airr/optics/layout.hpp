#pragma once
// Where the parts of an AIRR layout are, as rectangles in world space (mm), and the camera.
#include <string>

#include <glm/glm.hpp>

#include "airr/optics/geometry.hpp"
#include "airr/optics/scene.hpp"

namespace airr {

part_frame source_frame(const scene& s);
part_frame half_mirror_frame(const scene& s);
part_frame retroreflector_frame(const scene& s);

// Where the aerial image of the source's centre forms: its mirror image in the half mirror.
glm::dvec3 aerial_image_center(const scene& s);

// Whether two rectangles share a point (touching counts).
bool parts_intersect(const part_frame& a, const part_frame& b);

// Throws input_error "<origin>: layout: ..." if parts intersect.
void check_layout(const scene& s, const std::string& origin);

// Pinhole camera on +z in front of the aerial image, looking along -z.
struct pinhole_camera {
  glm::dvec3 position{0};
  glm::dvec3 right{1, 0, 0};
  glm::dvec3 up{0, 1, 0};
  glm::dvec3 forward{0, 0, -1};
  double tan_half_fov = 0;  // vertical
  int width = 1;
  int height = 1;
  double mm_per_pixel = 0;  // one pixel's size on the aerial-image plane
};
pinhole_camera make_camera(const scene& s);

// Direction through image position (px, py) in pixels from the top-left corner.
glm::dvec3 camera_direction(const pinhole_camera& c, double px, double py);
// Pixel position (x right, y down, from the top-left corner) of a world point.
glm::dvec2 camera_project(const pinhole_camera& c, const glm::dvec3& p);

}  // namespace airr
