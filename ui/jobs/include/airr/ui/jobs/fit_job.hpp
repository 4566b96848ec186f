#pragma once
// A sheet fit running in the background for the designer, from measurements or predicted from the
// sheet's model: progress, cancel, the result (background_job.hpp).
#include <string>

#include "airr/analysis/preset_prediction.hpp"
#include "airr/analysis/sheet_fit.hpp"
#include "airr/ui/jobs/background_job.hpp"

namespace airr::ui {

class fit_job : public background_job<analysis::fit_progress, analysis::fit_result> {
 public:
  // Loads the data directory synchronously (throws input_error), then fits on a worker thread.
  explicit fit_job(const std::string& data_dir);
  // Predicts a preset for `sheet` on the default bench (preset_prediction.hpp), its measurements
  // in data_dir, on a worker thread.
  fit_job(const sheet_description& sheet, const std::string& data_dir, const analysis::prediction_params& p);

  const std::string& data_dir() const { return dir_; }

 private:
  std::string dir_;
};

}  // namespace airr::ui
