#include "airr/ui/jobs/zone_job.hpp"

#include <algorithm>

namespace airr::ui {

zone_job::zone_job(const scene& s, const eye_grid& g, const full_zone_params& p, std::uint64_t generation)
    : background_job(
          "viewing zone",
          [s, g, p](const context& ctx) -> std::optional<full_zone_map> {
            full_zone_map map = full_viewing_zone(
                s, g, p, [&ctx](int done, int total) { ctx.report(double(done) / double(std::max(1, total))); },
                &ctx.cancel);
            if (map.visible.empty()) return std::nullopt;  // cancelled
            return map;
          },
          5),
      generation_(generation) {}

}  // namespace airr::ui
