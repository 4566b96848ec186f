#include "airr/render/shift_table_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/render/embree_scene.hpp"

namespace airr {

namespace {

// How far a reflected ray starts off its mirror, along the mirror normal (edge lengths).
constexpr double restart_offset = 1e-6;
// More reflections than this cannot happen in a corner cube; it only guards the loop.
constexpr int max_reflections = 8;

const glm::dvec3 sheet_normal = glm::normalize(glm::dvec3(1, 1, 1));
const glm::dvec3 azimuth_t1 = glm::normalize(glm::dvec3(2, -1, -1));  // the x edge on the aperture plane
const glm::dvec3 azimuth_t2 = glm::cross(sheet_normal, azimuth_t1);
const glm::dvec3 aperture_centre(1.0 / 3, 1.0 / 3, 1.0 / 3);

double plane_sum(const glm::dvec3& v) { return v.x + v.y + v.z; }
bool in_aperture(const glm::dvec3& p) { return p.x >= 0 && p.y >= 0 && p.z >= 0; }  // p on x + y + z = 1

// The mirror plane (0: x = 0, 1: y = 0, 2: z = 0) of every triangle, after checking that the
// mesh is a corner cube below the aperture plane.
std::vector<int> faces_of_triangles(const triangle_mesh& cube) {
  const std::string origin = "corner cube mesh '" + cube.name + "'";
  if (cube.indices.empty() || cube.indices.size() % 3 != 0) throw input_error(origin + ": no triangles");
  std::vector<int> faces;
  for (std::size_t t = 0; t < cube.indices.size() / 3; ++t) {
    int face = -1;
    for (int axis = 0; axis < 3 && face < 0; ++axis) {
      bool on_plane = true;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = cube.indices[3 * t + k];
        if (i >= cube.positions.size()) throw input_error(origin + ": triangle " + std::to_string(t) + ": bad index");
        on_plane = on_plane && std::abs(cube.positions[i][axis]) <= 1e-6f;
      }
      if (on_plane) face = axis;
    }
    if (face < 0) throw input_error(origin + ": triangle " + std::to_string(t) + " is not on x = 0, y = 0 or z = 0");
    faces.push_back(face);
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (std::find(faces.begin(), faces.end(), axis) == faces.end()) {
      throw input_error(origin + ": no triangle on the plane " + "xyz"[axis] + " = 0");
    }
  }
  for (const glm::vec3& v : cube.positions) {
    if (std::min({v.x, v.y, v.z}) < -1e-6f || v.x + v.y + v.z > 1 + 1e-6f) {
      throw input_error(origin + ": vertices must lie in x, y, z >= 0, x + y + z <= 1 (the aperture plane)");
    }
  }
  return faces;
}

void check_params(const shift_table_params& p) {
  auto fail = [](const std::string& field, const std::string& problem) {
    throw input_error("shift table parameters: " + field + ": " + problem);
  };
  if (p.grid < 1) fail("grid", "must be at least 1");
  if (p.bins < 1) fail("bins", "must be at least 1");
  if (!(p.s_max > 0)) fail("s_max", "must be positive");
  if (!(p.generation_distance > 0)) fail("generation_distance", "must be positive");
  if (p.theta_deg.empty()) fail("theta_deg", "must not be empty");
  if (p.phi_deg.empty()) fail("phi_deg", "must not be empty");
  for (std::size_t i = 0; i < p.theta_deg.size(); ++i) {
    if (!(p.theta_deg[i] >= 0 && p.theta_deg[i] < 90)) fail("theta_deg", "angles must be in [0, 90)");
    if (i > 0 && !(p.theta_deg[i] > p.theta_deg[i - 1])) fail("theta_deg", "angles must be strictly ascending");
  }
}

// The square grid of parallel rays for one incidence direction.
struct ray_grid {
  glm::dvec3 dir;     // towards the cube
  glm::dvec3 corner;  // centre of ray (0, 0) on the generation plane
  glm::dvec3 step_u;  // to the next column
  glm::dvec3 step_v;  // to the next row
};

glm::dvec3 incidence_direction(double theta_deg, double phi_deg) {
  const double th = radians(theta_deg), ph = radians(phi_deg);
  const glm::dvec3 u = std::cos(ph) * azimuth_t1 + std::sin(ph) * azimuth_t2;
  return -(std::cos(th) * sheet_normal + std::sin(th) * u);
}

// Generation-plane axes perpendicular to d (u: the azimuth direction in the aperture plane).
void plane_axes(double phi_deg, const glm::dvec3& d, glm::dvec3& e1, glm::dvec3& e2) {
  const double ph = radians(phi_deg);
  const glm::dvec3 u = std::cos(ph) * azimuth_t1 + std::sin(ph) * azimuth_t2;
  e1 = glm::cross(sheet_normal, u);
  e2 = glm::cross(d, e1);
}

// Bounding box of the cube's vertices projected along d: centre and the larger side.
void projected_box(const triangle_mesh& cube, const glm::dvec3& e1, const glm::dvec3& e2, glm::dvec2& centre,
                   double& side) {
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::vec3& v : cube.positions) {
    const glm::dvec3 r = glm::dvec3(v) - aperture_centre;
    const glm::dvec2 q(glm::dot(r, e1), glm::dot(r, e2));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  centre = 0.5 * (lo + hi);
  side = std::max(hi.x - lo.x, hi.y - lo.y);
}

ray_grid make_ray_grid(const triangle_mesh& cube, double theta_deg, double phi_deg, double side, int grid,
                       double distance) {
  ray_grid g;
  g.dir = incidence_direction(theta_deg, phi_deg);
  glm::dvec3 e1, e2;
  plane_axes(phi_deg, g.dir, e1, e2);
  glm::dvec2 centre;
  double own_side = 0;
  projected_box(cube, e1, e2, centre, own_side);
  const double pitch = side / grid;
  const glm::dvec3 plane_centre = aperture_centre - distance * g.dir;
  g.corner = plane_centre + (centre.x - 0.5 * side + 0.5 * pitch) * e1 + (centre.y - 0.5 * side + 0.5 * pitch) * e2;
  g.step_u = pitch * e1;
  g.step_v = pitch * e2;
  return g;
}

struct tally {
  std::vector<std::uint64_t> histogram;
  std::uint64_t entering = 0;
  std::uint64_t kept = 0;
  std::uint64_t overflow = 0;  // shifts >= s_max, counted in the last bin
};

// Traces one ray from the generation plane; adds it to `t` if it enters the aperture.
void trace_ray(RTCScene scene, const std::vector<int>& face_of, const glm::dvec3& origin, const glm::dvec3& d,
               const shift_table_params& p, tally& t) {
  const glm::dvec3 entry = origin + ((1.0 - plane_sum(origin)) / plane_sum(d)) * d;
  if (!in_aperture(entry)) return;
  ++t.entering;

  glm::dvec3 org = origin, dir = d;
  int reflections = 0;
  unsigned faces_hit = 0;
  while (reflections <= max_reflections) {
    RTCRayHit rh = make_ray_hit(org, dir);
    intersect(scene, rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    ++reflections;
    faces_hit |= 1u << face_of[rh.hit.primID];
    const glm::dvec3 hit = org + double(rh.ray.tfar) * dir;
    glm::dvec3 normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    dir = reflect(dir, normal);
    if (glm::dot(dir, normal) < 0) normal = -normal;
    // Off the mirror along its normal, so that rounding never puts the origin behind it.
    org = hit + restart_offset * normal;
  }
  if (reflections != 3 || faces_hit != 7u || plane_sum(dir) <= 0) return;
  const glm::dvec3 exit = org + ((1.0 - plane_sum(org)) / plane_sum(dir)) * dir;
  if (!in_aperture(exit)) return;
  ++t.kept;
  const double shift = glm::length(exit - entry);
  int bin = int(shift / p.s_max * p.bins);
  if (bin >= p.bins) {
    bin = p.bins - 1;
    ++t.overflow;
  }
  ++t.histogram[std::size_t(bin)];
}

}  // namespace

shift_table trace_shift_table(const triangle_mesh& cube, const shift_table_params& p,
                              const std::function<void(double fraction)>& progress) {
  check_params(p);
  const std::vector<int> face_of = faces_of_triangles(cube);
  embree_device device;
  embree_mesh_scene scene(device, cube);

  const std::size_t jobs = p.theta_deg.size() * p.phi_deg.size();
  std::size_t jobs_done = 0;
  shift_table table;
  table.theta_deg = p.theta_deg;
  table.s_max = p.s_max;
  nlohmann::json entering = nlohmann::json::array(), kept = nlohmann::json::array(), overflow = nlohmann::json::array();

  for (double theta : p.theta_deg) {
    // One ray pitch for every phi, from the largest bounding square, so that summing the counts
    // over phi weights every azimuth by its aperture area alone.
    double side = 0;
    for (double phi : p.phi_deg) {
      glm::dvec3 e1, e2;
      plane_axes(phi, incidence_direction(theta, phi), e1, e2);
      glm::dvec2 centre;
      double s = 0;
      projected_box(cube, e1, e2, centre, s);
      side = std::max(side, s);
    }

    tbb::enumerable_thread_specific<tally> tallies([&] {
      tally t;
      t.histogram.assign(std::size_t(p.bins), 0);
      return t;
    });
    for (double phi : p.phi_deg) {
      const ray_grid g = make_ray_grid(cube, theta, phi, side, p.grid, p.generation_distance);
      tbb::parallel_for(tbb::blocked_range<int>(0, p.grid, 4), [&](const tbb::blocked_range<int>& rows) {
        tally& t = tallies.local();
        for (int row = rows.begin(); row < rows.end(); ++row) {
          for (int col = 0; col < p.grid; ++col) {
            const glm::dvec3 origin = g.corner + double(col) * g.step_u + double(row) * g.step_v;
            trace_ray(scene.get(), face_of, origin, g.dir, p, t);
          }
        }
      });
      if (progress) progress(double(++jobs_done) / double(jobs));
    }

    // Integer counts: the sum is the same whichever thread traced which row.
    tally total;
    total.histogram.assign(std::size_t(p.bins), 0);
    for (const tally& t : tallies) {
      for (std::size_t b = 0; b < total.histogram.size(); ++b) total.histogram[b] += t.histogram[b];
      total.entering += t.entering;
      total.kept += t.kept;
      total.overflow += t.overflow;
    }
    if (total.kept == 0) {
      char angle[32];
      std::snprintf(angle, sizeof angle, "%g", theta);
      throw input_error("corner cube mesh '" + cube.name + "': no retroreflected rays at theta " + angle + " deg");
    }
    std::vector<double> row(total.histogram.size());
    for (std::size_t b = 0; b < row.size(); ++b) row[b] = double(total.histogram[b]) / double(total.kept);
    table.probability.push_back(std::move(row));
    table.retro_fraction.push_back(double(total.kept) / double(total.entering));
    entering.push_back(total.entering);
    kept.push_back(total.kept);
    overflow.push_back(total.overflow);
  }

  table.provenance = {
      {"generator", "Embree ray tracing of the corner cube (spec section 3)"},
      {"grid", p.grid},
      {"theta_deg", p.theta_deg},
      {"phi_deg", p.phi_deg},
      {"bins", p.bins},
      {"s_max", p.s_max},
      {"generation_distance", p.generation_distance},
      {"ray_pitch", "per theta, the largest bounding square of the projected cube over phi divided by grid"},
      {"rays_entering", entering},
      {"rays_kept", kept},
      {"overflow", "shifts >= s_max are counted in the last bin"},
      {"rays_at_or_above_s_max", overflow},
  };
  finalize_shift_table(table);
  return table;
}

}  // namespace airr
