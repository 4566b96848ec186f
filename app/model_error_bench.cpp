#include "model_error_bench.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/measure/noise_level.hpp"
#include "airr/render/layout_model_image.hpp"
#include "airr/render/render_session.hpp"
#include "bench_case.hpp"

namespace {

// RMS of a - b over pixels and channels, relative to the mean of `reference`.
double relative_rms(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>& reference) {
  double squares = 0, sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = double(a[i]) - double(b[i]);
    squares += d * d;
    sum += reference[i];
  }
  const double n = double(a.size());
  return sum > 0 ? std::sqrt(squares / n) / (sum / n) : 0.0;
}

}  // namespace

void run_model_error_bench(const model_error_options& o) {
  std::printf("model image against the tracer at %llu spp, %dx%d, default scene; relative RMS (of the tracer's mean)\n",
              static_cast<unsigned long long>(o.spp), o.size, o.size);
  std::printf("%-8s %6s %12s %12s %12s %14s %10s\n", "preset", "tilt", "tracer noise", "model image", "first look",
              "model, noise", "model s");
  std::printf("%-8s %6s %12s %12s %12s %14s %10s\n", "", "deg", "", "", "", "taken out", "");
  for (const std::string& preset : o.presets) {
    for (double tilt : o.tilts_deg) {
      const bench_case c = load_bench_case(o.scene_path, o.size, preset, tilt);
      const airr::scene& s = c.s;
      const airr::retro_model_list& models = c.models;
      const airr::image_rgb* display = c.display();
      const auto t0 = std::chrono::steady_clock::now();
      const auto full = airr::compute_layout_model_image(
          s, models, display, airr::model_image_params::for_image(s.observer.width, s.observer.height));
      const double model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const airr::image_rgb first = airr::model_image_first_look(s, models, display);

      airr::render_session session(s, {.threads = o.threads, .target_spp = o.spp, .preview_stride = 1});
      const airr::render_snapshot traced = session.wait_for(0, o.spp);
      const std::vector<float> even = traced.even_rgb();
      const airr::image_rgb odd_image{traced.width, traced.height, *traced.odd_rgb};
      const airr::image_rgb even_image{traced.width, traced.height, even};
      // Each half has twice the full mean's variance; their difference four times.
      const double noise = airr::pair_relative_noise(odd_image, even_image) / std::sqrt(2.0);
      if (!full || first.rgb.empty()) {
        std::printf("%-8s %6.0f %11.2f%% %12s %12s %14s %10s\n", preset.c_str(), tilt, 100 * noise, "none", "none", "",
                    "");
        continue;
      }
      const double e_full = relative_rms(*traced.rgb, full->image.rgb, *traced.rgb);
      const double e_first = relative_rms(*traced.rgb, first.rgb, *traced.rgb);
      const double e_clean = std::sqrt(std::max(0.0, e_full * e_full - noise * noise));
      std::printf("%-8s %6.0f %11.2f%% %11.2f%% %11.2f%% %13.2f%% %10.2f\n", preset.c_str(), tilt, 100 * noise,
                  100 * e_full, 100 * e_first, 100 * e_clean, model_s);
      std::fflush(stdout);
    }
  }
}
