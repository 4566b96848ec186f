#include "airr/ui/jobs/fit_job.hpp"

#include "airr/analysis/fit_data.hpp"

namespace airr::ui {

namespace {

using job = background_job<analysis::fit_progress, analysis::fit_result>;

// The fit's progress callback: reports, and goes on until cancelled.
analysis::fit_progress_callback reporting(const job::context& ctx) {
  return [&ctx](const analysis::fit_progress& p) {
    ctx.report(p);
    return !ctx.cancel.load();
  };
}

job::work fit_measurements(const std::string& data_dir) {
  analysis::fit_data data = analysis::load_fit_data(data_dir);
  return [data = std::move(data)](const job::context& ctx) -> std::optional<analysis::fit_result> {
    return analysis::fit_sheet(data, {}, reporting(ctx));
  };
}

}  // namespace

fit_job::fit_job(const std::string& data_dir) : background_job("fit", fit_measurements(data_dir)), dir_(data_dir) {}

fit_job::fit_job(const sheet_description& sheet, const std::string& data_dir, const analysis::prediction_params& p)
    : background_job("prediction",
                     [sheet, data_dir, p](const context& ctx) -> std::optional<analysis::fit_result> {
                       return analysis::predict_preset(sheet, analysis::synthesis_bench(scene{}), data_dir, p,
                                                       reporting(ctx));
                     }),
      dir_(data_dir) {}

}  // namespace airr::ui
