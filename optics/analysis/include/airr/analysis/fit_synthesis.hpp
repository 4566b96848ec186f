#pragma once
// A fit data directory (fit_data.hpp) whose measurements are simulated from a known sheet model
// by the model PSF: MTF curves per tilt (at D 150 mm) and per floating distance (at tilt 0), with a
// pixel's aperture and optionally an LSF window, and white-square images per tilt. `airr fit
// --synthesise` writes one from a preset, `airr predict-preset` from a sheet's geometry.
#include <cstdint>
#include <string>

#include "airr/analysis/sheet_fit.hpp"
#include "airr/core/item_share.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/model_params.hpp"

namespace airr::analysis {

struct synthesis_params {
  std::uint64_t samples = 1000000;  // per PSF
  std::uint64_t seed = 7;
  // Half-width (mm) of the Hamming window the simulated measurement puts on its LSFs (its region
  // of interest: light landing farther away, e.g. a sheet's stray reflections, is not measured);
  // 0: none.
  double lsf_window_mm = 0;
};

// The measured sheet: its model (files relative to base_dir), named in fit.json's name and note.
struct synthesis_truth {
  retro_model_params model;
  std::string base_dir;
  std::string name;
  std::string note;
  // The sheet's own shift distributions (a file: a preset's, or sheet_shift_table.hpp's), copied
  // into the data directory as shift_table.json and named in fit.json, so the fit simulates with
  // them. Empty: none (the shipped corner cube's).
  std::string shift_table;
};

// The bench a synthesis measures with: `setup`'s layout (its other sheets the first's mirror
// images; empty: the default layout) with panels for parts, no props, a uniform display and a
// 40 x 40 camera of 0.4 mm pixels framing a 10 mm white square.
scene synthesis_bench(scene setup);
// The same from a scene file (its sheets checked as the fit's setups are); empty: the default.
scene synthesis_bench_file(const std::string& setup_path);

// Writes fit.json, setup.json (the bench), 17 MTF CSVs and 10 white-square EXRs into dir (made if
// missing), each file atomically. Every sheet of the bench takes truth's model. `progress` may
// be empty; returning false cancels (fit_cancelled). Throws input_error for a model that fails.
// The 17 measurements run as items through `share` (an MPI job's ranks) when given.
void synthesise_fit_data(const std::string& dir, const scene& bench, const synthesis_truth& truth,
                         const synthesis_params& p, const fit_progress_callback& progress,
                         const item_share& share = {});

}  // namespace airr::analysis
