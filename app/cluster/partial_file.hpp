#pragma once
// The airr-partial file (format "airr-partial", version 1) a shard of numbered-item work writes
// (--shard i/N --part FILE) and `airr merge` reads back: the command line without its shard
// options, the build, the working directory, the input files' hashes, and the shard's items of
// each batch of the command's work. Reading checks every field it uses: a bad file is one
// input_error "<file>: <field>: <problem>".
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "airr/render/render_shards.hpp"

// One batch of a command's items (one call of its item_share): item i's `width` numbers.
struct partial_batch {
  std::size_t n = 0, width = 0;
  std::map<std::size_t, std::vector<double>> items;
};

struct partial_file {
  std::string airr_version;
  std::string shard;  // "i/N"
  airr::shard_index place;
  std::vector<std::string> command;
  std::string directory;
  nlohmann::json inputs;  // file name to content hash
  std::vector<partial_batch> batches;
};

// Limits a partial's sizes are held to (docs/scaling.md): items per batch, numbers per item.
inline constexpr std::size_t max_partial_items = 10'000'000, max_partial_width = 65'536;

std::string partial_text(const partial_file& p);

// Reads and checks a partial: its format and version, each field's type, the shard, every
// batch's sizes (within the limits, and no more numbers than the file can hold) and every item
// (index below the batch's size, `width` numbers or "nan", "inf", "-inf").
partial_file read_partial(const std::string& path);
