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

namespace {

constexpr const char* part_format = "airr-partial";

struct recorded_call {
  std::size_t n = 0, width = 0;
  std::map<std::size_t, std::vector<double>> items;
};

struct shard_state {
  std::vector<std::string> command_line;
  std::vector<recorded_call> calls;                  // a shard's own items, call by call
  std::optional<std::vector<recorded_call>> replay;  // a merge's items
  std::size_t next_call = 0;
};
shard_state& state() {
  static shard_state s;
  return s;
}

nlohmann::json number_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}
double json_number(const nlohmann::json& j, const std::string& where) {
  if (j.is_number()) return j.get<double>();
  if (j == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (j == "inf") return std::numeric_limits<double>::infinity();
  if (j == "-inf") return -std::numeric_limits<double>::infinity();
  throw airr::input_error(where + ": not a number");
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

struct partial {
  std::string path;
  airr::shard_index place;
  nlohmann::json j;
};

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
      const recorded_call& call = (*st.replay)[st.next_call++];
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
      recorded_call call{n, width, {}};
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
  const std::vector<std::string> command = without_shard_options(state().command_line);
  nlohmann::json j = {{"format", part_format},
                      {"version", 1},
                      {"airr_version", AIRR_VERSION},
                      {"shard", o.shard},
                      {"command", command},
                      {"directory", std::filesystem::current_path().string()},
                      {"inputs", input_fingerprints(command)}};
  nlohmann::json calls = nlohmann::json::array();
  for (const recorded_call& c : state().calls) {
    nlohmann::json items = nlohmann::json::array();
    for (const auto& [i, v] : c.items) {
      nlohmann::json item = nlohmann::json::array({i});
      for (double x : v) item.push_back(number_json(x));
      items.push_back(item);
    }
    calls.push_back({{"n", c.n}, {"width", c.width}, {"items", items}});
  }
  j["calls"] = calls;
  airr::write_file_atomic(o.part, j.dump() + "\n");
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
  std::vector<partial> parts;
  airr::shard_roll roll;
  for (const std::string& p : paths) {
    partial part{p, {}, {}};
    try {
      part.j = nlohmann::json::parse(airr::read_text_file(p));
    } catch (const nlohmann::json::exception& e) {
      throw airr::input_error(p + ": not a partial result (" + std::string(e.what()) + ")");
    }
    if (!part.j.is_object() || part.j.value("format", "") != part_format || part.j.value("version", 0) != 1)
      throw airr::input_error(p + ": not a partial result (format " + part_format + ", version 1)");
    part.place = airr::parse_shard(part.j.value("shard", ""), p + ": shard");
    if (!parts.empty()) {
      const nlohmann::json& first = parts.front().j;
      for (const char* key : {"airr_version", "command", "directory", "inputs"}) {
        if (part.j[key] != first[key])
          throw airr::input_error(p + ": not a shard of the work " + parts.front().path + " is a shard of (its " + key +
                                  " differs)");
      }
      if (part.place.count != parts.front().place.count)
        throw airr::input_error(p + ": split into " + std::to_string(part.place.count) + " shards, not " +
                                std::to_string(parts.front().place.count));
    }
    roll.add(p, part.place);
    parts.push_back(std::move(part));
  }
  const int count = parts.front().place.count;
  roll.check_complete(count);
  const nlohmann::json& first = parts.front().j;
  const std::vector<std::string> command = first.at("command").get<std::vector<std::string>>();
  // The command line's paths are the shards' working directory's: the merge runs it there.
  const std::string directory = first.value("directory", "");
  std::error_code ec;
  std::filesystem::current_path(directory, ec);
  if (ec)
    throw airr::input_error(parts.front().path + ": the shards ran in " + directory + ", which is not here (" +
                            ec.message() + ")");
  if (input_fingerprints(command) != first.at("inputs"))
    throw airr::input_error(parts.front().path + ": an input file changed since the shards ran");
  // Every call's items from the shard that computed them.
  std::vector<recorded_call> calls(first.at("calls").size());
  for (const partial& part : parts) {
    const nlohmann::json& pc = part.j.at("calls");
    if (pc.size() != calls.size()) throw airr::input_error(part.path + ": holds another number of batches");
    for (std::size_t k = 0; k < calls.size(); ++k) {
      calls[k].n = pc[k].at("n").get<std::size_t>();
      calls[k].width = pc[k].at("width").get<std::size_t>();
      for (const nlohmann::json& item : pc[k].at("items")) {
        const std::size_t i = item.at(0).get<std::size_t>();
        if (i >= calls[k].n || i % std::size_t(count) != std::size_t(part.place.index) ||
            item.size() != calls[k].width + 1)
          throw airr::input_error(part.path + ": batch " + std::to_string(k) + " holds an item it should not");
        std::vector<double> v;
        for (std::size_t x = 1; x < item.size(); ++x) v.push_back(json_number(item[x], part.path));
        calls[k].items[i] = std::move(v);
      }
    }
  }
  for (std::size_t k = 0; k < calls.size(); ++k) {
    if (calls[k].items.size() != calls[k].n)
      throw airr::input_error("merge: batch " + std::to_string(k) + " lacks items (the shards ran other work)");
  }
  state().replay = std::move(calls);
  state().next_call = 0;
  return command;
}
