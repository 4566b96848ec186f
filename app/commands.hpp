#pragma once
// The subcommands of the `airr` command line; each registers itself on the app.
#include <CLI/CLI.hpp>

void add_render_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_make_assets_command(CLI::App& app);
void add_shift_table_command(CLI::App& app);
void add_mtf_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_psf_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_fit_command(CLI::App& app);
