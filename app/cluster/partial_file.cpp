#include "cluster/partial_file.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"

namespace {

constexpr const char* format_name = "airr-partial";

nlohmann::json number_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

// A whole number in [lo, hi], or the reader's error naming `field`.
std::size_t whole_number(const airr::json_reader& r, const nlohmann::json& j, const std::string& field, std::size_t lo,
                         std::size_t hi) {
  if (!j.is_number_integer()) r.fail(field, "must be a whole number");
  if (j.is_number_integer() && !j.is_number_unsigned() && j.get<std::int64_t>() < 0)
    r.fail(field, "must not be negative (is " + std::to_string(j.get<std::int64_t>()) + ")");
  const std::uint64_t v = j.get<std::uint64_t>();
  if (v < lo || v > hi)
    r.fail(field, "must be " + std::to_string(lo) + " to " + std::to_string(hi) + " (is " + std::to_string(v) + ")");
  return std::size_t(v);
}

double item_number(const airr::json_reader& r, const nlohmann::json& j, const std::string& field) {
  if (j.is_number()) return j.get<double>();
  if (j == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (j == "inf") return std::numeric_limits<double>::infinity();
  if (j == "-inf") return -std::numeric_limits<double>::infinity();
  r.fail(field, "must be a number (or \"nan\", \"inf\", \"-inf\")");
}

// The value of a key that must be present.
const nlohmann::json& required(airr::json_reader& r, const std::string& key) {
  r.require(key);
  return r.raw(key);
}

partial_batch read_batch(airr::json_reader& b, std::size_t file_bytes) {
  partial_batch batch;
  batch.n = whole_number(b, required(b, "n"), b.field("n"), 0, max_partial_items);
  batch.width = whole_number(b, required(b, "width"), b.field("width"), 1, max_partial_width);
  // Each number of an item takes a character of the file at least.
  if (batch.width > file_bytes) b.fail(b.field("width"), "more numbers per item than the file holds");
  const nlohmann::json& items = required(b, "items");
  if (!items.is_array()) b.fail(b.field("items"), "must be an array of items");
  if (items.size() > batch.n)
    b.fail(b.field("items"),
           "holds " + std::to_string(items.size()) + " items, more than the batch's " + std::to_string(batch.n));
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::string where = b.field("items") + "[" + std::to_string(k) + "]";
    const nlohmann::json& item = items[k];
    if (!item.is_array() || item.size() != batch.width + 1)
      b.fail(where, "must be an array of the item's index and its " + std::to_string(batch.width) + " numbers");
    const std::size_t i = whole_number(b, item[0], where + "[0]", 0, batch.n - 1);
    if (batch.items.count(i)) b.fail(where, "item " + std::to_string(i) + " appears twice");
    std::vector<double> v(batch.width);
    for (std::size_t x = 0; x < batch.width; ++x)
      v[x] = item_number(b, item[x + 1], where + "[" + std::to_string(x + 1) + "]");
    batch.items[i] = std::move(v);
  }
  b.finish();
  return batch;
}

}  // namespace

std::string partial_text(const partial_file& p) {
  nlohmann::json batches = nlohmann::json::array();
  for (const partial_batch& c : p.batches) {
    nlohmann::json items = nlohmann::json::array();
    for (const auto& [i, v] : c.items) {
      nlohmann::json item = nlohmann::json::array({i});
      for (double x : v) item.push_back(number_json(x));
      items.push_back(item);
    }
    batches.push_back({{"n", c.n}, {"width", c.width}, {"items", items}});
  }
  const nlohmann::json j = {{"format", format_name}, {"version", 1},         {"airr_version", p.airr_version},
                            {"shard", p.shard},      {"command", p.command}, {"directory", p.directory},
                            {"inputs", p.inputs},    {"calls", batches}};
  return j.dump() + "\n";
}

partial_file read_partial(const std::string& path) {
  const std::string text = airr::read_text_file(path);
  const nlohmann::json j = airr::parse_json(text, path);
  if (!j.is_object() || !j.contains("format") || j["format"] != format_name)
    throw airr::input_error(path + ": not a partial result (format " + format_name + ", version 1)");
  airr::json_reader r(j, path, "");
  partial_file p;
  r.raw("format");
  const nlohmann::json& version = required(r, "version");
  if (version != 1) r.fail("version", "must be 1 (this build reads version 1 of " + std::string(format_name) + ")");
  p.airr_version = r.string("airr_version");
  p.shard = r.string("shard");
  p.place = airr::parse_shard(p.shard, path + ": shard");
  const nlohmann::json& command = required(r, "command");
  if (!command.is_array() || command.empty()) r.fail("command", "must be a non-empty array of the command's words");
  for (std::size_t k = 0; k < command.size(); ++k) {
    if (!command[k].is_string()) r.fail("command[" + std::to_string(k) + "]", "must be a string");
    p.command.push_back(command[k].get<std::string>());
  }
  p.directory = r.string("directory");
  p.inputs = required(r, "inputs");
  if (!p.inputs.is_object()) r.fail("inputs", "must be an object of file names and hashes");
  for (const auto& [name, hash] : p.inputs.items()) {
    if (!hash.is_string()) r.fail("inputs." + name, "must be a string");
  }
  const nlohmann::json& calls = required(r, "calls");
  if (!calls.is_array()) r.fail("calls", "must be an array of batches");
  for (std::size_t k = 0; k < calls.size(); ++k) {
    airr::json_reader b(calls[k], path, "calls[" + std::to_string(k) + "]");
    p.batches.push_back(read_batch(b, text.size()));
  }
  r.finish();
  return p;
}
