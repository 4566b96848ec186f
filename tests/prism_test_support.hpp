#pragma once
// Many paths through a prism sheet at one incidence, counted by where they ended.
#include <cstdint>

#include <glm/glm.hpp>

#include "airr/core/random.hpp"
#include "airr/models/prism_sheet.hpp"

namespace airr::test {

struct fates {
  double front = 0, retro = 0, stray = 0, transmitted = 0, lost = 0, n = 0;
  double cube_retro = 0;  // retroreflected by one cube corner's three faces alone
};

inline fates trace_many(const prism_sheet_geometry& g, const glm::dvec3& wi, int n, std::uint64_t seed) {
  pcg32 rng(seed, 7);
  fates f;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 entry = prism_cell_point(g, {rng.next_double(), rng.next_double()});
    const prism_path p = trace_prism_sheet(g, wi, entry, rng.next_double(), rng);
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

}  // namespace airr::test
