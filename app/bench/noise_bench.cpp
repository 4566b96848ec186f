#include "bench/noise_bench.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "airr/core/error.hpp"
#include "airr/formats/image.hpp"
#include "airr/measure/noise_level.hpp"
#include "bench/other_build.hpp"

namespace fs = std::filesystem;

namespace {

// One `airr render` of the preset's scene; returns the image and the wall time.
airr::image_rgb render_once(const build_under_test& b, const noise_bench_options& o, const std::string& preset,
                            std::uint64_t spp, int seed, const fs::path& dir, double& seconds) {
  const fs::path out = dir / "render.exr", log = dir / "render.log";
  const std::string size = std::to_string(o.size);
  const std::string cmd =
      shell_quoted(b.airr) + " render " + shell_quoted(o.scene_path) + " --spp " + std::to_string(spp) + " --seed " +
      std::to_string(seed) + " --threads " + std::to_string(o.threads) + " --set observer.width=" + size +
      " --set observer.height=" + size +
      " --set retroreflectors.0.model.type=sinc_shift --set retroreflectors.0.model.preset=" + preset + " -o " +
      shell_quoted(out.string()) + " > " + shell_quoted(log.string()) + " 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (status != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line)) last = line.empty() ? last : line;
    throw airr::input_error("noise: " + b.airr + " render failed (" + preset + ", " + std::to_string(spp) +
                            " spp): " + last);
  }
  return airr::load_image(out.string()).pixels;
}

// The measured pairs of one build and preset, and the noise law through them.
struct build_result {
  std::vector<airr::noise_point> points;
  airr::noise_law law;
};

build_result measure(const build_under_test& b, const noise_bench_options& o, const std::string& preset) {
  const scratch_dir dir("noise");
  build_result r;
  for (std::uint64_t spp : o.spp) {
    double t1 = 0, t2 = 0;
    const airr::image_rgb a = render_once(b, o, preset, spp, 1, dir.path, t1);
    const airr::image_rgb c = render_once(b, o, preset, spp, 2, dir.path, t2);
    r.points.push_back({spp, 0.5 * (t1 + t2), airr::pair_relative_noise(a, c)});
    std::fprintf(stderr, "noise: %s, %s, %llu spp: %.2f%% in %.1f s\n", b.label.c_str(), preset.c_str(),
                 static_cast<unsigned long long>(spp), 100 * r.points.back().noise, r.points.back().seconds);
  }
  r.law = airr::fit_noise_law(r.points);
  return r;
}

void print_result(const build_under_test& b, const build_result& r) {
  std::printf("  %s (%s):\n   ", b.label.c_str(), b.airr.c_str());
  for (const auto& p : r.points) {
    std::printf(" %llu spp: %.2f%% in %.2f s;", static_cast<unsigned long long>(p.spp), 100 * p.noise, p.seconds);
  }
  std::printf("\n    law: noise = %.4f spp^-%.3f; %.4f s per spp + %.2f s startup\n", r.law.amplitude, r.law.exponent,
              r.law.seconds_per_spp, r.law.startup_s);
  std::printf("   ");
  for (double target : {0.02, 0.01}) {
    const airr::noise_target t = airr::time_to_noise(r.law, r.points, target);
    std::printf(" %.0f%%: %.0f spp, %.1f s (%s);", 100 * target, t.spp, t.seconds,
                t.within_measured ? "within the measured range" : "extrapolated");
  }
  std::printf("\n");
}

}  // namespace

void run_noise_bench(const noise_bench_options& o) {
  const std::vector<build_under_test> builds = builds_under_test(o.compare);
  std::printf(
      "noise benchmark: %s at %dx%d. Noise of one render = RMS difference of two renders with seeds 1 and 2, "
      "divided by sqrt 2 and by the mean; times are wall times of each build's `airr render` (startup included)\n",
      o.scene_path.c_str(), o.size, o.size);
  for (const std::string& preset : o.presets) {
    std::printf("%s\n", preset.c_str());
    std::vector<build_result> results;
    for (const build_under_test& b : builds) {
      results.push_back(measure(b, o, preset));
      print_result(b, results.back());
    }
    if (results.size() == 2) {
      std::printf("  speed-up (other build's time / this build's):");
      for (double target : {0.02, 0.01}) {
        const double mine = airr::time_to_noise(results[0].law, results[0].points, target).seconds;
        const double theirs = airr::time_to_noise(results[1].law, results[1].points, target).seconds;
        std::printf(" %.0f%%: %.2fx;", 100 * target, theirs / mine);
      }
      std::printf("\n");
    }
    std::fflush(stdout);
  }
}

namespace {

// Amdahl's parallel part from a speed-up `s` with `r` times the threads.
double parallel_part(double s, double r) { return r > 1 ? (1 - 1 / s) / (1 - 1 / r) : NAN; }

}  // namespace

void run_scaling_bench(const noise_bench_options& o) {
  if (o.scaling_threads.size() < 2) throw airr::input_error("--scaling needs two or more thread counts");
  const build_under_test self = builds_under_test("").front();
  std::printf(
      "scaling benchmark: %s at %dx%d, this build's `airr render` at %zu thread counts; per spp and startup from "
      "the time law of each (seconds = startup + spp x seconds per spp), pairs of seeds as in --noise\n",
      o.scene_path.c_str(), o.size, o.size, o.scaling_threads.size());
  for (const std::string& preset : o.presets) {
    std::printf("%s\n", preset.c_str());
    std::vector<build_result> results;
    for (int n : o.scaling_threads) {
      noise_bench_options one = o;
      one.threads = n;
      results.push_back(measure(self, one, preset));
      const build_result& r = results.back();
      std::printf("  %d thread%s: %.4f s per spp + %.2f s startup;", n, n == 1 ? "" : "s", r.law.seconds_per_spp,
                  r.law.startup_s);
      for (const auto& p : r.points) {
        std::printf(" %llu spp %.2f%% in %.2f s;", static_cast<unsigned long long>(p.spp), 100 * p.noise, p.seconds);
      }
      std::printf("\n");
    }
    const build_result& base = results.front();
    for (std::size_t i = 1; i < results.size(); ++i) {
      const double r = double(o.scaling_threads[i]) / o.scaling_threads.front();
      const double per_spp = base.law.seconds_per_spp / results[i].law.seconds_per_spp;
      const double startup = base.law.startup_s / results[i].law.startup_s;
      const double one_percent = airr::time_to_noise(base.law, base.points, 0.01).seconds /
                                 airr::time_to_noise(results[i].law, results[i].points, 0.01).seconds;
      std::printf(
          "  %d -> %d threads: per spp %.2fx (parallel part %.1f%%), startup %.2fx (parallel part %.1f%%), time to "
          "1%% %.2fx\n",
          o.scaling_threads.front(), o.scaling_threads[i], per_spp, 100 * parallel_part(per_spp, r), startup,
          100 * parallel_part(startup, r), one_percent);
    }
    std::fflush(stdout);
  }
}
