#pragma once
// An optimisation or a tolerance analysis of a design spec running in the background for the
// designer (the same as `airr optimise` and `airr tolerance`): progress with the best layout so
// far, cancel, the result.
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "airr/measure/design_search.hpp"
#include "airr/measure/design_tolerance.hpp"

namespace airr::ui {

class design_job {
 public:
  enum class kind { optimise, tolerance };
  // Starts at once; the tolerance analysis runs about the spec's base scene.
  design_job(const design_spec& spec, kind k);
  ~design_job();  // cancels and joins
  design_job(const design_job&) = delete;
  design_job& operator=(const design_job&) = delete;

  kind what() const { return kind_; }
  const design_spec& spec() const { return spec_; }
  void cancel() { cancel_ = true; }
  bool running() const { return running_; }
  double seconds() const;
  design_progress progress() const;  // the tolerance analysis fills done and total alone
  std::optional<design_result> optimised() const;
  std::optional<tolerance_result> tolerances() const;
  std::string error() const;

 private:
  const design_spec spec_;
  const kind kind_;
  std::atomic<bool> cancel_{false}, running_{true};
  std::chrono::steady_clock::time_point start_;
  std::atomic<double> seconds_{0};
  mutable std::mutex mutex_;
  design_progress progress_;
  std::optional<design_result> optimised_;
  std::optional<tolerance_result> tolerances_;
  std::string error_;
  std::thread worker_;
};

}  // namespace airr::ui
