#include "airr/models/diffraction.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "airr/core/geometry.hpp"

namespace airr {

double aperture::area() const { return polygon.empty() ? pi * diameter_mm * diameter_mm / 4 : polygon_area(polygon); }

double aperture::perimeter() const { return polygon.empty() ? pi * diameter_mm : polygon_perimeter(polygon); }

namespace {
// Past 64 / sqrt(area) less than about 1% of the light goes.
double reach_of_area(double area) { return 64 / std::sqrt(area); }
}  // namespace

double far_field_reach(const aperture& a) { return reach_of_area(a.area()); }

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
  // Over each edge a -> b (d = b - a): the outward normal times the length is (d.y, -d.x), and the
  // edge's integral of exp(-2 pi i f . x) is |d| sinc(u) exp(-i pi f . (a + b)), u = pi f . d, which
  // is |d| (E(a) - E(b)) / (2 i u) with E(x) = exp(-2 pi i f . x): one exponential per vertex.
  const std::size_t n = a.polygon.size();
  auto vertex_wave = [&](std::size_t j) {
    const double phase = -2 * pi * glm::dot(f, a.polygon[j]);
    return std::complex<double>(std::cos(phase), std::sin(phase));
  };
  std::complex<double> sum(0, 0);
  const std::complex<double> first = vertex_wave(0);
  std::complex<double> at_p = first;
  for (std::size_t j = 0; j < n; ++j) {
    const std::complex<double> at_q = j + 1 < n ? vertex_wave(j + 1) : first;
    const glm::dvec2 d = a.polygon[j + 1 < n ? j + 1 : 0] - a.polygon[j];
    const double u = pi * glm::dot(f, d);
    // Near u = 0 the difference cancels: sinc(u) exp(i u) to second order instead.
    const std::complex<double> wave = std::abs(u) < 1e-4 ? at_p * std::complex<double>(1 - u * u * (1.0 / 6 + 0.5), u)
                                                         : (at_p - at_q) * std::complex<double>(0, -0.5 / u);
    sum += (f.x * d.y - f.y * d.x) * wave;
    at_p = at_q;
  }
  return std::norm(sum) / (4 * pi * pi * f2 * f2);
}

// One draw of a point uniformly distributed in the unit disc from the square around it: kept with
// probability pi / 4, empty otherwise.
inline std::optional<glm::dvec2> point_in_disc(pcg32& rng) {
  const glm::dvec2 p(2 * rng.next_double() - 1, 2 * rng.next_double() - 1);
  if (glm::dot(p, p) < 1) return p;
  return std::nullopt;
}

// A uniformly distributed direction in the plane, from a point drawn in the unit disc (no sine or
// cosine: the sampler draws about ten of them per accepted frequency).
inline glm::dvec2 uniform_direction(pcg32& rng) {
  while (true) {
    const std::optional<glm::dvec2> p = point_in_disc(rng);
    if (!p) continue;
    const double p2 = glm::dot(*p, *p);
    if (p2 > 1e-12) return *p / std::sqrt(p2);
  }
}

}  // namespace

double far_field_intensity(const aperture& a, const glm::dvec2& f) { return intensity(a, a.area(), f); }

namespace {

// The circle's Airy pattern, area^2 (2 J1(x) / x)^2 with x = pi D |f|, by rejection from area^2 up to
// x1 and area^2 4 c / x^3 beyond: x (J1^2 + Y1^2) falls with x (Nicholson's formula), so
// J1(x)^2 <= c / x for x >= 1 with c = J1(1)^2 + Y1(1)^2, and x1 = (4 c)^(1/3) > 1 joins the two.
glm::dvec2 sample_airy(const aperture& a, pcg32& rng, double f_max) {
  static const double c = std::pow(std::cyl_bessel_j(1.0, 1.0), 2) + std::pow(std::cyl_neumann(1.0, 1.0), 2);
  static const double x1 = std::cbrt(4 * c);
  const double area = a.area(), scale = pi * a.diameter_mm;  // x = scale |f|
  const double f1 = std::min(x1 / scale, f_max);
  // Masses of the two parts of the bound over the plane (in units of area^2).
  const double inner = pi * f1 * f1;
  const double outer = f1 < f_max ? 8 * pi * c / (scale * scale * scale) * (1 / f1 - 1 / f_max) : 0.0;
  while (true) {
    const bool in = rng.next_double() * (inner + outer) < inner;
    const double u = rng.next_double();
    const double r = in ? f1 * std::sqrt(u) : 1 / (1 / f1 - u * (1 / f1 - 1 / f_max));
    const glm::dvec2 f = r * uniform_direction(rng);
    const double x = scale * r;
    const double bound = r <= f1 ? area * area : area * area * 4 * c / (x * x * x);
    if (rng.next_double() * bound < intensity(a, area, f)) return f;
  }
}

// A polygon's far field beyond the central lobe lies in streaks across its edges. Write f = a n + b t
// for edge j (t along it, n across it, length L): its term t_j in the edge bound is |a| L min(1,
// beta / |b|), beta = 1 / (pi L). Cauchy-Schwarz, (sum_j t_j)^2 <= (sum_k c_k) (sum_j t_j^2 / c_j)
// for any c_j > 0, and a^2 <= |f|^2 bound |F|^2 by C sum_j L^2 m_j(b) / (c_j 4 pi^2 (a^2 + b^2)), C =
// sum_k c_k, m(b) = min(1, (beta / b)^2). Beyond f0 each edge's share is a Cauchy profile in a
// (scale |b|, cut to |f| >= f0) times a power law in b: b is drawn in closed form from m(b) pi / s(b),
// s = max(|b|, f0), which is the share's integral over a for |b| >= f0 and bounds it, 2 asin(|b| /
// f0) / |b|, below, where a draw is kept in that ratio. The masses are finite, where a radial bound's
// grow as log(f_max / f0). With c_j the square root of edge j's own mass the streaks' total is about
// C^2, near the least such a sum can be.
struct streak {
  glm::dvec2 edge{0}, along{0}, across{0};
  double length = 0, beta = 0;
  std::array<double, 3> pieces{};
  double scale = 0;  // the share's factor, C L^2 / (c_j 4 pi^2)
};

// The integral of m(b) / s(b) over b >= 0 between its breaks: over [0, min(beta, f0)], up to
// max(beta, f0) and beyond.
std::array<double, 3> streak_pieces(double beta, double f0) {
  if (beta <= f0) return {beta / f0, beta / f0 - beta * beta / (f0 * f0), beta * beta / (2 * f0 * f0)};
  return {1.0, std::log(beta / f0), 0.5};
}

// b >= 0 in piece k of m(b) / s(b), from a uniform r in [0, 1) by inverting that piece's integral.
double streak_b(const streak& s, double f0, int k, double r) {
  const double beta = s.beta, lo = std::min(beta, f0), hi = std::max(beta, f0);
  if (k == 0) return lo * r;
  if (k == 2) return hi / std::sqrt(1 - r);
  // Beyond f0, piece 1's integral is log(beta / f0), worked out once a draw.
  return beta <= f0 ? 1 / (1 / beta - r * (1 / beta - 1 / f0)) : f0 * std::exp(r * s.pieces[1]);
}

// a across a streak at b, distributed as 1 / (a^2 + b^2) over |f| >= f0, as b cot(phi) for phi the
// angle of a point drawn uniformly in the box [-1, 1] x (0, x], x = min(|b| / f0, 1), and kept
// within the unit disc and within asin(x) of the horizontal. It is kept with probability
// asin(x) / (2 x): pi / 4 for |b| >= f0 (a Cauchy variate), and below that pi / 4 times the share's
// integral over a, 2 asin(x) / |b|, over its bound, pi / f0. Empty when refused: the disc's draw
// is refused as often, so the pieces keep their weights.
std::optional<double> streak_a(double b, double f0, pcg32& rng) {
  b = std::abs(b);
  const double x = std::min(b / f0, 1.0);
  const double p = 2 * rng.next_double() - 1, q = x * rng.next_double();
  if (!(q > 0) || p * p + q * q > 1 || q * std::sqrt(1 - x * x) > std::abs(p) * x) return std::nullopt;
  return b * p / q;
}

// A bound on a polygon's |F(f)|^2 from the same edge sum without its phases (|sinc u| <= min(1,
// 1 / |u|)): no sine or cosine, and far below the sampler's radial bound beyond the central lobe,
// so most trials are refused without evaluating F.
double edge_bound(const std::vector<streak>& streaks, const glm::dvec2& f) {
  double sum = 0;
  for (const streak& s : streaks) {
    const glm::dvec2 d = s.edge;
    const double u = pi * std::abs(glm::dot(f, d));
    sum += std::abs(f.x * d.y - f.y * d.x) * (u > 1 ? 1 / u : 1.0);
  }
  const double f2 = glm::dot(f, f);
  return sum * sum / (4 * pi * pi * f2 * f2);
}

// The bound the streaks add up to at f (|f| >= f0).
double streak_bound(const std::vector<streak>& streaks, const glm::dvec2& f) {
  double sum = 0;
  for (const streak& s : streaks) {
    const double b = std::abs(glm::dot(f, s.along));
    sum += b > s.beta ? s.scale * s.beta * s.beta / (b * b) : s.scale;
  }
  return sum / glm::dot(f, f);
}

// A polygon's |F|^2 by rejection from area^2 within f0 = perimeter / (2 pi area) and the streaks'
// bound beyond, a lower bound taking most of the central lobe and the edge bound refusing most other
// trials before F is evaluated.
glm::dvec2 sample_polygon_far_field(const aperture& a, pcg32& rng, double f_max) {
  // Kept per thread: a sheet draws one far field per retroreflected path.
  thread_local std::vector<streak> streaks;
  thread_local std::vector<double> weights;
  streaks.clear();
  double perimeter = 0;
  const std::size_t n = a.polygon.size();
  for (std::size_t j = 0; j < n; ++j) {
    const glm::dvec2 d = a.polygon[j + 1 < n ? j + 1 : 0] - a.polygon[j];
    const double length = glm::length(d);
    perimeter += length;
    if (length > 0) streaks.push_back({d, d / length, glm::dvec2(-d.y, d.x) / length, length, 1 / (pi * length)});
  }
  const polygon_moments shape = moments(a.polygon);
  if (!(shape.area > 0)) return glm::dvec2(0);  // corners in a line: no aperture to spread by
  const double area = shape.area;
  if (!(f_max > 0)) f_max = reach_of_area(area);
  const double f0 = std::min(perimeter / (2 * pi * area), f_max);
  weights.assign(1, area * area * pi * f0 * f0);
  if (f0 < f_max) {
    double c_sum = 0;
    for (streak& s : streaks) {
      s.pieces = streak_pieces(s.beta, f0);
      s.scale = s.length * std::sqrt(s.pieces[0] + s.pieces[1] + s.pieces[2]);  // c_j for now
      c_sum += s.scale;
    }
    for (streak& s : streaks) {
      s.scale = c_sum / s.scale * s.length * s.length / (4 * pi * pi);
      for (double piece : s.pieces) weights.push_back(2 * pi * s.scale * piece);
    }
  }
  double total = 0;
  for (double w : weights) total += w;
  while (true) {
    double pick = rng.next_double() * total;
    std::size_t k = 0;
    while (k + 1 < weights.size() && pick >= weights[k]) pick -= weights[k++];
    glm::dvec2 f;
    double bound;
    if (k == 0) {
      const std::optional<glm::dvec2> p = point_in_disc(rng);
      if (!p) continue;  // kept with probability pi / 4, as a streak's draw
      f = f0 * *p;
      bound = area * area;
    } else {
      const streak& s = streaks[(k - 1) / 3];
      const double r = std::min(pick / weights[k], 1 - 1e-16);
      const double b = streak_b(s, f0, int((k - 1) % 3), r) * (rng.next_double() < 0.5 ? -1 : 1);
      const std::optional<double> across = streak_a(b, f0, rng);
      if (!across) continue;
      f = b * s.along + *across * s.across;
      if (glm::dot(f, f) >= f_max * f_max) continue;
      bound = streak_bound(streaks, f);
    }
    const double v = rng.next_double() * bound;
    // Taken without F where a lower bound already takes it: |F| >= area - 2 pi^2 f^T J f about the
    // centroid (cos x >= 1 - x^2 / 2), most of the central lobe.
    const double least = area - 2 * pi * pi * glm::dot(f, shape.spread * f);
    if (least > 0 && v < least * least) return f;
    if (v >= edge_bound(streaks, f)) continue;
    if (v < intensity(a, area, f)) return f;
  }
}

}  // namespace

glm::dvec2 sample_far_field(const aperture& a, pcg32& rng, double f_max) {
  if (!a.polygon.empty()) return sample_polygon_far_field(a, rng, f_max);
  return sample_airy(a, rng, f_max > 0 ? f_max : far_field_reach(a));
}

std::optional<glm::dvec3> diffracted(const glm::dvec3& w, const glm::dvec2& f, double wavelength_mm) {
  const glm::dvec2 t = glm::dvec2(w) + wavelength_mm * f;
  const double t2 = glm::dot(t, t);
  if (t2 >= 1) return std::nullopt;
  return glm::dvec3(t, std::sqrt(1 - t2));
}

}  // namespace airr
