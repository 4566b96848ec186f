#pragma once
// airr bench --model-error: how far the model image (the control variate's, the designer's view of
// it and its first look) is from the converged tracer, per sheet preset and sheet tilt, on the
// default scene; with --compare, the other build's table beside it.
#include <cstdint>
#include <string>
#include <vector>

struct model_error_options {
  std::string scene_path;
  int size = 256;
  std::uint64_t spp = 128;
  std::vector<std::string> presets{"rf-ay", "rf-an"};
  std::vector<double> tilts_deg{0, 5, 10, 15, 20, 25, 30, 35, 40, 45};
  int threads = 0;
  std::string compare;  // another build's airr; empty: this build only
};

// The arguments of `airr bench --model-error` for these options (another build's run).
std::string model_error_arguments(const model_error_options& o);

// Prints one line per preset and tilt; throws input_error naming what failed.
void run_model_error_bench(const model_error_options& o);
