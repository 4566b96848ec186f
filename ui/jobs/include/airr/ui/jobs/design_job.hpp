#pragma once
// An optimisation or a tolerance analysis of a design spec running in the background for the
// designer (the same as `airr optimise` and `airr tolerance`): progress with the best layout so
// far, cancel, the result (background_job.hpp).
#include <optional>

#include "airr/design/search.hpp"
#include "airr/design/tolerance.hpp"
#include "airr/ui/jobs/background_job.hpp"

namespace airr::ui {

// What a design job ends with: the search's result or the analysis's.
struct design_outcome {
  std::optional<design_result> optimised;
  std::optional<tolerance_result> tolerances;
};

class design_job : public background_job<design_progress, design_outcome> {
 public:
  enum class kind { optimise, tolerance };
  // Starts at once; the tolerance analysis runs about the spec's base scene.
  design_job(const design_spec& spec, kind k);

  kind what() const { return kind_; }
  const design_spec& spec() const { return spec_; }
  // progress(): the tolerance analysis fills done and total alone.
  std::optional<design_result> optimised() const;
  std::optional<tolerance_result> tolerances() const;

 private:
  const design_spec spec_;
  const kind kind_;
};

}  // namespace airr::ui
