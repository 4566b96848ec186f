#include "airr/design/tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include <tbb/parallel_for.h>

#include "airr/core/cancel.hpp"
#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

namespace {

// The layout with each tolerance's value moved by its offset; empty when it is no valid layout.
std::optional<design_evaluation> evaluate_offsets(const design_spec& spec, const scene& nominal,
                                                  const std::vector<double>& nominal_values,
                                                  const std::vector<double>& offsets) {
  std::vector<scene_override> set;
  for (std::size_t t = 0; t < spec.tolerances.size(); ++t)
    if (offsets[t] != 0) set.push_back(design_override(spec.tolerances[t].key, nominal_values[t] + offsets[t]));
  try {
    scene s = with_overrides(nominal, set, spec.path);
    validate_scene(s, spec.path);
    check_layout(s, spec.path);
    return evaluate_design(spec, s);
  } catch (const input_error&) {
    return std::nullopt;
  }
}

// Layouts evaluated as shared items: each one's metrics travel as numbers (valid, objectives,
// constraints); its score and broken constraints follow from them.
template <class Evaluate>
std::vector<std::optional<design_evaluation>> shared_evaluations(const design_spec& spec, const item_share& share,
                                                                 std::size_t n, const Evaluate& evaluate) {
  const std::size_t objectives = spec.objectives.size(), width = 1 + objectives + spec.constraints.size();
  const std::vector<double> values = share(n, width, [&](std::size_t i, double* out) {
    const std::optional<design_evaluation> e = evaluate(i);
    out[0] = e ? 1 : 0;
    if (!e) return;
    std::copy(e->objective_values.begin(), e->objective_values.end(), out + 1);
    std::copy(e->constraint_values.begin(), e->constraint_values.end(), out + 1 + objectives);
  });
  std::vector<std::optional<design_evaluation>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = values.data() + i * width;
    if (v[0] == 0) continue;
    design_evaluation e;
    e.objective_values.assign(v + 1, v + 1 + objectives);
    e.constraint_values.assign(v + 1 + objectives, v + width);
    e.score = design_score(spec, e.objective_values);
    e.broken = broken_constraints(spec, e.constraint_values);
    out[i] = std::move(e);
  }
  return out;
}

std::vector<double> metric_values(const design_evaluation& e) {
  std::vector<double> v = e.objective_values;
  v.insert(v.end(), e.constraint_values.begin(), e.constraint_values.end());
  return v;
}

double percentile(std::vector<double> sorted, double p) {
  if (sorted.empty()) return NAN;
  const double at = p * double(sorted.size() - 1);
  const std::size_t i = std::size_t(at);
  const double f = at - double(i);
  return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}

}  // namespace

std::string layout_failures(const tolerance_layout& l) {
  if (!l.valid) return "no valid layout";
  std::string out;
  for (const std::string& b : l.broken) out += (out.empty() ? "" : "; ") + b;
  return out;
}

std::vector<std::size_t> worst_layouts(const tolerance_result& r, std::size_t count) {
  std::vector<std::size_t> order(r.layouts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto badness = [&](std::size_t i) {
    const tolerance_layout& l = r.layouts[i];
    return std::tuple(!l.valid, l.broken.size(), -l.score);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return badness(a) > badness(b); });
  order.resize(std::min(count, order.size()));
  return order;
}

tolerance_result run_tolerance(const design_spec& spec, const scene& nominal,
                               const std::function<void(int, int)>& progress, const std::atomic<bool>* cancel,
                               const item_share& share) {
  if (spec.tolerances.empty()) throw input_error(spec.path + ": tolerances: none given");
  // Shared among an MPI job's ranks, a batch is large enough to keep many ranks busy between
  // exchanges.
  const std::size_t batch_size = share ? 1024 : 16;
  check_design_expressions(spec);
  check_design_memory(spec, "tolerance", batch_size);
  std::vector<double> nominal_values, sizes;
  for (const design_tolerance& t : spec.tolerances) {
    nominal_values.push_back(scene_number(nominal, t.key));
    sizes.push_back(t.percent ? t.size / 100 * std::abs(nominal_values.back()) : t.size);
  }
  tolerance_result out;
  for (const design_objective& o : spec.objectives)
    out.metrics.push_back({std::string(to_string(o.metric)) + " (objective)", {}, 0, 0, 0, 0, 0});
  for (const design_constraint& c : spec.constraints)
    out.metrics.push_back({std::string(to_string(c.metric)) + " (constraint)", {}, 0, 0, 0, 0, 0});
  const int samples = spec.tolerance.samples, total = samples + 2 * int(spec.tolerances.size());
  // Every layout's offsets are drawn first, in order, so the samples are the same on any number of
  // threads; the layouts are then evaluated in parallel, a batch at a time (cancel and progress
  // between batches), and taken in order.
  std::vector<std::vector<double>> draws(std::size_t(samples), std::vector<double>(spec.tolerances.size()));
  pcg32 rng(spec.tolerance.seed, 11);
  for (std::vector<double>& offsets : draws) {
    for (std::size_t t = 0; t < spec.tolerances.size(); ++t) {
      const double u1 = rng.next_double(), u2 = rng.next_double();
      offsets[t] = spec.tolerances[t].uniform ? sizes[t] * (2 * u1 - 1)
                                              : sizes[t] * std::sqrt(-2 * std::log(1 - u1)) * std::cos(2 * pi * u2);
    }
  }
  auto evaluate_all = [&](const std::vector<std::vector<double>>& offsets, std::size_t first, std::size_t end) {
    auto evaluate = [&](std::size_t i) { return evaluate_offsets(spec, nominal, nominal_values, offsets[first + i]); };
    if (share) return shared_evaluations(spec, share, end - first, evaluate);
    std::vector<std::optional<design_evaluation>> e(end - first);
    tbb::parallel_for(std::size_t(0), end - first, [&](std::size_t i) { e[i] = evaluate(i); });
    return e;
  };
  int passing = 0;
  for (std::size_t first = 0; first < draws.size(); first += batch_size) {
    if (cancel_requested(cancel)) {
      out.cancelled = true;
      break;
    }
    const std::size_t end = std::min(draws.size(), first + batch_size);
    const std::vector<std::optional<design_evaluation>> evaluated = evaluate_all(draws, first, end);
    for (std::size_t i = 0; i < evaluated.size(); ++i) {
      const std::optional<design_evaluation>& e = evaluated[i];
      tolerance_layout& layout = out.layouts.emplace_back();
      for (std::size_t t = 0; t < spec.tolerances.size(); ++t)
        layout.values.push_back(nominal_values[t] + draws[first + i][t]);
      ++out.samples;
      if (!e) {
        ++out.invalid;
        continue;
      }
      const std::vector<double> v = metric_values(*e);
      layout.valid = true;
      layout.metrics = v;
      layout.score = e->score;
      layout.broken = e->broken;
      for (std::size_t m = 0; m < v.size(); ++m) out.metrics[m].values.push_back(v[m]);
      if (e->feasible()) ++passing;
    }
    if (progress) progress(int(end), total);
  }
  out.yield = out.samples > 0 ? double(passing) / out.samples : 0;
  for (metric_distribution& m : out.metrics) {
    if (m.values.empty()) continue;
    double sum = 0, sum2 = 0;
    for (double v : m.values) sum += v;
    m.mean = sum / double(m.values.size());
    for (double v : m.values) sum2 += (v - m.mean) * (v - m.mean);
    m.sd = m.values.size() > 1 ? std::sqrt(sum2 / double(m.values.size() - 1)) : 0;
    std::vector<double> sorted = m.values;
    std::sort(sorted.begin(), sorted.end());
    m.p5 = percentile(sorted, 0.05);
    m.p50 = percentile(sorted, 0.5);
    m.p95 = percentile(sorted, 0.95);
  }
  if (!out.cancelled) {
    // Each tolerance alone at +size and -size.
    std::vector<std::vector<double>> alone;
    for (std::size_t t = 0; t < spec.tolerances.size(); ++t) {
      for (double sign : {1.0, -1.0}) {
        alone.emplace_back(spec.tolerances.size(), 0.0);
        alone.back()[t] = sign * sizes[t];
      }
    }
    const auto e = evaluate_all(alone, 0, alone.size());
    for (std::size_t t = 0; t < spec.tolerances.size(); ++t) {
      const auto &a = e[2 * t], &b = e[2 * t + 1];
      std::vector<double> change(out.metrics.size(), NAN);
      if (a && b) {
        const std::vector<double> va = metric_values(*a), vb = metric_values(*b);
        for (std::size_t m = 0; m < change.size(); ++m) change[m] = 0.5 * (va[m] - vb[m]);
      }
      out.sensitivity.push_back(change);
    }
    if (progress) progress(total, total);
  }
  return out;
}

histogram_steps metric_histogram(const metric_distribution& d, int bins) {
  histogram_steps h;
  if (d.values.empty() || bins < 1) return h;
  const auto [lo_it, hi_it] = std::minmax_element(d.values.begin(), d.values.end());
  const double lo = *lo_it, hi = std::max(*hi_it, lo + 1e-12);
  std::vector<double> count(std::size_t(bins), 0.0);
  for (double v : d.values) count[std::size_t(std::clamp(int((v - lo) / (hi - lo) * bins), 0, bins - 1))] += 1;
  for (int b = 0; b < bins; ++b) {
    for (const double edge : {lo + (hi - lo) * b / bins, lo + (hi - lo) * (b + 1) / bins}) {
      h.x.push_back(edge);
      h.y.push_back(count[std::size_t(b)]);
    }
  }
  return h;
}

}  // namespace airr
