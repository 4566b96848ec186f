#include "cluster/item_shards.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>

#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/render/render_shards.hpp"
#include "airr_version.hpp"
#include "cluster/mpi_job.hpp"
#include "cluster/partial_file.hpp"

namespace {

struct shard_state {
  std::vector<std::string> command_line;
  std::vector<partial_batch> calls;                  // a shard's own items, call by call
  std::optional<std::vector<partial_batch>> replay;  // a merge's items
  std::size_t next_call = 0;
};
shard_state& state() {
  static shard_state s;
  return s;
}

// The command line without its --shard and --part options.
std::vector<std::string> without_shard_options(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--shard" || args[i] == "--part") {
      ++i;
      continue;
    }
    if (args[i].rfind("--shard=", 0) == 0 || args[i].rfind("--part=", 0) == 0) continue;
    out.push_back(args[i]);
  }
  return out;
}

// The contents' hash of each argument that names an existing file and is no output (the scene, a
// spec): a partial of inputs changed since is refused.
nlohmann::json input_fingerprints(const std::vector<std::string>& args) {
  const std::vector<std::string> outputs = {"-o", "--output", "--png", "--plot", "--csv"};
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (i > 0 && std::find(outputs.begin(), outputs.end(), args[i - 1]) != outputs.end()) continue;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(a, ec)) continue;
    out[a] = std::to_string(std::hash<std::string>{}(airr::read_text_file(a)));
  }
  return out;
}

}  // namespace

void add_shard_options(CLI::App* cmd, shard_options& o) {
  auto* shard = cmd->add_option("--shard", o.shard,
                                "Compute shard i of N (0 <= i < N) of the work alone into --part, for airr merge");
  cmd->add_option("--part", o.part, "The shard's partial result (JSON)")->needs(shard);
}

void set_command_line(int argc, char** argv) { state().command_line.assign(argv + 1, argv + argc); }

airr::item_share command_item_share(const shard_options& o,
                                    const std::function<void(std::size_t, std::size_t)>& job_progress) {
  shard_state& st = state();
  if (st.replay) {
    return [&st](std::size_t n, std::size_t width, const airr::item_compute&) {
      if (st.next_call >= st.replay->size() || (*st.replay)[st.next_call].n != n ||
          (*st.replay)[st.next_call].width != width)
        throw airr::input_error("merge: the partials do not hold this command's work");
      const partial_batch& call = (*st.replay)[st.next_call++];
      std::vector<double> all(n * width);
      for (const auto& [i, v] : call.items) std::copy(v.begin(), v.end(), all.begin() + std::ptrdiff_t(i * width));
      return all;
    };
  }
  if (!o.shard.empty()) {
    if (this_job().size > 1) throw airr::input_error("--shard: not under mpirun or srun, whose ranks split the work");
    if (o.part.empty()) throw airr::input_error("--shard: give --part FILE for the shard's partial result");
    const airr::shard_index place = airr::parse_shard(o.shard, "--shard");
    return [&st, place](std::size_t n, std::size_t width, const airr::item_compute& compute) {
      // Other shards' items read as zeros (no valid layout, nothing seen) for the rest of the run,
      // whose outputs this shard does not write.
      std::vector<double> all(n * width, 0.0);
      std::vector<std::size_t> mine;
      for (std::size_t i = std::size_t(place.index); i < n; i += std::size_t(place.count)) mine.push_back(i);
      tbb::parallel_for(std::size_t(0), mine.size(),
                        [&](std::size_t k) { compute(mine[k], all.data() + mine[k] * width); });
      partial_batch call{n, width, {}};
      for (std::size_t i : mine)
        call.items[i] =
            std::vector<double>(all.begin() + std::ptrdiff_t(i * width), all.begin() + std::ptrdiff_t((i + 1) * width));
      st.calls.push_back(std::move(call));
      return all;
    };
  }
  return job_share(job_progress);
}

bool write_shard_part(const shard_options& o) {
  if (o.shard.empty() || state().replay) return false;
  partial_file p;
  p.airr_version = AIRR_VERSION;
  p.shard = o.shard;
  p.command = without_shard_options(state().command_line);
  p.directory = std::filesystem::current_path().string();
  p.inputs = input_fingerprints(p.command);
  p.batches = state().calls;
  airr::write_file_atomic(o.part, partial_text(p));
  std::fprintf(stderr, "wrote %s (shard %s: %zu batches of items)\n", o.part.c_str(), o.shard.c_str(),
               state().calls.size());
  return true;
}

bool are_partials(const std::vector<std::string>& paths) {
  if (paths.empty()) return false;
  std::ifstream in(paths.front());
  char c = 0;
  in >> c;
  return c == '{';
}

std::vector<std::string> merged_command_line(const std::vector<std::string>& paths) {
  std::vector<partial_file> parts;
  airr::shard_roll roll;
  for (const std::string& path : paths) {
    partial_file part = read_partial(path);
    if (!parts.empty()) {
      const partial_file& first = parts.front();
      const char* differs = part.airr_version != first.airr_version ? "airr_version"
                            : part.command != first.command         ? "command"
                            : part.directory != first.directory     ? "directory"
                            : part.inputs != first.inputs           ? "inputs"
                                                                    : nullptr;
      if (differs)
        throw airr::input_error(path + ": not a shard of the work " + paths.front() + " is a shard of (its " + differs +
                                " differs)");
      if (part.place.count != first.place.count)
        throw airr::input_error(path + ": split into " + std::to_string(part.place.count) + " shards, not " +
                                std::to_string(first.place.count));
      if (part.batches.size() != first.batches.size())
        throw airr::input_error(path + ": holds another number of batches");
    }
    roll.add(path, part.place);
    parts.push_back(std::move(part));
  }
  const int count = parts.front().place.count;
  roll.check_complete(count);
  const partial_file& first = parts.front();
  // The command line's paths are the shards' working directory's: the merge runs it there.
  std::error_code ec;
  std::filesystem::current_path(first.directory, ec);
  if (ec)
    throw airr::input_error(paths.front() + ": the shards ran in " + first.directory + ", which is not here (" +
                            ec.message() + ")");
  if (input_fingerprints(first.command) != first.inputs)
    throw airr::input_error(paths.front() + ": an input file changed since the shards ran");
  // Every batch's items from the shard that computed them.
  std::vector<partial_batch> calls(first.batches.size());
  for (std::size_t p = 0; p < parts.size(); ++p) {
    for (std::size_t k = 0; k < calls.size(); ++k) {
      const partial_batch& b = parts[p].batches[k];
      if (p > 0 && (b.n != calls[k].n || b.width != calls[k].width))
        throw airr::input_error(paths[p] + ": calls[" + std::to_string(k) + "]: another size than in " + paths.front());
      calls[k].n = b.n;
      calls[k].width = b.width;
      for (const auto& [i, v] : b.items) {
        if (i % std::size_t(count) != std::size_t(parts[p].place.index))
          throw airr::input_error(paths[p] + ": batch " + std::to_string(k) + " holds an item it should not");
        calls[k].items[i] = v;
      }
    }
  }
  for (std::size_t k = 0; k < calls.size(); ++k) {
    if (calls[k].items.size() != calls[k].n)
      throw airr::input_error("merge: batch " + std::to_string(k) + " lacks items (the shards ran other work)");
  }
  state().replay = std::move(calls);
  state().next_call = 0;
  return first.command;
}
