// Polarization's conventions and parts (docs/polarization.md): Malus's law, a quarter-wave film
// passed twice by way of a mirror, the Fresnel equations in their textbook form, and a total-
// internal-reflection cube corner against the electric field followed through its faces in 3D.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/models/corner_cube.hpp"
#include "airr/models/dielectric.hpp"
#include "airr/models/polarization.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/retro_model.hpp"

using namespace airr;

namespace {

void expect_stokes_near(const stokes& a, const stokes& b, double tolerance, const std::string& what) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << what << ", S" << i;
}

void expect_mueller_near(const mueller& a, const mueller& b, double tolerance, const std::string& what) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.m[r][c], b.m[r][c], tolerance) << what << ", m" << r << c;
}

// Intensity along a world axis (a polarizer's pass axis) of Stokes vector s written in frame f.
double intensity_along(const stokes& s, const polarization_frame& f, const glm::dvec3& axis) {
  return (linear_polarizer(angle_in(f, axis)) * s)[0];
}

}  // namespace

// Turning frames: a polarizer at a, light at a, and rotators composed agree with the part at 0 seen
// from a turned frame; a Jones rotation's Mueller matrix is the rotator.
TEST(Polarization, FramesTurnAsTheirAnglesSay) {
  for (double deg = -90; deg <= 180; deg += 15) {
    const double a = radians(deg);
    expect_stokes_near(rotator(-a) * linear_light(0), linear_light(a), 1e-12, "light at " + std::to_string(deg));
    expect_mueller_near(rotator(-a) * linear_polarizer(0) * rotator(a), linear_polarizer(a), 1e-12,
                        "polarizer at " + std::to_string(deg));
    jones turn;
    turn.m = {{{std::cos(a), std::sin(a)}, {-std::sin(a), std::cos(a)}}};
    expect_mueller_near(mueller_of(turn), rotator(a), 1e-12, "Jones rotation " + std::to_string(deg));
  }
  // Circular light keeps its S3 in every frame about the same k.
  expect_stokes_near(rotator(0.7) * circular_light(true), circular_light(true), 1e-12, "circular");
  // S3 > 0 is the field turning from x towards y: Jones (1, i) / sqrt 2.
  jones to_circular;  // takes (1, 0) to (1, i) / sqrt 2
  to_circular.m = {{{std::sqrt(0.5), 0.0}, {complex(0, std::sqrt(0.5)), 0.0}}};
  expect_stokes_near(mueller_of(to_circular) * linear_light(0), circular_light(true), 1e-12, "(1, i)");
  // A frame's angle of its own axes.
  const polarization_frame f = polarization_frame::with_x(glm::normalize(glm::dvec3(0.2, -0.3, 1)), {1, 0, 0});
  EXPECT_NEAR(angle_in(f, f.x), 0, 1e-12);
  EXPECT_NEAR(angle_in(f, f.y), pi / 2, 1e-12);
  EXPECT_NEAR(glm::dot(glm::cross(f.x, f.y), f.k), 1, 1e-12);
}

// A surface's s direction is across the light arriving and leaving (reflected or refracted, in
// the plane of incidence): the frames built on it as it is equal those that project it again.
TEST(Polarization, ASurfacesSDirectionIsAcrossTheLightInAndOut) {
  pcg32 rng(7, 1);
  const auto direction = [&] {
    return glm::normalize(glm::dvec3(rng.next_double(), rng.next_double(), rng.next_double()) - 0.5);
  };
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec3 k = direction(), n = direction();
    const polarization_frame sp = polarization_frame::at_surface(k, n);
    const polarization_frame projected = polarization_frame::with_x(k, glm::cross(k, n));
    const glm::dvec3 out[2] = {reflect(k, n), glm::normalize(k + 0.3 * n)};  // reflected, refracted-like
    for (const glm::dvec3& k_out : out) {
      const polarization_frame a = polarization_frame::with_unit_x(k_out, sp.x);
      const polarization_frame b = polarization_frame::with_x(k_out, sp.x);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(a.x[c], b.x[c], 1e-14) << i;
        EXPECT_NEAR(a.y[c], b.y[c], 1e-14) << i;
      }
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sp.x[c], projected.x[c], 1e-14) << i;
      EXPECT_NEAR(sp.y[c], projected.y[c], 1e-14) << i;
    }
  }
}

// The parts' closed forms are mueller_of of their Jones matrices.
TEST(Polarization, ClosedFormsAreTheJonesMatricesMuellerMatrices) {
  const complex rs(0.3, -0.7), rp(-0.55, 0.2);
  jones d;
  d.m = {{{rs, 0.0}, {0.0, rp}}};
  expect_mueller_near(interface_mueller(rs, rp), mueller_of(d), 1e-14, "interface");
  for (double deg : {-60.0, 0.0, 20.0, 45.0, 110.0}) {
    const double a = radians(deg), c = std::cos(a), s = std::sin(a);
    jones turn, back, retarder, polarizer;
    turn.m = {{{c, s}, {-s, c}}};
    back.m = {{{c, -s}, {s, c}}};
    retarder.m = {{{1.0, 0.0}, {0.0, std::polar(1.0, 1.1)}}};
    polarizer.m = {{{std::sqrt(0.8), 0.0}, {0.0, std::sqrt(0.05)}}};
    expect_mueller_near(linear_retarder(a, 1.1), mueller_of(back * retarder * turn), 1e-14, "retarder");
    expect_mueller_near(linear_polarizer(a, 0.8, 0.05), mueller_of(back * polarizer * turn), 1e-14, "polarizer");
    // Given as a world axis in a frame, at that angle from its x towards its y (its length free).
    const polarization_frame f = polarization_frame::about(glm::normalize(glm::dvec3(0.3, -0.4, 0.8)));
    const glm::dvec3 axis = 2.5 * (c * f.x + s * f.y);
    expect_mueller_near(linear_polarizer(f, axis, 0.8, 0.05), mueller_of(back * polarizer * turn), 1e-14,
                        "polarizer, axis");
    // And a row of a path's matrix through them, without the matrices.
    const glm::dvec4 row(0.9, -0.3, 0.45, 0.2);
    const auto row_near = [&](const glm::dvec4& got, const mueller& m, const char* what) {
      for (int k = 0; k < 4; ++k) {
        const double want = row[0] * m.m[0][k] + row[1] * m.m[1][k] + row[2] * m.m[2][k] + row[3] * m.m[3][k];
        EXPECT_NEAR(got[k], want, 1e-14) << what << ", column " << k << " at " << deg << " deg";
      }
    };
    row_near(row_through_axial_part(row, f, axis, 1.0, std::polar(1.0, 1.1)), linear_retarder(a, 1.1), "retarder row");
    row_near(row_through_axial_part(row, f, axis, std::sqrt(0.8), std::sqrt(0.05)), linear_polarizer(a, 0.8, 0.05),
             "polarizer row");
  }
}

// Malus's law: unpolarized light through two polarizers at 0 and theta passes cos^2(theta) / 2.
TEST(Polarization, MalussLawForAPolarizerPair) {
  for (int deg = 0; deg <= 90; deg += 5) {
    const double theta = radians(deg);
    const stokes out = linear_polarizer(theta) * linear_polarizer(0) * unpolarized();
    EXPECT_NEAR(out[0], 0.5 * std::cos(theta) * std::cos(theta), 1e-12) << deg << " deg";
  }
  // An imperfect pair: pass 0.9, block 0.01 (extinction 90:1) crossed passes 0.9 * 0.01.
  const stokes crossed = linear_polarizer(pi / 2, 0.9, 0.01) * linear_polarizer(0, 0.9, 0.01) * unpolarized();
  EXPECT_NEAR(crossed[0], 0.9 * 0.01, 1e-12);
}

// A quarter-wave film on a mirror at normal incidence, its fast axis at 45 deg to horizontal light:
// there and back it turns horizontal into vertical, leaving cos^2(delta) horizontal for a film of
// retardance delta each way (a retarder of 2 delta); laid at 0 or 90 deg it changes nothing. The
// film's axis is fixed in the world, so the light's frames on the way in and out (whose y axes
// point opposite ways) see it at different angles.
TEST(Polarization, AQuarterWaveFilmPassedTwiceTurnsHorizontalIntoVertical) {
  const glm::dvec3 X{1, 0, 0}, Y{0, 1, 0}, normal{0, 0, 1};
  const polarization_frame in = polarization_frame::with_x({0, 0, -1}, X);
  for (double waves : {0.25, 0.22, 0.27, 0.3}) {
    const double delta = 2 * pi * waves;
    for (double axis_deg : {45.0, -45.0, 0.0, 90.0}) {
      const glm::dvec3 axis = std::cos(radians(axis_deg)) * X + std::sin(radians(axis_deg)) * Y;
      const stokes there = linear_retarder(angle_in(in, axis), delta) * linear_light(0);
      const polarized_step mirror = reflect_polarized(in, normal, -1.0, 1.0);
      const stokes back = linear_retarder(angle_in(mirror.out, axis), delta) * (mirror.m * there);
      ASSERT_NEAR(mirror.out.k.z, 1, 1e-12);
      const double h = intensity_along(back, mirror.out, X), v = intensity_along(back, mirror.out, Y);
      const bool diagonal = std::abs(axis_deg) == 45;
      const double expected_h = diagonal ? std::cos(delta) * std::cos(delta) : 1.0;
      EXPECT_NEAR(h, expected_h, 1e-12) << waves << " waves at " << axis_deg << " deg";
      EXPECT_NEAR(h + v, 1, 1e-12) << waves << " waves at " << axis_deg << " deg";
    }
  }
}

// The Fresnel equations in their textbook (sine and tangent) form, glass of index 1.5 from air.
TEST(Polarization, FresnelAmplitudesMatchTheFresnelEquations) {
  const double n = 1.5;
  for (int deg = 0; deg <= 80; deg += 5) {
    const double i = radians(deg), t = std::asin(std::sin(i) / n);
    const fresnel_coefficients f = fresnel_amplitudes(std::cos(i), n);
    const double normal = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    const double rs = deg == 0 ? normal : std::pow(std::sin(i - t) / std::sin(i + t), 2);
    const double rp = deg == 0 ? normal : std::pow(std::tan(i - t) / std::tan(i + t), 2);
    EXPECT_NEAR(std::norm(f.rs), rs, 1e-12) << deg << " deg";
    EXPECT_NEAR(std::norm(f.rp), rp, 1e-12) << deg << " deg";
    // What passes: T = n cos(t) / cos(i) |t|^2, and R + T = 1 for each.
    const double energy = n * std::cos(t) / std::cos(i);
    EXPECT_NEAR(std::norm(f.rs) + energy * std::norm(f.ts), 1, 1e-12) << deg << " deg";
    EXPECT_NEAR(std::norm(f.rp) + energy * std::norm(f.tp), 1, 1e-12) << deg << " deg";
    // The unpolarized reflectance the tracer uses is their mean.
    EXPECT_NEAR(fresnel_dielectric(std::cos(i), n), 0.5 * (rs + rp), 1e-14) << deg << " deg";
    // As Mueller matrices in the s/p frames: unpolarized light reflected is partly s-polarized.
    const glm::dvec3 k{std::sin(i), 0, -std::cos(i)};
    const polarized_step r = reflect_polarized(polarization_frame::about(k), {0, 0, 1}, f.rs, f.rp);
    const stokes out = r.m * unpolarized();
    EXPECT_NEAR(out[0], 0.5 * (rs + rp), 1e-12) << deg << " deg";
    if (deg > 0) {
      EXPECT_NEAR(intensity_along(out, r.out, {0, 1, 0}), 0.5 * rs, 1e-12) << deg << " deg (s is y)";
    }
  }
  const fresnel_coefficients brewster = fresnel_amplitudes(std::cos(std::atan(n)), n);
  EXPECT_LT(std::norm(brewster.rp), 1e-24);
  EXPECT_GT(std::norm(brewster.rs), 0.1);
}

// Total internal reflection, glass (1.5) to air beyond the critical angle: every amplitude ratio
// has modulus 1 and the phases tan(phi_s / 2) = -sqrt(sin^2 - n^2) / cos,
// tan(phi_p / 2) = -sqrt(sin^2 - n^2) / (n^2 cos) with n = 1 / 1.5 (Born & Wolf, with the
// e^{-i omega t} of docs/polarization.md).
TEST(Polarization, TotalInternalReflectionHasTheTextbookPhases) {
  const double n = 1 / 1.5;
  EXPECT_FALSE(fresnel_amplitudes(std::cos(radians(41)), n).total);
  for (double deg = 42; deg <= 89; deg += 4) {
    const double i = radians(deg), root = std::sqrt(std::sin(i) * std::sin(i) - n * n);
    const fresnel_coefficients f = fresnel_amplitudes(std::cos(i), n);
    EXPECT_TRUE(f.total) << deg;
    EXPECT_NEAR(std::abs(f.rs), 1, 1e-12) << deg;
    EXPECT_NEAR(std::abs(f.rp), 1, 1e-12) << deg;
    EXPECT_NEAR(std::arg(f.rs), -2 * std::atan(root / std::cos(i)), 1e-12) << deg;
    EXPECT_NEAR(std::arg(f.rp), -2 * std::atan(root / (n * n * std::cos(i))), 1e-12) << deg;
    EXPECT_GE(f.cos_t.imag(), 0) << deg;
  }
}

// A clear medium's amplitudes (worked out in real arithmetic) equal the complex formulas' (run
// for an index with a vanishing imaginary part), below and beyond the critical angle.
TEST(Polarization, FresnelAmplitudesOfAClearMediumEqualTheComplexFormulas) {
  pcg32 rng(7, 1);
  for (const double n : {1.5, 1 / 1.5, 1.33, 1 / 1.33}) {
    for (int k = 0; k < 1000; ++k) {
      const double cos_i = k == 0 ? 1.0 : k == 1 ? 0.0 : rng.next_double();
      const fresnel_coefficients real = fresnel_amplitudes(cos_i, n);
      const fresnel_coefficients general = fresnel_amplitudes(cos_i, complex(n, 1e-200));
      for (const auto& [a, b] :
           {std::pair{real.rs, general.rs}, std::pair{real.rp, general.rp}, std::pair{real.ts, general.ts},
            std::pair{real.tp, general.tp}, std::pair{real.cos_t, general.cos_t}}) {
        EXPECT_LT(std::abs(a - b), 1e-12) << "index " << n << ", cos_i " << cos_i;
      }
    }
  }
}

// A metal's amplitudes (the principal root and the shared reciprocals worked out in real arithmetic)
// equal the textbook formulas written with the library's complex root and division.
TEST(Polarization, FresnelAmplitudesOfAMetalEqualTheTextbookFormulas) {
  pcg32 rng(7, 2);
  for (const complex eta : {complex(0.96, 6.69), complex(0.96, 6.69) / 1.5, complex(0.2, 3.0), complex(2.5, 0.4)}) {
    for (int k = 0; k < 1000; ++k) {
      const double cos_i = k == 0 ? 1.0 : k == 1 ? 0.0 : rng.next_double();
      const complex ci(cos_i);
      complex cos_t = std::sqrt(1.0 - (1 - cos_i * cos_i) / (eta * eta));
      if (cos_t.imag() < 0) cos_t = -cos_t;
      const fresnel_coefficients f = fresnel_amplitudes(cos_i, eta);
      for (const auto& [a, b] :
           {std::pair{f.cos_t, cos_t}, std::pair{f.rs, (ci - eta * cos_t) / (ci + eta * cos_t)},
            std::pair{f.rp, (eta * ci - cos_t) / (eta * ci + cos_t)}, std::pair{f.ts, 2.0 * ci / (ci + eta * cos_t)},
            std::pair{f.tp, 2.0 * ci / (eta * ci + cos_t)}}) {
        EXPECT_LT(std::abs(a - b), 1e-12 * std::max(1.0, std::abs(b))) << "eta " << eta << ", cos_i " << cos_i;
      }
    }
  }
}

namespace {

using field = std::array<complex, 3>;  // a complex electric field vector in world coordinates

complex along(const field& e, const glm::dvec3& u) { return e[0] * u.x + e[1] * u.y + e[2] * u.z; }

field combine(complex a, const glm::dvec3& u, complex b, const glm::dvec3& v) {
  return {a * u.x + b * v.x, a * u.y + b * v.y, a * u.z + b * v.z};
}

// The Stokes vector of field e in frame f.
stokes stokes_of(const field& e, const polarization_frame& f) {
  const complex ex = along(e, f.x), ey = along(e, f.y);
  const complex cross = std::conj(ex) * ey;
  return {std::norm(ex) + std::norm(ey), std::norm(ex) - std::norm(ey), 2 * cross.real(), 2 * cross.imag()};
}

// The field after total internal reflection at a face of normal m, with the textbook phases
// (TotalInternalReflectionHasTheTextbookPhases), built from s = k x m and p = k x s of its own.
field reflect_field(const field& e, glm::dvec3& k, const glm::dvec3& m, double n) {
  const double cos_i = std::abs(glm::dot(k, m)), sin2 = 1 - cos_i * cos_i;
  const double root = std::sqrt(sin2 - n * n);
  const complex rs = std::polar(1.0, -2 * std::atan(root / cos_i));
  const complex rp = std::polar(1.0, -2 * std::atan(root / (n * n * cos_i)));
  const glm::dvec3 s = glm::normalize(glm::cross(k, m)), p_in = glm::cross(k, s);
  const glm::dvec3 k_out = k - 2 * glm::dot(k, m) * m, p_out = glm::cross(k_out, s);
  k = k_out;
  return combine(rs * along(e, s), s, rp * along(e, p_in), p_out);
}

}  // namespace

// A cube corner of index 1.5 reflecting by total internal reflection, for each of the six orders
// in which light meets its faces: the Mueller chain (frames turned face by face) against the
// electric field followed through the faces in 3D, for linear, diagonal and circular light and
// two directions. Each order keeps the light fully polarized and retroreflects it; the six orders'
// mean (the aperture's six sectors, equal at normal incidence) depolarizes linear light alike at
// every angle, as the literature on TIR cube corners describes, and keeps all of it.
TEST(Polarization, TirCubeCornerMatchesTheFieldFollowedThroughItsFaces) {
  const double index = 1.5, n = 1 / index;
  const std::array<glm::dvec3, 3> axes{glm::dvec3{1, 0, 0}, glm::dvec3{0, 1, 0}, glm::dvec3{0, 0, 1}};
  const std::array<std::array<int, 3>, 6> orders{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  const glm::dvec3 normal_incidence = -glm::normalize(glm::dvec3(1, 1, 1));
  const glm::dvec3 tilted = -glm::normalize(glm::dvec3(1, 1.15, 0.9));
  for (const glm::dvec3& k_in : {normal_incidence, tilted}) {
    const polarization_frame in = polarization_frame::with_x(k_in, {1, -1, 0});
    // Stokes vectors add only in one frame: each order's is written in the frame of the light out.
    const polarization_frame common = polarization_frame::with_x(-k_in, {1, -1, 0});
    mueller mean;
    for (const auto& order : orders) {
      const std::array<glm::dvec3, 3> faces{axes[order[0]], axes[order[1]], axes[order[2]]};
      const polarized_step path = cube_corner_polarized(in, faces, n);
      EXPECT_NEAR(glm::length(path.out.k + k_in), 0, 1e-12) << "retroreflected";
      mean = mean + mueller::scale(1.0 / 6) * reframe(path.out, common) * path.m;
      const std::array<std::array<complex, 2>, 4> inputs{{{1.0, 0.0},
                                                          {std::sqrt(0.5), std::sqrt(0.5)},
                                                          {std::sqrt(0.5), complex(0, std::sqrt(0.5))},
                                                          {0.6, complex(0.48, -0.64)}}};
      for (const auto& amplitudes : inputs) {
        field e = combine(amplitudes[0], in.x, amplitudes[1], in.y);
        const stokes s_in = stokes_of(e, in);
        glm::dvec3 k = k_in;
        for (const glm::dvec3& m : faces) e = reflect_field(e, k, m, n);
        const stokes expected = stokes_of(e, path.out);
        const stokes got = path.m * s_in;
        expect_stokes_near(got, expected, 1e-12,
                           "order " + std::to_string(order[0]) + std::to_string(order[1]) + std::to_string(order[2]));
        EXPECT_NEAR(degree_of_polarization(got), 1, 1e-12);
        EXPECT_NEAR(got[0], s_in[0], 1e-12) << "lossless";
      }
    }
    if (k_in != normal_incidence) continue;
    EXPECT_NEAR(mean.m[0][0], 1, 1e-12);
    std::printf("TIR cube corner (index %.2f), the six orders' mean at normal incidence, linear light at:\n", index);
    double first = -1;
    for (int deg = 0; deg < 180; deg += 15) {
      const double dop = degree_of_polarization(mean * linear_light(radians(deg)));
      std::printf("  %3d deg: degree of polarization %.4f\n", deg, dop);
      EXPECT_LT(dop, 0.9) << deg;
      if (first < 0) first = dop;
      EXPECT_NEAR(dop, first, 1e-9) << "the same at every angle (three-fold symmetry), " << deg;
    }
    std::printf("  circular: %.4f\n", degree_of_polarization(mean * circular_light(true)));
    // Aluminium-coated faces (n = 0.96 + 6.69i at 550 nm) turn the light far less.
    mueller metal;
    for (const auto& order : orders) {
      const polarized_step path =
          cube_corner_polarized(in, {axes[order[0]], axes[order[1]], axes[order[2]]}, complex(0.96, 6.69) / index);
      metal = metal + mueller::scale(1.0 / 6) * reframe(path.out, common) * path.m;
    }
    const stokes metal_out = metal * linear_light(0);
    std::printf("aluminium-coated: keeps %.4f of the light, degree of polarization %.4f (linear), %.4f (circular)\n",
                metal_out[0], degree_of_polarization(metal_out), degree_of_polarization(metal * circular_light(true)));
    EXPECT_GT(degree_of_polarization(metal_out), 0.9);
    EXPECT_LT(metal_out[0], 1);
  }
}

// Reciprocity: the cube corner met the other way (faces in the reverse order, from the light's
// way out) is the path's matrix reversed, G M^T G in the reversed frames.
TEST(Polarization, APathMetTheOtherWayIsItsMatrixReversed) {
  const glm::dvec3 k_in = -glm::normalize(glm::dvec3(1, 1.15, 0.9));
  const polarization_frame in = polarization_frame::with_x(k_in, {1, -1, 0});
  const std::array<glm::dvec3, 3> faces{glm::dvec3{0, 1, 0}, glm::dvec3{0, 0, 1}, glm::dvec3{1, 0, 0}};
  for (const complex eta : {complex(1 / 1.5), complex(0.96, 6.69) / 1.5}) {
    const polarized_step there = cube_corner_polarized(in, faces, eta);
    const polarized_step back = cube_corner_polarized(reversed(there.out), {faces[2], faces[1], faces[0]}, eta);
    expect_mueller_near(reframe(back.out, reversed(in)) * back.m, reversed_path(there.m), 1e-12,
                        "eta " + std::to_string(eta.real()));
  }
}

// The prism sheet's walk with polarization, at normal incidence (no diffraction): over its paths
// by one cube corner's three faces its mean matrix depolarizes as the cube corner's six orders do
// (TirCubeCornerMatchesTheFieldFollowedThroughItsFaces: 0.213 for linear light, 0.260 circular;
// aluminium-coated 0.995), its sectors being equal; the sheet's model gives the light's own path.
TEST(Polarization, ThePrismSheetsWalkDepolarizesAsItsCubeCornersDo) {
  for (const bool metal : {false, true}) {
    prism_sheet_geometry g;
    g.wavelength_nm = 0;
    g.metallised = metal;
    const prism_sheet_retro sheet(g);
    const glm::dvec3 wi{0, 0, 1};
    pcg32 rng(7, 3);
    mueller corner, all;
    double corner_weight = 0, all_weight = 0;
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec2 cell{rng.next_double(), rng.next_double()};
      const double u_front = rng.next_double();
      pcg32 more = rng.split(), again = more;
      std::optional<mueller> m;
      const prism_path path = trace_prism_sheet(g, wi, prism_cell_point(g, cell), u_front, more, &m);
      if (path.fate != prism_fate::retroreflected || !(path.weight > 0)) continue;
      ASSERT_TRUE(m);
      if (path.face_reflections == 3 && path.front_reflections == 0) {
        corner = corner + mueller::scale(path.weight) * *m;
        corner_weight += path.weight;
      }
      // The model's sample is the same path, the other way.
      const retro_sample s = sheet.sample_polarized(wi, {cell, {u_front, 0.5}, again});
      ASSERT_TRUE(s.polarization);
      expect_mueller_near(*s.polarization, reversed_path(*m), 1e-12, "sample " + std::to_string(i));
      all = all + mueller::scale(s.weight) * *s.polarization;
      all_weight += s.weight;
    }
    const mueller mean = mueller::scale(1 / corner_weight) * corner, mean_all = mueller::scale(1 / all_weight) * all;
    const double linear = degree_of_polarization(mean * linear_light(0.3));
    const double circular = degree_of_polarization(mean * circular_light(true));
    std::printf(
        "prism sheet (%s), one cube corner's paths: degree of polarization %.4f (linear), %.4f (circular); "
        "every retroreflected path: %.4f, %.4f\n",
        metal ? "metal" : "TIR", linear, circular, degree_of_polarization(mean_all * linear_light(0.3)),
        degree_of_polarization(mean_all * circular_light(true)));
    EXPECT_NEAR(linear, metal ? 0.995 : 0.213, 0.015);
    EXPECT_NEAR(circular, metal ? 1.0 : 0.260, 0.015);
  }
}
