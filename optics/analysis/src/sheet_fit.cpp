#include "airr/analysis/sheet_fit.hpp"

#include "airr/core/interpolate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "airr/analysis/minimise.hpp"
#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/models/retro_sinc_shift.hpp"

namespace airr::analysis {

namespace {

// The setup's R when its sheet is a sinc-shift sheet; otherwise 300 mm, the R of every shipped preset.
double reference_distance(const scene& setup) {
  const auto& m = setup.sheet().model;
  if (m.type != "sinc_shift") return 300.0;
  return resolve_sinc_shift_params(m, {.base_dir = setup.base_dir}).reference_distance_mm;
}

// A measured curve resampled on the grid the simulation is compared on.
struct mtf_target {
  const mtf_measurement* m = nullptr;
  double f_max = 1.0;
  std::vector<double> measured;  // at f_max * i / n, i = 1..n
  double mean = 0;
};

mtf_target make_target(const mtf_measurement& m, int n) {
  mtf_target t;
  t.m = &m;
  t.f_max = std::min(1.0, m.lp_per_mm.back());
  for (int i = 1; i <= n; ++i) t.measured.push_back(interpolate_linear(m.lp_per_mm, m.mtf, t.f_max * i / n));
  for (double v : t.measured) t.mean += v;
  t.mean /= n;
  return t;
}

fit_input input_of(const mtf_target& t) {
  const mtf_measurement& m = *t.m;
  return {.file = m.file,
          .kind = m.kind,
          .tilt_deg = m.tilt_deg,
          .floating_distance_mm = m.floating_distance_mm,
          .pixel_mm = m.pixel_mm,
          .lsf_window_half_width_mm = m.window_half_width_mm,
          .along_y = m.along_y,
          .compared_up_to_lp_per_mm = t.f_max,
          .measured_mean_mtf = t.mean};
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

double mse(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return a.empty() ? 0.0 : s / double(a.size());
}

// Counts simulations, reports progress and throws fit_cancelled when asked to stop.
class progress_meter {
 public:
  progress_meter(const fit_progress_callback& cb, double planned) : cb_(cb), planned_(planned) {}
  void set_stage(std::string stage) {
    stage_ = std::move(stage);
    report();
  }
  void add(double units) {
    done_ += units;
    report();
  }
  // Re-estimates the work still to come.
  void plan_remaining(double units) { planned_ = done_ + units; }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  void finish() {
    done_ = planned_;
    report();
  }

 private:
  void report() {
    if (!cb_) return;
    fraction_ = std::max(fraction_, std::min(1.0, planned_ > 0 ? done_ / planned_ : 1.0));
    const double t = seconds();
    const double eta = fraction_ > 0 ? t * (1 - fraction_) / fraction_ : 0.0;
    if (!cb_({stage_, fraction_, eta})) throw fit_cancelled();
  }
  const fit_progress_callback& cb_;
  double planned_ = 1, done_ = 0, fraction_ = 0;
  std::string stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

std::string deg_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", t);
  return buf;
}

class sheet_fitter {
 public:
  sheet_fitter(const fit_data& d, const fit_params& p, progress_meter& meter, const item_share& share)
      : d_(d), p_(p), meter_(meter), share_(share) {}

  // Independent simulations, one per item: side by side through the share (an MPI job's ranks),
  // else here one after another. Each counts as one simulation wherever it ran.
  std::vector<double> items(std::size_t n, std::size_t width, const item_compute& compute) {
    const std::vector<double> out = run_items(share_, n, width, compute, [&](std::size_t) { count(); });
    if (share_)
      for (std::size_t i = 0; i < n; ++i) count();
    return out;
  }

  // The simulated curve, uncounted (safe to call from several items at once).
  std::vector<double> simulate(const mtf_target& t, double a, double c) const {
    const psf_samples ps = sample(t.m->tilt_deg, t.m->floating_distance_mm, a, c);
    const int n = int(t.measured.size());
    auto curve = measured_like_mtf(ps, {.max_lp_per_mm = t.f_max, .points = n + 1, .pixel_mm = t.m->pixel_mm},
                                   t.m->window_half_width_mm, t.m->along_y);
    curve.mtf.erase(curve.mtf.begin());  // f = 0
    return curve.mtf;
  }

  // The curve's mean squared difference, or with a_by_mean_mtf the squared difference of the means.
  double a_loss(const mtf_target& t, double a, double c) const {
    const std::vector<double> sim = simulate(t, a, c);
    if (!p_.a_by_mean_mtf) return mse(sim, t.measured);
    const double d = mean_of(sim) - t.mean;
    return d * d;
  }

  // The loss at each a, as items.
  std::vector<double> a_losses(const mtf_target& t, const std::vector<double>& as, double c) {
    return items(as.size(), 1, [&](std::size_t i, double* out) { *out = a_loss(t, as[i], c); });
  }

  // The minimum holds when the loss at a (1 -+ 2%) is not lower.
  void check_minimum(const mtf_target& t, double c, fit_a_entry& r) {
    const std::vector<double> l = a_losses(t, {r.a_per_mm * 0.98, r.a_per_mm * 1.02}, c);
    r.loss_at_a_minus_2_percent = l[0];
    r.loss_at_a_plus_2_percent = l[1];
    r.evaluations += 2;
    r.minimum_checked = r.loss_at_a_minus_2_percent >= r.loss && r.loss_at_a_plus_2_percent >= r.loss;
  }

  // Brent's minimum over log a. Without a guess: a scan of log a over the whole bracket picks the
  // neighbourhood. With one (a nearby solution): steps downhill from it until the loss rises on
  // both sides.
  fit_a_entry fit_a(const mtf_target& t, double c, std::optional<double> guess = std::nullopt, bool check = true) {
    const auto loss = [&](double log_a) {
      count();
      return a_loss(t, std::exp(log_a), c);
    };
    const auto scan = [&](const std::vector<double>& log_as) {
      std::vector<double> as;
      for (double x : log_as) as.push_back(std::exp(x));
      return a_losses(t, as, c);
    };
    const double lo = std::log(p_.a_min_per_mm), hi = std::log(p_.a_max_per_mm);
    const min_bracket b = guess ? downhill_bracket(loss, lo, hi, std::log(*guess), 0.05)
                                : grid_scan_batch(scan, lo, hi, p_.a_scan_points);
    const minimum m = brent_minimum(loss, b, p_.a_tolerance);
    fit_a_entry r;
    r.tilt_deg = t.m->tilt_deg;
    r.a_per_mm = std::exp(m.x);
    r.loss = m.fx;
    r.evaluations = b.evaluations + m.evaluations;
    r.input = input_of(t);
    if (check) check_minimum(t, c, r);
    r.at_bracket_end = m.x - lo < 2 * p_.a_tolerance || hi - m.x < 2 * p_.a_tolerance;
    return r;
  }

  // Mean MTF of each distance entry with a(0) and c, and their slope against D.
  std::pair<std::vector<double>, double> distance_means(const std::vector<mtf_target>& ts, double a0, double c) {
    std::vector<double> d;
    for (const auto& t : ts) d.push_back(t.m->floating_distance_mm);
    const std::vector<double> m =
        items(ts.size(), 1, [&](std::size_t i, double* out) { *out = mean_of(simulate(ts[i], a0, c)); });
    return {m, least_squares_slope(d, m)};
  }

  // c with a(0) refitted at every trial c: the fixed point that alternating the two fits seeks. The
  // root of the slope mismatch on [0, c_max], which rises with c (a larger corner blurs
  // independently of D and flattens the slope of mean MTF against D). Returns the root and a(0)'s
  // fit at every trial c; `history` gets every trial.
  std::pair<root_result, std::map<double, fit_a_entry>> c_with_a0_refitted(const mtf_target& t0,
                                                                           const std::vector<mtf_target>& ts,
                                                                           double slope_real,
                                                                           std::vector<fit_c_trial>& history) {
    std::map<double, fit_a_entry> fits;
    std::optional<double> a0;
    const auto mismatch = [&](double c) {
      const fit_a_entry f = fit_a(t0, c, a0, false);
      fits[c] = f;
      a0 = f.a_per_mm;
      const double sl = distance_means(ts, f.a_per_mm, c).second;
      history.push_back({.c_mm = c, .a0_per_mm = f.a_per_mm, .slope_simulated_per_mm = sl});
      return sl - slope_real;
    };
    const root_result r = rising_root(mismatch, 0.0, p_.c_max_mm, p_.c_tolerance_mm, 60);
    return {r, std::move(fits)};
  }

  std::uint64_t simulations() const { return simulations_; }

  // One simulation, uncounted (safe to call from several items at once).
  psf_samples sample(double tilt, double distance, double a, double c) const {
    const scene s = fit_scene(d_.setup, tilt, distance, a, c, 1.0, p_.shift_index, d_.shift_table);
    return sample_psf(s, make_sheet_models(s), {.samples = p_.psf_samples, .seed = p_.seed});
  }

 private:
  void count() {
    ++simulations_;
    meter_.add(1);
  }

  const fit_data& d_;
  const fit_params& p_;
  progress_meter& meter_;
  const item_share& share_;
  std::uint64_t simulations_ = 0;
};

}  // namespace

scene fit_scene(const scene& setup, double tilt_deg, double floating_distance_mm, double a_per_mm, double c_mm,
                double mu, double shift_index, const std::string& shift_table) {
  scene s = measurement_layout(setup, tilt_deg, floating_distance_mm);
  const double r_mm = reference_distance(setup);
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    auto& m = s.retroreflectors[i].model;
    m = {.type = "sinc_shift", .values = {}};
    // The setup's angle lookup carries over (at the image centre, where the fit's PSF is taken,
    // both lookups see the chief ray's angle).
    const retro_model_params& was = setup.retroreflectors[i].model;
    if (was.type == "sinc_shift") set_model_value(m, "lookup", read_model_values(was).text("lookup"));
    set_model_value(m, "reference_distance_mm", r_mm);
    set_model_value(m, "a_per_mm", a_per_mm);
    set_model_value(m, "c_mm", c_mm);
    set_model_value(m, "mu", mu);
    if (shift_index != 1.0) set_model_value(m, "shift_index", shift_index);
    if (!shift_table.empty()) set_model_value(m, "shift_table", shift_table);
  }
  return s;
}

fit_result fit_sheet(const fit_data& d, const fit_params& p, const fit_progress_callback& progress,
                     const item_share& share) {
  if (p.psf_samples < 100) throw input_error("fit: psf_samples must be at least 100");
  if (!(p.a_min_per_mm > 0) || !(p.a_max_per_mm > p.a_min_per_mm))
    throw input_error("fit: the a bracket must satisfy 0 < a_min < a_max");
  if (p.frequencies < 2) throw input_error("fit: frequencies must be at least 2");

  std::vector<mtf_target> tilts, distances;
  for (const auto& m : d.tilt_series) tilts.push_back(make_target(m, p.frequencies));
  for (const auto& m : d.distance_series) distances.push_back(make_target(m, p.frequencies));
  const mtf_target& tilt0 = tilts.front();

  // Planned simulations: a scan, a warm a fit about 20, the coupled c root about 15 trials.
  const double a_units = 20.0;
  const double after_alternation = double(tilts.size() - 1) * a_units + double(d.white_squares.size());
  progress_meter meter(progress, p.a_scan_points + 15 * (a_units + double(distances.size())) + after_alternation);
  sheet_fitter fitter(d, p, meter, share);

  std::vector<double> d_values, d_means;
  for (const auto& t : distances) d_values.push_back(t.m->floating_distance_mm), d_means.push_back(t.mean);
  const double slope_real = least_squares_slope(d_values, d_means);

  fit_report report;
  report.data_dir = d.dir;
  report.fit_json = d.fit_json;
  report.setup_scene = d.scene_path;
  report.files = d.files();
  report.settings = p;

  // Alternating "a(0) given c" and "c given a(0)" oscillates when the corner's blur dominates
  // (RF-Ay: c jumps between 0 and 2.9 mm, as a(0) reacts about ten times as strongly as c). So c
  // is the root of the slope mismatch with a(0) refitted at every trial c, the alternation's
  // fixed point; its final bracket shows how far that point is pinned down.
  meter.set_stage("c with a(0) refitted at each trial c");
  fit_c_entry& cr = report.c;
  const auto [coupled, a0_fits] = fitter.c_with_a0_refitted(tilt0, distances, slope_real, cr.history);
  const double c = coupled.x;
  auto a0 = a0_fits.at(c);
  fitter.check_minimum(tilt0, c, a0);
  a0.note = "refitted at every trial c; this is the fit at the final c";
  meter.plan_remaining(double(distances.size()) + after_alternation);
  const auto [sim_means, slope_sim] = fitter.distance_means(distances, a0.a_per_mm, c);

  // Each further tilt starts from its neighbour's a (a varies smoothly with tilt).
  report.a = {a0};
  for (std::size_t i = 1; i < tilts.size(); ++i) {
    meter.set_stage("a at tilt " + deg_text(tilts[i].m->tilt_deg) + " deg");
    report.a.push_back(fitter.fit_a(tilts[i], c, report.a.back().a_per_mm));
  }
  auto a_at = [&](double tilt) {
    for (const auto& a : report.a)
      if (a.tilt_deg == tilt) return a.a_per_mm;
    throw input_error(d.fit_json + ": no a fitted at tilt " + deg_text(tilt));
  };

  // mu at each white square: the unclamped mu, the loss at the clamped mu and the brightness at mu 1.
  meter.set_stage("mu at the white squares' tilts");
  const std::vector<double> mu_fits = fitter.items(d.white_squares.size(), 3, [&](std::size_t i, double* out) {
    const auto& w = d.white_squares[i];
    const double a = a_at(w.tilt_deg);
    const scene s = fit_scene(d.setup, w.tilt_deg, w.floating_distance_mm, a, c, 1.0, p.shift_index, d.shift_table);
    const psf_samples ps = fitter.sample(w.tilt_deg, w.floating_distance_mm, a, c);
    const cv::Mat unit = white_square_image(s, ps, w.width_mm, w.height_mm);
    const double sim_sim = unit.dot(unit), real_sim = w.luminance.dot(unit);
    if (!(sim_sim > 0))
      throw input_error(w.origin + ": the model shows no light of the white square in the camera's frame");
    const double raw = real_sim / sim_sim;
    const cv::Mat residual = w.luminance - std::clamp(raw, 0.0, 1.0) * unit;
    out[0] = raw;
    out[1] = residual.dot(residual) / double(residual.total());
    out[2] = ps.brightness();
  });
  std::vector<double> mu_theta, mu_values;
  for (std::size_t i = 0; i < d.white_squares.size(); ++i) {
    const auto& w = d.white_squares[i];
    const double raw = mu_fits[3 * i], loss = mu_fits[3 * i + 1], mu = std::clamp(raw, 0.0, 1.0);
    mu_theta.push_back(w.tilt_deg);
    mu_values.push_back(mu);
    report.mu.push_back({.tilt_deg = w.tilt_deg,
                         .mu = mu,
                         .loss = loss,
                         .relative_rms = std::sqrt(loss) / std::max(1e-300, cv::mean(w.luminance)[0]),
                         .unclamped_mu = raw,
                         .clamped = raw != mu,
                         .evaluations = 1,
                         .brightness_at_mu_1 = mu_fits[3 * i + 2],
                         .image = w.file,
                         .floating_distance_mm = w.floating_distance_mm,
                         .square_mm = {w.width_mm, w.height_mm}});
  }
  meter.finish();

  sheet_preset preset;
  preset.name = d.name;
  preset.reference_distance_mm = reference_distance(d.setup);
  preset.c_mm = c;
  preset.shift_index = p.shift_index;
  preset.shift_table = d.shift_table;
  for (const auto& a : report.a) {
    preset.theta_deg.push_back(a.tilt_deg);
    preset.a_per_mm.push_back(a.a_per_mm);
  }
  if (!mu_values.empty()) {
    for (double t : preset.theta_deg) preset.mu.push_back(interpolate_by_angle(mu_theta, mu_values, t));
    if (mu_values.size() < preset.theta_deg.size())
      report.mu_note = "tilts without a white square take mu interpolated linearly over tilt";
  } else {
    preset.mu = {d.mu.value_or(1.0)};
    report.mu_note = std::string("mu not fitted: no white_squares in the data; mu = ") + std::to_string(preset.mu[0]) +
                     (d.mu ? " from fit.json" : " (default)");
  }

  for (std::size_t i = 0; i < distances.size(); ++i)
    cr.mean_mtf.push_back({.floating_distance_mm = distances[i].m->floating_distance_mm,
                           .measured_mean_mtf = distances[i].mean,
                           .simulated_mean_mtf = sim_means[i],
                           .input = input_of(distances[i])});
  // Named again: clang 14 cannot capture a structured binding in a lambda.
  const auto& fits = a0_fits;
  auto a0_at = [&](double trial_c) { return fits.count(trial_c) ? fits.at(trial_c).a_per_mm : a0.a_per_mm; };
  cr.c_mm = c;
  cr.loss = (slope_sim - slope_real) * (slope_sim - slope_real);
  cr.slope_measured_per_mm = slope_real;
  cr.slope_simulated_per_mm = slope_sim;
  cr.a0_per_mm = a0.a_per_mm;
  cr.trial_c_values = coupled.evaluations;
  cr.bound = coupled.bound;
  cr.bracket_mm = {coupled.lo, coupled.hi};
  cr.a0_at_bracket_ends_per_mm = {a0_at(coupled.lo), a0_at(coupled.hi)};
  cr.slope_mismatch_at_bracket_ends_per_mm = {coupled.g_lo, coupled.g_hi};
  cr.converged = coupled.bound == root_bound::none && coupled.hi - coupled.lo <= p.alternation_tolerance * c;
  report.simulations = fitter.simulations();
  report.seconds = meter.seconds();

  preset.provenance = {{"source", "airr fit"},  {"name", d.name},     {"note", d.note},
                       {"data_dir", d.dir},     {"files", d.files()}, {"setup_scene", scene_to_json(d.setup)},
                       {"fit", to_json(report)}};
  return {std::move(preset), std::move(report)};
}

}  // namespace airr::analysis
