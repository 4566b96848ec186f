#pragma once
// A sheet's own shift distributions (shift_table.hpp), traced from its explicit model: at each
// tilt of the bench, the chief ray's incidence on the sheet, and the histogram of the exit-point
// shift of the light the sheet retroreflects there. The sinc-shift model reads the shipped corner
// cube's table, whose shift falls steeply between 35 and 40 deg; a real sheet's falls where its
// own geometry makes it (a hollow 1.16 mm prism sheet: between 32 and 35 deg), and a preset that
// reads the shipped table makes up the difference with a (a per mm jumping from 3 to 16 and back).
// The same samples give the sheet's Mueller matrix at each row: the mean over the retroreflected
// paths of each path's own (retro_sample::polarization), weighted by its throughput, which is the
// one matrix closest to them all in the least-squares sense; a preset carries it (preset.hpp).
#include <cstdint>
#include <optional>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/model_params.hpp"
#include "airr/models/polarization.hpp"
#include "airr/models/shift_table.hpp"

namespace airr::analysis {

struct sheet_shift_params {
  double step_deg = 1.0;  // rows at 0, step, ..., max_deg
  double max_deg = 45.0;
  std::uint64_t samples = 100000;  // per row
  std::uint64_t seed = 7;
  int bins = 150;
  double s_max = 1.5;  // in units of the sheet's cube edge, as the shipped table
};

// The length the sheet's shifts are counted in: its cube edge (a prism sheet's), which the fitted
// c then comes out near; empty for a sheet that names none (the shipped table then stands).
std::optional<double> sheet_shift_unit_mm(const retro_model_params& model, const std::string& base_dir);

struct traced_sheet {
  // Its retro_fraction: the weight retroreflected per entering sample, the sheet's losses included.
  shift_table shifts;
  std::vector<mueller> polarization;  // one per row, relative to the weight; identity for a model without
};

// The table at the incidence the chief ray of measurement_layout(bench, tilt, 150) has at each
// row's tilt, rows indexed by that tilt (the angle outside the sheet: shift_index 1), with the
// Mueller matrix there. Throws input_error for a sheet that retroreflects nothing at some row's
// tilt. Rows run as items through `share` when given.
traced_sheet trace_sheet_shift_table(const retro_model_params& model, const std::string& base_dir, const scene& bench,
                                     double unit_mm, const sheet_shift_params& p, const item_share& share = {});

}  // namespace airr::analysis
