#pragma once
// --shard i/N --part FILE for the commands whose work is numbered items (sweep, viewzone --full,
// tolerance): the shard computes items i, i + N, ... of each of the command's batches and writes
// them, with the command line, to FILE (format airr-partial), and no other output. `airr merge` of
// all N partials runs the command line again, in the shards' working directory, with every item's
// numbers read from them, so it writes what one process writes.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "airr/core/item_share.hpp"

struct shard_options {
  std::string shard;  // "i/N", empty: none
  std::string part;   // the partial file
};

void add_shard_options(CLI::App* cmd, shard_options& o);

// The command's arguments after the program name, as main received them (for the partials).
void set_command_line(int argc, char** argv);

// How the command's items run: read back from partials in a merge; the shard's own items in a
// shard (the others zeros); shared among the ranks in an MPI job, rank 0 told the job's progress
// (`job_progress(done, n)`); else on the cores (empty).
airr::item_share command_item_share(const shard_options& o,
                                    const std::function<void(std::size_t, std::size_t)>& job_progress = {});

// In a shard, writes its partial (atomically) and returns true: the command writes nothing else.
bool write_shard_part(const shard_options& o);

// Whether the files are partials (airr-partial JSON) rather than render shards.
bool are_partials(const std::vector<std::string>& paths);

// Checks the partials (one per shard, all of one command line, build and unchanged input files),
// moves to the shards' working directory and makes their items what the command's item_share reads
// from then on; returns the command line (without the program's name) to run again, which then
// writes the command's outputs. Throws input_error naming the file.
std::vector<std::string> merged_command_line(const std::vector<std::string>& paths);
