#pragma once
// airr bench --model-image: where an edit's model image spends its time, at view quality (what the
// designer is shown after the first look), at the control variate's quick and full qualities, per
// sheet preset and tilt; with --compare, the other build's full-quality model image beside it.
#include <string>
#include <vector>

struct model_image_bench_options {
  std::string scene_path;
  int size = 512;
  int runs = 3;  // per case; the median is reported
  std::vector<std::string> presets{"rf-ay", "rf-an"};
  std::vector<double> tilts_deg{0, 20, 45};
  std::vector<std::string> qualities{"view", "quick", "full"};  // of these, in this order
  std::string compare;  // another build's airr; empty: this build only (needs the view quality)
};

// Prints one line per preset, tilt and quality; throws input_error naming what failed.
void run_model_image_bench(const model_image_bench_options& o);
