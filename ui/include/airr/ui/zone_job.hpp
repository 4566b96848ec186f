#pragma once
// The viewing zone's full pass running in the background for the designer: progress, cancel,
// the result, and the layout generation it belongs to.
#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "airr/measure/viewing_zone_full.hpp"

namespace airr::ui {

class zone_job {
 public:
  zone_job(const scene& s, const eye_grid& g, const full_zone_params& p, std::uint64_t generation);
  ~zone_job();  // cancels and joins
  zone_job(const zone_job&) = delete;
  zone_job& operator=(const zone_job&) = delete;

  bool running() const { return running_; }
  double progress() const { return double(done_) / double(std::max(1, total_.load())); }
  std::optional<full_zone_map> result() const;
  std::string error() const;
  std::uint64_t generation() const { return generation_; }

 private:
  std::uint64_t generation_;
  std::atomic<bool> cancel_{false}, running_{true};
  std::atomic<int> done_{0}, total_{1};
  mutable std::mutex mutex_;
  std::optional<full_zone_map> result_;
  std::string error_;
  std::thread worker_;
};

}  // namespace airr::ui
