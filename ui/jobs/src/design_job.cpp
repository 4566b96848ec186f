#include "airr/ui/jobs/design_job.hpp"

namespace airr::ui {

namespace {

using job = background_job<design_progress, design_outcome>;

job::work design_work(const design_spec& spec, design_job::kind k) {
  return [spec, k](const job::context& ctx) -> std::optional<design_outcome> {
    design_outcome out;
    if (k == design_job::kind::optimise) {
      out.optimised = optimise_design(spec, ctx.report, &ctx.cancel);
    } else {
      out.tolerances = run_tolerance(
          spec, spec.base,
          [&ctx](int done, int total) {
            design_progress p;
            p.done = done;
            p.total = total;
            ctx.report(p);
          },
          &ctx.cancel);
    }
    return out;
  };
}

}  // namespace

design_job::design_job(const design_spec& spec, kind k)
    : background_job(k == kind::optimise ? "optimise" : "tolerance", design_work(spec, k), 5), spec_(spec), kind_(k) {}

std::optional<design_result> design_job::optimised() const {
  const auto r = result();
  return r ? r->optimised : std::nullopt;
}

std::optional<tolerance_result> design_job::tolerances() const {
  const auto r = result();
  return r ? r->tolerances : std::nullopt;
}

}  // namespace airr::ui
