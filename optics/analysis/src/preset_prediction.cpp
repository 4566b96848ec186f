#include "airr/analysis/preset_prediction.hpp"

#include <cmath>
#include <filesystem>
#include <optional>

#include "airr/analysis/fit_data.hpp"
#include "airr/analysis/fit_simulation.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_model.hpp"

namespace airr::analysis {

namespace {

// The shares of the whole prediction the sheet's shift table and the synthesis take (both simulate
// the explicit sheet); the fit takes the rest.
constexpr double table_share = 0.1, synthesis_share = 0.3;

fit_progress_callback scaled(const fit_progress_callback& progress, double from, double to) {
  if (!progress) return {};
  return [=](const fit_progress& f) {
    return progress({.stage = f.stage, .fraction = from + (to - from) * f.fraction, .eta_seconds = 0});
  };
}

// Mean MTF over (0, 1] lp/mm of a PSF as the bench measures it (its pixel, its LSF window).
double bench_mean_mtf(const psf_samples& psf, double lsf_window_mm) {
  const int n = 200;
  const auto c =
      measured_like_mtf(psf, {.max_lp_per_mm = 1.0, .points = n + 1, .pixel_mm = 0.25}, lsf_window_mm, false);
  double sum = 0;
  for (int i = 1; i <= n; ++i) sum += c.mtf[i];
  return sum / n;
}

// A prism or tile sheet's light meets its cube corners inside the plate: the preset reads the
// shift table at the angle inside (preset.hpp). Other sheets keep the table at the angle outside.
double shift_index_of(const sheet_description& sheet) {
  const bool plate = sheet.model.type == "prism_sheet" || sheet.model.type == "tile_sheet";
  return plate ? read_model_values(sheet.model).number("index") : 1.0;
}

// The traced Mueller matrices at the preset's tilts; none when the sheet does not change the light's
// polarization (a model that does not follow it).
std::vector<mueller> polarization_at(const traced_sheet& traced, const std::vector<double>& tilts) {
  bool changes = false;
  for (const mueller& m : traced.polarization)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 4; ++k) changes |= std::abs(m.m[i][k] - (i == k ? 1.0 : 0.0)) > 1e-9;
  std::vector<mueller> out;
  if (!changes) return out;
  for (double t : tilts) out.push_back(interpolate_by_angle(traced.shifts.theta_deg, traced.polarization, t));
  return out;
}

}  // namespace

fit_result predict_preset(const sheet_description& sheet, const scene& bench, const std::string& data_dir,
                          const prediction_params& p, const fit_progress_callback& progress, const item_share& share) {
  // The sheet's shift table (when it names a cube edge) and Mueller matrix, from the same samples.
  const std::optional<double> unit = sheet_shift_unit_mm(sheet.model, sheet.base_dir);
  if (progress && !progress({.stage = "the sheet's shift table and polarization", .fraction = 0}))
    throw fit_cancelled();
  const traced_sheet traced =
      trace_sheet_shift_table(sheet.model, sheet.base_dir, bench, unit.value_or(1.0), p.shifts, share);
  std::string table;
  if (p.sheet_shifts && unit) {
    std::filesystem::create_directories(data_dir);
    table = (std::filesystem::path(data_dir) / "shift_table.json").string();
    save_shift_table(traced.shifts, table);
  }
  synthesise_fit_data(data_dir, bench,
                      {.model = sheet.model,
                       .base_dir = sheet.base_dir,
                       .name = sheet.name,
                       .note = "the sheet " + sheet.name + " (" + sheet.model.type + ") on the simulated bench",
                       .shift_table = table},
                      p.synthesis, scaled(progress, table_share, synthesis_share), share);
  fit_params fit = p.fit;
  // The sheet's own table is tabulated at the angle outside; the shipped one is read inside the plate.
  fit.shift_index = table.empty() ? shift_index_of(sheet) : 1.0;
  // The sinc-shift lobe takes the shape of a shift-dominated sheet's curve, not of a diffraction
  // cut-off (docs/models.md): a predicted preset matches the mean MTF, the designer's figure.
  fit.a_by_mean_mtf = true;
  fit_result r = fit_sheet(load_fit_data(data_dir), fit, scaled(progress, synthesis_share, 1), share);
  r.preset.name = sheet.name;
  r.preset.polarization = polarization_at(traced, r.preset.theta_deg);
  r.preset.provenance["source"] = "airr predict-preset";
  r.preset.provenance["sheet"] = {
      {"name", sheet.name},
      {"note", sheet.note},
      {"model", model_values_to_json(sheet.model, find_retro_model_kind(sheet.model.type).fields)}};
  r.preset.provenance["lsf_window_mm"] = p.synthesis.lsf_window_mm;
  return r;
}

std::vector<std::vector<prediction_agreement>> compare_predictions(const sheet_description& sheet,
                                                                   const std::vector<sheet_preset>& presets,
                                                                   const scene& bench,
                                                                   const std::vector<double>& tilts_deg,
                                                                   const synthesis_params& p, const item_share& share) {
  scene setup = bench;
  for (auto& s : setup.retroreflectors) {
    s.model = sheet.model;
    rebase_model_paths(s.model, sheet.base_dir, setup.base_dir);
  }
  const psf_params pp{.samples = p.samples, .seed = p.seed};
  // Per tilt, the explicit sheet's mean MTF and brightness, then each preset's.
  const std::size_t stride = 2 + 2 * presets.size();
  const std::vector<double> v = run_items(share, tilts_deg.size(), stride, [&](std::size_t i, double* o) {
    const double t = tilts_deg[i];
    const scene truth = measurement_layout(setup, t, 150);
    const psf_samples a = sample_psf(truth, make_sheet_models(truth), pp);
    o[0] = bench_mean_mtf(a, p.lsf_window_mm);
    o[1] = a.brightness();
    for (std::size_t k = 0; k < presets.size(); ++k) {
      const sheet_preset& preset = presets[k];
      const scene model =
          fit_scene(setup, t, 150, interpolate_by_angle(preset.theta_deg, preset.a_per_mm, t), preset.c_mm,
                    interpolate_by_angle(preset.theta_deg, preset.mu, t), preset.shift_index, preset.shift_table);
      const psf_samples b = sample_psf(model, make_sheet_models(model), pp);
      o[2 + 2 * k] = bench_mean_mtf(b, p.lsf_window_mm);
      o[3 + 2 * k] = b.brightness();
    }
  });
  std::vector<std::vector<prediction_agreement>> out(presets.size());
  for (std::size_t k = 0; k < presets.size(); ++k) {
    for (std::size_t i = 0; i < tilts_deg.size(); ++i) {
      const double* row = v.data() + stride * i;
      out[k].push_back({.tilt_deg = tilts_deg[i],
                        .explicit_mean_mtf = row[0],
                        .predicted_mean_mtf = row[2 + 2 * k],
                        .explicit_brightness = row[1],
                        .predicted_brightness = row[3 + 2 * k]});
    }
  }
  return out;
}

std::vector<prediction_agreement> compare_prediction(const sheet_description& sheet, const sheet_preset& preset,
                                                     const scene& bench, const std::vector<double>& tilts_deg,
                                                     const synthesis_params& p, const item_share& share) {
  return compare_predictions(sheet, {preset}, bench, tilts_deg, p, share).front();
}

}  // namespace airr::analysis
