#pragma once
// Many paths through a prism sheet (or any plate traced as geometry: a tile sheet) at one
// incidence, counted by where they ended; the spread of its retroreflected light; the lossless
// sheet's energy check.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "airr/core/random.hpp"
#include "airr/models/prism_sheet.hpp"
#include "test_helpers.hpp"

namespace airr::test {

struct fates {
  double front = 0, retro = 0, stray = 0, transmitted = 0, lost = 0, n = 0;
  double cube_retro = 0;  // retroreflected by one cube corner's three faces alone
};

// One path entering at a point of the sheet's cell drawn from rng.
using path_source = std::function<prism_path(const glm::dvec3& wi, pcg32& rng)>;

inline path_source prism_paths(const prism_sheet_geometry& g) {
  return [g](const glm::dvec3& wi, pcg32& rng) {
    const glm::dvec2 entry = prism_cell_point(g, {rng.next_double(), rng.next_double()});
    return trace_prism_sheet(g, wi, entry, rng.next_double(), rng);
  };
}

inline fates trace_many(const path_source& paths, const glm::dvec3& wi, int n, std::uint64_t seed) {
  pcg32 rng(seed, 7);
  fates f;
  for (int i = 0; i < n; ++i) {
    const prism_path p = paths(wi, rng);
    f.n += 1;
    switch (p.fate) {
      case prism_fate::front_reflection:
        f.front += p.weight;
        break;
      case prism_fate::retroreflected:
        f.retro += p.weight;
        if (p.face_reflections == 3 && p.front_reflections == 0) f.cube_retro += p.weight;
        break;
      case prism_fate::stray:
        f.stray += p.weight;
        break;
      case prism_fate::transmitted:
        f.transmitted += p.weight;
        break;
      case prism_fate::lost:
        f.lost += 1;
        break;
    }
  }
  return f;
}

inline fates trace_many(const prism_sheet_geometry& g, const glm::dvec3& wi, int n, std::uint64_t seed) {
  return trace_many(prism_paths(g), wi, n, seed);
}

// The angles between `n` rays retroreflected by one cube corner's three faces and the exact reversal.
inline std::vector<double> retro_spread_angles(const path_source& paths, const glm::dvec3& wi, int n,
                                               std::uint64_t seed, std::uint64_t stream) {
  pcg32 rng(seed, stream);
  std::vector<double> angles;
  while (int(angles.size()) < n) {
    const prism_path p = paths(wi, rng);
    if (p.fate == prism_fate::retroreflected && p.face_reflections == 3 && p.front_reflections == 0)
      angles.push_back(std::acos(std::min(1.0, glm::dot(p.wo, wi))));
  }
  return angles;
}

inline std::vector<double> retro_spread_angles(const prism_sheet_geometry& g, const glm::dvec3& wi, int n,
                                               std::uint64_t seed, std::uint64_t stream) {
  return retro_spread_angles(prism_paths(g), wi, n, seed, stream);
}

inline double median_retro_spread(const path_source& paths, const glm::dvec3& wi, std::uint64_t seed,
                                  std::uint64_t stream) {
  std::vector<double> angles = retro_spread_angles(paths, wi, 20000, seed, stream);
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  return angles[angles.size() / 2];
}

inline double median_retro_spread(const prism_sheet_geometry& g, const glm::dvec3& wi, std::uint64_t seed,
                                  std::uint64_t stream) {
  return median_retro_spread(prism_paths(g), wi, seed, stream);
}

// A sheet without absorption at 0, 20, 40 and 60 deg (azimuth 13): front reflection,
// retroreflected, stray and transmitted light add up to all of it within 0.5%, and at most 0.02%
// of the paths are lost (numerical slips: a face met again as it was left once lost 0.3%).
// Returns the counts per angle.
inline std::vector<fates> expect_no_light_lost(const path_source& paths, std::uint64_t seed) {
  std::vector<fates> out;
  for (const double theta : {0.0, 20.0, 40.0, 60.0}) {
    const fates f = trace_many(paths, unit_direction(theta, 13), 20000, seed);
    const double total = (f.front + f.retro + f.stray + f.transmitted) / f.n;
    std::printf("theta %g: front %.3f retro %.3f stray %.3f transmitted %.3f lost %.0f\n", theta, f.front / f.n,
                f.retro / f.n, f.stray / f.n, f.transmitted / f.n, f.lost);
    EXPECT_NEAR(total, 1.0, 0.005) << theta;
    EXPECT_LE(f.lost / f.n, 2e-4) << theta;
    out.push_back(f);
  }
  return out;
}

inline std::vector<fates> expect_no_light_lost(const prism_sheet_geometry& g, std::uint64_t seed) {
  return expect_no_light_lost(prism_paths(g), seed);
}

}  // namespace airr::test
