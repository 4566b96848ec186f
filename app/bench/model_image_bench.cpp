#include "bench/model_image_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "airr/core/error.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/render/display_parts_image.hpp"
#include "airr/render/model_image.hpp"
#include "bench/bench_case.hpp"
#include "bench/model_error_bench.hpp"
#include "bench/other_build.hpp"

namespace {

enum { view, quick, full };
const char* const quality_names[] = {"view", "quick", "full"};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// The other build's full-quality model image of each case, in seconds: the "model s" column of
// its `airr bench --model-error` (which times compute_layout_model_image at for_image's full
// quality), at two samples per pixel so that its tracer's part is short.
std::vector<double> other_build_seconds(const build_under_test& b, const model_image_bench_options& o) {
  model_error_options m;
  m.scene_path = o.scene_path;
  m.size = o.size;
  m.spp = 2;
  m.presets = o.presets;
  m.tilts_deg = o.tilts_deg;
  const std::string out = run_build(b, model_error_arguments(m), "model image bench");
  std::vector<double> seconds;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string preset;
    double tilt = 0;
    if (!(words >> preset >> tilt) || std::find(o.presets.begin(), o.presets.end(), preset) == o.presets.end()) {
      continue;
    }
    std::string word, last;
    while (words >> word) last = word;
    seconds.push_back(std::stod(last));
  }
  if (seconds.size() != o.presets.size() * o.tilts_deg.size()) {
    throw airr::input_error("model image bench: " + b.airr + " --model-error printed " +
                            std::to_string(seconds.size()) + " cases, not " +
                            std::to_string(o.presets.size() * o.tilts_deg.size()));
  }
  return seconds;
}

// The view image moved by a drag's step (the tilt by 0.5 deg): the designer's first look while
// dragging. Prints its row; returns the median in ms.
double moved_ms(const bench_case& c, const airr::model_image_params& view_params, int runs) {
  const auto from = airr::compute_model_image(c.s, c.models.front(), c.display(), view_params);
  if (!from) throw airr::input_error("model image bench: no pixel sees the sheet");
  airr::scene moved = c.s;
  moved.sheet().pose.pitch_deg += 0.5;
  std::vector<double> total;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const airr::image_rgb image = airr::remap_model_image(*from, moved, view_params);
    total.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (image.rgb.empty()) {
      std::printf("%-6s %5g %-7s %8s  (the view image cannot be moved by 0.5 deg of tilt: beyond its limits)\n", "",
                  c.s.sheet().pose.pitch_deg, "moved", "-");
      return NAN;
    }
  }
  std::printf("%-6s %5g %-7s %8.1f  (the view image moved by 0.5 deg of tilt)\n", "", c.s.sheet().pose.pitch_deg,
              "moved", median(total));
  return median(total);
}

// The display seen directly and in the half mirror at view quality, which the designer's view
// image adds to the sheets'. Prints its row; returns the median in ms.
double display_parts_ms(const bench_case& c, const airr::model_image_params& view_params, int runs) {
  std::vector<double> total;
  double mean = 0;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<airr::image_rgb> texels =
        airr::display_parts_texels(c.s, c.display(), view_params.display_samples);
    const airr::image_rgb parts = airr::display_parts_image(c.s, texels, view_params);
    total.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    mean = 0;
    for (float v : parts.rgb) mean += v;
    if (!parts.rgb.empty()) mean /= double(parts.rgb.size());
  }
  std::printf("%-6s %5g %-7s %8.1f  (the display seen directly and in the half mirror; their mean %.3g)\n", "",
              c.s.sheet().pose.pitch_deg, "display", median(total), mean);
  return median(total);
}

}  // namespace

void run_model_image_bench(const model_image_bench_options& o) {
  std::vector<int> qualities;
  for (int q : {view, quick, full}) {
    if (std::find(o.qualities.begin(), o.qualities.end(), quality_names[q]) != o.qualities.end())
      qualities.push_back(q);
  }
  if (qualities.size() != o.qualities.size() || qualities.empty()) {
    throw airr::input_error("model image bench: --qualities takes view, quick and full, each at most once");
  }
  if (!o.compare.empty() && qualities.front() != view) {
    throw airr::input_error("model image bench: --compare sets the other build against this build's view quality");
  }
  const std::vector<build_under_test> builds = builds_under_test(o.compare);
  std::printf(
      "model image of sheet 0 at %dx%d, median of %d runs (ms); the loop's parts are summed over the bins that run "
      "side by side\n",
      o.size, o.size, o.runs);
  std::printf("%-6s %5s %-7s %8s %8s %8s %8s %8s %8s %9s %9s %8s\n", "preset", "tilt", "quality", "total", "paths",
              "bins", "spectra", "samples", "loop", "(kernels", "correlate", "gather)");
  std::vector<double> medians[3], moved_medians, display_medians;
  for (const std::string& preset : o.presets) {
    for (double tilt : o.tilts_deg) {
      const bench_case c = load_bench_case(o.scene_path, o.size, preset, tilt);
      for (const int quality : qualities) {
        const airr::model_image_params params =
            quality == view ? airr::model_image_params::for_view()
                            : airr::model_image_params::for_image(o.size, o.size, quality == quick);
        std::vector<double> total, paths, bins, spectra, landings, loop, kernels, correlate, gather;
        for (int r = 0; r < o.runs; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          const auto m = airr::compute_model_image(c.s, c.models.front(), c.display(), params);
          total.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          if (!m) throw airr::input_error("model image bench: no pixel sees the sheet");
          paths.push_back(1e3 * m->paths_seconds);
          bins.push_back(1e3 * m->bins_seconds);
          spectra.push_back(1e3 * m->spectra_seconds);
          landings.push_back(1e3 * m->landings_seconds);
          loop.push_back(1e3 * m->loop_seconds);
          kernels.push_back(1e3 * m->kernels_seconds);
          correlate.push_back(1e3 * m->correlate_seconds);
          gather.push_back(1e3 * m->gather_seconds);
        }
        std::printf("%-6s %5g %-7s %8.0f %8.0f %8.0f %8.0f %8.0f %8.0f %9.0f %9.0f %8.0f\n", preset.c_str(), tilt,
                    quality_names[quality], median(total), median(paths), median(bins), median(spectra),
                    median(landings), median(loop), median(kernels), median(correlate), median(gather));
        medians[quality].push_back(median(total));
        if (quality == view) {
          const double moved = moved_ms(c, params, o.runs);
          if (!std::isnan(moved)) moved_medians.push_back(moved);
          display_medians.push_back(display_parts_ms(c, params, o.runs));
        }
      }
    }
  }
  std::printf("median over the cases:");
  for (const int quality : qualities) {
    std::printf("%s %s %.0f ms", quality == qualities.front() ? "" : ",", quality_names[quality],
                median(medians[quality]));
  }
  if (qualities.front() == view)
    std::printf("; moved %.1f ms; display %.1f ms", median(moved_medians), median(display_medians));
  std::printf("\n");
  if (builds.size() == 2) {
    std::fflush(stdout);
    const std::vector<double> other = other_build_seconds(builds[1], o);
    std::vector<double> other_ms;
    for (double s : other) other_ms.push_back(1e3 * s);
    std::printf("other build (%s), full quality, one run per case:", builds[1].airr.c_str());
    for (double ms : other_ms) std::printf(" %.0f", ms);
    std::printf(" ms; median %.0f ms\n", median(other_ms));
    std::printf("the other build's full-quality model image / this build's view-quality one: %.1fx (medians)\n",
                median(other_ms) / median(medians[view]));
  }
}
