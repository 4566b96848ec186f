#include "bench/designer_latency_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "airr/render/render_session.hpp"

designer_latencies measure_designer_latencies(const airr::scene& s, int edits) {
  airr::render_session session(
      s, {.background_priority = true, .first_look = true, .quick_model_image = true, .components = true});
  session.wait_for(0, 1);
  designer_latencies d;
  d.edits = edits;
  airr::scene edited = s;
  for (int i = 0; i < edits; ++i) {
    edited.sheet().pose.pitch_deg = (i % 2) ? s.sheet().pose.pitch_deg : s.sheet().pose.pitch_deg + 5.0;
    const std::uint64_t gen = session.edit(edited);
    bool first_look = false, model_image = false, preview = false;
    // Called under the session's lock at every publication: each estimate's own edit_seconds.
    session.wait_until([&](const airr::render_snapshot& snap) {
      if (snap.generation != gen) return false;
      if (snap.model_image && snap.first_look && !first_look) {
        first_look = true;
        d.first_look_ms.push_back(1e3 * snap.edit_seconds);
      }
      if (snap.model_image && !snap.first_look && !model_image) {
        model_image = true;
        d.model_image_ms.push_back(1e3 * snap.edit_seconds);
      }
      if (snap.preview && !snap.model_image && !preview) {
        preview = true;
        d.traced_preview_ms.push_back(1e3 * snap.edit_seconds);
      }
      if (snap.spp >= 1) d.traced_ms.push_back(1e3 * snap.edit_seconds);
      return snap.spp >= 1 || !snap.error.empty();
    });
  }
  session.stop();
  return d;
}

static void print_line(const char* what, std::vector<double> ms, int edits) {
  if (ms.empty()) {
    std::printf("               %s: never shown in %d edits\n", what, edits);
    return;
  }
  std::sort(ms.begin(), ms.end());
  std::printf("               median %.1f ms, min %.1f ms, max %.1f ms (%s; shown after %zu of %d edits)\n",
              ms[ms.size() / 2], ms.front(), ms.back(), what, ms.size(), edits);
}

void print_designer_latencies(const designer_latencies& d) {
  std::printf("designer's session (first look, model image, quick control variate beside the tracer):\n");
  print_line("to the model image's first look", d.first_look_ms, d.edits);
  print_line("to the model image at view quality", d.model_image_ms, d.edits);
  print_line("to the tracer's preview", d.traced_preview_ms, d.edits);
  print_line("to the first full-resolution traced image", d.traced_ms, d.edits);
}
