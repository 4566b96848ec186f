#pragma once
// Polarized light as Stokes vectors, what parts do to it as Mueller matrices, and the frames both
// are written in. docs/polarization.md states the conventions (frames, handedness, the sign of
// circular light, retarders' fast axes) and the tests that pin them.
#include <array>
#include <cmath>
#include <complex>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"

namespace airr {

using complex = std::complex<double>;

// (S0, S1, S2, S3) in a frame (x, y, k): S1 = I_x - I_y, S2 = I_+45 - I_-45, S3 = 2 Im(Ex* Ey)
// (positive when the field turns from x towards y).
using stokes = glm::dvec4;

inline stokes unpolarized(double intensity = 1) { return {intensity, 0, 0, 0}; }
// Linear light at `angle_rad` from the frame's x towards its y.
stokes linear_light(double angle_rad, double intensity = 1);
// Circular light, S3 = +intensity (`positive`) or -intensity.
stokes circular_light(bool positive, double intensity = 1);
// sqrt(S1^2 + S2^2 + S3^2) / S0 (0 for no light).
double degree_of_polarization(const stokes& s);

// A Jones matrix: the complex amplitudes (Ex, Ey) out of a part from those in, m[row][col].
struct jones {
  std::array<std::array<complex, 2>, 2> m{{{1.0, 0.0}, {0.0, 1.0}}};
};
jones operator*(const jones& a, const jones& b);

// A Mueller matrix, m[row][col].
struct mueller {
  std::array<std::array<double, 4>, 4> m{};
  static mueller identity();
  static mueller scale(double factor);  // a neutral attenuator (or gain)
};
mueller operator*(const mueller& a, const mueller& b);
stokes operator*(const mueller& a, const stokes& s);
mueller operator+(const mueller& a, const mueller& b);

// The Mueller matrix of a Jones matrix (both in the same frames): M_ij = tr(s_i J s_j J^H) / 2 with
// the Pauli matrices of the Stokes definition above.
mueller mueller_of(const jones& j);

// Stokes vectors of a frame turned by `angle_rad` (its new x at that angle from the old, towards
// the old y) from those of the old frame.
mueller rotator(double angle_rad);

// Parts in the frame their angles are measured in: a linear polarizer (diattenuator) whose pass
// axis lies at `axis_rad` from x towards y, passing `t_pass` and `t_block` of the intensity along
// and across it; a linear retarder whose fast axis lies at `axis_rad`, delaying the slow axis by
// `retardance_rad`.
mueller linear_polarizer(double axis_rad, double t_pass = 1, double t_block = 0);
mueller linear_retarder(double axis_rad, double retardance_rad);

// An interface (or any part) that keeps s and p apart, with amplitude ratios rs and rp, in the s/p
// frames of the light in and out (polarization_frame::at_surface).
mueller interface_mueller(complex rs, complex rp);
// interface_mueller(rs, rp) * x without forming the interface's matrix or multiplying its zeros.
mueller interface_times(complex rs, complex rp, const mueller& x);

// The frame a Stokes vector is written in: x and y across the unit propagation direction k, with
// x cross y = k.
struct polarization_frame {
  glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, k{0, 0, 1};
  // Any frame about k (continuous except at k.z = -1).
  static polarization_frame about(const glm::dvec3& k) {
    const basis b = make_basis(k);
    return {b.t, b.b, k};
  }
  // The frame about k whose x is `x` made perpendicular to k (x not along k).
  static polarization_frame with_x(const glm::dvec3& k, const glm::dvec3& x);
  // The frame about k whose x is `s`, a unit vector across k already (the s direction a surface
  // gives the light arriving and leaving alike): nothing to project or normalise.
  static polarization_frame with_unit_x(const glm::dvec3& k, const glm::dvec3& s) { return {s, glm::cross(k, s), k}; }
  // The s/p frame of light travelling along k at a surface of unit normal n (either side):
  // x = s = k x n normalised, y = p = k x s. At normal incidence s is any direction across k.
  static polarization_frame at_surface(const glm::dvec3& k, const glm::dvec3& n);
};

// The angle of a world axis (a polarizer's or a film's) seen along the frame's k: from x towards y.
double angle_in(const polarization_frame& f, const glm::dvec3& axis);

// cos and sin of twice an angle: what a rotator of Stokes vectors needs.
struct double_angle {
  double c = 1, s = 0;
  explicit double_angle(double angle) : c(std::cos(2 * angle)), s(std::sin(2 * angle)) {}
  double_angle(double cos_2, double sin_2) : c(cos_2), s(sin_2) {}
  // Of a world axis seen in a frame (angle_in's angle), from its components alone: no
  // trigonometry on the tracer's hot path.
  double_angle(const polarization_frame& f, const glm::dvec3& axis) {
    const double a = glm::dot(axis, f.x), b = glm::dot(axis, f.y), r = a * a + b * b;
    if (r > 0) c = (a * a - b * b) / r, s = 2 * a * b / r;
  }
};

// linear_polarizer with its axis a world direction, at its angle_in the frame: worked out from the
// axis's components, with no trigonometry (the tracer's path).
mueller linear_polarizer(const polarization_frame& f, const glm::dvec3& axis, double t_pass = 1, double t_block = 0);
// A row of a path's matrix times a part with amplitude factors `along` and `across` its axis, a
// world direction seen in the frame: row * M without forming M (a polarizer: along sqrt(t_pass),
// across sqrt(t_block); a retarder: 1 and e^(i retardance)).
glm::dvec4 row_through_axial_part(const glm::dvec4& row, const polarization_frame& f, const glm::dvec3& axis,
                                  complex along, complex across);
// The same with the axis's double_angle in the frame worked out already (one part, several rows).
glm::dvec4 row_through_axial_part(const glm::dvec4& row, double_angle axis, complex along, complex across);

// The rotator that rewrites a Stokes vector of frame `from` in frame `to` (same k).
mueller reframe(const polarization_frame& from, const polarization_frame& to);
// reframe(from, to) * m, without the rotator's zeros.
mueller reframed(const polarization_frame& from, const polarization_frame& to, const mueller& m);

// Reciprocity: a part met the other way. The light reversed is written in reversed(frame),
// (x, -y, -k); a path's Mueller matrix from `in` to `out` becomes, from reversed(out) to
// reversed(in), G M^T G with G = diag(1, 1, -1, 1) (the Jones matrix's transpose in the
// reversed frames; sums of such matrices alike).
inline polarization_frame reversed(const polarization_frame& f) { return {f.x, -f.y, -f.k}; }
mueller reversed_path(const mueller& m);

// One interaction at a surface of unit normal n: its Mueller matrix from the light's frame `in`
// to `out`, the s/p frame of the light leaving (its k the new direction).
struct polarized_step {
  mueller m;
  polarization_frame out;
};
// Reflection with amplitude ratios rs and rp (dielectric.hpp's for an interface).
polarized_step reflect_polarized(const polarization_frame& in, const glm::dvec3& n, complex rs, complex rp);
// Transmission into the unit direction k_out with amplitude ratios ts and tp; `energy` turns
// squared amplitudes into the intensity passed (Re(eta cos_t) / cos_i for an interface).
polarized_step transmit_polarized(const polarization_frame& in, const glm::dvec3& n, const glm::dvec3& k_out,
                                  complex ts, complex tp, double energy);
// The same onto a path's matrix so far (from its first frame to `in`): `path` becomes step.m * path,
// worked out without the interface's and the turn's zeros (a walk's every event); returns step.out.
polarization_frame reflect_onto(mueller& path, const polarization_frame& in, const glm::dvec3& n, complex rs,
                                complex rp);
polarization_frame transmit_onto(mueller& path, const polarization_frame& in, const glm::dvec3& n,
                                 const glm::dvec3& k_out, complex ts, complex tp, double energy);

}  // namespace airr
