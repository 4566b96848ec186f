// airr shift-table -o FILE [--grid N] [--model PATH]: traces the corner cube and writes the
// shift distributions P(theta) with their provenance (spec section 3).
#include <chrono>
#include <ctime>

#include <tbb/task_arena.h>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/models/shift_table.hpp"
#include "airr/render/shift_table_tracer.hpp"
#include "cli/commands.hpp"
#include "cli/progress_bar.hpp"

namespace {

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

void add_shift_table_command(CLI::App& app) {
  struct options {
    std::string out;
    std::string model;  // empty: the shipped corner cube
    int grid = airr::shift_table_params{}.grid;
  };
  auto opt = std::make_shared<options>();
  auto* cmd = app.add_subcommand("shift-table", "Trace the corner cube and write its shift distributions P(theta)");
  cmd->add_option("-o,--output", opt->out, "Output shift table (.json)")->required();
  cmd->add_option("--grid", opt->grid, "Rays per side of the grid, per incidence direction")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--model", opt->model, "Corner-cube glTF model (default: the shipped models/corner_cube.gltf)");
  cmd->callback([opt] {
    if (opt->model.empty()) opt->model = airr::asset_dir() + "/models/corner_cube.gltf";
    const airr::triangle_mesh cube = airr::load_gltf_mesh(opt->model);
    airr::shift_table_params params;
    params.grid = opt->grid;

    progress_bar bar("shift-table");
    airr::shift_table table;
    try {
      table = airr::trace_shift_table(cube, params, [&](double fraction) {
        if (fraction < 1) bar.update(fraction);  // finish() draws the last state
      });
    } catch (const airr::input_error& e) {
      throw airr::input_error(opt->model + ": " + e.what());
    }
    const double seconds = bar.seconds();
    bar.finish();

    auto& prov = table.provenance;
    prov["date"] = utc_now_iso8601();
    prov["command"] =
        "airr shift-table -o " + opt->out + " --grid " + std::to_string(opt->grid) + " --model " + opt->model;
    prov["model"] = opt->model;
    prov["run_seconds"] = seconds;
    prov["threads"] = tbb::this_task_arena::max_concurrency();
    airr::save_shift_table(table, opt->out);

    std::uint64_t entering = 0, kept = 0;
    for (const auto& n : prov["rays_entering"]) entering += n.get<std::uint64_t>();
    for (const auto& n : prov["rays_kept"]) kept += n.get<std::uint64_t>();
    std::fprintf(stderr, "wrote %s (%zu angles, %d bins, %llu of %llu entering rays kept) in %.1f s on %d threads\n",
                 opt->out.c_str(), table.theta_deg.size(), table.bins(), static_cast<unsigned long long>(kept),
                 static_cast<unsigned long long>(entering), seconds, int(prov["threads"]));
  });
}
