#include "airr/ui/jobs/ghost_job.hpp"

#include <algorithm>

#include "airr/render/ray_file.hpp"

namespace airr::ui {

namespace {

// Up to ghost_paths_kept paths of the class, as polylines: each segment's start, then the eye.
std::vector<std::vector<glm::vec3>> paths_of(const scene& s, const std::string& expression,
                                             const std::atomic<bool>& cancel) {
  const ray_record r =
      record_rays(s, {.select = expression, .segment_limit = 2000, .spp = 1}, [&](double) { return !cancel.load(); });
  std::vector<std::vector<glm::vec3>> out;
  // Spread over the paths found rather than the first few of one corner.
  const std::size_t step = std::max<std::size_t>(1, r.paths.size() / ghost_paths_kept);
  for (std::size_t i = 0; i < r.paths.size() && out.size() < std::size_t(ghost_paths_kept); i += step) {
    const ray_path& p = r.paths[i];
    std::vector<glm::vec3> line;
    for (std::uint32_t k = 0; k < p.segment_count; ++k) line.push_back(r.segments[p.first_segment + k].start);
    const ray_segment& last = r.segments[p.first_segment + p.segment_count - 1];
    line.push_back(last.start + last.length * last.direction);
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

ghost_job::ghost_job(const scene& s, const ghost_params& p, std::uint64_t generation)
    : background_job(
          "ghosts",
          [s, p](const context& ctx) -> std::optional<ghost_findings> {
            ghost_params q = p;
            q.cancel = &ctx.cancel;
            ghost_findings f;
            f.table = compute_ghost_table(s, q, [&ctx](const std::string&, double done) { ctx.report(0.8 * done); });
            if (ctx.cancel) return std::nullopt;
            for (std::size_t k = 0; k < f.table.classes.size(); ++k) {
              f.paths.push_back(paths_of(s, f.table.classes[k].expression, ctx.cancel));
              if (ctx.cancel) return std::nullopt;
              ctx.report(0.8 + 0.2 * double(k + 1) / double(f.table.classes.size()));
            }
            return f;
          },
          5),
      generation_(generation) {}

}  // namespace airr::ui
