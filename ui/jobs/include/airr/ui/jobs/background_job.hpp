#pragma once
// The one shape of the designer's background work (a fit or prediction, the viewing zone's full
// pass, an optimisation or tolerance analysis): it starts at once on its own thread; the UI thread
// reads its progress, result or error at any time; it is cancelled and joined when dropped.
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "airr/render/memory_need.hpp"
#include "airr/render/render_session.hpp"

namespace airr::ui {

template <class Progress, class Result>
class background_job {
 public:
  // What the work is handed: `report` for its progress, and the flag it stops at.
  struct context {
    std::function<void(const Progress&)> report;
    const std::atomic<bool>& cancel;
  };
  // Returns the result, or nothing when it stopped early; what it throws becomes the job's error.
  using work = std::function<std::optional<Result>(const context&)>;

  // `name` says what ran out when an allocation fails ("fit: out of memory ..."); `nice` > 0
  // lowers the thread's priority by that much (the window comes first).
  background_job(std::string name, work w, int nice = 0) : start_(std::chrono::steady_clock::now()) {
    worker_ = std::thread([this, name = std::move(name), w = std::move(w), nice] {
      if (nice > 0) lower_thread_priority(nice);
      const context ctx{[this](const Progress& p) {
                          std::lock_guard lock(mutex_);
                          progress_ = p;
                        },
                        cancel_};
      try {
        std::optional<Result> r = w(ctx);
        std::lock_guard lock(mutex_);
        result_ = std::move(r);
      } catch (const std::exception& e) {
        const std::string message = failure_message(e, name);
        std::lock_guard lock(mutex_);
        error_ = message;
      }
      seconds_ = elapsed();
      running_ = false;
    });
  }
  ~background_job() {
    cancel();
    if (worker_.joinable()) worker_.join();
  }
  background_job(const background_job&) = delete;
  background_job& operator=(const background_job&) = delete;

  void cancel() { cancel_ = true; }
  bool running() const { return running_; }
  // Seconds since the start, or the whole run's once it ended.
  double seconds() const { return running_ ? elapsed() : seconds_.load(); }
  Progress progress() const {
    std::lock_guard lock(mutex_);
    return progress_;
  }
  std::optional<Result> result() const {
    std::lock_guard lock(mutex_);
    return result_;
  }
  std::string error() const {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

  std::atomic<bool> cancel_{false}, running_{true};
  const std::chrono::steady_clock::time_point start_;
  std::atomic<double> seconds_{0};
  mutable std::mutex mutex_;
  Progress progress_{};
  std::optional<Result> result_;
  std::string error_;
  std::thread worker_;  // last: started once everything above is ready
};

}  // namespace airr::ui
