#pragma once
// The viewing zone's full pass running in the background for the designer: progress (the share
// of eyes done), cancel, the result, and the layout generation it belongs to (background_job.hpp).
#include <cstdint>

#include "airr/measure/viewing_zone_full.hpp"
#include "airr/ui/jobs/background_job.hpp"

namespace airr::ui {

class zone_job : public background_job<double, full_zone_map> {
 public:
  zone_job(const scene& s, const eye_grid& g, const full_zone_params& p, std::uint64_t generation);
  std::uint64_t generation() const { return generation_; }

 private:
  std::uint64_t generation_;
};

}  // namespace airr::ui
