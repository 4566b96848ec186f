#pragma once
// Where the aerial image can be seen (spec section 8), the geometric pass: for an eye position,
// the share of the aerial image's area that an ideal retroreflection reaches through the parts'
// real apertures.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// Where the line o + t d (unit d) first meets a prop, for t in (0, t_max); infinity when it meets
// none. The render library builds one from the scene's props (scene_prop_hits in prop_hits.hpp).
using prop_hit_function = std::function<double(const glm::dvec3& o, const glm::dvec3& d, double t_max)>;

// The parts an ideal path meets or is blocked by, built once per layout. A scene with visible
// props needs their prop_hit_function (std::invalid_argument otherwise: the map would be wrong).
struct viewing_parts {
  part_frame half_mirror, display, panel, aerial;
  std::vector<part_frame> sheets;
  prop_hit_function props;
  explicit viewing_parts(const scene& s, prop_hit_function prop_hits = {});
};

// Whether the aerial-image point `p` is seen from `eye`: the line from the eye through p meets
// the half mirror beyond p, then (straight on, or mirrored) the front of a sheet, and straight
// back and (mirrored, or straight on) the display's emitting area, with no other part or prop
// between.
bool aerial_point_visible(const viewing_parts& parts, const glm::dvec3& eye, const glm::dvec3& p);

// The visible fraction at `eye`: `rows` slabs across the aerial image, each a trapezoid between
// its edge rows, halved where its middle row shows a corner of the visible region. On each row the
// visible stretches are found by stepping and their ends by bisection (to 1e-6 of the row).
// Without `refine`, the midpoint rule over `rows` rows: half the cost, off by up to half a row
// where the visible region's top or bottom is flat (for maps that are redrawn on every edit).
double visible_fraction(const viewing_parts& parts, const glm::dvec3& eye, int rows = 64, bool refine = true);

// A grid of eye positions: on a plane `distance_mm` in front of the aerial image's centre (the
// observer's orbit at azimuth and elevation 0; x to the right, y up, in mm), or on the sphere of
// that radius around it (azimuth x, elevation y, in degrees, as the observer's orbit).
struct eye_grid {
  enum class shape { plane, sphere } kind = shape::plane;
  double distance_mm = 300;
  double x_min = -150, x_max = 150, y_min = -150, y_max = 150;
  int nx = 21, ny = 21;
  double x_at(int i) const { return nx == 1 ? 0.5 * (x_min + x_max) : x_min + (x_max - x_min) * i / (nx - 1); }
  double y_at(int j) const { return ny == 1 ? 0.5 * (y_min + y_max) : y_min + (y_max - y_min) * j / (ny - 1); }
};

// The eye at grid coordinates (x, y), and a position's grid coordinates (for marking the observer).
glm::dvec3 eye_position(const scene& s, const eye_grid& g, double x, double y);
glm::dvec2 eye_grid_coordinates(const scene& s, const eye_grid& g, const glm::dvec3& eye);

// Moves the observer to grid coordinates (x, y), looking at the aerial image's centre: on the
// sphere, the orbit's azimuth, elevation and distance; on the plane, a look-at position.
void place_observer(scene& s, const eye_grid& g, double x, double y);

// Throws input_error naming the field for a grid out of range (sizes 1 to 1001, finite bounds,
// distance > 0, elevations within +-89 degrees).
void check_eye_grid(const eye_grid& g);

// The grid a user asks for (airr viewzone, airr.viewzone): `per_side` eyes each way on the plane
// `distance_mm` in front of the aerial image (x, y in mm) or on the sphere of that radius (azimuth,
// elevation in degrees); `x` and `y` are (first, last), empty for -200 to 200 mm or -60 to 60
// degrees. Checked as check_eye_grid does.
eye_grid requested_eye_grid(bool sphere, double distance_mm, int per_side, const std::vector<double>& x = {},
                            const std::vector<double>& y = {});

struct viewing_zone_map {
  eye_grid grid;
  std::vector<double> visible;  // ny rows of nx, row j at y_at(j)
  double seconds = 0;
};

// The visible fraction over the grid, rows of eyes in parallel; `progress(done, total)` after each
// row of eyes. Empty `visible` when `cancel` was set. `prop_hits` and `refine` as for
// viewing_parts and visible_fraction.
viewing_zone_map geometric_viewing_zone(const scene& s, const eye_grid& g, const prop_hit_function& prop_hits,
                                        int rows_per_eye = 64, const std::function<void(int, int)>& progress = {},
                                        const std::atomic<bool>* cancel = nullptr, bool refine = true);

}  // namespace airr
