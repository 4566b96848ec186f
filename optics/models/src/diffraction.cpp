#include "airr/models/diffraction.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "airr/core/geometry.hpp"

namespace airr {

double aperture::area() const { return polygon.empty() ? pi * diameter_mm * diameter_mm / 4 : polygon_area(polygon); }

double aperture::perimeter() const { return polygon.empty() ? pi * diameter_mm : polygon_perimeter(polygon); }

double far_field_reach(const aperture& a) { return 64 / std::sqrt(a.area()); }

model_field spectrum_field() {
  return choice_field("spectrum", {"single", "display_rgb"},
                      "Diffraction at wavelength_nm, or over the display's white (sRGB primaries' dominant "
                      "wavelengths 611, 549, 464 nm in equal shares, each blurring its own channel)");
}

diffracted_light read_spectrum(const model_values& v) {
  return v.text("spectrum") == "display_rgb" ? diffracted_light::display_rgb : diffracted_light::single;
}

drawn_light draw_light(diffracted_light light, double wavelength_nm, pcg32& rng) {
  if (light == diffracted_light::single) return {wavelength_nm, glm::dvec3(1.0)};
  const int k = std::min(2, int(3 * rng.next_double()));
  drawn_light out{display_primaries_nm[std::size_t(k)], glm::dvec3(0.0)};
  out.channels[k] = 3;
  return out;
}

namespace {

// |F(f)|^2 of an aperture of the given area (worked out once per draw, not per trial).
double intensity(const aperture& a, double area, const glm::dvec2& f) {
  const double f2 = glm::dot(f, f);
  if (a.polygon.empty()) {
    const double x = pi * a.diameter_mm * std::sqrt(f2);
    const double amplitude = x < 1e-9 ? 1.0 : 2 * std::cyl_bessel_j(1.0, x) / x;
    return area * area * amplitude * amplitude;
  }
  if (f2 * area < 1e-18) return area * area;
  // Over each edge a -> b (d = b - a, midpoint m): the outward normal times the length is
  // (d.y, -d.x), and the edge's integral of exp(-2 pi i f . x) is |d| exp(-2 pi i f . m) sinc(pi f . d).
  std::complex<double> sum(0, 0);
  const std::size_t n = a.polygon.size();
  for (std::size_t j = 0; j < n; ++j) {
    const glm::dvec2 p = a.polygon[j], q = a.polygon[(j + 1) % n], d = q - p, m = 0.5 * (p + q);
    const double u = pi * glm::dot(f, d);
    const double sinc = std::abs(u) < 1e-9 ? 1.0 : std::sin(u) / u;
    const double phase = -2 * pi * glm::dot(f, m);
    sum += (f.x * d.y - f.y * d.x) * sinc * std::complex<double>(std::cos(phase), std::sin(phase));
  }
  return std::norm(sum) / (4 * pi * pi * f2 * f2);
}

}  // namespace

double far_field_intensity(const aperture& a, const glm::dvec2& f) { return intensity(a, a.area(), f); }

glm::dvec2 sample_far_field(const aperture& a, pcg32& rng, double f_max) {
  const double area = a.area(), perimeter = a.perimeter();
  if (!(f_max > 0)) f_max = far_field_reach(a);
  // The bound: area^2 within f0, (perimeter / (2 pi |f|))^2 beyond (the edge sum's magnitude is at
  // most |f| perimeter).
  const double f0 = std::min(perimeter / (2 * pi * area), f_max);
  const double inner = area * area * pi * f0 * f0;
  const double outer = f0 < f_max ? perimeter * perimeter / (2 * pi) * std::log(f_max / f0) : 0.0;
  while (true) {
    const bool in = rng.next_double() * (inner + outer) < inner;
    const double u = rng.next_double();
    const double r = in ? f0 * std::sqrt(u) : f0 * std::pow(f_max / f0, u);
    const double angle = 2 * pi * rng.next_double();
    const glm::dvec2 f(r * std::cos(angle), r * std::sin(angle));
    const double bound = r <= f0 ? area * area : std::pow(perimeter / (2 * pi * r), 2);
    if (rng.next_double() * bound < intensity(a, area, f)) return f;
  }
}

std::optional<glm::dvec3> diffracted(const glm::dvec3& w, const glm::dvec2& f, double wavelength_mm) {
  const glm::dvec2 t = glm::dvec2(w) + wavelength_mm * f;
  const double t2 = glm::dot(t, t);
  if (t2 >= 1) return std::nullopt;
  return glm::dvec3(t, std::sqrt(1 - t2));
}

}  // namespace airr
