// airr bench: tracer rays/s, raw Embree rays/s on the same geometry and ray count (rtcIntersect1
// and coherent streams), their ratios, and the render session's latency from an edit to its first
// new image; with --noise the time to a noise level (noise_bench.cpp), with --prop-triangles what a
// large prop costs (prop_bench.cpp).
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/render/render_session.hpp"
#include "airr/render/tracer.hpp"
#include "bench/designer_latency_bench.hpp"
#include "bench/drag_bench.hpp"
#include "bench/memory_bench.hpp"
#include "bench/model_error_bench.hpp"
#include "bench/model_image_bench.hpp"
#include "bench/noise_bench.hpp"
#include "bench/prop_bench.hpp"
#include "cli/commands.hpp"

namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

// Camera rays through jittered pixel positions, intersected only: one by one (rtcIntersect1), or
// as the tracer sends them, the same sample of 64 neighbouring pixels in one coherent stream
// (rtcIntersect1M, which Embree traces in packets).
constexpr int stream_size = 64;
double raw_embree_seconds(const airr::tracer_scene& ts, std::uint64_t ray_count, bool streams, double& checksum) {
  const int w = ts.camera.width, h = ts.camera.height;
  const std::uint64_t per_pixel = std::max<std::uint64_t>(1, ray_count / (std::uint64_t(w) * h));
  std::atomic<double> sum{0};
  const auto t0 = clock_type::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& r) {
    double local = 0;
    std::array<RTCRayHit, stream_size> hits;
    for (int y = r.begin(); y < r.end(); ++y) {
      for (std::uint64_t i = 0; i < per_pixel; ++i) {
        for (int x0 = 0; x0 < w; x0 += stream_size) {
          const int n = std::min(stream_size, w - x0);
          for (int k = 0; k < n; ++k) {
            airr::pcg32 rng = airr::sample_rng(std::uint64_t(y) * w + x0 + k, i, 7);
            const glm::dvec3 d = airr::camera_direction(ts.camera, x0 + k + rng.next_double(), y + rng.next_double());
            hits[std::size_t(k)] = airr::make_ray_hit(ts.camera.position, d);
            if (!streams) airr::intersect(ts.embree->get(), hits[std::size_t(k)]);
          }
          if (streams) airr::intersect_coherent(ts.embree->get(), hits.data(), unsigned(n));
          for (int k = 0; k < n; ++k) {
            if (hits[std::size_t(k)].hit.geomID != RTC_INVALID_GEOMETRY_ID) local += hits[std::size_t(k)].ray.tfar;
          }
        }
      }
    }
    double cur = sum.load();
    while (!sum.compare_exchange_weak(cur, cur + local)) {
    }
  });
  checksum = sum;
  return since(t0);
}

// The tracer alone over every pixel at `spp`, as `airr render` traces them (no model image).
struct traced {
  double seconds = 0;
  std::uint64_t rays = 0;
};
traced trace_all(const airr::tracer_scene& ts, std::uint64_t spp) {
  const int w = ts.camera.width, h = ts.camera.height;
  std::vector<float> sums(std::size_t(w) * h * 3, 0.0f);
  std::atomic<std::uint64_t> rays{0};
  const std::atomic<bool> never{false};
  const auto t0 = clock_type::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& r) {
    std::uint64_t local = 0;
    airr::trace_rows(ts, r.begin(), r.end(), 0, spp, sums, never, local);
    rays += local;
  });
  return {since(t0), rays.load()};
}

// The scene's first sheet as each model the tracer can take (their default parameters), the
// tracer's time for the same image, and each against the sinc-shift model's. The models take
// turns, a round of each per run, so that the machine's drift over the runs falls on all of them
// alike; the ratio is the median of the rounds' ratios.
void run_sheet_bench(const airr::scene& base, const std::string& scene_path, std::uint64_t spp, int runs) {
  std::printf("sheet models: %s (%dx%d, %llu spp, median of %d runs taken in turns), the tracer alone\n",
              scene_path.c_str(), base.observer.width, base.observer.height, static_cast<unsigned long long>(spp),
              runs);
  const std::array<std::string, 3> types{"sinc_shift", "prism_sheet", "bead_sheet"};
  airr::embree_device device;
  std::array<airr::tracer_scene, 3> scenes;
  for (std::size_t m = 0; m < types.size(); ++m) {
    airr::scene s = base;
    s.sheet().model = airr::with_model_type(m == 0 ? base.sheet().model : airr::retro_model_params{}, types[m]);
    airr::build_tracer_scene(scenes[m], device, s);
  }
  std::array<std::vector<traced>, 3> times;
  std::array<std::vector<double>, 3> ratios;
  for (int i = 0; i < runs; ++i) {
    for (std::size_t m = 0; m < types.size(); ++m) times[m].push_back(trace_all(scenes[m], spp));
    for (std::size_t m = 0; m < types.size(); ++m)
      ratios[m].push_back(times[m].back().seconds / times[0].back().seconds);
  }
  for (std::size_t m = 0; m < types.size(); ++m) {
    auto& t = times[m];
    std::sort(t.begin(), t.end(), [](const traced& a, const traced& b) { return a.seconds < b.seconds; });
    std::sort(ratios[m].begin(), ratios[m].end());
    const traced& mid = t[t.size() / 2];
    std::printf("%-12s %9.3g s  %12.0f rays/s  %5.2fx the sinc-shift model's time (rounds: %.2f to %.2f)\n",
                types[m].c_str(), mid.seconds, double(mid.rays) / mid.seconds, ratios[m][ratios[m].size() / 2],
                ratios[m].front(), ratios[m].back());
  }
}

}  // namespace

void add_bench_command(CLI::App& app) {
  struct options {
    std::string scene_path;  // empty: the shipped default scene
    std::uint64_t spp = 16;
    int edits = 20;
    bool noise = false;
    bool scaling = false;
    noise_bench_options noise_options;
    bool model_error = false;
    bool model_image = false;
    bool drag = false;
    drag_bench_options drag_options;
    int runs = 3;
    std::vector<double> model_error_tilts;
    std::vector<std::string> qualities;
    std::uint64_t prop_triangles = 0;
    bool memory = false;
    bool sheets = false;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand(
      "bench",
      "Measure tracer and Embree ray throughput and edit-to-image latency, or (--noise) the time to a noise level");
  cmd->add_option("scene", opt->scene_path, "Scene JSON file (default: the shipped default scene)");
  cmd->add_option("--spp", opt->spp, "Samples per pixel for the throughput runs")->check(CLI::Range(1, 4096));
  cmd->add_option("--edits", opt->edits, "Edits for the latency measurement")->check(CLI::Range(1, 10000));
  cmd->add_flag("--noise", opt->noise,
                "Instead: time and samples per pixel to 2% and 1% relative RMS noise at 512 x 512 for RF-Ay and RF-AN, "
                "from pairs of renders with independent seeds");
  cmd->add_flag("--scaling", opt->scaling,
                "Instead: the render's speed-up with threads (--scaling-threads, default 1 2): per spp and startup, "
                "with the parallel part of each (Amdahl), from --noise's measurement at each thread count");
  cmd->add_option("--scaling-threads", opt->noise_options.scaling_threads,
                  "With --scaling: thread counts, the first the base (default 1 2)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--model-error", opt->model_error,
                "Instead: the model image's (and the designer's first look's) relative RMS difference from the tracer "
                "per preset and sheet tilt 0-45 deg (default 256 x 256, --spp 128)");
  cmd->add_flag("--model-image", opt->model_image,
                "Instead: where an edit's model image spends its time (paths, bins, spectra, kernels, correlation, "
                "gathering), quick and full quality, per preset and tilt (default 512 x 512, tilts 0 20 45)");
  cmd->add_flag("--drag", opt->drag,
                "Instead: replay a drag of the sheet's tilt (--edits, default 30, at 10 per second, then rest) and "
                "report each frame's latency and distance from its layout's converged image, and the time to 2% and "
                "1% after it");
  cmd->add_option("--rest", opt->drag_options.rest_s, "With --drag: seconds measured after the drag")
      ->check(CLI::Range(1.0, 600.0))
      ->capture_default_str();
  cmd->add_option("--drag-csv", opt->drag_options.csv, "With --drag: write every frame as a CSV row here");
  cmd->add_option("--runs", opt->runs, "With --model-image or --sheets: runs per case (the median is reported)")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--tilts", opt->model_error_tilts, "With --model-error or --model-image: sheet tilts (deg)");
  cmd->add_option("--qualities", opt->qualities,
                  "With --model-image: which of the view, quick and full qualities to measure (default all three)")
      ->check(CLI::IsMember({"view", "quick", "full"}));
  cmd->add_flag("--memory", opt->memory,
                "Instead: the peak resident memory of airr render (1 spp) at half --size and at --size (default 4096), "
                "with and without --components, and the bytes a pixel costs");
  cmd->add_option("--prop-triangles", opt->prop_triangles,
                  "Instead: what a housing prop of this many triangles costs (load, Embree build, rays/s with and "
                  "without it)")
      ->check(CLI::Range(10, 20'000'000));
  cmd->add_flag(
      "--sheets", opt->sheets,
      "Instead: the tracer's time for the scene's image with its sheet as the sinc-shift model, a prism sheet "
      "and a bead sheet (their defaults), each against the sinc-shift's (--spp, --runs: rounds of the three taken in "
      "turns, the median of their ratios)");
  cmd->add_option(
      "--compare", opt->noise_options.compare,
      "With --noise, --model-image, --model-error or --memory: also measure another build's airr executable, side "
      "by side");
  cmd->add_option("--noise-spp", opt->noise_options.spp,
                  "With --noise or --scaling: samples per pixel of the measured render pairs (two or more)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  cmd->add_option(
         "--size", opt->noise_options.size,
         "Image width and height (default: the scene's; with --noise 512, --model-image 512, --model-error 256)")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  cmd->add_option("--presets", opt->noise_options.presets, "With --noise or --scaling: sheet presets")
      ->capture_default_str();
  cmd->add_option("--threads", opt->noise_options.threads, "With --noise: worker threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->callback([opt, cmd] {
    if (opt->scene_path.empty()) opt->scene_path = airr::default_scene_path();
    if (opt->model_error) {
      model_error_options m;
      m.scene_path = opt->scene_path;
      if (cmd->count("--size")) m.size = opt->noise_options.size;
      if (cmd->count("--spp")) m.spp = opt->spp;
      if (cmd->count("--presets")) m.presets = opt->noise_options.presets;
      if (cmd->count("--tilts")) m.tilts_deg = opt->model_error_tilts;
      m.threads = opt->noise_options.threads;
      m.compare = opt->noise_options.compare;
      run_model_error_bench(m);
      return;
    }
    if (opt->model_image) {
      model_image_bench_options m;
      m.scene_path = opt->scene_path;
      if (cmd->count("--size")) m.size = opt->noise_options.size;
      if (cmd->count("--presets")) m.presets = opt->noise_options.presets;
      if (cmd->count("--tilts")) m.tilts_deg = opt->model_error_tilts;
      if (cmd->count("--qualities")) m.qualities = opt->qualities;
      m.runs = opt->runs;
      m.compare = opt->noise_options.compare;
      run_model_image_bench(m);
      return;
    }
    if (opt->drag) {
      drag_bench_options d = opt->drag_options;
      d.scene_path = opt->scene_path;
      if (cmd->count("--size")) d.size = opt->noise_options.size;
      if (cmd->count("--edits")) d.edits = opt->edits;
      run_drag_bench(d);
      return;
    }
    if (opt->memory) {
      memory_bench_options m;
      m.scene_path = std::filesystem::absolute(opt->scene_path).string();
      if (cmd->count("--size")) m.size = opt->noise_options.size;
      m.compare = opt->noise_options.compare;
      m.threads = opt->noise_options.threads;
      run_memory_bench(m);
      return;
    }
    if (opt->prop_triangles > 0) {
      run_prop_bench(opt->scene_path, opt->prop_triangles, opt->spp);
      return;
    }
    if (opt->noise || opt->scaling) {
      opt->noise_options.scene_path = std::filesystem::absolute(opt->scene_path).string();
      if (opt->scaling)
        run_scaling_bench(opt->noise_options);
      else
        run_noise_bench(opt->noise_options);
      return;
    }
    airr::scene s = load_scene_noting(opt->scene_path);
    if (cmd->count("--size")) s.observer.width = s.observer.height = opt->noise_options.size;
    if (opt->sheets) {
      run_sheet_bench(s, opt->scene_path, opt->spp, opt->runs);
      return;
    }
    airr::embree_device device;
    airr::tracer_scene ts;
    airr::build_tracer_scene(ts, device, s);
    const int w = ts.camera.width, h = ts.camera.height;

    // Tracer throughput.
    const traced traced_run = trace_all(ts, opt->spp);
    const std::uint64_t rays = traced_run.rays;
    const double tracer_s = traced_run.seconds;
    const double tracer_rate = double(rays) / tracer_s;

    double checksum = 0, stream_checksum = 0;
    const double raw_s = raw_embree_seconds(ts, rays, false, checksum);
    const double stream_s = raw_embree_seconds(ts, rays, true, stream_checksum);
    const std::uint64_t raw_rays = std::max<std::uint64_t>(1, rays / (std::uint64_t(w) * h)) * std::uint64_t(w) * h;
    const double raw_rate = double(raw_rays) / raw_s, stream_rate = double(raw_rays) / stream_s;

    // Edit latency: alternate the tilt and wait for the first image of each new generation.
    airr::render_session session(s);
    session.wait_for(0, 1);
    std::vector<double> latencies, first_images;
    airr::scene edited = s;
    for (int i = 0; i < opt->edits; ++i) {
      edited.sheet().pose.pitch_deg = (i % 2) ? s.sheet().pose.pitch_deg : s.sheet().pose.pitch_deg + 5.0;
      const auto e0 = clock_type::now();
      const std::uint64_t gen = session.edit(edited);
      session.wait_for(gen, 0);  // the first image of the edit: the coarse preview
      first_images.push_back(1e3 * since(e0));
      session.wait_for(gen, 1);
      latencies.push_back(1e3 * since(e0));
    }
    session.stop();
    std::sort(latencies.begin(), latencies.end());
    std::sort(first_images.begin(), first_images.end());
    const designer_latencies designer = measure_designer_latencies(s, opt->edits);

    std::printf("scene: %s (%dx%d, %llu spp)\n", opt->scene_path.c_str(), w, h,
                static_cast<unsigned long long>(opt->spp));
    std::printf("tracer:        %12.0f rays/s  (%llu rays in %.3f s)\n", tracer_rate,
                static_cast<unsigned long long>(rays), tracer_s);
    std::printf("raw embree:    %12.0f rays/s  (%llu rays in %.3f s, checksum %.1f)\n", raw_rate,
                static_cast<unsigned long long>(raw_rays), raw_s, checksum);
    std::printf("raw streams:   %12.0f rays/s  (rtcIntersect1M, coherent streams of %d camera rays; checksum %.1f)\n",
                stream_rate, stream_size, stream_checksum);
    std::printf("ratio:         %12.3f  (tracer / raw rtcIntersect1)\n", tracer_rate / raw_rate);
    std::printf("               %12.3f  (tracer / raw streams, the packet ceiling)\n", tracer_rate / stream_rate);
    std::printf(
        "edit latency:  median %.1f ms, min %.1f ms, max %.1f ms over %zu edits (to the first image, a preview)\n",
        first_images[first_images.size() / 2], first_images.front(), first_images.back(), first_images.size());
    std::printf("               median %.1f ms, min %.1f ms, max %.1f ms (to the first full-resolution 1-spp image)\n",
                latencies[latencies.size() / 2], latencies.front(), latencies.back());
    print_designer_latencies(designer);
  });
}
