#pragma once
// Where the parts of an AIRR layout are, as rectangles in world space (mm), where the aerial image
// forms, and the observer's camera.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/emission_profile.hpp"

namespace airr {

// The rotation of a pose (see scene.hpp for the convention); columns are the part's u, v, n.
glm::dmat3 pose_rotation(const pose& p);
part_frame pose_frame(const pose& p, double width_mm, double height_mm);
// The pose with rotation `r` (a proper rotation; columns u, v, n) and centre `center`: the inverse
// of pose_rotation, with yaw 0 when the normal is vertical.
pose pose_from_rotation(const glm::dmat3& r, const glm::dvec3& center);

// Maps a prop's mesh (millimetres, in its own frame) into the world: its pose times its scale.
glm::dmat4 prop_transform(const prop_params& p);

// The display's emission profile (read once per file), or null when it is Lambertian; and the
// profile's value for light leaving the display along `towards_display` reversed (1 without one).
std::shared_ptr<const emission_profile> scene_emission_profile(const scene& s);
double emission_at(const emission_profile* profile, const part_frame& display, const glm::dvec3& towards_display);

// The unit direction towards the sun's centre, and a luminaire's frame (for a disc, width and
// height are its diameter).
glm::dvec3 sun_direction(const sun_params& s);
part_frame luminaire_frame(const luminaire_params& l);
// The luminaire's edge as the views draw it: a rectangle's four corners, a disc's `sides` points.
std::vector<glm::dvec3> luminaire_outline(const luminaire_params& l, int sides = 24);

// The display's emitting area, and the whole panel including its bezel.
part_frame source_frame(const scene& s);
part_frame source_panel_frame(const scene& s);
part_frame half_mirror_frame(const scene& s);
part_frame retroreflector_frame(const scene& s, std::size_t sheet = 0);

// The aerial image: the display's emitting area mirrored in the half-mirror plane (u keeps its
// direction; the mirrored normal points away from the half mirror).
part_frame aerial_image_frame(const scene& s);
glm::dvec3 aerial_image_center(const scene& s);

// The pose of a part's mirror image in the half mirror: its centre and plane mirrored, its front
// facing the mirror as the original's does, its width axis turned so that the frame stays
// right-handed.
pose mirrored_in_half_mirror(const scene& s, const part_frame& f);

// Whether the observer's ideal path reaches sheet i by reflection in the half mirror: the sheet
// is across the half mirror from the display, so the display's light reaches it through the
// mirror (and comes back to the aerial image by reflection). Otherwise the path passes through.
bool sheet_seen_by_reflection(const scene& s, std::size_t sheet = 0);

// The incidence angle (degrees) at sheet i's centre of the light from the display's centre: from
// the aerial image's centre (the display's mirror image) when the sheet is on the display's side of
// the half mirror (light reaches it by reflection), from the display's centre when it is on the
// other side (light reaches it through the mirror). In the canonical layout it is the sheet's tilt.
// Models that look their parameters up once per render use it.
double sheet_chief_incidence_deg(const scene& s, std::size_t sheet = 0);

// The floating distance D: from the half mirror's centre to the aerial image's centre. Setting it
// moves the display along the line from the half mirror's centre through the display's centre,
// which moves the aerial image along the line from the half mirror's centre through it (in the
// canonical layout: the display along -y, the aerial image along +z). Throws input_error for
// D <= 0 or a display centred on the half mirror's centre.
double floating_distance(const scene& s);
void set_floating_distance(scene& s, double d_mm);

// The ideal light path through an aerial-image point as a polyline from the observer: to the half
// mirror, straight on to the first sheet's plane and back, mirrored to the display's plane (as far
// as it gets; for drawing).
std::vector<glm::dvec3> ideal_light_path(const scene& s, const glm::dvec3& aerial_point);

// A part's corners, counter-clockwise from (-u, -v).
std::array<glm::dvec3, 4> corners(const part_frame& f);

// Whether two rectangles share a point (touching counts).
bool parts_intersect(const part_frame& a, const part_frame& b);

// The length of the segment along which a triangle cuts through a part (mm): 0 when they do not
// meet, only touch, or lie in one plane.
double part_cut_length(const part_frame& f, const std::array<glm::dvec3, 3>& triangle);

// Throws input_error "<origin>: <field>: ..." for intersecting parts, an observer inside a part or
// behind the half mirror, a display whose aerial image would form behind the half mirror, or a
// degenerate pose.
void check_layout(const scene& s, const std::string& origin);

// The observer: a pinhole or a thin lens at `position`, looking along `forward`.
struct pinhole_camera {
  glm::dvec3 position{0};
  glm::dvec3 right{1, 0, 0};
  glm::dvec3 up{0, 1, 0};
  glm::dvec3 forward{0, 0, -1};
  double tan_half_fov = 0;  // vertical
  int width = 1;
  int height = 1;
  double mm_per_pixel = 0;     // one pixel's size on the plane through the aim point, facing the camera
  double target_distance = 0;  // from the camera to its aim point (the aerial image's centre in orbit)
  double aperture_mm = 0;      // thin lens: aperture diameter f / N; 0: pinhole
  double focus_distance = 0;   // thin lens: distance of the plane in focus, along forward
};
pinhole_camera make_camera(const scene& s);

// The observer's position and aim point.
glm::dvec3 observer_position(const scene& s);
glm::dvec3 observer_target(const scene& s);

// Direction through image position (px, py) in pixels from the top-left corner (pinhole).
glm::dvec3 camera_direction(const pinhole_camera& c, double px, double py);
// A camera ray through (px, py); lens in [0, 1)^2 picks the point on the aperture (thin lens).
struct camera_ray {
  glm::dvec3 origin;
  glm::dvec3 dir;
};
camera_ray make_camera_ray(const pinhole_camera& c, double px, double py, const glm::dvec2& lens);
// Pixel position (x right, y down, from the top-left corner) of a world point.
glm::dvec2 camera_project(const pinhole_camera& c, const glm::dvec3& p);

// The observer presets: the camera of the paper's measurements (50 mm lens at f/4, 300 mm from
// the aerial image, in focus on it) and the eye (4 mm pupil, in focus on the aerial image).
enum class observer_preset { paper_camera, eye };
void apply_observer_preset(scene& s, observer_preset preset);

// The vertical field of view (deg) that frames the aerial image with a margin, or every part.
double fov_for_aerial_image(const scene& s);
double fov_for_whole_device(const scene& s);

}  // namespace airr
