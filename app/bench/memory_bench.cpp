#include "bench/memory_bench.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <vector>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "bench/other_build.hpp"

namespace fs = std::filesystem;

namespace {

struct measured_run {
  double peak_mb = 0;  // the child's peak resident set (ru_maxrss)
  double seconds = 0;
};

// Runs `args` (argv, without a shell, so that the peak is the render's own), its output to `log`.
measured_run run_measured(const std::vector<std::string>& args, const fs::path& log, const std::string& what) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);  // else the child's stdout, reopened, writes what is buffered once more
  std::fflush(stderr);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw airr::input_error(what + ": cannot start " + args[0]);
  if (pid == 0) {
    if (!std::freopen(log.c_str(), "w", stdout) || !std::freopen(log.c_str(), "a", stderr)) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  if (::wait4(pid, &status, 0, &usage) != pid) throw airr::input_error(what + ": lost the render's process");
  measured_run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peak_mb = double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw airr::input_error(what + ": " + args[0] + " render failed: " + last_line(airr::read_text_file(log.string())));
  }
  return r;
}

}  // namespace

void run_memory_bench(const memory_bench_options& o) {
  const std::vector<build_under_test> builds = builds_under_test(o.compare);
  const int sizes[2] = {o.size / 2, o.size};
  std::printf("memory benchmark: %s, airr render at 1 spp, peak resident memory (ru_maxrss) of the process\n",
              o.scene_path.c_str());
  std::printf("%-12s %-8s %-11s %10s %9s\n", "build", "size", "components", "peak MB", "time s");
  // [build][components][size]
  std::vector<std::array<std::array<double, 2>, 2>> peaks(builds.size());
  const scratch_dir dir("memory");
  for (std::size_t b = 0; b < builds.size(); ++b) {
    for (int components = 0; components < 2; ++components) {
      for (int k = 0; k < 2; ++k) {
        const std::string side = std::to_string(sizes[k]);
        std::vector<std::string> args = {builds[b].airr,
                                         "render",
                                         o.scene_path,
                                         "--spp",
                                         "1",
                                         "--threads",
                                         std::to_string(o.threads),
                                         "--set",
                                         "observer.width=" + side,
                                         "--set",
                                         "observer.height=" + side,
                                         "-o",
                                         (dir.path / "render.exr").string()};
        if (components) args.push_back("--components");
        const measured_run r = run_measured(args, dir.path / "render.log", "memory (" + builds[b].label + ")");
        peaks[b][std::size_t(components)][std::size_t(k)] = r.peak_mb;
        std::printf("%-12s %-8s %-11s %10.1f %9.1f\n", builds[b].label.c_str(), (side + "^2").c_str(),
                    components ? "yes" : "no", r.peak_mb, r.seconds);
        std::fflush(stdout);
      }
    }
  }
  const double added = double(sizes[1]) * sizes[1] - double(sizes[0]) * sizes[0];
  for (std::size_t b = 0; b < builds.size(); ++b) {
    std::printf("%s (%s): bytes a pixel (the peak's rise from %d^2 to %d^2 over the pixels added):",
                builds[b].label.c_str(), builds[b].airr.c_str(), sizes[0], sizes[1]);
    for (int components = 0; components < 2; ++components) {
      const auto& p = peaks[b][std::size_t(components)];
      std::printf(" %.0f %s;", (p[1] - p[0]) * 1048576.0 / added, components ? "with components" : "without");
    }
    std::printf(" beyond the pixels %.0f MB\n",
                peaks[b][0][1] - (peaks[b][0][1] - peaks[b][0][0]) * double(sizes[1]) * sizes[1] / added);
  }
  if (builds.size() == 2) {
    std::printf("other build's bytes a pixel / this build's:");
    for (int components = 0; components < 2; ++components) {
      const auto& mine = peaks[0][std::size_t(components)];
      const auto& theirs = peaks[1][std::size_t(components)];
      std::printf(" %.2fx %s;", (theirs[1] - theirs[0]) / (mine[1] - mine[0]),
                  components ? "with components" : "without");
    }
    std::printf("\n");
  }
}
