#include "airr/models/corner_cube.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "airr/models/dielectric.hpp"

namespace airr {

triangle_mesh make_corner_cube() {
  triangle_mesh m;
  m.name = "corner_cube";
  m.positions = {{0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, {0.f, 0.f, 1.f}};
  m.indices = {0, 2, 3,   // x = 0
               0, 3, 1,   // y = 0
               0, 1, 2};  // z = 0
  return m;
}

triangle_mesh make_corner_cube_tile(double pitch_mm) {
  const double h = pitch_mm * 1e-3, s = 2 * h / std::sqrt(3.0), depth = std::sqrt(2.0) * h / 3;
  // The ridges' crossings are the lattice points (m + n / 2) s, n h; each is made once, so that
  // neighbouring cube corners share their vertices exactly (no cracks between them).
  triangle_mesh m;
  m.name = "corner_cube_tile";
  std::map<std::pair<int, int>, std::uint32_t> made;
  auto lattice = [&](int i, int n) {  // i counts half sides: x = i s / 2
    const auto [it, fresh] = made.emplace(std::make_pair(i, n), std::uint32_t(m.positions.size()));
    if (fresh) m.positions.emplace_back(float(i * s / 2), float(n * h), 0.f);
    return it->second;
  };
  // The four cube corners whose apexes lie in the cell, by their aperture triangles' vertices
  // (half sides, rows); each apex lies under its triangle's centroid.
  const std::array<std::array<std::pair<int, int>, 3>, 4> corners = {{
      {{{0, 0}, {2, 0}, {1, 1}}},   // a vertex along +y, apex (s / 2, h / 3)
      {{{0, 0}, {1, 1}, {-1, 1}}},  // a vertex along -y, apex (0, 2 h / 3)
      {{{-1, 1}, {1, 1}, {0, 2}}},  // along +y, apex (0, 4 h / 3)
      {{{1, 1}, {2, 2}, {0, 2}}},   // along -y, apex (s / 2, 5 h / 3)
  }};
  for (const auto& c : corners) {
    std::array<std::uint32_t, 3> v{};
    glm::dvec2 centroid(0);
    for (std::size_t k = 0; k < 3; ++k) {
      v[k] = lattice(c[k].first, c[k].second);
      centroid += glm::dvec2(c[k].first * s / 2, c[k].second * h) / 3.0;
    }
    const auto apex = std::uint32_t(m.positions.size());
    m.positions.emplace_back(float(centroid.x), float(centroid.y), float(-depth));
    for (std::size_t k = 0; k < 3; ++k) m.indices.insert(m.indices.end(), {apex, v[(k + 1) % 3], v[k]});
  }
  return m;
}

polarized_step cube_corner_polarized(const polarization_frame& in, const std::array<glm::dvec3, 3>& faces,
                                     std::complex<double> eta) {
  polarized_step path{mueller::identity(), in};
  for (const glm::dvec3& n : faces) {
    const fresnel_coefficients f = fresnel_amplitudes(std::abs(glm::dot(path.out.k, n)), eta);
    path.out = reflect_onto(path.m, path.out, n, f.rs, f.rp);
  }
  return path;
}

}  // namespace airr
