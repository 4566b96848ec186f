#pragma once
// airr bench --drag: what a designer sees while dragging the sheet's tilt. A recorded drag (edits
// of the tilt in equal steps at a fixed rate, then rest) is replayed into a session set up as the
// designer's; every frame of a 60 Hz display is compared with the converged image of the layout
// the designer has at that moment (stale images count against it), and after the drag the time
// to 2% and 1% is measured. Converged images are renders whose own noise (from their halves) is
// taken out of each comparison.
#include <cstdint>
#include <string>

struct drag_bench_options {
  std::string scene_path;
  int size = 0;  // 0: the scene's
  int edits = 30;
  double rate_hz = 10;    // edits per second
  double step_deg = 0.5;  // tilt change per edit
  double rest_s = 20;     // after the drag
  std::uint64_t reference_spp = 64;
  std::uint64_t final_reference_spp = 512;  // the last layout's, for the 1% figure
  std::string csv;                          // per-frame rows, when not empty
};

// Prints the frames' summary per edit, the worst frame, and the times after the drag; throws
// input_error naming what failed.
void run_drag_bench(const drag_bench_options& o);
