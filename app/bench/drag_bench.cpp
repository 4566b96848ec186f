#include "bench/drag_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/measure/noise_level.hpp"
#include "airr/render/render_session.hpp"
#include "cli/progress_bar.hpp"

namespace {

using clock_type = std::chrono::steady_clock;

// A converged image of one layout and its own remaining noise (relative RMS of its mean).
struct reference {
  std::vector<float> rgb;
  double noise = 0;
};

// The mean of two renders whose seeds differ from the session's (whose samples it would share),
// and its noise from their difference (half of it: the noise of one is the difference's over
// sqrt 2, of their mean another sqrt 2 less).
reference converge(airr::scene s, std::uint64_t spp, std::uint64_t seed) {
  std::vector<float> halves[2];
  for (int k = 0; k < 2; ++k) {
    s.seed = seed + std::uint64_t(k);
    airr::render_session session(s, {.target_spp = spp, .preview_stride = 1});
    const airr::render_snapshot snap = session.wait_for(0, spp);
    if (!snap.rgb) throw airr::input_error("drag bench: a reference render gave no image");
    halves[k] = *snap.rgb;
  }
  reference r;
  r.rgb.resize(halves[0].size());
  for (std::size_t i = 0; i < r.rgb.size(); ++i) r.rgb[i] = 0.5f * (halves[0][i] + halves[1][i]);
  r.noise = 0.5 * airr::relative_rms_difference(halves[0], halves[1], r.rgb);
  return r;
}

// Distance of what was shown from the converged image, the reference's own noise taken out.
double error_against(const std::vector<float>& shown, const reference& r) {
  const double d = airr::relative_rms_difference(shown, r.rgb, r.rgb);
  return std::sqrt(std::max(0.0, d * d - r.noise * r.noise));
}

// One change of what the session shows.
struct shown_event {
  double t = 0;  // seconds since the drag began
  std::uint64_t generation = 0;
  std::shared_ptr<const std::vector<float>> image;
  std::string estimate;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

}  // namespace

void run_drag_bench(const drag_bench_options& o) {
  airr::scene base = airr::load_scene(o.scene_path);
  if (o.size > 0) base.observer.width = base.observer.height = o.size;
  if (o.edits < 1 || !(o.rate_hz > 0) || !(o.rest_s > 0)) throw airr::input_error("drag bench: options out of range");
  // Layout k: the scene with its tilt moved by k steps (0: as loaded, before the drag).
  std::vector<airr::scene> layouts;
  for (int k = 0; k <= o.edits; ++k) {
    airr::scene s = base;
    s.sheet().pose.pitch_deg += k * o.step_deg;
    layouts.push_back(s);
  }
  std::vector<reference> refs;
  {
    progress_bar bar("converged images");
    for (int k = 1; k <= o.edits; ++k) {
      refs.push_back(converge(layouts[std::size_t(k)], k == o.edits ? o.final_reference_spp : o.reference_spp,
                              base.seed + 1000 + 2 * std::uint64_t(k)));
      bar.update(double(k) / o.edits, std::to_string(k) + " of " + std::to_string(o.edits));
    }
    bar.finish(std::to_string(o.edits) + " layouts");
  }

  // The replay: the designer's session, a recorder of what it shows, edits at the drag's rate.
  airr::render_session session(
      layouts[0], {.background_priority = true, .first_look = true, .quick_model_image = true, .components = true});
  session.wait_for(0, 1);
  // The designer looks at the opening layout for a moment before dragging (its view-quality model
  // image, the first edit's first look, is ready by then).
  std::this_thread::sleep_for(std::chrono::seconds(1));
  std::vector<shown_event> events;
  std::vector<std::uint64_t> generations(std::size_t(o.edits), 0);
  std::mutex events_mutex;
  const auto t0 = clock_type::now();
  std::atomic<bool> stop{false};
  std::thread recorder([&] {
    const void* last = nullptr;
    session.wait_until([&](const airr::render_snapshot& snap) {
      if (snap.shown && snap.shown.get() != last) {
        last = snap.shown.get();
        const std::lock_guard lock(events_mutex);
        events.push_back({std::chrono::duration<double>(clock_type::now() - t0).count(), snap.generation, snap.shown,
                          airr::estimate_name(snap)});
      }
      return stop.load();
    });
  });
  for (int k = 1; k <= o.edits; ++k) {
    std::this_thread::sleep_until(t0 + std::chrono::duration<double>((k - 1) / o.rate_hz));
    const std::uint64_t gen = session.edit(layouts[std::size_t(k)]);
    const std::lock_guard lock(events_mutex);
    generations[std::size_t(k - 1)] = gen;
  }
  const double drag_end = o.edits / o.rate_hz, end = (o.edits - 1) / o.rate_hz + o.rest_s;
  std::this_thread::sleep_until(t0 + std::chrono::duration<double>(end));
  stop = true;
  session.stop();
  recorder.join();

  // Frames at 60 Hz: each shows the last image published before it; the designer's layout then is
  // the last edit's.
  auto edit_at = [&](double t) { return std::clamp(int(std::floor(t * o.rate_hz)), 0, o.edits - 1); };
  auto edit_of = [&](std::uint64_t gen) {
    const auto it = std::find(generations.begin(), generations.end(), gen);
    return it == generations.end() ? -1 : int(it - generations.begin());
  };
  std::ostringstream csv;
  csv << "time_s,edit,shown_edit,estimate,latency_ms,relative_rms\n";
  std::printf(
      "drag: %d edits of the tilt by %g deg at %g per second from %g deg, %dx%d, 1 s after opening; frames at 60 Hz\n",
      o.edits, o.step_deg, o.rate_hz, base.sheet().pose.pitch_deg, base.observer.width, base.observer.height);
  std::printf("%4s %9s %12s %12s %10s %12s  %s\n", "edit", "frames", "worst rms", "stale", "first ms", "last ms",
              "last shown");
  std::vector<double> worst_per_edit(std::size_t(o.edits), 0.0);
  double worst = 0, worst_t = 0;
  std::string worst_what;
  std::vector<int> frames(std::size_t(o.edits), 0), stale(std::size_t(o.edits), 0);
  std::vector<double> first_ms(std::size_t(o.edits), NAN), last_ms(std::size_t(o.edits), NAN);
  std::vector<std::string> last_what(std::size_t(o.edits));
  std::size_t e = 0;
  for (double t = 1.0 / 60; t < drag_end; t += 1.0 / 60) {
    while (e + 1 < events.size() && events[e + 1].t <= t) ++e;
    if (events.empty() || events[e].t > t) continue;
    const int k = edit_at(t), shown_edit = edit_of(events[e].generation);
    const double rms = error_against(*events[e].image, refs[std::size_t(k)]);
    const double latency = shown_edit == k ? 1e3 * (events[e].t - k / o.rate_hz) : NAN;
    ++frames[std::size_t(k)];
    if (shown_edit != k) ++stale[std::size_t(k)];
    worst_per_edit[std::size_t(k)] = std::max(worst_per_edit[std::size_t(k)], rms);
    if (rms > worst) worst = rms, worst_t = t, worst_what = events[e].estimate;
    csv << t << "," << k + 1 << "," << shown_edit + 1 << "," << events[e].estimate << "," << latency << "," << rms
        << "\n";
  }
  for (const shown_event& ev : events) {
    const int k = edit_of(ev.generation);
    if (k < 0 || ev.t >= (k + 1) / o.rate_hz) continue;
    const double ms = 1e3 * (ev.t - k / o.rate_hz);
    if (std::isnan(first_ms[std::size_t(k)])) first_ms[std::size_t(k)] = ms;
    last_ms[std::size_t(k)] = ms;
    last_what[std::size_t(k)] = ev.estimate;
  }
  for (int k = 0; k < o.edits; ++k) {
    const std::size_t i = std::size_t(k);
    std::printf("%4d %9d %11.2f%% %12d %10.1f %12.1f  %s\n", k + 1, frames[i], 100 * worst_per_edit[i], stale[i],
                first_ms[i], last_ms[i], last_what[i].c_str());
  }
  if (!o.csv.empty()) airr::write_file_atomic(o.csv, csv.str());
  std::printf("worst frame during the drag: %.2f%% at %.3f s (%s); median edit's worst frame %.2f%%\n", 100 * worst,
              worst_t, worst_what.c_str(), 100 * percentile(worst_per_edit, 0.5));

  // After the drag: the first time what is shown stays within 2% and 1% of the last layout's
  // converged image (its own noise taken out).
  const reference& last = refs.back();
  const double last_edit_t = (o.edits - 1) / o.rate_hz;
  for (double target : {0.02, 0.01}) {
    double reached = NAN;
    std::string what;
    for (const shown_event& ev : events) {
      if (ev.t < last_edit_t || edit_of(ev.generation) != o.edits - 1) continue;
      const double rms = error_against(*ev.image, last);
      if (rms <= target && std::isnan(reached)) reached = ev.t - last_edit_t, what = ev.estimate;
      if (rms > target) reached = NAN;
    }
    if (std::isnan(reached)) {
      std::printf("after the drag: %.0f%% not reached within %.0f s\n", 100 * target, o.rest_s);
    } else {
      std::printf("after the drag: within %.0f%% %.2f s after the last edit (%s)\n", 100 * target, reached,
                  what.c_str());
    }
  }
  std::printf(
      "converged images: two renders of %llu spp each (the last layout's %llu), of other seeds than the session's, "
      "their noise taken out of each comparison (last: %.2f%%)\n",
      static_cast<unsigned long long>(o.reference_spp), static_cast<unsigned long long>(o.final_reference_spp),
      100 * last.noise);
}
