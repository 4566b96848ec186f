#pragma once
// A sheet fit running in the background for the designer, from measurements or predicted from the
// sheet's model: progress, cancel, the result.
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "airr/analysis/preset_prediction.hpp"
#include "airr/analysis/sheet_fit.hpp"

namespace airr::ui {

class fit_job {
 public:
  // Loads the data directory synchronously (throws input_error), then fits on a worker thread.
  explicit fit_job(const std::string& data_dir);
  // Predicts a preset for `sheet` on the default bench (preset_prediction.hpp), its measurements
  // in data_dir, on a worker thread.
  fit_job(const sheet_description& sheet, const std::string& data_dir, const analysis::prediction_params& p);
  ~fit_job();  // cancels and joins
  fit_job(const fit_job&) = delete;
  fit_job& operator=(const fit_job&) = delete;

  void cancel() { cancel_ = true; }
  bool running() const { return running_; }
  analysis::fit_progress progress() const;
  std::optional<analysis::fit_result> result() const;
  std::string error() const;
  const std::string& data_dir() const { return dir_; }

 private:
  using work = std::function<analysis::fit_result(const analysis::fit_progress_callback&)>;
  void start(work w);

  std::string dir_;
  std::atomic<bool> cancel_{false}, running_{true};
  mutable std::mutex mutex_;
  analysis::fit_progress progress_;
  std::optional<analysis::fit_result> result_;
  std::string error_;
  std::thread worker_;
};

}  // namespace airr::ui
