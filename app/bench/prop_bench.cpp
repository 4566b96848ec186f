// A large prop's cost: a housing of N triangles (an open box around the device, its front open
// towards the observer, finely tessellated) written as GLB, its load time (read, checked, placed),
// the Embree build time, and the tracer's rays/s beside raw camera rays with and without it.
#include "bench/prop_bench.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "airr/render/prop_hits.hpp"
#include "airr/render/tracer.hpp"

namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

// Five faces of the box [-0.2, 0.2] x [-0.25, 0.2] x [-0.25, 0.1] m, open at +z, each a k x k grid.
airr::triangle_mesh housing(std::uint64_t triangles) {
  const int k = std::max(1, int(std::sqrt(double(triangles) / 10.0)));
  airr::triangle_mesh m;
  m.name = "housing";
  const glm::vec3 lo(-0.2f, -0.25f, -0.25f), hi(0.2f, 0.2f, 0.1f);
  auto face = [&](int axis, float at) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const auto base = std::uint32_t(m.positions.size());
    for (int j = 0; j <= k; ++j) {
      for (int i = 0; i <= k; ++i) {
        glm::vec3 p;
        p[axis] = at;
        p[a] = lo[a] + (hi[a] - lo[a]) * float(i) / float(k);
        p[b] = lo[b] + (hi[b] - lo[b]) * float(j) / float(k);
        m.positions.push_back(p);
      }
    }
    for (int j = 0; j < k; ++j) {
      for (int i = 0; i < k; ++i) {
        const std::uint32_t v = base + std::uint32_t(j * (k + 1) + i), row = std::uint32_t(k + 1);
        m.indices.insert(m.indices.end(), {v, v + 1, v + row + 1, v, v + row + 1, v + row});
      }
    }
  };
  face(0, lo.x);
  face(0, hi.x);
  face(1, lo.y);
  face(1, hi.y);
  face(2, lo.z);
  return m;
}

struct throughput {
  double build_s = 0, tracer_rate = 0, camera_rate = 0;
};

throughput measure(const airr::scene& s, std::uint64_t spp) {
  airr::embree_device device;
  airr::tracer_scene ts;
  ts.use_model_image = false;
  auto t0 = clock_type::now();
  airr::build_tracer_scene(ts, device, s);
  throughput out;
  out.build_s = since(t0);
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(std::size_t(w) * h * 3, 0.0f);
  std::atomic<std::uint64_t> rays{0};
  const std::atomic<bool> never{false};
  t0 = clock_type::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& r) {
    std::uint64_t local = 0;
    airr::trace_rows(ts, r.begin(), r.end(), 0, spp, sums, never, local);
    rays += local;
  });
  out.tracer_rate = double(rays) / since(t0);
  // Camera rays alone, one by one, as many as the tracer traced.
  const std::uint64_t n = rays;
  std::atomic<std::uint64_t> hits{0};
  t0 = clock_type::now();
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, n, 4096), [&](const tbb::blocked_range<std::uint64_t>& r) {
    std::uint64_t local = 0;
    for (std::uint64_t i = r.begin(); i < r.end(); ++i) {
      airr::pcg32 rng = airr::sample_rng(i, 0, 11);
      const glm::dvec3 d = airr::camera_direction(ts.camera, rng.next_double() * w, rng.next_double() * h);
      RTCRayHit rh = airr::make_ray_hit(ts.camera.position, d);
      airr::intersect(ts.embree->get(), rh);
      local += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    hits += local;
  });
  out.camera_rate = double(n) / since(t0);
  return out;
}

// The designer's geometric viewing zone after an edit (its 25 x 25 eyes within +-60 deg, 32 rows
// each), timed with the props' scene it needs, and how many props' scenes the edit built.
struct zone_edits {
  double prop_moved_s = 0, observer_moved_s = 0, sheet_moved_s = 0;
  std::uint64_t prop_moved_builds = 0, observer_moved_builds = 0, sheet_moved_builds = 0;
};

zone_edits time_zone_edits(airr::scene s) {
  airr::eye_grid g;
  g.kind = airr::eye_grid::shape::sphere;
  g.nx = g.ny = 25;
  g.x_min = g.y_min = -60;
  g.x_max = g.y_max = 60;
  auto edit = [&](double& seconds, std::uint64_t& builds) {
    const std::uint64_t before = airr::prop_scene_builds();
    const auto t0 = clock_type::now();
    airr::geometric_viewing_zone(s, g, airr::scene_prop_hits(s), 32);
    seconds = since(t0);
    builds = airr::prop_scene_builds() - before;
  };
  zone_edits z;
  s.props.front().pose.center_mm[0] += 10;
  edit(z.prop_moved_s, z.prop_moved_builds);
  s.observer.azimuth_deg += 5;
  edit(z.observer_moved_s, z.observer_moved_builds);
  s.sheet().pose.pitch_deg += 2;
  edit(z.sheet_moved_s, z.sheet_moved_builds);
  return z;
}

}  // namespace

void run_prop_bench(const std::string& scene_path, std::uint64_t triangles, std::uint64_t spp) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("airr-prop-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "housing.glb").string();
  auto t0 = clock_type::now();
  const airr::triangle_mesh m = housing(triangles);
  airr::save_gltf_mesh(m, file);
  const double write_s = since(t0);
  const double megabytes = double(std::filesystem::file_size(file)) / 1e6;
  t0 = clock_type::now();
  const airr::triangle_mesh loaded = airr::load_prop_mesh(file, "");
  const double load_s = since(t0);

  airr::scene bare = airr::load_scene(scene_path);
  airr::scene boxed = bare;
  airr::prop_params p;
  p.name = "housing";
  p.mesh = file;
  boxed.props.push_back(p);
  const throughput a = measure(bare, spp), b = measure(boxed, spp);
  // The viewing zone's lines of sight: the first build, then an edit that moves the prop.
  t0 = clock_type::now();
  const airr::prop_hit_function first = airr::scene_prop_hits(boxed);
  const double sight_first_s = since(t0);
  boxed.props.front().pose.center_mm[0] += 10;
  t0 = clock_type::now();
  const airr::prop_hit_function moved = airr::scene_prop_hits(boxed);
  const double sight_moved_s = since(t0);
  const zone_edits zone = time_zone_edits(boxed);
  std::filesystem::remove_all(dir);

  std::printf("prop: housing of %zu triangles, %zu vertices, %.1f MB GLB (written in %.2f s)\n",
              loaded.indices.size() / 3, loaded.positions.size(), megabytes, write_s);
  std::printf("load:          %.3f s (read, checked, placed in mm)\n", load_s);
  std::printf("embree build:  %.3f s with the prop, %.3f s without\n", b.build_s, a.build_s);
  std::printf("tracer:        %12.0f rays/s with the prop, %12.0f without (%.3f)\n", b.tracer_rate, a.tracer_rate,
              b.tracer_rate / a.tracer_rate);
  std::printf("camera rays:   %12.0f rays/s with the prop, %12.0f without (%.3f, Embree's traversal alone)\n",
              b.camera_rate, a.camera_rate, b.camera_rate / a.camera_rate);
  std::printf("sight lines:   %.1f ms to build the props' scene, %.2f ms after an edit that moves the prop\n",
              1e3 * sight_first_s, 1e3 * sight_moved_s);
  std::printf("viewing zone:  %.1f ms after an edit that moves the prop (props' scene rebuilt: %s)\n",
              1e3 * zone.prop_moved_s, zone.prop_moved_builds ? "yes" : "no");
  std::printf("viewing zone:  %.1f ms after an edit that moves the observer (props' scene rebuilt: %s)\n",
              1e3 * zone.observer_moved_s, zone.observer_moved_builds ? "yes" : "no");
  std::printf("viewing zone:  %.1f ms after an edit that tilts the sheet (props' scene rebuilt: %s)\n",
              1e3 * zone.sheet_moved_s, zone.sheet_moved_builds ? "yes" : "no");
}
