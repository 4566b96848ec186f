#include "airr/ui/fit_job.hpp"

#include "airr/analysis/fit_data.hpp"

namespace airr::ui {

fit_job::fit_job(const std::string& data_dir) : dir_(data_dir) {
  analysis::fit_data data = analysis::load_fit_data(data_dir);
  worker_ = std::thread([this, data = std::move(data)] {
    try {
      auto r = analysis::fit_sheet(data, {}, [this](const analysis::fit_progress& p) {
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
