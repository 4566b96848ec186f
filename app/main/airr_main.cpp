// `airr`: the command-line face of AIRR Studio.
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "airr/render/memory_need.hpp"
#include "airr_version.hpp"
#include "cli/commands.hpp"
#include "cluster/item_shards.hpp"
#include "cluster/mpi_job.hpp"

void add_commands(CLI::App& app) {
  add_render_command(app);
  add_bench_command(app);
  add_make_assets_command(app);
  add_shift_table_command(app);
  add_mtf_command(app);
  add_compare_command(app);
  add_psf_command(app);
  add_sweep_command(app);
  add_fit_command(app);
  add_predict_preset_command(app);
  add_optimise_command(app);
  add_tolerance_command(app);
  add_viewzone_command(app);
  add_export_gltf_command(app);
  add_merge_command(app);
  add_gain_command(app);
  add_ghosts_command(app);
}

int main(int argc, char** argv) {
  // Past a file-size limit (ulimit -f) a write then fails with an error naming the file, instead
  // of the signal killing the program half-way.
  std::signal(SIGXFSZ, SIG_IGN);
  const mpi_job& job = this_job();
  CLI::App app{"airr: simulate aerial imaging by retroreflection (AIRR)"};
  app.set_version_flag("--version", std::string("airr ") + AIRR_VERSION);
  app.require_subcommand(1);
  add_commands(app);
  set_command_line(argc, argv);
  // In an MPI job, commands that do not split their work run on rank 0 alone (written once).
  if (job.size > 1 && argc > 1) {
    const std::string command = argv[1];
    const bool splits = command == "render" || command == "sweep" || command == "viewzone" || command == "tolerance" ||
                        command == "fit" || command == "predict-preset" || command == "optimise";
    if (!splits) {
      if (!job.root()) return 0;
      std::fprintf(stderr, "note: %s does not split across ranks; rank 0 runs it alone\n", command.c_str());
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    // An allocation that failed past the commands' own memory checks is said as such.
    const std::string message = airr::failure_message(e, argc > 1 ? argv[1] : "airr");
    if (job.size == 1) {
      std::fprintf(stderr, "error: %s\n", message.c_str());
      return 1;
    }
    // The ranks of an MPI job fail alike on bad input: rank 0 says why; any rank's failure ends them all.
    if (job.root())
      std::fprintf(stderr, "error: %s\n", message.c_str());
    else
      std::fprintf(stderr, "error: rank %d: %s\n", job.rank, message.c_str());
    abort_job(1);
  }
  return 0;
}
