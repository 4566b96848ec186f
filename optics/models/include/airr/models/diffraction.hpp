#pragma once
// Fraunhofer diffraction by a flat aperture: a beam that leaves through it spreads over spatial
// frequencies f (cycles per mm, in the aperture's plane) with density |F(f)|^2 / area, F the
// aperture's Fourier transform, integral over the aperture of exp(-2 pi i f . x). A ray of
// wavelength lambda leaving in direction w has its in-plane direction cosines moved by lambda f.
#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/polygon.hpp"
#include "airr/core/random.hpp"
#include "airr/models/model_fields.hpp"

namespace airr {

// A convex polygon (counter-clockwise, mm) or, with no vertices, a circle of `diameter_mm`.
struct aperture {
  polygon2 polygon;
  double diameter_mm = 0;

  double area() const;
  double perimeter() const;
};

// F(f) in closed form: the polygon's sum over its edges (from the divergence theorem), the
// circle's Airy amplitude.
double far_field_intensity(const aperture& a, const glm::dvec2& f);

// A spatial frequency drawn from |F(f)|^2 over |f| < f_max (0: 64 / sqrt(area), past which less
// than about 1% of the light goes), by rejection: a circle's from area^2 and a bound falling as
// |f|^-3, a polygon's from area^2 and a bound made of one streak across each edge.
glm::dvec2 sample_far_field(const aperture& a, pcg32& rng, double f_max = 0);

// The default cut-off of sample_far_field.
double far_field_reach(const aperture& a);

// The light a sheet diffracts: one wavelength (its `wavelength_nm`), or the display's white, each
// path's wavelength drawn in equal shares from the dominant wavelengths of the sRGB primaries, the
// path carrying that primary's channel alone (each channel blurs by its own wavelength: colour
// fringes).
enum class diffracted_light { single, display_rgb };
inline constexpr std::array<double, 3> display_primaries_nm{611.3, 549.1, 464.3};

// The sheet models' "spectrum" field and its reading.
model_field spectrum_field();
diffracted_light read_spectrum(const model_values& v);

// A path's wavelength in nm and what it carries of the tracer's R, G, B channels: one wavelength
// carries all three alike; display_rgb draws a primary (one draw from rng) whose path carries its
// channel alone, three times over, so that the mean over paths is white.
struct drawn_light {
  double wavelength_nm = 0;
  glm::dvec3 channels{1.0};
};
drawn_light draw_light(diffracted_light light, double wavelength_nm, pcg32& rng);

// `w` (a unit direction, z > 0 the side it leaves to) moved by the spread: its x, y direction
// cosines shifted by wavelength_mm f. Empty when that would leave no direction (evanescent).
std::optional<glm::dvec3> diffracted(const glm::dvec3& w, const glm::dvec2& f, double wavelength_mm);

}  // namespace airr
