// Stress test for the render session, meant for the ThreadSanitizer build: 10,000 random edits,
// pauses and target changes while another thread reads snapshots; afterwards the last layout's
// image must equal a fresh render of it, bit for bit. Exits non-zero on any mismatch.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "airr/optics/assets.hpp"
#include "airr/optics/random.hpp"
#include "airr/render/render_session.hpp"

using namespace airr;

int main(int argc, char** argv) {
  const int edits = argc > 1 ? std::atoi(argv[1]) : 10000;
  scene base;
  const std::string panel = asset_dir() + "/models/panel.gltf";
  base.source.mesh = base.half_mirror.mesh = base.sheet().mesh = panel;
  base.source.width_mm = base.source.height_mm = 20;
  base.observer.width = base.observer.height = 24;

  render_session session(base, {.threads = 2, .target_spp = 1 << 20, .max_wave_spp = 4});
  std::atomic<bool> done{false};
  std::atomic<long> reads{0}, bad{0};
  std::thread reader([&] {
    while (!done) {
      const render_snapshot s = session.snapshot();
      if (s.rgb && s.rgb->size() != std::size_t(s.width) * s.height * 3) ++bad;
      ++reads;
    }
  });

  pcg32 rng(2024, 7);
  scene last = base;
  for (int i = 0; i < edits; ++i) {
    scene s = base;
    s.sheet().pose.pitch_deg = 40 * rng.next_double();
    airr::set_floating_distance(s, 150 + 150 * rng.next_double());
    s.source.pose.center_mm[0] = 10 * (rng.next_double() - 0.5);
    s.half_mirror.reflectance = 0.2 + 0.5 * rng.next_double();
    s.half_mirror.transmittance = 1.0 - s.half_mirror.reflectance;
    if (rng.next_double() < 0.3) {
      s.sheet().model.type = "sinc_shift";
      airr::set_model_value(s.sheet().model, "a_per_mm", 1 + 5 * rng.next_double());
    }
    session.edit(s);
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
    if (i % 1000 == 0) std::fprintf(stderr, "%d edits\n", i);
  }
  session.set_paused(false);
  session.set_target_spp(8);
  const std::uint64_t gen = session.edit(last);
  const render_snapshot final_snap = session.wait_for(gen, 8);
  done = true;
  reader.join();
  session.stop();

  render_session fresh(last, {.threads = 1, .target_spp = 8});
  const render_snapshot reference = fresh.wait_for(0, 8);
  const bool same = final_snap.rgb && reference.rgb && *final_snap.rgb == *reference.rgb;
  std::printf("%d edits, %ld snapshot reads, %ld bad snapshots, final image %s a fresh render\n", edits, reads.load(),
              bad.load(), same ? "equals" : "DIFFERS from");
  return (same && bad == 0) ? 0 : 1;
}
