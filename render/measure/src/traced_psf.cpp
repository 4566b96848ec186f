#include "airr/measure/traced_psf.hpp"

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "airr/core/error.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/embree_scene.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

namespace {

// A disc of diameter disc_mm centred on a square of side `side_mm`, as coverage (4 x 4
// sub-samples per pixel); its drawn area in mm^2.
double draw_disc(image_rgb& img, double side_mm, double disc_mm) {
  const int n = img.width;
  const double pixel = side_mm / n, r2 = 0.25 * disc_mm * disc_mm;
  double covered = 0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      int in = 0;
      for (int sy = 0; sy < 4; ++sy) {
        for (int sx = 0; sx < 4; ++sx) {
          const double u = (x + (sx + 0.5) / 4) * pixel - 0.5 * side_mm,
                       v = (y + (sy + 0.5) / 4) * pixel - 0.5 * side_mm;
          in += u * u + v * v <= r2;
        }
      }
      const float c = float(in) / 16.0f;
      std::fill_n(img.at(x, y), 3, c);
      covered += c;
    }
  }
  return covered * pixel * pixel;
}

// A file removed when it goes out of scope.
struct temporary_file {
  std::filesystem::path path;
  ~temporary_file() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

}  // namespace

traced_psf trace_psf(const scene& base, int size, double mm_per_pixel, const traced_psf_params& p,
                     const std::function<void(double)>& progress) {
  if (size < 3 || size > 1025 || size % 2 == 0)
    throw input_error("traced PSF: " + std::to_string(size) + " pixels per side (an odd number 3..1025)");
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw input_error("traced PSF: the pixel size must be a positive number of mm");
  const double side = 4 * p.disc_mm;
  if (!(p.disc_mm > 0) || side > base.source.width_mm || side > base.source.height_mm)
    throw input_error("traced PSF: the disc (" + std::to_string(p.disc_mm) +
                      " mm) must be positive and a quarter of the display's width and height at most");
  const auto t0 = std::chrono::steady_clock::now();

  scene s = base;
  // The display shrinks about its centre (the aerial image's centre stays where it was).
  s.source.width_mm = s.source.height_mm = side;
  s.source.emission_profile.clear();
  s.seed = p.seed;
  image_rgb disc{129, 129, std::vector<float>(129 * 129 * 3)};
  traced_psf out;
  out.disc_area_mm2 = draw_disc(disc, side, p.disc_mm);
  temporary_file file{std::filesystem::temp_directory_path() /
                      ("airr-traced-psf-" + std::to_string(::getpid()) + "-" +
                       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".exr")};
  write_image(file.path.string(), disc, {{"airr:generator", "traced PSF disc"}});
  s.source.image = file.path.string();

  const glm::dvec3 aim = aerial_image_center(base), eye = observer_position(base);
  s.observer.placement = observer_placement::look_at;
  s.observer.lens = observer_lens::pinhole;
  s.observer.position_mm = {eye.x, eye.y, eye.z};
  s.observer.look_at_mm = {aim.x, aim.y, aim.z};
  s.observer.width = s.observer.height = size;
  s.observer.fov_deg = degrees(2 * std::atan(0.5 * size * mm_per_pixel / glm::length(aim - eye)));

  embree_device device;
  tracer_scene ts;
  ts.use_model_image = false;  // the tracer alone
  build_tracer_scene(ts, device, s);
  std::vector<double> sums(std::size_t(size) * size, 0.0);
  int rows_done = 0;
  std::mutex progress_mutex;
  tbb::task_arena arena(p.threads > 0 ? p.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, size, 1), [&](const tbb::blocked_range<int>& r) {
      for (int y = r.begin(); y < r.end(); ++y) {
        for (int x = 0; x < size; ++x) {
          const std::array<double, 6> rotation = pixel_sequence_rotation(ts, x, y);
          double sum = 0;
          std::uint64_t rays = 0;
          for (std::uint64_t i = 0; i < p.spp; ++i) {
            const glm::vec3 c = estimate_components(ts, x, y, i, rotation, rays)[component_aerial];
            sum += (double(c.r) + c.g + c.b) / 3.0;
          }
          sums[std::size_t(y) * size + x] = sum / double(p.spp);
        }
        const std::lock_guard lock(progress_mutex);
        ++rows_done;
        if (progress) progress(double(rows_done) / size);
      }
    });
  });

  out.grid.size = size;
  out.grid.mm_per_pixel = mm_per_pixel;
  out.grid.density.assign(std::size_t(size) * size, 0.0);
  const double per_radiance = 1.0 / (white_radiance(s.source) * out.disc_area_mm2);
  for (std::size_t i = 0; i < out.grid.density.size(); ++i) out.grid.density[i] = sums[i] * per_radiance;
  out.spp = p.spp;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace airr
