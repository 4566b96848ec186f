#pragma once
// Tolerance analysis of a design spec's layout: Monte Carlo over its tolerances (each scene value
// off its nominal by a normal or uniform error, all at once), the distribution of every objective's
// and constraint's metric, the yield (the share of layouts meeting every constraint), and each
// tolerance's sensitivity alone (the change of each metric per tolerance size, by central
// differences at +-size).
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/design/metrics.hpp"
#include "airr/formats/design_spec.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

struct metric_distribution {
  std::string name;            // "r50_mm (objective)", "size_z_mm (constraint)"
  std::vector<double> values;  // one per valid sample
  double mean = 0, sd = 0, p5 = 0, p50 = 0, p95 = 0;
};

// One layout the Monte Carlo drew: each tolerance's value (its nominal plus the drawn offset, in
// the spec's order), and what it made.
struct tolerance_layout {
  std::vector<double> values;
  bool valid = false;               // a layout at all (else the rest is empty)
  std::vector<double> metrics;      // objectives, then constraints
  double score = 0;                 // design_score
  std::vector<std::string> broken;  // its broken constraints, empty when it meets every one
};

struct tolerance_result {
  int samples = 0;
  int invalid = 0;                           // samples that made no valid layout (counted as failing)
  double yield = 0;                          // share meeting every constraint (1 when there are none and all are valid)
  std::vector<metric_distribution> metrics;  // objectives, then constraints
  // sensitivity[t][m]: metric m's change per size of tolerance t (NaN where either side made no
  // valid layout)
  std::vector<std::vector<double>> sensitivity;
  std::vector<tolerance_layout> layouts;  // every sample, in the order drawn
  bool cancelled = false;
};

// What kept a layout from passing: "no valid layout", or its broken constraints joined by "; ";
// empty when it meets every constraint.
std::string layout_failures(const tolerance_layout& l);

// The indices of the `count` worst layouts: those that make no layout first, then those breaking
// the most constraints, then the lowest scores.
std::vector<std::size_t> worst_layouts(const tolerance_result& r, std::size_t count);

// A metric's values counted in `bins` equal bins over their range, as a step line: each bin's two
// edges at its count.
struct histogram_steps {
  std::vector<double> x, y;
};
histogram_steps metric_histogram(const metric_distribution& d, int bins = 40);

// Runs the Monte Carlo about `nominal` (the spec's base scene, or a layout the optimiser wrote);
// deterministic for the spec's tolerance seed. The layouts of each batch run on this machine's
// cores, or as the items of `share` (an MPI job's ranks) when given. `progress(done, total)` after each layout.
tolerance_result run_tolerance(const design_spec& spec, const scene& nominal,
                               const std::function<void(int, int)>& progress = {},
                               const std::atomic<bool>* cancel = nullptr, const item_share& share = {});

}  // namespace airr
