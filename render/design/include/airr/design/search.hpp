#pragma once
// The optimiser of a design spec: a global search over the variables' box (NLopt's ISRES, which
// keeps to the constraints, seeded by the spec), then a local polish from the best point found
// (NLopt's Nelder-Mead, or COBYLA keeping the constraints), restarted while it improves. A spec
// asking for a Pareto front runs one such search per point of it. Each evaluation builds the layout the variables make
// and scores it (metrics.hpp); a layout that is no valid layout (parts meeting) counts as breaking every
// constraint.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/design_spec.hpp"

namespace airr {

struct design_trial {
  int index = 0;
  std::string phase;  // "global" or "local"; for a Pareto front's searches e.g. "front 3/7 local"
  std::vector<double> x;
  bool valid = true;    // a layout at all
  std::string problem;  // why not
  design_evaluation evaluation;
};

struct design_progress {
  int done = 0, total = 0;
  std::string stage;  // "global", "local", or e.g. "front 3/7 local"
  double seconds = 0;
  bool have_best = false;
  double best_score = 0;
  bool best_feasible = false;
  std::vector<double> best_x;  // the variables of the best so far
};

struct design_result {
  std::vector<design_trial> trials;
  int best = -1;  // the trial: the best feasible one, or when none is, the least infeasible
  bool cancelled = false;
  std::vector<int> front;  // of two objectives: the feasible trials no other beats in both, by the first's value
  const design_trial& best_trial() const { return trials.at(std::size_t(best)); }
};

// Runs the search; `progress` after every evaluation, `cancel` checked before each. Deterministic
// for the spec (its seed included). A Pareto front's searches that do not wait on each other run as
// items of `share` (an MPI job's ranks; each rank's progress tells of its own searches); the result
// is the same with or without it.
design_result optimise_design(const design_spec& spec, const std::function<void(const design_progress&)>& progress = {},
                              const std::atomic<bool>* cancel = nullptr, const item_share& share = {});

// The feasible trials no other feasible trial is at least as good as in both objectives and
// better in one (of equal ones the first), ordered by the first objective's value.
std::vector<int> pareto_front(const design_spec& spec, const std::vector<design_trial>& trials);

// The front as CSV: index, the variables, the two objectives' values.
std::string design_front_csv(const design_spec& spec, const design_result& r);

// Every trial as CSV: index, phase, the variables, the objectives' and constraints' values, the
// score, feasible (1 or 0) and valid (1 or 0).
std::string design_trials_csv(const design_spec& spec, const design_result& r);

}  // namespace airr
