#include "airr/design/search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <nlopt.hpp>

#include "airr/core/error.hpp"

namespace airr {

namespace {

// A layout that is no layout breaks each constraint by this much.
constexpr double invalid_violation = 1e6;

// Constraint k's violation at t, signed as NLopt wants it: negative inside.
double signed_violation(const design_spec& spec, const design_trial& t, std::size_t k) {
  if (!t.valid) return invalid_violation;
  const design_constraint& c = spec.constraints[k];
  const double v = t.evaluation.constraint_values[k];
  double g = -std::numeric_limits<double>::infinity();
  if (c.min) g = std::max(g, *c.min - v);
  if (c.max) g = std::max(g, v - *c.max);
  return g;
}

double total_violation(const design_spec& spec, const design_trial& t) {
  double sum = 0;
  for (std::size_t k = 0; k < spec.constraints.size(); ++k) sum += std::max(0.0, signed_violation(spec, t, k));
  return t.valid ? sum : invalid_violation;
}

// Feasible beats infeasible; among feasible the higher score, among infeasible the smaller
// violation.
bool better_trial(const design_spec& spec, const design_trial& t, const design_trial& b) {
  const bool tf = t.valid && t.evaluation.feasible(), bf = b.valid && b.evaluation.feasible();
  if (tf != bf) return tf;
  return tf ? t.evaluation.score > b.evaluation.score : total_violation(spec, t) < total_violation(spec, b);
}

class search_state {
 public:
  // `done_before` of `total` evaluations were made by earlier searches (a Pareto front's), which
  // `stage` names.
  search_state(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
               const std::atomic<bool>* cancel, int done_before, int total, std::string stage)
      : spec_(spec),
        progress_(progress),
        cancel_(cancel),
        start_(std::chrono::steady_clock::now()),
        done_before_(done_before),
        total_(total),
        stage_(std::move(stage)) {}

  // The trial at x, evaluated once (NLopt asks for the objective and each constraint at one x).
  const design_trial& at(const std::vector<double>& x) {
    const auto found = seen_.find(x);
    if (found != seen_.end()) return result.trials[found->second];
    if (cancel_ && cancel_->load()) {
      result.cancelled = true;
      throw nlopt::forced_stop();
    }
    design_trial t;
    t.index = int(result.trials.size());
    t.phase = phase;
    t.x = x;
    try {
      t.evaluation = evaluate_design(spec_, design_scene(spec_, x));
    } catch (const input_error& e) {
      t.valid = false;
      t.problem = one_line(e.what());
      t.evaluation.score = -std::numeric_limits<double>::infinity();
      t.evaluation.broken.push_back("no valid layout: " + t.problem);
    }
    seen_[x] = result.trials.size();
    result.trials.push_back(t);
    consider(result.trials.back());
    if (progress_) {
      design_progress p;
      p.done = done_before_ + int(result.trials.size());
      p.total = total_;
      p.stage = stage_.empty() ? phase : stage_ + " " + phase;
      p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      p.have_best = result.best >= 0;
      if (p.have_best) {
        p.best_score = result.best_trial().evaluation.score;
        p.best_feasible = result.best_trial().evaluation.feasible();
        p.best_x = result.best_trial().x;
      }
      progress_(p);
    }
    return result.trials.back();
  }

  double violation(const design_trial& t, std::size_t k) const { return signed_violation(spec_, t, k); }

  std::string phase = "global";
  design_result result;

 private:
  void consider(const design_trial& t) {
    if (result.best < 0 || better_trial(spec_, t, result.best_trial())) result.best = t.index;
  }

  const design_spec& spec_;
  const std::function<void(const design_progress&)>& progress_;
  const std::atomic<bool>* cancel_;
  std::chrono::steady_clock::time_point start_;
  int done_before_ = 0, total_ = 0;
  std::string stage_;
  std::map<std::vector<double>, std::size_t> seen_;
};

struct constraint_slot {
  search_state* state;
  std::size_t k;
};

double objective(const std::vector<double>& x, std::vector<double>&, void* data) {
  const design_trial& t = static_cast<search_state*>(data)->at(x);
  // A metric that is not a number here (nothing seen) scores as no layout.
  return t.valid && std::isfinite(t.evaluation.score) ? -t.evaluation.score : invalid_violation;
}

double constraint(const std::vector<double>& x, std::vector<double>&, void* data) {
  const auto* slot = static_cast<constraint_slot*>(data);
  return slot->state->violation(slot->state->at(x), slot->k);
}

void run(nlopt::opt& opt, std::vector<double>& x) {
  double f = 0;
  try {
    opt.optimize(x, f);
  } catch (const nlopt::forced_stop&) {
  } catch (const nlopt::roundoff_limited&) {
  } catch (const std::invalid_argument&) {
  }
}

// One search; a given `start` is evaluated first, so the result is at least as good.
design_result search_once(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
                          const std::atomic<bool>* cancel, int done_before, int total, const std::string& stage,
                          const std::vector<double>& start = {}) {
  search_state state(spec, progress, cancel, done_before, total, stage);
  const unsigned n = unsigned(spec.variables.size());
  std::vector<double> lo, hi, x;
  for (const design_variable& v : spec.variables) {
    lo.push_back(v.min);
    hi.push_back(v.max);
    x.push_back(0.5 * (v.min + v.max));
  }
  std::vector<constraint_slot> slots;
  for (std::size_t k = 0; k < spec.constraints.size(); ++k) slots.push_back({&state, k});
  auto configure = [&](nlopt::opt& opt, int evaluations) {
    opt.set_lower_bounds(lo);
    opt.set_upper_bounds(hi);
    opt.set_min_objective(objective, &state);
    for (constraint_slot& s : slots) opt.add_inequality_constraint(constraint, &s, 0.0);
    opt.set_maxeval(evaluations);
  };
  if (!start.empty()) {
    try {
      state.at(start);
    } catch (const nlopt::forced_stop&) {
      return std::move(state.result);
    }
  }
  nlopt::srand(spec.search.seed);
  nlopt::opt global(nlopt::GN_ISRES, n);
  configure(global, spec.search.global_evaluations);
  run(global, x);
  // The local polish, restarted from the best layout while it still improves. Without constraints
  // Nelder-Mead: it follows the sharp ridges that parts' edges make in the visible fraction, where
  // COBYLA's linear models stall.
  const std::size_t local_end = state.result.trials.size() + std::size_t(spec.search.local_evaluations);
  state.phase = "local";
  while (!state.result.cancelled && state.result.best >= 0 && state.result.trials.size() < local_end) {
    const int start_best = state.result.best;
    x = state.result.best_trial().x;
    nlopt::opt local(spec.constraints.empty() ? nlopt::LN_NELDERMEAD : nlopt::LN_COBYLA, n);
    configure(local, int(local_end - state.result.trials.size()));
    std::vector<double> step;
    for (unsigned i = 0; i < n; ++i) step.push_back(0.05 * (hi[i] - lo[i]));
    local.set_initial_step(step);
    local.set_xtol_abs(std::vector<double>(n, 1e-4));
    run(local, x);
    if (state.result.best == start_best) break;
  }
  return std::move(state.result);
}

// The spec optimising objective `main` alone, the other held at least as good as `level` when given
// (one more constraint, after the spec's own).
design_spec front_search_spec(const design_spec& spec, int main, std::optional<double> level) {
  design_spec sub = spec;
  sub.front.points = 0;
  sub.objectives[std::size_t(main)].weight = 1;
  sub.objectives[std::size_t(1 - main)].weight = 0;
  if (level) {
    const design_objective& o = spec.objectives[std::size_t(1 - main)];
    design_constraint c{o.metric, o.over, std::nullopt, std::nullopt, o.threshold, o.expression};
    const double slack = 1e-9 * (1 + std::abs(*level));
    (o.maximise ? c.min : c.max) = o.maximise ? *level - slack : *level + slack;
    sub.constraints.push_back(c);
  }
  return sub;
}

// A search as numbers, for sharing: its count of trials, its best and whether it was cancelled,
// then per trial valid, phase (0 global, 1 local), x, the objectives' and the constraints' values.
std::size_t trial_width(const design_spec& spec) {
  return 2 + spec.variables.size() + spec.objectives.size() + spec.constraints.size();
}

void encode_search(const design_spec& spec, const design_result& r, double* out) {
  out[0] = double(r.trials.size());
  out[1] = double(r.best);
  out[2] = r.cancelled ? 1 : 0;
  double* o = out + 3;
  for (const design_trial& t : r.trials) {
    *o++ = t.valid ? 1 : 0;
    *o++ = t.phase == "local" ? 1 : 0;
    for (double v : t.x) *o++ = v;
    const auto& e = t.evaluation;
    for (std::size_t i = 0; i < spec.objectives.size(); ++i)
      *o++ = i < e.objective_values.size() ? e.objective_values[i] : 0;
    for (std::size_t i = 0; i < spec.constraints.size(); ++i)
      *o++ = i < e.constraint_values.size() ? e.constraint_values[i] : 0;
  }
}

// The search again from its numbers (`sub` the spec it ran); a layout that was none is built again
// for its reason.
design_result decode_search(const design_spec& sub, const double* in) {
  design_result r;
  r.best = int(in[1]);
  r.cancelled = in[2] != 0;
  const double* o = in + 3;
  for (std::size_t k = 0; k < std::size_t(in[0]); ++k) {
    design_trial t;
    t.index = int(k);
    t.valid = *o++ != 0;
    t.phase = *o++ != 0 ? "local" : "global";
    t.x.assign(o, o + sub.variables.size());
    o += sub.variables.size();
    t.evaluation.objective_values.assign(o, o + sub.objectives.size());
    o += sub.objectives.size();
    t.evaluation.constraint_values.assign(o, o + sub.constraints.size());
    o += sub.constraints.size();
    if (t.valid) {
      t.evaluation.score = design_score(sub, t.evaluation.objective_values);
      t.evaluation.broken = broken_constraints(sub, t.evaluation.constraint_values);
    } else {
      design_trial fresh;
      fresh.index = t.index;
      fresh.phase = t.phase;
      fresh.x = t.x;
      t = fresh;
      try {
        evaluate_design(sub, design_scene(sub, t.x));
        throw std::logic_error("a shared search's invalid layout builds here");
      } catch (const input_error& e) {
        t.valid = false;
        t.problem = one_line(e.what());
        t.evaluation.score = -std::numeric_limits<double>::infinity();
        t.evaluation.broken.push_back("no valid layout: " + t.problem);
      }
    }
    r.trials.push_back(std::move(t));
  }
  return r;
}

// One of a front's searches: its number, the spec it optimises and where it starts.
struct front_search {
  int k = 0;
  design_spec sub;
  std::vector<double> start;
};

// A Pareto front's searches (the epsilon-constraint method, which also finds a front that is not
// convex): each objective alone, then each end made exact (the other objective's best with this
// one held at its best), then the first objective's best with the second held at `points` - 2
// levels evenly between the ends. Every trial is kept, scored by the spec's own weights. The
// searches of each of those three waves do not wait on each other: they run as items of `share`.
design_result search_front(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
                           const std::atomic<bool>* cancel, const item_share& share) {
  const int points = spec.front.points, searches = points + 2;
  const int budget = spec.search.global_evaluations + spec.search.local_evaluations;
  design_result merged;
  std::vector<int> ends(4, -1);  // trials: each objective alone, then each end exact
  auto end = [&](int i) -> const design_trial& { return merged.trials[std::size_t(ends[std::size_t(i)])]; };
  auto stage_of = [&](int k) { return "front " + std::to_string(k + 1) + "/" + std::to_string(searches); };
  // A search's trials: NLopt's budget, the start and the local polish's last step; each with the
  // held level's constraint too.
  const std::size_t width = 3 + std::size_t(budget + 2) * (trial_width(spec) + 1);
  for (int wave = 0; wave < 3 && !merged.cancelled; ++wave) {
    std::vector<front_search> wave_searches;
    for (int k = wave == 0 ? 0 : wave == 1 ? 2 : 4; k < (wave == 0 ? 2 : wave == 1 ? 4 : searches); ++k) {
      int main = k % 2;
      std::optional<double> level;
      std::vector<double> start;
      if (k == 2 || k == 3) {
        if (ends[std::size_t(k - 2)] < 0) continue;
        main = 3 - k;  // the other objective, this one held at its best
        level = end(k - 2).evaluation.objective_values[std::size_t(k - 2)];
        start = end(k - 2).x;
      } else if (k >= 4) {
        if (ends[2] < 0 || ends[3] < 0) break;
        main = 0;
        const double a = end(2).evaluation.objective_values[1], b = end(3).evaluation.objective_values[1];
        level = a + (b - a) * double(k - 3) / double(points - 1);
      }
      wave_searches.push_back({k, front_search_spec(spec, main, level), start});
    }
    const auto run_search = [&](const front_search& f) {
      return search_once(f.sub, progress, cancel, f.k * budget, searches * budget, stage_of(f.k), f.start);
    };
    std::vector<design_result> parts;
    if (share) {
      const std::vector<double> values = share(wave_searches.size(), width, [&](std::size_t i, double* out) {
        const design_result r = run_search(wave_searches[i]);
        if (3 + r.trials.size() * trial_width(wave_searches[i].sub) > width)
          throw std::logic_error("a front's search ran over its budget");
        encode_search(wave_searches[i].sub, r, out);
      });
      for (std::size_t i = 0; i < wave_searches.size(); ++i)
        parts.push_back(decode_search(wave_searches[i].sub, values.data() + i * width));
    } else {
      for (const front_search& f : wave_searches) {
        parts.push_back(run_search(f));
        if (parts.back().cancelled) break;
      }
    }
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const design_result& part = parts[i];
      const int k = wave_searches[i].k;
      merged.cancelled = merged.cancelled || part.cancelled;
      const int offset = int(merged.trials.size());
      for (design_trial t : part.trials) {
        t.index = int(merged.trials.size());
        t.phase = stage_of(k) + " " + t.phase;
        if (t.valid) {
          t.evaluation.constraint_values.resize(spec.constraints.size());
          t.evaluation.broken = broken_constraints(spec, t.evaluation.constraint_values);
          t.evaluation.score = design_score(spec, t.evaluation.objective_values);
        }
        merged.trials.push_back(t);
        if (merged.best < 0 || better_trial(spec, t, merged.best_trial())) merged.best = t.index;
      }
      // An end is the search's best when it met the spec's constraints (and the held level).
      if (k < 4 && part.best >= 0 && part.best_trial().valid && part.best_trial().evaluation.feasible())
        ends[std::size_t(k)] = offset + part.best;
    }
  }
  return merged;
}

}  // namespace

design_result optimise_design(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
                              const std::atomic<bool>* cancel, const item_share& share) {
  check_design_expressions(spec);
  check_design_memory(spec, "optimise", 1);
  const int budget = spec.search.global_evaluations + spec.search.local_evaluations;
  design_result r = spec.front.points > 0 ? search_front(spec, progress, cancel, share)
                                          : search_once(spec, progress, cancel, 0, budget, "");
  if (spec.objectives.size() == 2) r.front = pareto_front(spec, r.trials);
  return r;
}

std::vector<int> pareto_front(const design_spec& spec, const std::vector<design_trial>& trials) {
  // Both objectives as larger-is-better.
  auto gain = [&](const design_trial& t, int i) {
    return (spec.objectives[std::size_t(i)].maximise ? 1 : -1) * t.evaluation.objective_values[std::size_t(i)];
  };
  std::vector<int> front;
  for (const design_trial& t : trials) {
    if (!t.valid || !t.evaluation.feasible()) continue;
    bool dominated = false;
    for (const design_trial& u : trials) {
      if (!u.valid || !u.evaluation.feasible()) continue;
      const bool no_worse = gain(u, 0) >= gain(t, 0) && gain(u, 1) >= gain(t, 1);
      const bool better = gain(u, 0) > gain(t, 0) || gain(u, 1) > gain(t, 1);
      // Of equal pairs, the first evaluated stands for them.
      if ((no_worse && better) || (!better && no_worse && u.index < t.index)) {
        dominated = true;
        break;
      }
    }
    if (!dominated) front.push_back(t.index);
  }
  std::sort(front.begin(), front.end(), [&](int a, int b) {
    return trials[std::size_t(a)].evaluation.objective_values[0] <
           trials[std::size_t(b)].evaluation.objective_values[0];
  });
  return front;
}

std::string design_front_csv(const design_spec& spec, const design_result& r) {
  std::ostringstream out;
  out.precision(10);
  out << "index";
  for (const design_variable& v : spec.variables) out << "," << v.key;
  for (const design_objective& o : spec.objectives) out << "," << (o.maximise ? "max " : "min ") << to_string(o.metric);
  out << "\n";
  for (int i : r.front) {
    const design_trial& t = r.trials[std::size_t(i)];
    out << t.index;
    for (double v : t.x) out << "," << v;
    for (double v : t.evaluation.objective_values) out << "," << v;
    out << "\n";
  }
  return out.str();
}

std::string design_trials_csv(const design_spec& spec, const design_result& r) {
  std::ostringstream out;
  out.precision(10);
  out << "index,phase";
  for (const design_variable& v : spec.variables) out << "," << v.key;
  for (const design_objective& o : spec.objectives) out << "," << (o.maximise ? "max " : "min ") << to_string(o.metric);
  for (const design_constraint& c : spec.constraints) out << ",constraint " << to_string(c.metric);
  out << ",score,feasible,valid\n";
  for (const design_trial& t : r.trials) {
    out << t.index << "," << t.phase;
    for (double v : t.x) out << "," << v;
    for (std::size_t i = 0; i < spec.objectives.size(); ++i)
      out << "," << (t.valid ? t.evaluation.objective_values[i] : NAN);
    for (std::size_t i = 0; i < spec.constraints.size(); ++i)
      out << "," << (t.valid ? t.evaluation.constraint_values[i] : NAN);
    out << "," << t.evaluation.score << "," << (t.valid && t.evaluation.feasible() ? 1 : 0) << "," << (t.valid ? 1 : 0)
        << "\n";
  }
  return out.str();
}

}  // namespace airr
