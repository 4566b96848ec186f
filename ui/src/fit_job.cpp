#include "airr/ui/fit_job.hpp"

#include "airr/analysis/fit_data.hpp"

namespace airr::ui {

fit_job::fit_job(const std::string& data_dir) : dir_(data_dir) {
  analysis::fit_data data = analysis::load_fit_data(data_dir);
  start([data = std::move(data)](const analysis::fit_progress_callback& progress) {
    return analysis::fit_sheet(data, {}, progress);
  });
}

fit_job::fit_job(const sheet_description& sheet, const std::string& data_dir, const analysis::prediction_params& p)
    : dir_(data_dir) {
  start([sheet, data_dir, p](const analysis::fit_progress_callback& progress) {
    return analysis::predict_preset(sheet, analysis::synthesis_bench(scene{}), data_dir, p, progress);
  });
}

void fit_job::start(work w) {
  worker_ = std::thread([this, w = std::move(w)] {
    try {
      auto r = w([this](const analysis::fit_progress& p) {
        std::lock_guard lock(mutex_);
        progress_ = p;
        return !cancel_.load();
      });
      std::lock_guard lock(mutex_);
      result_ = std::move(r);
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    running_ = false;
  });
}

fit_job::~fit_job() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
}

analysis::fit_progress fit_job::progress() const {
  std::lock_guard lock(mutex_);
  return progress_;
}

std::optional<analysis::fit_result> fit_job::result() const {
  std::lock_guard lock(mutex_);
  return result_;
}

std::string fit_job::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

}  // namespace airr::ui
