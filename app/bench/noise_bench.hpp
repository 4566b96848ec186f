#pragma once
// airr bench --noise: the time and samples per pixel a build needs to reach 2% and 1% relative RMS
// noise on the default scene at 512 x 512, per sheet preset. Every build is timed the same way,
// through its own `airr render` (so another build's binary can be measured side by side in the
// same run), and the noise of each render comes from a pair with independent seeds, so no
// reference's own noise counts.
#include <cstdint>
#include <string>
#include <vector>

struct noise_bench_options {
  std::string scene_path;
  int size = 512;
  std::vector<std::uint64_t> spp{16, 64};
  std::vector<std::string> presets{"rf-ay", "rf-an"};
  std::string compare;  // another build's airr; empty: this build only
  int threads = 0;
  std::vector<int> scaling_threads{1, 2};  // run_scaling_bench's thread counts, the first the base
};

// Prints one block per preset; throws input_error naming what failed (a render, an image).
void run_noise_bench(const noise_bench_options& o);

// airr bench --scaling: the same measurement of this build at each of o.scaling_threads, and
// how the time per spp and the startup (scene, model image) speed up from the first count to
// each other: the speed-up S and the parallel part p of that time by Amdahl's law,
// S = 1 / ((1 - p) + p / r) for r times the threads.
void run_scaling_bench(const noise_bench_options& o);
