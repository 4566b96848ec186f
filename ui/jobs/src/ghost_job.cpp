#include "airr/ui/jobs/ghost_job.hpp"

#include <algorithm>

#include "airr/render/ray_file.hpp"

namespace airr::ui {

namespace {

// Up to ghost_paths_kept paths of a class, as polylines: each segment's start, then the eye.
std::vector<std::vector<glm::vec3>> paths_of(const ray_record& r) {
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
            // Every class's paths in one pass, each up to its own 2000 segments.
            std::vector<std::string> expressions;
            for (const ghost_class& c : f.table.classes) expressions.push_back(c.expression);
            const std::vector<ray_record> records =
                record_rays(s, expressions, {.segment_limit = 2000, .spp = 1}, [&ctx](double done) {
                  ctx.report(0.8 + 0.2 * done);
                  return !ctx.cancel.load();
                });
            if (ctx.cancel) return std::nullopt;
            for (const ray_record& r : records) f.paths.push_back(paths_of(r));
            return f;
          },
          5),
      generation_(generation) {}

}  // namespace airr::ui
