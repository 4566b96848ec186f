// The prism sheet traced as geometry: its retroreflected fraction is the cube corner's effective
// area (the aperture's overlap with its image through the apex, worked out here with polygons),
// its shifts are the corner-cube shift table's, and no light is lost.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/models/dielectric.hpp"
#include "airr/models/prism_sheet.hpp"
#include "airr/models/shift_table.hpp"
#include "chi_square.hpp"
#include "prism_test_support.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

using polygon = polygon2;

// The part of convex `subject` inside convex, counter-clockwise `clip` (Sutherland-Hodgman).
polygon clip_convex(polygon subject, const polygon& clip) {
  for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const glm::dvec2 a = clip[i], b = clip[(i + 1) % clip.size()];
    auto inside = [&](const glm::dvec2& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) >= 0; };
    polygon out;
    for (std::size_t j = 0; j < subject.size(); ++j) {
      const glm::dvec2 p = subject[j], q = subject[(j + 1) % subject.size()];
      if (inside(p)) out.push_back(p);
      if (inside(p) != inside(q)) {
        const double cp = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        const double cq = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
        out.push_back(p + (q - p) * (cp / (cp - cq)));
      }
    }
    subject = std::move(out);
  }
  return subject;
}

// Effective area of one triangular cube corner (aperture: an equilateral triangle of height 1
// pointing along +x from its centroid, apex sqrt(2)/3 below it) for light going along d inside:
// a ray retroreflects when its exit point, its entry point mirrored through where the line through
// the apex along d meets the aperture plane, is inside the aperture too. The aperture's overlap
// with its image mirrored through that point, over its area.
double effective_area(const glm::dvec3& d) {
  const double side = 2 / std::sqrt(3.0);
  const polygon t = {{2.0 / 3, 0}, {-1.0 / 3, side / 2}, {-1.0 / 3, -side / 2}};
  const double depth = std::sqrt(2.0) / 3;
  const glm::dvec2 q = glm::dvec2(d) * (depth / d.z);  // apex (0, 0, -depth) + s d at z = 0
  polygon image;
  for (const glm::dvec2& p : t) image.push_back(2.0 * q - p);
  return polygon_area(clip_convex(image, t)) / polygon_area(t);
}

}  // namespace

// The polygon computation itself: 2/3 at normal incidence (the central hexagon), as spec section 3
// says, and the shift table's fractions (its own Embree tracing of one cube in air) over azimuth.
TEST(PrismSheet, EffectiveAreaOfTheCubeCorner) {
  EXPECT_NEAR(effective_area({0, 0, -1}), 2.0 / 3, 1e-12);
  const shift_table table = load_shift_table(default_shift_table_path());
  for (std::size_t i = 0; i < table.theta_deg.size(); ++i) {
    // The table's cube in air: the ray's angle to the sheet normal is its internal angle.
    double mean = 0;
    const int steps = 720;
    for (int k = 0; k < steps; ++k)
      mean += effective_area(-test::unit_direction(table.theta_deg[i], 360.0 * (k + 0.5) / steps));
    mean /= steps;
    EXPECT_NEAR(mean, table.retro_fraction[i], 0.004) << table.theta_deg[i] << " deg";
  }
}

// With mirror faces, the light retroreflected by one cube corner's three faces, as a fraction of
// what entered, is the mean of the two cube orientations' effective areas at the internal
// direction times the exit's Fresnel transmission, within the binomial error: in air (index 1, no
// plate), where it is all the retroreflected light, and in a plate of index 1.5, where light the
// front surface reflects back in (totally, beyond the critical angle) can come back reversed
// after more faces.
TEST(PrismSheet, RetroreflectedFractionIsTheEffectiveArea) {
  for (const double index : {1.0, 1.5}) {
    prism_sheet_geometry g;
    g.index = index;
    g.plate_mm = index == 1.0 ? 0.0 : 0.1;
    g.metallised = true;
    g.face_reflectance = 1;
    for (const double theta : {0.0, 10.0, 25.0, 40.0}) {
      for (const double phi : {0.0, 17.0, 30.0, 90.0}) {
        const glm::dvec3 wi = test::unit_direction(theta, phi);
        const int n = 20000;
        const test::fates f = test::trace_many(g, wi, n, std::uint64_t(theta * 100 + phi));
        // Inside: the refracted direction; out again, the front surface passes 1 - F of it.
        const glm::dvec3 d = glm::normalize(glm::dvec3(-wi.x / index, -wi.y / index, 0) +
                                            glm::dvec3(0, 0, -std::sqrt(1 - (1 - wi.z * wi.z) / (index * index))));
        // The array's cubes point along the groove normals' directions: e_0 is +y at azimuth 0,
        // so a cube of one orientation points along +y, the other along -y.
        const glm::dvec3 d_up(d.y, -d.x, d.z), d_down(-d.y, d.x, d.z);
        const double era = 0.5 * (effective_area(d_up) + effective_area(d_down));
        const double entered = f.n - f.front;
        const double out = 1 - fresnel_dielectric(-d.z, 1 / index);
        const double expected = era * out;
        const double measured = f.cube_retro / entered;
        const double sigma = std::sqrt(expected * (1 - expected) / entered);
        std::printf(
            "index %.1f theta %4.1f phi %4.1f: by one cube %.4f, effective area x exit %.4f; retroreflected in all "
            "%.4f\n",
            index, theta, phi, measured, expected, f.retro / entered);
        EXPECT_NEAR(measured, expected, 4 * sigma + 1e-3) << "theta " << theta << " phi " << phi;
        if (index == 1.0) {
          EXPECT_EQ(f.retro, f.cube_retro);
        }
        EXPECT_LE(f.lost / f.n, 0.001);
      }
    }
  }
}

// The retroreflected paths' shifts in cube edges, over uniform azimuths, against the corner-cube
// shift table (chi-square).
TEST(PrismSheet, ShiftsFollowTheCornerCubeShiftTable) {
  const shift_table table = load_shift_table(default_shift_table_path());
  prism_sheet_geometry g;
  g.index = 1;
  g.plate_mm = 0;
  g.metallised = true;
  g.face_reflectance = 1;
  pcg32 rng(11, 3);
  for (const std::size_t row : {std::size_t(0), std::size_t(3), std::size_t(6)}) {
    const int bins = table.bins();
    std::vector<double> counts(std::size_t(bins), 0.0);
    double kept = 0;
    while (kept < 20000) {
      const glm::dvec3 wi = test::unit_direction(table.theta_deg[row], 360 * rng.next_double());
      const glm::dvec2 entry = prism_cell_point(g, {rng.next_double(), rng.next_double()});
      const prism_path p = trace_prism_sheet(g, wi, entry, rng.next_double(), rng);
      if (p.fate != prism_fate::retroreflected) continue;
      const double s = glm::length(p.shift_mm) / g.cube_edge_mm();
      counts[std::size_t(std::min(bins - 1, int(s / table.s_max * bins)))] += 1;
      kept += 1;
    }
    std::vector<double> expected;
    for (double pr : table.probability[row]) expected.push_back(pr * kept);
    const test::chi_square_result r = test::chi_square(counts, expected);
    std::printf("theta %g: chi-square %.1f on %d dof, p = %.3f\n", table.theta_deg[row], r.statistic, r.dof, r.p_value);
    EXPECT_GT(r.p_value, 1e-3) << "theta " << table.theta_deg[row];
  }
}

// A sheet with total internal reflection and no absorption: what is reflected by the front,
// retroreflected, scattered out of the front and transmitted out of the back adds up to all the
// light, and none is lost.
TEST(PrismSheet, NoLightIsLostByALosslessSheet) {
  const prism_sheet_geometry g;  // index 1.5, TIR faces
  for (const test::fates& f : test::expect_no_light_lost(g, 5))
    EXPECT_GT(f.transmitted, 0);  // where total internal reflection fails
}

// The model's own effective aperture (the polygon diffraction uses) has the effective area worked
// out here.
TEST(PrismSheet, EffectiveApertureHasTheEffectiveArea) {
  prism_sheet_geometry g;
  g.pitch_mm = 0.3;
  const double triangle = g.triangle_side_mm() * g.pitch_mm / 2;
  pcg32 rng(4, 4);
  for (int i = 0; i < 50; ++i) {
    const glm::dvec3 d = -test::unit_direction(40 * rng.next_double(), 360 * rng.next_double());
    // The array's triangles of pointing +1 point along +y at azimuth 0, the others along -y.
    const double up = effective_area({d.y, -d.x, d.z}), down = effective_area({-d.y, d.x, d.z});
    EXPECT_NEAR(polygon_area(effective_aperture(g, d, 1)) / triangle, up, 1e-9);
    EXPECT_NEAR(polygon_area(effective_aperture(g, d, -1)) / triangle, down, 1e-9);
  }
}
