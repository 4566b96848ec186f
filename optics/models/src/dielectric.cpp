#include "airr/models/dielectric.hpp"

#include <algorithm>
#include <cmath>

namespace airr {

double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1) return 1;
  const double cos_t = std::sqrt(1 - sin2_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

namespace {

// a / b by b's conjugate: the library's division (__divdc3) guards against overflow that these
// ratios of order-one numbers cannot meet, at several times the cost.
std::complex<double> over(std::complex<double> a, std::complex<double> b) { return a * std::conj(b) / std::norm(b); }

// The root with a non-negative real part, in real arithmetic: the library's (csqrt) guards against
// overflow and special values that the interfaces' order-one numbers never meet, at several times
// the cost. From the larger of the two half-sums, so neither part loses digits to cancellation.
std::complex<double> principal_root(std::complex<double> z) {
  const double x = z.real(), y = z.imag(), r = std::sqrt(x * x + y * y);
  if (r == 0) return 0.0;
  if (x >= 0) {
    const double t = std::sqrt(0.5 * (r + x));
    return {t, y / (2 * t)};
  }
  const double t = std::sqrt(0.5 * (r - x));
  return {std::abs(y) / (2 * t), std::copysign(t, y)};
}

}  // namespace

// A clear medium's interface in real arithmetic (the prism sheet's every face, a plate's): below
// the critical angle every amplitude is real; beyond it cos_t = i b and the ratios are (a - i c) /
// (a + i c) = ((a^2 - c^2) - 2 i a c) / (a^2 + c^2), with no complex root or division.
static fresnel_coefficients fresnel_amplitudes_real(double cos_i, double eta) {
  fresnel_coefficients f;
  const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
  if (sin2_t <= 1) {
    const double cos_t = std::sqrt(1 - sin2_t);
    const double s = cos_i + eta * cos_t, p = eta * cos_i + cos_t;
    f.cos_t = cos_t;
    f.rs = (cos_i - eta * cos_t) / s;
    f.rp = (eta * cos_i - cos_t) / p;
    f.ts = 2 * cos_i / s;
    f.tp = 2 * cos_i / p;
    return f;
  }
  const double b = std::sqrt(sin2_t - 1);
  f.cos_t = {0, b};
  f.total = true;
  const double a = cos_i, c = eta * b;    // s: (a - i c) / (a + i c)
  const double ap = eta * cos_i, cp = b;  // p: (ap - i cp) / (ap + i cp)
  const double ns = 1 / (a * a + c * c), np = 1 / (ap * ap + cp * cp);
  f.rs = {(a * a - c * c) * ns, -2 * a * c * ns};
  f.rp = {(ap * ap - cp * cp) * np, -2 * ap * cp * np};
  f.ts = {2 * a * a * ns, -2 * a * c * ns};
  f.tp = {2 * a * ap * np, -2 * a * cp * np};
  return f;
}

fresnel_coefficients fresnel_amplitudes(double cos_i, std::complex<double> eta) {
  using complex = std::complex<double>;
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  if (eta.imag() == 0) return fresnel_amplitudes_real(cos_i, eta.real());
  fresnel_coefficients f;
  const complex sin2_t = over(complex(1 - cos_i * cos_i), eta * eta);
  f.cos_t = principal_root(complex(1.0) - sin2_t);
  if (f.cos_t.imag() < 0) f.cos_t = -f.cos_t;
  f.total = eta.imag() == 0 && sin2_t.real() > 1;
  const complex ci(cos_i);
  // s and p each share a denominator between reflection and transmission: one reciprocal each.
  const complex ds = ci + eta * f.cos_t, dp = eta * ci + f.cos_t;
  const complex inv_s = std::conj(ds) / std::norm(ds), inv_p = std::conj(dp) / std::norm(dp);
  f.rs = (ci - eta * f.cos_t) * inv_s;
  f.rp = (eta * ci - f.cos_t) * inv_p;
  f.ts = 2.0 * ci * inv_s;
  f.tp = 2.0 * ci * inv_p;
  return f;
}

std::optional<glm::dvec3> refract(const glm::dvec3& d, const glm::dvec3& m, double ratio) {
  const double cos_i = -glm::dot(d, m);
  const double sin2_t = ratio * ratio * std::max(0.0, 1 - cos_i * cos_i);
  if (sin2_t >= 1) return std::nullopt;
  return ratio * d + (ratio * cos_i - std::sqrt(1 - sin2_t)) * m;
}

}  // namespace airr
