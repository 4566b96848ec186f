#include "airr/ui/zone_job.hpp"

#include "airr/render/render_session.hpp"

namespace airr::ui {

zone_job::zone_job(const scene& s, const eye_grid& g, const full_zone_params& p, std::uint64_t generation)
    : generation_(generation) {
  worker_ = std::thread([this, s, g, p] {
    lower_thread_priority(5);  // like the plots: the window comes first
    try {
      auto map = full_viewing_zone(
          s, g, p,
          [this](int done, int total) {
            done_ = done;
            total_ = total;
          },
          &cancel_);
      std::lock_guard lock(mutex_);
      if (!map.visible.empty()) result_ = std::move(map);
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    running_ = false;
  });
}

zone_job::~zone_job() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
}

std::optional<full_zone_map> zone_job::result() const {
  std::lock_guard lock(mutex_);
  return result_;
}

std::string zone_job::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

}  // namespace airr::ui
