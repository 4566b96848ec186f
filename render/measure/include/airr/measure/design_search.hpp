#pragma once
// The optimiser of a design spec: a global search over the variables' box (NLopt's ISRES, which
// keeps to the constraints, seeded by the spec), then a local polish from the best point found
// (NLopt's COBYLA, constraints kept). Each evaluation builds the layout the variables make and
// scores it (design_metrics.hpp); a layout that is no valid layout (parts meeting) counts as
// breaking every constraint.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "airr/formats/design_spec.hpp"
#include "airr/measure/design_metrics.hpp"

namespace airr {

struct design_trial {
  int index = 0;
  std::string phase;  // "global" or "local"
  std::vector<double> x;
  bool valid = true;    // a layout at all
  std::string problem;  // why not
  design_evaluation evaluation;
};

struct design_progress {
  int done = 0, total = 0;
  double seconds = 0;
  bool have_best = false;
  double best_score = 0;
  bool best_feasible = false;
};

struct design_result {
  std::vector<design_trial> trials;
  int best = -1;  // the trial: the best feasible one, or when none is, the least infeasible
  bool cancelled = false;
  const design_trial& best_trial() const { return trials.at(std::size_t(best)); }
};

// Runs the search; `progress` after every evaluation, `cancel` checked before each. Deterministic
// for the spec (its seed included).
design_result optimise_design(const design_spec& spec, const std::function<void(const design_progress&)>& progress = {},
                              const std::atomic<bool>* cancel = nullptr);

// Every trial as CSV: index, phase, the variables, the objectives' and constraints' values, the
// score, feasible (1 or 0) and valid (1 or 0).
std::string design_trials_csv(const design_spec& spec, const design_result& r);

}  // namespace airr
