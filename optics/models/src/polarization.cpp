#include "airr/models/polarization.hpp"

#include <cmath>

#include "airr/core/geometry.hpp"

namespace airr {

namespace {

// The Pauli matrices in the order of the Stokes parameters: S_i = tr(sigma_i E E^H).
const std::array<jones, 4>& stokes_pauli() {
  static const std::array<jones, 4> sigma = [] {
    std::array<jones, 4> s;
    s[0].m = {{{1.0, 0.0}, {0.0, 1.0}}};
    s[1].m = {{{1.0, 0.0}, {0.0, -1.0}}};
    s[2].m = {{{0.0, 1.0}, {1.0, 0.0}}};
    s[3].m = {{{0.0, complex(0, -1)}, {complex(0, 1), 0.0}}};
    return s;
  }();
  return sigma;
}

jones adjoint(const jones& j) {
  jones a;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) a.m[r][c] = std::conj(j.m[c][r]);
  return a;
}

// m rotator(angle) and rotator(angle) m, without the rotator's zeros (the tracer's hot path).
mueller times_rotator(mueller m, double_angle turn) {
  for (auto& row : m.m) {
    const double a = row[1], b = row[2];
    row[1] = a * turn.c - b * turn.s;
    row[2] = a * turn.s + b * turn.c;
  }
  return m;
}
mueller rotator_times(double_angle turn, mueller m) {
  for (int k = 0; k < 4; ++k) {
    const double a = m.m[1][k], b = m.m[2][k];
    m.m[1][k] = turn.c * a + turn.s * b;
    m.m[2][k] = -turn.s * a + turn.c * b;
  }
  return m;
}

// A part with amplitude factors `along` and `across` its axis at `axis` from x towards y: the
// Jones matrix turn(-axis) diag(along, across) turn(axis), whose Mueller matrix is the product of
// theirs (mueller_of, checked against it in tests/test_polarization.cpp).
mueller axial_part(double_angle axis, complex along, complex across) {
  return rotator_times(double_angle(axis.c, -axis.s), times_rotator(interface_mueller(along, across), axis));
}

}  // namespace

stokes linear_light(double angle_rad, double intensity) {
  return {intensity, intensity * std::cos(2 * angle_rad), intensity * std::sin(2 * angle_rad), 0};
}

stokes circular_light(bool positive, double intensity) { return {intensity, 0, 0, positive ? intensity : -intensity}; }

double degree_of_polarization(const stokes& s) {
  if (!(s[0] > 0)) return 0;
  return std::sqrt(s[1] * s[1] + s[2] * s[2] + s[3] * s[3]) / s[0];
}

jones operator*(const jones& a, const jones& b) {
  jones p;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) p.m[r][c] = a.m[r][0] * b.m[0][c] + a.m[r][1] * b.m[1][c];
  return p;
}

mueller mueller::identity() { return scale(1); }

mueller mueller::scale(double factor) {
  mueller a;
  for (int i = 0; i < 4; ++i) a.m[i][i] = factor;
  return a;
}

mueller operator*(const mueller& a, const mueller& b) {
  mueller p;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      p.m[r][c] = a.m[r][0] * b.m[0][c] + a.m[r][1] * b.m[1][c] + a.m[r][2] * b.m[2][c] + a.m[r][3] * b.m[3][c];
  return p;
}

stokes operator*(const mueller& a, const stokes& s) {
  stokes out;
  for (int r = 0; r < 4; ++r) out[r] = a.m[r][0] * s[0] + a.m[r][1] * s[1] + a.m[r][2] * s[2] + a.m[r][3] * s[3];
  return out;
}

mueller operator+(const mueller& a, const mueller& b) {
  mueller sum;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) sum.m[r][c] = a.m[r][c] + b.m[r][c];
  return sum;
}

mueller mueller_of(const jones& j) {
  const auto& sigma = stokes_pauli();
  const jones jh = adjoint(j);
  mueller out;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) {
      const jones p = sigma[i] * j * sigma[k] * jh;
      out.m[i][k] = 0.5 * (p.m[0][0] + p.m[1][1]).real();
    }
  }
  return out;
}

mueller rotator(double angle_rad) { return times_rotator(mueller::identity(), double_angle(angle_rad)); }

mueller linear_polarizer(double axis_rad, double t_pass, double t_block) {
  return axial_part(double_angle(axis_rad), std::sqrt(t_pass), std::sqrt(t_block));
}

mueller linear_retarder(double axis_rad, double retardance_rad) {
  return axial_part(double_angle(axis_rad), 1.0, std::polar(1.0, retardance_rad));
}

mueller linear_polarizer(const polarization_frame& f, const glm::dvec3& axis, double t_pass, double t_block) {
  return axial_part(double_angle(f, axis), std::sqrt(t_pass), std::sqrt(t_block));
}

glm::dvec4 row_through_axial_part(const glm::dvec4& row, const polarization_frame& f, const glm::dvec3& axis,
                                  complex along, complex across) {
  return row_through_axial_part(row, double_angle(f, axis), along, across);
}

namespace {

// The entries of mueller_of(diag(rs, rp)): [[plus, minus], [minus, plus]] on I and Q, and the
// rotation-scaling by c = conj(rs) rp on U and V.
struct interface_terms {
  double plus, minus;
  complex c;
};
interface_terms terms_of(complex rs, complex rp) {
  const double s = std::norm(rs), p = std::norm(rp);
  return {0.5 * (s + p), 0.5 * (s - p), std::conj(rs) * rp};
}

}  // namespace

glm::dvec4 row_through_axial_part(const glm::dvec4& row, double_angle t, complex along, complex across) {
  // row R(-axis) D R(axis), D = interface_mueller(along, across), each a few products on a row.
  const double a1 = row[1] * t.c + row[2] * t.s, a2 = -row[1] * t.s + row[2] * t.c;
  const auto [plus, minus, c] = terms_of(along, across);
  const double b1 = row[0] * minus + a1 * plus, b2 = a2 * c.real() + row[3] * c.imag();
  return {row[0] * plus + a1 * minus, b1 * t.c - b2 * t.s, b1 * t.s + b2 * t.c, -a2 * c.imag() + row[3] * c.real()};
}

mueller interface_mueller(complex rs, complex rp) {
  // mueller_of(diag(rs, rp)) written out: the tracer meets it at every interaction.
  const auto [plus, minus, c] = terms_of(rs, rp);
  mueller m;
  m.m[0] = {plus, minus, 0, 0};
  m.m[1] = {minus, plus, 0, 0};
  m.m[2] = {0, 0, c.real(), -c.imag()};
  m.m[3] = {0, 0, c.imag(), c.real()};
  return m;
}

polarization_frame polarization_frame::with_x(const glm::dvec3& k, const glm::dvec3& x) {
  const glm::dvec3 across = glm::normalize(x - glm::dot(x, k) * k);
  return {across, glm::cross(k, across), k};
}

mueller interface_times(complex rs, complex rp, const mueller& x) {
  const auto [plus, minus, c] = terms_of(rs, rp);
  mueller out;
  for (int k = 0; k < 4; ++k) {
    out.m[0][k] = plus * x.m[0][k] + minus * x.m[1][k];
    out.m[1][k] = minus * x.m[0][k] + plus * x.m[1][k];
    out.m[2][k] = c.real() * x.m[2][k] - c.imag() * x.m[3][k];
    out.m[3][k] = c.imag() * x.m[2][k] + c.real() * x.m[3][k];
  }
  return out;
}

polarization_frame polarization_frame::at_surface(const glm::dvec3& k, const glm::dvec3& n) {
  const glm::dvec3 s = glm::cross(k, n);
  const double s2 = glm::dot(s, s);
  // Within 1e-9 rad of normal incidence every direction across k is an s direction.
  if (s2 < 1e-18) return about(k);
  return with_unit_x(k, s / std::sqrt(s2));
}

double angle_in(const polarization_frame& f, const glm::dvec3& axis) {
  return std::atan2(glm::dot(axis, f.y), glm::dot(axis, f.x));
}

mueller reframe(const polarization_frame& from, const polarization_frame& to) {
  return times_rotator(mueller::identity(), double_angle(from, to.x));
}

mueller reframed(const polarization_frame& from, const polarization_frame& to, const mueller& m) {
  return rotator_times(double_angle(from, to.x), m);
}

mueller reversed_path(const mueller& m) {
  static constexpr std::array<double, 4> g{1, 1, -1, 1};
  mueller r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = g[i] * m.m[j][i] * g[j];
  return r;
}

polarization_frame reflect_onto(mueller& path, const polarization_frame& in, const glm::dvec3& n, complex rs,
                                complex rp) {
  const polarization_frame sp = polarization_frame::at_surface(in.k, n);
  // The step is interface_mueller(rs, rp) times the rotator into sp, whose product with the path
  // is rotator_times. s is across the plane of incidence, so the light leaving shares it.
  path = interface_times(rs, rp, rotator_times(double_angle(in, sp.x), path));
  return polarization_frame::with_unit_x(reflect(in.k, n), sp.x);
}

polarization_frame transmit_onto(mueller& path, const polarization_frame& in, const glm::dvec3& n,
                                 const glm::dvec3& k_out, complex ts, complex tp, double energy) {
  const polarization_frame sp = polarization_frame::at_surface(in.k, n);
  path = interface_times(std::sqrt(energy) * ts, std::sqrt(energy) * tp, rotator_times(double_angle(in, sp.x), path));
  return polarization_frame::with_unit_x(k_out, sp.x);
}

polarized_step reflect_polarized(const polarization_frame& in, const glm::dvec3& n, complex rs, complex rp) {
  polarized_step step{mueller::identity(), in};
  step.out = reflect_onto(step.m, in, n, rs, rp);
  return step;
}

polarized_step transmit_polarized(const polarization_frame& in, const glm::dvec3& n, const glm::dvec3& k_out,
                                  complex ts, complex tp, double energy) {
  polarized_step step{mueller::identity(), in};
  step.out = transmit_onto(step.m, in, n, k_out, ts, tp, energy);
  return step;
}

}  // namespace airr
