#include "airr/ui/design_job.hpp"

#include "airr/render/render_session.hpp"

namespace airr::ui {

design_job::design_job(const design_spec& spec, kind k)
    : spec_(spec), kind_(k), start_(std::chrono::steady_clock::now()) {
  worker_ = std::thread([this] {
    lower_thread_priority(5);  // like the plots: the window comes first
    try {
      if (kind_ == kind::optimise) {
        design_result r = optimise_design(
            spec_,
            [this](const design_progress& p) {
              std::lock_guard lock(mutex_);
              progress_ = p;
            },
            &cancel_);
        std::lock_guard lock(mutex_);
        optimised_ = std::move(r);
      } else {
        tolerance_result r = run_tolerance(
            spec_, spec_.base,
            [this](int done, int total) {
              std::lock_guard lock(mutex_);
              progress_.done = done;
              progress_.total = total;
            },
            &cancel_);
        std::lock_guard lock(mutex_);
        tolerances_ = std::move(r);
      }
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    running_ = false;
  });
}

design_job::~design_job() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
}

double design_job::seconds() const {
  if (!running_) return seconds_;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

design_progress design_job::progress() const {
  std::lock_guard lock(mutex_);
  return progress_;
}

std::optional<design_result> design_job::optimised() const {
  std::lock_guard lock(mutex_);
  return optimised_;
}

std::optional<tolerance_result> design_job::tolerances() const {
  std::lock_guard lock(mutex_);
  return tolerances_;
}

std::string design_job::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

}  // namespace airr::ui
