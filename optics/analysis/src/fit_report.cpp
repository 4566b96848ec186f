#include "airr/analysis/fit_report.hpp"

namespace airr::analysis {

using nlohmann::json;

namespace {

json pair_json(const std::array<double, 2>& v) { return json::array({v[0], v[1]}); }

json input_json(const fit_input& in) {
  return {{"file", in.file},
          {"kind", in.kind},
          {"tilt_deg", in.tilt_deg},
          {"floating_distance_mm", in.floating_distance_mm},
          {"pixel_mm", in.pixel_mm},
          {"lsf_window_half_width_mm", in.lsf_window_half_width_mm},
          {"axis", in.along_y ? "y" : "x"},
          {"compared_up_to_lp_per_mm", in.compared_up_to_lp_per_mm},
          {"measured_mean_mtf", in.measured_mean_mtf}};
}

json settings_json(const fit_params& p) {
  return {{"psf_samples", p.psf_samples},
          {"seed", p.seed},
          {"frequencies", p.frequencies},
          {"a_bracket_per_mm", {p.a_min_per_mm, p.a_max_per_mm}},
          {"a_scan_points", p.a_scan_points},
          {"a_tolerance", p.a_tolerance},
          {"c_bracket_mm", {0.0, p.c_max_mm}},
          {"c_tolerance_mm", p.c_tolerance_mm},
          {"alternation_tolerance", p.alternation_tolerance},
          {"shift_index", p.shift_index},
          {"a_matches", p.a_by_mean_mtf ? "mean_mtf" : "curve"},
          {"method",
           "a: log-a scan (first fit) or downhill steps from the neighbouring tilt's a, then Brent's minimum "
           "of the MTF MSE over (0, 1] lp/mm, checked at a (1 -+ 2%); "
           "c: Illinois root of d_sim(c) = d_real on [0, c_max] with a(0) refitted at every trial c (the "
           "fixed point of alternating the two fits); "
           "mu: closed-form least squares on the white-square images, clamped to [0, 1]; "
           "simulation: model PSF (no tracer), common random numbers"}};
}

json a_json(const fit_a_entry& a) {
  json j = {{"tilt_deg", a.tilt_deg},
            {"a_per_mm", a.a_per_mm},
            {"loss", a.loss},
            {"evaluations", a.evaluations},
            {"loss_at_a_minus_2_percent", a.loss_at_a_minus_2_percent},
            {"loss_at_a_plus_2_percent", a.loss_at_a_plus_2_percent},
            {"minimum_checked", a.minimum_checked},
            {"at_bracket_end", a.at_bracket_end},
            {"input", input_json(a.input)}};
  if (a.note) j["note"] = *a.note;
  return j;
}

json c_json(const fit_c_entry& c, double alternation_tolerance) {
  json history = json::array(), means = json::array();
  for (const auto& t : c.history)
    history.push_back(
        {{"c_mm", t.c_mm}, {"a0_per_mm", t.a0_per_mm}, {"slope_simulated_per_mm", t.slope_simulated_per_mm}});
  for (const auto& m : c.mean_mtf)
    means.push_back({{"floating_distance_mm", m.floating_distance_mm},
                     {"measured_mean_mtf", m.measured_mean_mtf},
                     {"simulated_mean_mtf", m.simulated_mean_mtf},
                     {"input", input_json(m.input)}});
  return {{"c_mm", c.c_mm},
          {"loss", c.loss},
          {"loss_definition", "(d_sim - d_real)^2, d = slope of mean MTF over (0, 1] lp/mm against D, per mm"},
          {"slope_measured_per_mm", c.slope_measured_per_mm},
          {"slope_simulated_per_mm", c.slope_simulated_per_mm},
          {"a0_per_mm", c.a0_per_mm},
          {"method", "root of d_sim(c) = d_real in [0, c_max], a(0) refitted at every trial c"},
          {"trial_c_values", c.trial_c_values},
          {"bound", to_string(c.bound)},
          {"bracket_mm", pair_json(c.bracket_mm)},
          {"a0_at_bracket_ends_per_mm", pair_json(c.a0_at_bracket_ends_per_mm)},
          {"slope_mismatch_at_bracket_ends_per_mm", pair_json(c.slope_mismatch_at_bracket_ends_per_mm)},
          {"converged", c.converged},
          {"convergence", "the bracket holding the sign change of d_sim - d_real is narrower than " +
                              std::to_string(alternation_tolerance) + " c"},
          {"history", history},
          {"mean_mtf", means}};
}

json mu_json(const fit_mu_entry& m) {
  return {{"tilt_deg", m.tilt_deg},
          {"mu", m.mu},
          {"loss", m.loss},
          {"relative_rms", m.relative_rms},
          {"unclamped_mu", m.unclamped_mu},
          {"clamped", m.clamped},
          {"evaluations", m.evaluations},
          {"brightness_at_mu_1", m.brightness_at_mu_1},
          {"image", m.image},
          {"floating_distance_mm", m.floating_distance_mm},
          {"square_mm", pair_json(m.square_mm)}};
}

}  // namespace

json to_json(const fit_report& r) {
  json a = json::array(), mu = json::array();
  for (const auto& e : r.a) a.push_back(a_json(e));
  for (const auto& e : r.mu) mu.push_back(mu_json(e));
  json j = {{"data_dir", r.data_dir},
            {"fit_json", r.fit_json},
            {"setup_scene", r.setup_scene},
            {"files", r.files},
            {"settings", settings_json(r.settings)},
            {"a", a},
            {"c", c_json(r.c, r.settings.alternation_tolerance)},
            {"mu", mu},
            {"simulations", r.simulations},
            {"seconds", r.seconds}};
  if (r.mu_note) j["mu_note"] = *r.mu_note;
  return j;
}

}  // namespace airr::analysis
