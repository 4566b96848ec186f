#include "model_image_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "airr/core/error.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/model_image.hpp"
#include "bench_case.hpp"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

void run_model_image_bench(const model_image_bench_options& o) {
  std::printf(
      "model image of sheet 0 at %dx%d, median of %d runs (ms); the loop's parts are summed over the bins that run "
      "side by side\n",
      o.size, o.size, o.runs);
  std::printf("%-6s %5s %-7s %8s %8s %8s %8s %8s %9s %9s %8s\n", "preset", "tilt", "quality", "total", "paths", "bins",
              "spectra", "loop", "(kernels", "correlate", "gather)");
  for (const std::string& preset : o.presets) {
    for (double tilt : o.tilts_deg) {
      const bench_case c = load_bench_case(o.scene_path, o.size, preset, tilt);
      for (const bool quick : {true, false}) {
        std::vector<double> total, paths, bins, spectra, loop, kernels, correlate, gather;
        for (int r = 0; r < o.runs; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          const auto m = airr::compute_model_image(c.s, c.models.front(), c.display(),
                                                   airr::model_image_params::for_image(o.size, o.size, quick));
          total.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          if (!m) throw airr::input_error("model image bench: no pixel sees the sheet");
          paths.push_back(1e3 * m->paths_seconds);
          bins.push_back(1e3 * m->bins_seconds);
          spectra.push_back(1e3 * m->spectra_seconds);
          loop.push_back(1e3 * m->loop_seconds);
          kernels.push_back(1e3 * m->kernels_seconds);
          correlate.push_back(1e3 * m->correlate_seconds);
          gather.push_back(1e3 * m->gather_seconds);
        }
        std::printf("%-6s %5g %-7s %8.0f %8.0f %8.0f %8.0f %8.0f %9.0f %9.0f %8.0f\n", preset.c_str(), tilt,
                    quick ? "quick" : "full", median(total), median(paths), median(bins), median(spectra), median(loop),
                    median(kernels), median(correlate), median(gather));
      }
    }
  }
}
