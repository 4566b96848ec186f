#include "bench/model_error_bench.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "airr/core/error.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/noise_level.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/render_session.hpp"
#include "bench/bench_case.hpp"
#include "bench/other_build.hpp"

std::string model_error_arguments(const model_error_options& o) {
  std::string args = "bench --model-error " + shell_quoted(o.scene_path) + " --size " + std::to_string(o.size) +
                     " --spp " + std::to_string(o.spp) + " --threads " + std::to_string(o.threads) + " --presets";
  for (const std::string& p : o.presets) args += " " + shell_quoted(p);
  args += " --tilts";
  for (double t : o.tilts_deg) args += " " + std::to_string(t);
  return args;
}

namespace {

// The second render's seed is the scene's plus this.
constexpr std::uint64_t second_seed_offset = 7919;

// The other build's `airr bench --model-error` on the same cases, each beside this build's view
// image: its model image's relative RMS difference from its own tracer, raw and with its tracer's
// noise taken out.
void print_other_build(const build_under_test& b, const model_error_options& o,
                       const std::vector<std::array<double, 4>>& rows) {
  std::fflush(stdout);
  const std::string out = run_build(b, model_error_arguments(o), "model error bench");
  std::printf("other build (%s): its model image against its tracer, beside this build's view image\n", b.airr.c_str());
  std::printf("%-8s %6s %12s %12s %14s %12s %14s\n", "preset", "tilt", "its noise", "its model", "its model,",
              "this view", "this view,");
  std::printf("%-8s %6s %12s %12s %14s %12s %14s\n", "", "deg", "", "", "noise out", "", "noise out");
  std::istringstream lines(out);
  std::size_t k = 0;
  for (std::string line; std::getline(lines, line) && k < rows.size();) {
    std::istringstream words(line);
    std::string preset;
    double tilt = 0;
    if (!(words >> preset >> tilt) || std::find(o.presets.begin(), o.presets.end(), preset) == o.presets.end()) {
      continue;
    }
    // Its row: tracer noise, model image, view image, first look, model and view with the noise taken out.
    double noise = 0, model = 0, view = 0, first = 0, clean = 0;
    char pct = 0;
    if (!(words >> noise >> pct >> model >> pct >> view >> pct >> first >> pct >> clean)) {
      std::printf("%-8s %6.0f %12s\n", preset.c_str(), tilt, "none");  // no model image there
      ++k;
      continue;
    }
    std::printf("%-8s %6.0f %11.2f%% %11.2f%% %13.2f%% %11.2f%% %13.2f%%\n", preset.c_str(), tilt, noise, model, clean,
                100 * rows[k][2], 100 * rows[k][3]);
    ++k;
  }
  if (k != rows.size()) {
    throw airr::input_error("model error bench: " + b.airr + " printed " + std::to_string(k) + " cases, not " +
                            std::to_string(rows.size()));
  }
}

}  // namespace

void run_model_error_bench(const model_error_options& o) {
  std::printf(
      "model image against the tracer at %llu spp, %dx%d, %s; relative RMS (of the tracer's mean); the tracer's noise "
      "is one render's, from a second render of another seed, and taken out of both renders' differences\n",
      static_cast<unsigned long long>(o.spp), o.size, o.size, o.scene_path.c_str());
  const std::vector<build_under_test> builds = builds_under_test(o.compare);
  std::printf("%-8s %6s %12s %12s %12s %12s %14s %14s %8s %8s\n", "preset", "tilt", "tracer noise", "model image",
              "view image", "first look", "model, noise", "view, noise", "model s", "view s");
  std::printf("%-8s %6s %12s %12s %12s %12s %14s %14s %8s %8s\n", "", "deg", "", "", "", "", "taken out", "taken out",
              "", "");
  std::vector<std::array<double, 4>> rows;  // per case: tracer noise, model image, view image, view taken out
  for (const std::string& preset : o.presets) {
    for (double tilt : o.tilts_deg) {
      const bench_case c = load_bench_case(o.scene_path, o.size, preset, tilt);
      const airr::scene& s = c.s;
      const airr::retro_model_list& models = c.models;
      const airr::image_rgb* display = c.display();
      const auto t0 = std::chrono::steady_clock::now();
      // As the designer is shown it: the display seen directly and in the half mirror added.
      airr::model_image_params full_params = airr::model_image_params::for_image(s.observer.width, s.observer.height);
      full_params.display_samples = 4;
      const auto full = airr::compute_layout_model_image(s, models, display, full_params);
      const double model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const auto t1 = std::chrono::steady_clock::now();
      const auto view = airr::compute_layout_model_image(s, models, display, airr::model_image_params::for_view());
      const double view_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      const airr::image_rgb first = airr::model_image_first_look(s, models, display);

      // Two renders of independent seeds: their difference gives one render's noise. (A render's
      // even and odd halves overstate it where its low-discrepancy samples balance each other
      // between the halves: the kiosk's own view at 128 x 128, 512 spp, 6.27% from its halves
      // against 5.73% from a second seed, which left no model error at all once taken out.)
      std::array<std::vector<float>, 2> traced;
      int width = 0, height = 0;
      for (std::size_t k = 0; k < traced.size(); ++k) {
        airr::scene seeded = s;
        seeded.seed = s.seed + k * second_seed_offset;
        airr::render_session session(seeded, {.threads = o.threads, .target_spp = o.spp, .preview_stride = 1});
        const airr::render_snapshot snap = session.wait_for(0, o.spp);
        traced[k] = *snap.rgb;
        width = snap.width;
        height = snap.height;
      }
      const double noise = airr::pair_relative_noise(airr::image_rgb{width, height, traced[0]},
                                                     airr::image_rgb{width, height, traced[1]});
      if (!full || !view || first.rgb.empty()) {
        std::printf("%-8s %6.0f %11.2f%% %12s %12s %12s\n", preset.c_str(), tilt, 100 * noise, "none", "none", "none");
        rows.push_back({noise, NAN, NAN, NAN});
        continue;
      }
      // Each render's difference from an image; the first render's is shown, and the mean square
      // of both less their noise is what the image itself differs by.
      auto differences = [&](const std::vector<float>& image) {
        return std::array<double, 2>{airr::relative_rms_difference(traced[0], image, traced[0]),
                                     airr::relative_rms_difference(traced[1], image, traced[0])};
      };
      auto clean = [&](const std::array<double, 2>& e) {
        return std::sqrt(std::max(0.0, 0.5 * (e[0] * e[0] + e[1] * e[1]) - noise * noise));
      };
      const std::array<double, 2> full_e = differences(full->image.rgb), view_e = differences(view->image.rgb);
      const double e_full = full_e[0], e_view = view_e[0];
      const double e_first = airr::relative_rms_difference(traced[0], first.rgb, traced[0]);
      const double e_clean = clean(full_e), e_view_clean = clean(view_e);
      std::printf("%-8s %6.0f %11.2f%% %11.2f%% %11.2f%% %11.2f%% %13.2f%% %13.2f%% %8.2f %8.3f\n", preset.c_str(),
                  tilt, 100 * noise, 100 * e_full, 100 * e_view, 100 * e_first, 100 * e_clean, 100 * e_view_clean,
                  model_s, view_s);
      rows.push_back({noise, e_full, e_view, e_view_clean});
      std::fflush(stdout);
    }
  }
  if (builds.size() == 2) print_other_build(builds[1], o, rows);
}
