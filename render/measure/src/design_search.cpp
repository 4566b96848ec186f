#include "airr/measure/design_search.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <nlopt.hpp>

#include "airr/core/error.hpp"

namespace airr {

namespace {

// A layout that is no layout breaks each constraint by this much.
constexpr double invalid_violation = 1e6;

class search_state {
 public:
  search_state(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
               const std::atomic<bool>* cancel)
      : spec_(spec), progress_(progress), cancel_(cancel), start_(std::chrono::steady_clock::now()) {
    total_ = spec.search.global_evaluations + spec.search.local_evaluations;
  }

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
      p.done = int(result.trials.size());
      p.total = total_;
      p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      p.have_best = result.best >= 0;
      if (p.have_best) {
        p.best_score = result.best_trial().evaluation.score;
        p.best_feasible = result.best_trial().evaluation.feasible();
      }
      progress_(p);
    }
    return result.trials.back();
  }

  double violation(const design_trial& t, std::size_t k) const {
    if (!t.valid) return invalid_violation;
    const design_constraint& c = spec_.constraints[k];
    const double v = t.evaluation.constraint_values[k];
    // Signed, as NLopt wants it: negative inside.
    double g = -std::numeric_limits<double>::infinity();
    if (c.min) g = std::max(g, *c.min - v);
    if (c.max) g = std::max(g, v - *c.max);
    return g;
  }

  double total_violation(const design_trial& t) const {
    double sum = 0;
    for (std::size_t k = 0; k < spec_.constraints.size(); ++k) sum += std::max(0.0, violation(t, k));
    return t.valid ? sum : invalid_violation;
  }

  std::string phase = "global";
  design_result result;

 private:
  // Feasible beats infeasible; among feasible the higher score, among infeasible the smaller
  // violation.
  void consider(const design_trial& t) {
    if (result.best < 0) {
      result.best = t.index;
      return;
    }
    const design_trial& b = result.best_trial();
    const bool tf = t.valid && t.evaluation.feasible(), bf = b.valid && b.evaluation.feasible();
    if (tf != bf) {
      if (tf) result.best = t.index;
      return;
    }
    if (tf ? t.evaluation.score > b.evaluation.score : total_violation(t) < total_violation(b)) result.best = t.index;
  }

  const design_spec& spec_;
  const std::function<void(const design_progress&)>& progress_;
  const std::atomic<bool>* cancel_;
  std::chrono::steady_clock::time_point start_;
  int total_ = 0;
  std::map<std::vector<double>, std::size_t> seen_;
};

struct constraint_slot {
  search_state* state;
  std::size_t k;
};

double objective(const std::vector<double>& x, std::vector<double>&, void* data) {
  const design_trial& t = static_cast<search_state*>(data)->at(x);
  return t.valid ? -t.evaluation.score : invalid_violation;
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

}  // namespace

design_result optimise_design(const design_spec& spec, const std::function<void(const design_progress&)>& progress,
                              const std::atomic<bool>* cancel) {
  search_state state(spec, progress, cancel);
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
