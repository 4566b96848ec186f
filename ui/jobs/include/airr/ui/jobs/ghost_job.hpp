#pragma once
// The ghost table of a layout, found in the background for the designer's Ghosts window: the
// classes ranked (ghost_table.hpp) and a few traced paths of each, to draw in the 3D and layout
// views (background_job.hpp).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "airr/measure/ghost_table.hpp"
#include "airr/ui/jobs/background_job.hpp"

namespace airr::ui {

struct ghost_findings {
  ghost_table table;
  // By class: a few of its paths, each the points it meets from the display to the eye (mm).
  std::vector<std::vector<std::vector<glm::vec3>>> paths;
};

// The most paths kept of a class (picked across the first 2000 segments' worth a pass traces).
inline constexpr int ghost_paths_kept = 8;

class ghost_job : public background_job<double, ghost_findings> {
 public:
  ghost_job(const scene& s, const ghost_params& p, std::uint64_t generation);
  std::uint64_t generation() const { return generation_; }

 private:
  std::uint64_t generation_;
};

}  // namespace airr::ui
