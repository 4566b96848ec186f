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
};

// Prints one block per preset; throws input_error naming what failed (a render, an image).
void run_noise_bench(const noise_bench_options& o);
