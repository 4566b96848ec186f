#include "airr/models/shift_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/core/table_search.hpp"

namespace airr {

std::shared_ptr<const shift_table> cached_shift_table(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const shift_table>> cache;
  std::lock_guard lock(mutex);
  auto& entry = cache[path];
  if (!entry) entry = std::make_shared<const shift_table>(load_shift_table(path));
  return entry;
}

namespace {

constexpr const char* format_name = "airr-shift-table";
constexpr int format_version = 1;
constexpr double row_sum_tolerance = 1e-6;

// Index of the bin whose cumulative range holds u (cumulative values end at exactly 1).
int bin_from_cdf(const std::vector<double>& cdf, double u) {
  const std::size_t above = first_greater(cdf.data(), cdf.size(), u);
  if (above < cdf.size()) return int(above);
  // u >= 1: the last bin with any probability.
  const auto first_full = std::lower_bound(cdf.begin(), cdf.end(), cdf.back());
  return int(first_full - cdf.begin());
}

}  // namespace

void finalize_shift_table(shift_table& table) {
  const std::size_t bins = table.probability.empty() ? 0 : table.probability[0].size();
  std::vector<std::vector<double>> cdf;
  cdf.reserve(table.probability.size());
  for (const auto& row : table.probability) {
    if (row.size() != bins || bins == 0)
      throw std::invalid_argument("shift table: rows must have the same, non-zero length");
    std::vector<double> c(bins);
    double sum = 0;
    for (std::size_t b = 0; b < bins; ++b) c[b] = sum += row[b];
    if (!(sum > 0)) throw std::invalid_argument("shift table: a row has no probability");
    for (double& v : c) v /= sum;  // sum / sum is exactly 1, so the last entries end at 1
    cdf.push_back(std::move(c));
  }
  table.cdf = std::move(cdf);
}

shift_table load_shift_table(const std::string& path) {
  const nlohmann::json j = read_json_file(path);
  json_reader r(j, path, "");

  std::string format;
  r.require("format");
  r.string("format", format);
  if (format != format_name) r.fail("format", "must be \"" + std::string(format_name) + "\", not \"" + format + "\"");
  int version = 0;
  r.require("version");
  r.integer("version", version);
  if (version != format_version) r.fail("version", "unsupported version " + std::to_string(version) + " (expected 1)");

  shift_table t;
  r.require("s_max");
  r.number("s_max", t.s_max);
  if (!(t.s_max > 0)) r.fail("s_max", "must be positive");
  long long bins = 0;
  r.require("bins");
  r.integer("bins", bins);
  if (bins < 1 || bins > 1000000) r.fail("bins", "must be between 1 and 1000000");

  t.theta_deg = r.number_array("theta_deg");
  if (t.theta_deg.empty()) r.fail("theta_deg", "must not be empty");
  for (std::size_t i = 0; i < t.theta_deg.size(); ++i) {
    if (t.theta_deg[i] < 0 || t.theta_deg[i] >= 90)
      r.fail("theta_deg[" + std::to_string(i) + "]", "must be in [0, 90)");
    if (i > 0 && !(t.theta_deg[i] > t.theta_deg[i - 1])) {
      r.fail("theta_deg[" + std::to_string(i) + "]", "angles must be strictly ascending");
    }
  }
  const std::size_t rows = t.theta_deg.size();

  r.require("probability");
  const auto& pj = r.raw("probability");
  if (!pj.is_array() || pj.size() != rows) {
    r.fail("probability", "must be an array of " + std::to_string(rows) + " rows (one per theta_deg)");
  }
  for (std::size_t i = 0; i < rows; ++i) {
    const std::string where = "probability[" + std::to_string(i) + "]";
    if (!pj[i].is_array() || pj[i].size() != std::size_t(bins)) {
      r.fail(where, "must be an array of " + std::to_string(bins) + " numbers (bins)");
    }
    std::vector<double> row;
    row.reserve(std::size_t(bins));
    double sum = 0;
    for (std::size_t b = 0; b < std::size_t(bins); ++b) {
      const std::string cell = where + "[" + std::to_string(b) + "]";
      if (!pj[i][b].is_number()) r.fail(cell, "must be a number");
      const double v = pj[i][b].get<double>();
      if (!std::isfinite(v)) r.fail(cell, "must be finite");
      if (v < 0) r.fail(cell, "must not be negative");
      row.push_back(v);
      sum += v;
    }
    if (std::abs(sum - 1.0) > row_sum_tolerance) r.fail(where, "sums to " + number_text(sum, 9) + ", not 1");
    t.probability.push_back(std::move(row));
  }

  t.retro_fraction = r.number_array("retro_fraction");
  if (t.retro_fraction.size() != rows) {
    r.fail("retro_fraction", "must have " + std::to_string(rows) + " entries (one per theta_deg), not " +
                                 std::to_string(t.retro_fraction.size()));
  }
  for (std::size_t i = 0; i < rows; ++i) {
    if (t.retro_fraction[i] < 0 || t.retro_fraction[i] > 1) {
      r.fail("retro_fraction[" + std::to_string(i) + "]", "must be in [0, 1]");
    }
  }

  r.require("provenance");
  t.provenance = r.raw("provenance");
  if (!t.provenance.is_object()) r.fail("provenance", "must be a JSON object");
  r.finish();
  finalize_shift_table(t);
  return t;
}

void save_shift_table(const shift_table& table, const std::string& path) {
  // One histogram per line keeps the file readable and its diffs small.
  auto array_line = [](const std::vector<double>& v) { return nlohmann::json(v).dump(); };
  std::ostringstream out;
  out << "{\n";
  out << "  \"format\": \"" << format_name << "\",\n";
  out << "  \"version\": " << format_version << ",\n";
  out << "  \"s_max\": " << nlohmann::json(table.s_max).dump() << ",\n";
  out << "  \"bins\": " << table.bins() << ",\n";
  out << "  \"theta_deg\": " << array_line(table.theta_deg) << ",\n";
  out << "  \"probability\": [\n";
  for (std::size_t i = 0; i < table.probability.size(); ++i) {
    out << "    " << array_line(table.probability[i]) << (i + 1 < table.probability.size() ? ",\n" : "\n");
  }
  out << "  ],\n";
  out << "  \"retro_fraction\": " << array_line(table.retro_fraction) << ",\n";
  const nlohmann::json provenance = table.provenance.is_object() ? table.provenance : nlohmann::json::object();
  std::string prov = provenance.dump(2);
  for (std::size_t p = prov.find('\n'); p != std::string::npos; p = prov.find('\n', p + 1)) prov.insert(p + 1, "  ");
  out << "  \"provenance\": " << prov << "\n";
  out << "}\n";
  write_file_atomic(path, out.str());
}

std::string default_shift_table_path() { return asset_dir() + "/shift_tables/corner_cube.json"; }

shift_rows shift_rows_at(const shift_table& table, double theta_deg) {
  const auto& theta = table.theta_deg;
  if (theta.empty() || table.probability.size() != theta.size()) {
    throw std::logic_error("sample_shift: the shift table is empty or inconsistent");
  }
  if (table.cdf.size() != table.probability.size()) {
    throw std::logic_error("sample_shift: the shift table has no CDF (call finalize_shift_table)");
  }
  shift_rows rows;
  if (theta_deg >= theta.back()) {
    rows.lower = rows.upper = theta.size() - 1;
  } else if (theta_deg > theta.front()) {
    const std::size_t k = std::size_t(std::upper_bound(theta.begin(), theta.end(), theta_deg) - theta.begin()) - 1;
    rows = {k, k + 1, (theta_deg - theta[k]) / (theta[k + 1] - theta[k])};
  }
  return rows;
}

double sample_shift(const shift_table& table, double theta_deg, double u_pick, double u_bin, double u_jitter) {
  return sample_shift(table, shift_rows_at(table, theta_deg), u_pick, u_bin, u_jitter);
}

double sample_shift(const shift_table& table, const shift_rows& rows, double u_pick, double u_bin, double u_jitter) {
  return shift_in_row(table, rows.picked(u_pick), u_bin, u_jitter);
}

double shift_in_row(const shift_table& table, std::size_t row, double u_bin, double u_jitter) {
  const int bin = bin_from_cdf(table.cdf[row], std::max(u_bin, 0.0));
  const double width = table.s_max / double(table.probability[row].size());
  return (double(bin) + std::clamp(u_jitter, 0.0, 1.0)) * width;
}

}  // namespace airr
