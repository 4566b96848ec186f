#pragma once
// Generates the corner-cube shift table (spec section 3) by tracing grids of parallel rays
// through the three mirror faces with Embree.
#include <functional>
#include <vector>

#include "airr/formats/mesh_gltf.hpp"
#include "airr/models/shift_table.hpp"

namespace airr {

struct shift_table_params {
  int grid = 1500;  // rays per side of the square grid, per (theta, phi)
  std::vector<double> theta_deg = {0, 5, 10, 15, 20, 25, 30, 35, 40, 45};
  std::vector<double> phi_deg = [] {
    std::vector<double> v;
    for (int phi = 0; phi <= 180; phi += 5) v.push_back(phi);
    return v;
  }();
  int bins = 150;
  double s_max = 1.5;                // histogram range [0, s_max], cube edge lengths
  double generation_distance = 5.0;  // from the aperture centre to the plane the rays start on
};

// `cube` must be the corner cube: every triangle on one of the planes x = 0, y = 0, z = 0, the
// aperture being x + y + z = 1 (throws input_error otherwise). phi is measured from the x edge
// projected on the aperture plane. The table's provenance holds the parameters and, per theta,
// rays_entering and rays_kept. `progress` (may be empty) gets the finished fraction on the
// calling thread. The result does not depend on the number of threads.
shift_table trace_shift_table(const triangle_mesh& cube, const shift_table_params& p,
                              const std::function<void(double fraction)>& progress = {});

}  // namespace airr
