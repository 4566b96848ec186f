#include "airr/analysis/sheet_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/analysis/psf_mtf.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/retro_model.hpp"
#include "airr/optics/retro_sinc_shift.hpp"
#include "airr/optics/scene_json.hpp"

namespace airr::analysis {

using nlohmann::json;

namespace {

double hamming(double t) { return 0.54 + 0.46 * std::cos(std::numbers::pi * t); }

double reference_distance(const scene& setup) {
  const auto& m = setup.retroreflector.model;
  if (m.type == retro_model_type::sinc_shift && !m.preset.empty())
    return resolve_sinc_shift_params(m, setup.base_dir).reference_distance_mm;
  return m.reference_distance_mm.value_or(300.0);
}

// A measured curve resampled on the grid the simulation is compared on.
struct mtf_target {
  const mtf_measurement* m = nullptr;
  double f_max = 1.0;
  std::vector<double> measured;  // at f_max * i / n, i = 1..n
  double mean = 0;
};

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto hi = std::size_t(std::upper_bound(x.begin(), x.end(), at) - x.begin());
  const double t = (at - x[hi - 1]) / (x[hi] - x[hi - 1]);
  return y[hi - 1] + t * (y[hi] - y[hi - 1]);
}

mtf_target make_target(const mtf_measurement& m, int n) {
  mtf_target t;
  t.m = &m;
  t.f_max = std::min(1.0, m.lp_per_mm.back());
  for (int i = 1; i <= n; ++i) t.measured.push_back(interpolate(m.lp_per_mm, m.mtf, t.f_max * i / n));
  for (double v : t.measured) t.mean += v;
  t.mean /= n;
  return t;
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

// Brent's minimiser (golden section with parabolic steps) of f on [lo, hi], starting from a
// known point x0 inside with value f0; stops when the bracket is 2 tol wide around the minimum.
template <class F>
std::pair<double, double> brent_minimum(F&& f, double lo, double hi, double x0, double f0, double tol) {
  constexpr double golden = 0.3819660112501051;
  double a = lo, b = hi, x = x0, w = x0, v = x0, fx = f0, fw = f0, fv = f0, d = 0, e = 0;
  for (int iter = 0; iter < 100; ++iter) {
    const double xm = 0.5 * (a + b), tol1 = tol, tol2 = 2 * tol1;
    if (std::abs(x - xm) <= tol2 - 0.5 * (b - a)) break;
    bool golden_step = true;
    if (std::abs(e) > tol1) {
      double r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      const double e_old = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * e_old) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = std::copysign(tol1, xm - x);
        golden_step = false;
      }
    }
    if (golden_step) {
      e = x >= xm ? a - x : b - x;
      d = golden * e;
    }
    const double u = std::abs(d) >= tol1 ? x + d : x + std::copysign(tol1, d);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return {x, fx};
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
  sheet_fitter(const fit_data& d, const fit_params& p, progress_meter& meter) : d_(d), p_(p), meter_(meter) {}

  psf_samples psf(double tilt, double distance, double a, double c) {
    const scene s = fit_scene(d_.setup, tilt, distance, a, c, 1.0);
    const auto model = make_retro_model(s.retroreflector.model, s.base_dir);
    psf_samples out = sample_psf(s, *model, {.samples = p_.psf_samples, .seed = p_.seed});
    ++simulations_;
    meter_.add(1);
    return out;
  }

  std::vector<double> simulate(const mtf_target& t, double a, double c) {
    const psf_samples ps = psf(t.m->tilt_deg, t.m->floating_distance_mm, a, c);
    const int n = int(t.measured.size());
    auto curve = measured_like_mtf(ps, {.max_lp_per_mm = t.f_max, .points = n + 1, .pixel_mm = t.m->pixel_mm},
                                   t.m->window_half_width_mm, t.m->along_y);
    curve.mtf.erase(curve.mtf.begin());  // f = 0
    return curve.mtf;
  }

  struct a_fit {
    double a = 0, loss = 0, loss_minus = 0, loss_plus = 0;
    int evaluations = 0;
    bool minimum_checked = false, at_bracket_end = false;
  };

  double a_loss(const mtf_target& t, double a, double c) { return mse(simulate(t, a, c), t.measured); }

  // The minimum holds when the loss at a (1 -+ 2%) is not lower.
  void check_minimum(const mtf_target& t, double c, a_fit& r) {
    r.loss_minus = a_loss(t, r.a * 0.98, c);
    r.loss_plus = a_loss(t, r.a * 1.02, c);
    r.evaluations += 2;
    r.minimum_checked = r.loss_minus >= r.loss && r.loss_plus >= r.loss;
  }

  // Without a guess: a scan of log a over the whole bracket picks the neighbourhood. With one
  // (a nearby solution): steps downhill from it until the loss rises on both sides.
  a_fit fit_a(const mtf_target& t, double c, std::optional<double> guess = std::nullopt, bool check = true) {
    a_fit r;
    auto loss = [&](double log_a) {
      ++r.evaluations;
      return a_loss(t, std::exp(log_a), c);
    };
    const double lo = std::log(p_.a_min_per_mm), hi = std::log(p_.a_max_per_mm);
    double left = lo, right = hi, x0 = 0, f0 = 0;
    if (!guess) {
      const int n = std::max(3, p_.a_scan_points);
      const double step = (hi - lo) / (n - 1);
      f0 = 1e300;
      for (int k = 0; k < n; ++k) {
        const double l = loss(lo + k * step);
        if (l < f0) x0 = lo + k * step, f0 = l;
      }
      left = std::max(lo, x0 - step), right = std::min(hi, x0 + step);
    } else {
      x0 = std::clamp(std::log(*guess), lo, hi);
      f0 = loss(x0);
      double step = 0.05;
      left = std::max(lo, x0 - step), right = std::min(hi, x0 + step);
      double f_left = left < x0 ? loss(left) : f0, f_right = right > x0 ? loss(right) : f0;
      while (f_left < f0 || f_right < f0) {
        step *= 2;
        if (f_left < f_right) {
          right = x0, f_right = f0, x0 = left, f0 = f_left;
          left = std::max(lo, x0 - step);
          if (left == x0) break;
          f_left = loss(left);
        } else {
          left = x0, f_left = f0, x0 = right, f0 = f_right;
          right = std::min(hi, x0 + step);
          if (right == x0) break;
          f_right = loss(right);
        }
      }
    }
    const auto [x, fx] = brent_minimum(loss, left, right, x0, f0, p_.a_tolerance);
    r.a = std::exp(x);
    r.loss = fx;
    if (check) check_minimum(t, c, r);
    r.at_bracket_end = x - lo < 2 * p_.a_tolerance || hi - x < 2 * p_.a_tolerance;
    return r;
  }

  // Mean MTF of each distance entry with a(0) and c, and their slope against D.
  std::pair<std::vector<double>, double> distance_means(const std::vector<mtf_target>& ts, double a0, double c) {
    std::vector<double> d, m;
    for (const auto& t : ts) {
      d.push_back(t.m->floating_distance_mm);
      m.push_back(mean_of(simulate(t, a0, c)));
    }
    return {m, least_squares_slope(d, m)};
  }

  struct c_root {
    double c = 0;                        // the end of the final bracket with the smaller mismatch
    double lo = 0, hi = 0, g_lo = 0, g_hi = 0;  // the final bracket and the mismatch at its ends
    int evaluations = 0;
    std::string bound;  // "lower" or "upper" when the root lies outside [0, c_max] and c is clamped
  };

  // The root of g on [0, c_max] (g rises with c: a larger corner blurs independently of D and
  // flattens the slope of mean MTF against D) by Illinois regula falsi, down to a bracket
  // c_tolerance wide.
  template <class G>
  c_root find_c(G&& g) {
    c_root r;
    r.g_lo = r.g_hi = g(0.0);
    r.evaluations = 1;
    if (r.g_lo >= 0) {
      r.bound = "lower";  // even without a shift the simulated slope is no steeper than measured
      return r;
    }
    r.hi = p_.c_max_mm;
    r.g_hi = g(r.hi);
    ++r.evaluations;
    if (r.g_hi <= 0) {
      r.bound = "upper";
      r.c = r.lo = r.hi;
      r.g_lo = r.g_hi;
      return r;
    }
    int side = 0;
    double f_lo = r.g_lo, f_hi = r.g_hi;  // the end values regula falsi uses, halved when stale
    while (r.evaluations < 60 && r.hi - r.lo > p_.c_tolerance_mm) {
      double c = (r.lo * f_hi - r.hi * f_lo) / (f_hi - f_lo);
      if (!(c > r.lo && c < r.hi)) c = 0.5 * (r.lo + r.hi);
      const double gc = g(c);
      ++r.evaluations;
      if (gc > 0) {
        r.hi = c, r.g_hi = f_hi = gc;
        if (side == -1) f_lo /= 2;
        side = -1;
      } else {
        r.lo = c, r.g_lo = f_lo = gc;
        if (side == 1) f_hi /= 2;
        side = 1;
      }
    }
    r.c = std::abs(r.g_lo) <= std::abs(r.g_hi) ? r.lo : r.hi;
    return r;
  }

  // c with a(0) refitted at every trial c: the fixed point that alternating the two fits seeks.
  // Returns the root and a(0)'s fit at every trial c.
  std::pair<c_root, std::map<double, a_fit>> c_with_a0_refitted(const mtf_target& t0, const std::vector<mtf_target>& ts,
                                                                double slope_real, json& history) {
    std::map<double, a_fit> fits;
    std::optional<double> a0;
    const c_root r = find_c([&](double c) {
      const a_fit f = fit_a(t0, c, a0, false);
      fits[c] = f;
      a0 = f.a;
      const double sl = distance_means(ts, f.a, c).second;
      history.push_back({{"c_mm", c}, {"a0_per_mm", f.a}, {"slope_simulated_per_mm", sl}});
      return sl - slope_real;
    });
    return {r, std::move(fits)};
  }

  std::uint64_t simulations() const { return simulations_; }

 private:
  const fit_data& d_;
  const fit_params& p_;
  progress_meter& meter_;
  std::uint64_t simulations_ = 0;
};

json measurement_json(const mtf_measurement& m, const mtf_target& t) {
  return {{"file", m.file},
          {"kind", m.kind},
          {"tilt_deg", m.tilt_deg},
          {"floating_distance_mm", m.floating_distance_mm},
          {"pixel_mm", m.pixel_mm},
          {"lsf_window_half_width_mm", m.window_half_width_mm},
          {"axis", m.along_y ? "y" : "x"},
          {"compared_up_to_lp_per_mm", t.f_max},
          {"measured_mean_mtf", t.mean}};
}

}  // namespace

scene fit_scene(const scene& setup, double tilt_deg, double floating_distance_mm, double a_per_mm, double c_mm, double mu) {
  scene s = setup;
  s.retroreflector.tilt_deg = tilt_deg;
  s.floating_distance_mm = floating_distance_mm;
  auto& m = s.retroreflector.model;
  m.reference_distance_mm = reference_distance(setup);
  m.type = retro_model_type::sinc_shift;
  m.preset.clear();
  m.a_per_mm = a_per_mm;
  m.c_mm = c_mm;
  m.mu = mu;
  return s;
}

psf_mtf_curve measured_like_mtf(const psf_samples& psf, const psf_mtf_params& params, double window_half_width_mm,
                                bool along_y) {
  auto axis = [&](std::size_t i) { return along_y ? psf.offset_mm[i].y : psf.offset_mm[i].x; };
  double centre = 0;
  if (window_half_width_mm > 0) {
    // The measurement centres its window on the edge, the LSF's windowed centroid.
    for (int iter = 0; iter < 8; ++iter) {
      double sw = 0, sx = 0;
      for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
        const double t = (axis(i) - centre) / window_half_width_mm;
        if (std::abs(t) >= 1) continue;
        sw += psf.weight[i] * hamming(t);
        sx += psf.weight[i] * hamming(t) * axis(i);
      }
      if (sw > 0) centre = sx / sw;
    }
  }
  // psf_mtf's estimator on its frequency grid, with the phase advanced by a recurrence: one sine
  // and cosine per sample instead of one per sample and frequency (the fit evaluates it often).
  const int n = std::max(1, params.points);
  const double df = params.max_lp_per_mm / std::max(1, n - 1);
  std::vector<double> re(std::size_t(n), 0.0), im(std::size_t(n), 0.0);
  double total = 0;
  for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
    const double x = axis(i) - centre;
    double w = psf.weight[i];
    if (window_half_width_mm > 0) {
      const double t = x / window_half_width_mm;
      if (std::abs(t) >= 1) continue;
      w *= hamming(t);
    }
    total += w;
    const double phase = -2.0 * std::numbers::pi * df * x, step_re = std::cos(phase), step_im = std::sin(phase);
    double z_re = w, z_im = 0;
    for (int k = 0; k < n; ++k) {
      re[std::size_t(k)] += z_re;
      im[std::size_t(k)] += z_im;
      const double next_re = z_re * step_re - z_im * step_im;
      z_im = z_re * step_im + z_im * step_re;
      z_re = next_re;
    }
  }
  psf_mtf_curve curve;
  for (int k = 0; k < n; ++k) {
    const double f = df * k;
    double m = total > 0 ? std::hypot(re[std::size_t(k)], im[std::size_t(k)]) / total : 0.0;
    if (params.pixel_mm > 0 && f > 0) {
      const double u = std::numbers::pi * f * params.pixel_mm;
      m *= std::abs(std::sin(u) / u);
    }
    curve.lp_per_mm.push_back(f);
    curve.mtf.push_back(m);
  }
  return curve;
}

cv::Mat white_square_image(const scene& s, const psf_samples& psf, double width_mm, double height_mm) {
  const part_frame src = source_frame(s), hm = half_mirror_frame(s);
  const pinhole_camera cam = make_camera(s);
  auto aerial = [&](const glm::dvec3& p) { return p - 2.0 * glm::dot(p - hm.center, hm.n) * hm.n; };
  // The square's ideal image, a rectangle in pixel coordinates (x right, y down).
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double su : {-0.5, 0.5}) {
    for (double sv : {-0.5, 0.5}) {
      const glm::dvec2 q = camera_project(cam, aerial(src.center + su * width_mm * src.u + sv * height_mm * src.v));
      x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
    }
  }
  // An offset on the aerial-image plane (x right, y up) moves the image by this many pixels.
  const glm::dvec3 c = aerial(src.center);
  const glm::dvec2 p0 = camera_project(cam, c);
  const glm::dvec2 jx = camera_project(cam, c + glm::dvec3(1, 0, 0)) - p0, jy = camera_project(cam, c + glm::dvec3(0, 1, 0)) - p0;

  // Splat the PSF bilinearly onto integer pixel shifts that can bring light into the frame.
  const int W = cam.width, H = cam.height;
  const int mx0 = int(std::floor(-x1)) - 1, mx1 = int(std::ceil(W - x0)) + 1;
  const int my0 = int(std::floor(-y1)) - 1, my1 = int(std::ceil(H - y0)) + 1;
  const int kw = mx1 - mx0 + 1, kh = my1 - my0 + 1;
  std::vector<double> kernel(std::size_t(kw) * kh, 0.0);
  for (std::size_t k = 0; k < psf.offset_mm.size(); ++k) {
    const glm::dvec2 shift = psf.offset_mm[k].x * jx + psf.offset_mm[k].y * jy;
    const double fx = std::floor(shift.x), fy = std::floor(shift.y), tx = shift.x - fx, ty = shift.y - fy;
    if (fx < mx0 || fx + 1 > mx1 || fy < my0 || fy + 1 > my1) continue;
    const std::size_t ix = std::size_t(int(fx) - mx0), iy = std::size_t(int(fy) - my0);
    kernel[iy * kw + ix] += psf.weight[k] * (1 - tx) * (1 - ty);
    kernel[iy * kw + ix + 1] += psf.weight[k] * tx * (1 - ty);
    kernel[(iy + 1) * kw + ix] += psf.weight[k] * (1 - tx) * ty;
    kernel[(iy + 1) * kw + ix + 1] += psf.weight[k] * tx * ty;
  }
  // Fraction of pixel [p, p + 1) the shifted rectangle covers along one axis.
  auto overlap = [](double p, double lo, double hi) { return std::max(0.0, std::min(p + 1, hi) - std::max(p, lo)); };
  // The square's coverage is separable: sum over shifts of K(mx, my) ox(i - mx) oy(j - my).
  std::vector<double> rows(std::size_t(kh) * W, 0.0);  // [my][i]
  for (int my = 0; my < kh; ++my) {
    const double* krow = kernel.data() + std::size_t(my) * kw;
    if (std::all_of(krow, krow + kw, [](double v) { return v == 0; })) continue;
    for (int i = 0; i < W; ++i) {
      double sum = 0;
      for (int mx = 0; mx < kw; ++mx) {
        if (krow[mx] != 0) sum += krow[mx] * overlap(i - (mx + mx0), x0, x1);
      }
      rows[std::size_t(my) * W + i] = sum;
    }
  }
  cv::Mat img(H, W, CV_64FC1, cv::Scalar(0));
  const double scale = psf.launched ? s.source.intensity / double(psf.launched) : 0.0;
  for (int j = 0; j < H; ++j) {
    double* out = img.ptr<double>(j);
    for (int my = 0; my < kh; ++my) {
      const double oy = overlap(j - (my + my0), y0, y1);
      if (oy == 0) continue;
      const double* r = rows.data() + std::size_t(my) * W;
      for (int i = 0; i < W; ++i) out[i] += oy * r[i];
    }
    for (int i = 0; i < W; ++i) out[i] *= scale;
  }
  return img;
}

fit_result fit_sheet(const fit_data& d, const fit_params& p, const fit_progress_callback& progress) {
  if (p.psf_samples < 100) throw input_error("fit: psf_samples must be at least 100");
  if (!(p.a_min_per_mm > 0) || !(p.a_max_per_mm > p.a_min_per_mm)) throw input_error("fit: the a bracket must satisfy 0 < a_min < a_max");
  if (p.frequencies < 2) throw input_error("fit: frequencies must be at least 2");

  std::vector<mtf_target> tilts, distances;
  for (const auto& m : d.tilt_series) tilts.push_back(make_target(m, p.frequencies));
  for (const auto& m : d.distance_series) distances.push_back(make_target(m, p.frequencies));
  const mtf_target& tilt0 = tilts.front();

  // Planned simulations: a scan, a warm a fit about 20, the coupled c root about 15 trials.
  const double a_units = 20.0;
  const double after_alternation = double(tilts.size() - 1) * a_units + double(d.white_squares.size());
  progress_meter meter(progress, p.a_scan_points + 15 * (a_units + double(distances.size())) + after_alternation);
  sheet_fitter fitter(d, p, meter);

  std::vector<double> d_values, d_means;
  for (const auto& t : distances) d_values.push_back(t.m->floating_distance_mm), d_means.push_back(t.mean);
  const double slope_real = least_squares_slope(d_values, d_means);

  // Alternating "a(0) given c" and "c given a(0)" oscillates when the corner's blur dominates
  // (RF-Ay: c jumps between 0 and 2.9 mm, as a(0) reacts about ten times as strongly as c). So c
  // is the root of the slope mismatch with a(0) refitted at every trial c, the alternation's
  // fixed point; its final bracket shows how far that point is pinned down.
  meter.set_stage("c with a(0) refitted at each trial c");
  json history = json::array();
  const auto [coupled, a0_fits] = fitter.c_with_a0_refitted(tilt0, distances, slope_real, history);
  const double c = coupled.c;
  auto a0 = a0_fits.at(c);
  fitter.check_minimum(tilt0, c, a0);
  const bool converged = coupled.bound.empty() && coupled.hi - coupled.lo <= p.alternation_tolerance * c;
  meter.plan_remaining(double(distances.size()) + after_alternation);
  const auto [sim_means, slope_sim] = fitter.distance_means(distances, a0.a, c);

  // Each further tilt starts from its neighbour's a (a varies smoothly with tilt).
  std::vector<sheet_fitter::a_fit> a_fits = {a0};
  for (std::size_t i = 1; i < tilts.size(); ++i) {
    meter.set_stage("a at tilt " + deg_text(tilts[i].m->tilt_deg) + " deg");
    a_fits.push_back(fitter.fit_a(tilts[i], c, a_fits.back().a));
  }
  auto a_at = [&](double tilt) {
    for (std::size_t i = 0; i < tilts.size(); ++i)
      if (tilts[i].m->tilt_deg == tilt) return a_fits[i].a;
    throw input_error(d.fit_json + ": no a fitted at tilt " + deg_text(tilt));
  };

  json mu_report = json::array();
  std::vector<double> mu_theta, mu_values;
  for (const auto& w : d.white_squares) {
    meter.set_stage("mu at tilt " + deg_text(w.tilt_deg) + " deg");
    const scene s = fit_scene(d.setup, w.tilt_deg, w.floating_distance_mm, a_at(w.tilt_deg), c, 1.0);
    const psf_samples ps = fitter.psf(w.tilt_deg, w.floating_distance_mm, a_at(w.tilt_deg), c);
    const cv::Mat unit = white_square_image(s, ps, w.width_mm, w.height_mm);
    const double sim_sim = unit.dot(unit), real_sim = w.luminance.dot(unit);
    if (!(sim_sim > 0))
      throw input_error(w.origin + ": the model shows no light of the white square in the camera's frame");
    const double raw = real_sim / sim_sim, mu = std::clamp(raw, 0.0, 1.0);
    const cv::Mat residual = w.luminance - mu * unit;
    const double loss = residual.dot(residual) / double(residual.total());
    mu_theta.push_back(w.tilt_deg);
    mu_values.push_back(mu);
    mu_report.push_back({{"tilt_deg", w.tilt_deg},
                         {"mu", mu},
                         {"loss", loss},
                         {"relative_rms", std::sqrt(loss) / std::max(1e-300, cv::mean(w.luminance)[0])},
                         {"unclamped_mu", raw},
                         {"clamped", raw != mu},
                         {"evaluations", 1},
                         {"brightness_at_mu_1", ps.brightness()},
                         {"image", w.file},
                         {"floating_distance_mm", w.floating_distance_mm},
                         {"square_mm", {w.width_mm, w.height_mm}}});
  }
  meter.finish();

  sheet_preset preset;
  preset.name = d.name;
  preset.reference_distance_mm = reference_distance(d.setup);
  preset.c_mm = c;
  json a_report = json::array();
  for (std::size_t i = 0; i < tilts.size(); ++i) {
    const auto& f = a_fits[i];
    preset.theta_deg.push_back(tilts[i].m->tilt_deg);
    preset.a_per_mm.push_back(f.a);
    json entry = {{"tilt_deg", tilts[i].m->tilt_deg},
                  {"a_per_mm", f.a},
                  {"loss", f.loss},
                  {"evaluations", f.evaluations},
                  {"loss_at_a_minus_2_percent", f.loss_minus},
                  {"loss_at_a_plus_2_percent", f.loss_plus},
                  {"minimum_checked", f.minimum_checked},
                  {"at_bracket_end", f.at_bracket_end},
                  {"input", measurement_json(*tilts[i].m, tilts[i])}};
    if (preset.theta_deg.size() == 1) entry["note"] = "refitted at every trial c; this is the fit at the final c";
    a_report.push_back(entry);
  }
  std::string mu_note;
  if (!mu_values.empty()) {
    for (double t : preset.theta_deg) preset.mu.push_back(interpolate_by_angle(mu_theta, mu_values, t));
    if (mu_values.size() < preset.theta_deg.size()) mu_note = "tilts without a white square take mu interpolated linearly over tilt";
  } else {
    preset.mu = {d.mu.value_or(1.0)};
    mu_note = std::string("mu not fitted: no white_squares in the data; mu = ") + std::to_string(preset.mu[0]) +
              (d.mu ? " from fit.json" : " (default)");
  }

  json means = json::array();
  for (std::size_t i = 0; i < distances.size(); ++i)
    means.push_back({{"floating_distance_mm", distances[i].m->floating_distance_mm},
                     {"measured_mean_mtf", distances[i].mean},
                     {"simulated_mean_mtf", sim_means[i]},
                     {"input", measurement_json(*distances[i].m, distances[i])}});
  json c_report = {{"c_mm", c},
                   {"loss", (slope_sim - slope_real) * (slope_sim - slope_real)},
                   {"loss_definition", "(d_sim - d_real)^2, d = slope of mean MTF over (0, 1] lp/mm against D, per mm"},
                   {"slope_measured_per_mm", slope_real},
                   {"slope_simulated_per_mm", slope_sim},
                   {"a0_per_mm", a0.a},
                   {"method", "root of d_sim(c) = d_real in [0, c_max], a(0) refitted at every trial c"},
                   {"trial_c_values", coupled.evaluations},
                   {"bound", coupled.bound},
                   {"bracket_mm", {coupled.lo, coupled.hi}},
                   {"a0_at_bracket_ends_per_mm", {a0_fits.count(coupled.lo) ? a0_fits.at(coupled.lo).a : a0.a,
                                                  a0_fits.count(coupled.hi) ? a0_fits.at(coupled.hi).a : a0.a}},
                   {"slope_mismatch_at_bracket_ends_per_mm", {coupled.g_lo, coupled.g_hi}},
                   {"converged", converged},
                   {"convergence", "the bracket holding the sign change of d_sim - d_real is narrower than " +
                                       std::to_string(p.alternation_tolerance) + " c"},
                   {"history", history},
                   {"mean_mtf", means}};

  json report = {{"data_dir", d.dir},
                 {"fit_json", d.fit_json},
                 {"setup_scene", d.scene_path},
                 {"files", d.files()},
                 {"settings",
                  {{"psf_samples", p.psf_samples},
                   {"seed", p.seed},
                   {"frequencies", p.frequencies},
                   {"a_bracket_per_mm", {p.a_min_per_mm, p.a_max_per_mm}},
                   {"a_scan_points", p.a_scan_points},
                   {"a_tolerance", p.a_tolerance},
                   {"c_bracket_mm", {0.0, p.c_max_mm}},
                   {"c_tolerance_mm", p.c_tolerance_mm},
                   {"alternation_tolerance", p.alternation_tolerance},
                   {"method",
                    "a: log-a scan (first fit) or downhill steps from the neighbouring tilt's a, then Brent's minimum "
                    "of the MTF MSE over (0, 1] lp/mm, checked at a (1 -+ 2%); "
                    "c: Illinois root of d_sim(c) = d_real on [0, c_max] with a(0) refitted at every trial c (the "
                    "fixed point of alternating the two fits); "
                    "mu: closed-form least squares on the white-square images, clamped to [0, 1]; "
                    "simulation: model PSF (no tracer), common random numbers"}}},
                 {"a", a_report},
                 {"c", c_report},
                 {"mu", mu_report},
                 {"simulations", fitter.simulations()},
                 {"seconds", meter.seconds()}};
  if (!mu_note.empty()) report["mu_note"] = mu_note;

  preset.provenance = {{"source", "airr fit"},
                       {"name", d.name},
                       {"note", d.note},
                       {"data_dir", d.dir},
                       {"files", d.files()},
                       {"setup_scene", scene_to_json(d.setup)},
                       {"fit", report}};
  return {std::move(preset), std::move(report)};
}

}  // namespace airr::analysis
