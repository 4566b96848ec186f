#pragma once
// The layout's ambient light as the tracer meets it (spec section 11): the room's surround, the
// sun's disc and the luminaires, in world space, with the luminances in cd/m2.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

struct ambient_lights {
  float room = 0;  // the surround's luminance (0: a dark room)
  // The sun (luminance 0: none): towards its centre, the cosine of its angular radius, and the
  // illuminance it makes on a plane facing it.
  float sun = 0;
  glm::dvec3 sun_dir{0, 1, 0};
  double sun_cos_radius = 1;
  double sun_lux = 0;
  struct luminaire {
    part_frame frame;  // a disc: width is its diameter
    bool disc = false;
    float luminance = 0;
    double area_mm2 = 0;
  };
  std::vector<luminaire> luminaires;  // in the scene's order
};

ambient_lights make_ambient_lights(const environment_params& e);

// The nearest luminaire a ray meets closer than t_max (which: -1 if none), and whether it met the
// emitting front.
struct luminaire_hit {
  int which = -1;
  double t = 0;
  bool front = false;
};
luminaire_hit meet_luminaire(const ambient_lights& a, const glm::dvec3& origin, const glm::dvec3& dir, double t_max);

// Whether a direction leaving the scene sees the sun's disc.
inline bool sees_sun(const ambient_lights& a, const glm::dvec3& dir) {
  return a.sun > 0 && glm::dot(dir, a.sun_dir) >= a.sun_cos_radius;
}

// A point drawn uniformly on luminaire k's emitting area from two uniform numbers.
glm::dvec3 luminaire_point(const ambient_lights::luminaire& l, double u1, double u2);
// A direction drawn uniformly over the sun's disc (its solid angle) from two uniform numbers.
glm::dvec3 sun_sample_direction(const ambient_lights& a, double u1, double u2);

}  // namespace airr
