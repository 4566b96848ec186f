// The designer's threads driven far faster than a person can, for the ThreadSanitizer build.
// 1. The render session under random edits, pauses and target changes, while the designer's side
//    takes snapshots and hands them, with scenes, to the analysis worker, and a third thread keeps
//    replacing the source image on disk (each replacement is read again). Afterwards the last
//    layout's image must equal a fresh render of it, bit for bit.
// 2. Sheet fits started and cancelled at random moments while their progress is polled.
// Exits non-zero on any mismatch; TSan's halt_on_error turns any report into a failure.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>

#include <tbb/global_control.h>

#include "airr/core/assets.hpp"
#include "airr/core/random.hpp"
#include "airr/formats/image.hpp"
#include "airr/render/render_session.hpp"
#include "airr/ui/jobs/analysis_worker.hpp"
#include "airr/ui/jobs/fit_job.hpp"

using namespace airr;
namespace fs = std::filesystem;

namespace {

image_rgb stripes(int period) {
  image_rgb img;
  img.width = img.height = 16;
  img.rgb.resize(16 * 16 * 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = (x / period) % 2 ? 0.9f : 0.1f;
  return img;
}

bool session_worker_and_reloads(int edits, const fs::path& dir) {
  const std::string source_image = (dir / "source.png").string();
  write_image(source_image, stripes(2), {});

  scene base;
  const std::string panel = asset_dir() + "/models/panel.gltf";
  base.source.mesh = base.half_mirror.mesh = base.sheet().mesh = panel;
  base.source.width_mm = base.source.height_mm = 20;
  base.source.image = source_image;
  base.observer.width = base.observer.height = 24;

  render_session session(base, {.threads = 2, .target_spp = 1 << 20, .max_wave_spp = 4});
  ui::analysis_worker worker;
  std::mutex scene_mutex;
  scene latest = base;
  std::atomic<bool> done{false}, reloading{true};
  std::atomic<long> reads{0}, bad{0}, reloads{0}, predicted{0}, measured{0};

  // The designer's frame loop: snapshots to the screen and, when new, to the analysis worker.
  std::thread designer([&] {
    std::uint64_t last_gen = 0, last_spp = 0;
    std::shared_ptr<const ui::predicted_plots> last_predicted;
    std::shared_ptr<const ui::measured_plots> last_measured;
    while (!done) {
      const render_snapshot s = session.snapshot();
      if (s.rgb && s.rgb->size() != std::size_t(s.width) * s.height * 3) ++bad;
      if (s.rgb && (s.generation != last_gen || s.spp != last_spp)) {
        std::lock_guard lock(scene_mutex);
        worker.submit_render(s, latest);
        last_gen = s.generation;
        last_spp = s.spp;
      }
      if (auto p = worker.predicted(); p != last_predicted) ++predicted, last_predicted = p;
      if (auto m = worker.measured(); m != last_measured) ++measured, last_measured = m;
      ++reads;
    }
  });
  // Someone saving a new version of the source image again and again.
  std::thread saver([&] {
    for (int i = 0; reloading; ++i) {
      write_image(source_image, stripes(1 + i % 4), {});
      ++reloads;
      std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
  });

  pcg32 rng(2024, 7);
  scene last = base;
  // At least the given number of edits, and on until the worker has published three analyses of
  // scenes (each takes seconds under ThreadSanitizer) and three of renders, so that it ran beside
  // the edits.
  int i = 0;
  for (; i < edits || ((predicted < 3 || measured < 3) && i < 1000 * edits); ++i) {
    scene s = base;
    s.sheet().pose.pitch_deg = 40 * rng.next_double();
    set_floating_distance(s, 150 + 150 * rng.next_double());
    s.source.pose.center_mm[0] = 10 * (rng.next_double() - 0.5);
    s.half_mirror.reflectance = 0.2 + 0.5 * rng.next_double();
    s.half_mirror.transmittance = 1.0 - s.half_mirror.reflectance;
    if (rng.next_double() < 0.3) {
      s.sheet().model.type = "sinc_shift";
      set_model_value(s.sheet().model, "a_per_mm", 1 + 5 * rng.next_double());
    }
    const std::uint64_t gen = session.edit(s);
    {
      std::lock_guard lock(scene_mutex);
      latest = s;
    }
    if (i % 50 == 0) worker.submit_scene(s, gen, {});
    last = s;
    const double r = rng.next_double();
    if (r < 0.02)
      session.set_paused(true);
    else if (r < 0.04)
      session.set_paused(false);
    else if (r < 0.05)
      session.set_target_spp(1 + rng.next_u32() % 16);
    else if (r < 0.06)
      session.set_target_spp(1 << 20);
    else if (r < 0.20)
      std::this_thread::sleep_for(std::chrono::microseconds(rng.next_u32() % 400));  // let waves run
    // The last fifth of the edits see one, final source image.
    if (i == edits * 4 / 5) {
      reloading = false;
      saver.join();
    }
    // Now and then the hand rests: the worker finishes the scene and turns to the render. Long
    // enough for a loaded machine (ctest runs other tests beside this one), where the worker's
    // lower priority can stretch a scene's analysis well beyond its few seconds here alone.
    if (i % 2000 == 1999) {
      const long before = measured;
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
      while (measured == before && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (i % 1000 == 0) std::fprintf(stderr, "%d edits\n", i);
  }
  if (saver.joinable()) {
    reloading = false;
    saver.join();
  }
  session.set_paused(false);
  session.set_target_spp(8);
  const std::uint64_t gen = session.edit(last);
  const render_snapshot final_snap = session.wait_for(gen, 8);
  done = true;
  designer.join();
  worker.wait_idle();
  session.stop();

  render_session fresh(last, {.threads = 1, .target_spp = 8});
  const render_snapshot reference = fresh.wait_for(0, 8);
  const bool same = final_snap.rgb && reference.rgb && *final_snap.rgb == *reference.rgb;
  std::printf(
      "session: %d edits, %ld snapshot reads (%ld bad), %ld source-image replacements, %ld scene and %ld render "
      "analyses published; final image %s a fresh render\n",
      i, reads.load(), bad.load(), reloads.load(), predicted.load(), measured.load(), same ? "equals" : "DIFFERS from");
  return same && bad == 0;
}

bool fits_cancelled(int rounds) {
  pcg32 rng(77, 3);
  int cancelled = 0, finished = 0, wrong = 0;
  for (int i = 0; i < rounds; ++i) {
    ui::fit_job job(asset_dir() + "/fit_example");
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(rng.next_u32() % 400);
    while (std::chrono::steady_clock::now() < until && job.running()) {
      const analysis::fit_progress p = job.progress();
      if (!(p.fraction >= 0 && p.fraction <= 1)) ++wrong;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    job.cancel();
    while (job.running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (job.result())
      ++finished;
    else if (job.error() == "fit cancelled")
      ++cancelled;
    else
      ++wrong;
  }
  std::printf("fit: %d runs, %d cancelled, %d finished, %d wrong\n", rounds, cancelled, finished, wrong);
  return wrong == 0;
}

}  // namespace

int main(int argc, char** argv) {
  // TBB is not built with ThreadSanitizer, so its task hand-offs between its own threads look like
  // races in the loop code its headers inline; its loops run on the calling thread here, and the
  // project's own threads (session, worker, fit, designer) are what this checks.
  tbb::global_control one_tbb_thread(tbb::global_control::max_allowed_parallelism, 1);
  const int edits = argc > 1 ? std::atoi(argv[1]) : 10000;
  const int fits = argc > 2 ? std::atoi(argv[2]) : 20;
  const fs::path dir = fs::temp_directory_path() / ("airr-stress-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const bool session_ok = session_worker_and_reloads(edits, dir);
  const bool fits_ok = fits_cancelled(fits);
  fs::remove_all(dir);
  return session_ok && fits_ok ? 0 : 1;
}
