#include "airr/core/csv_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"

namespace airr {

int csv_table::column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : int(it - header.begin());
}

std::string csv_table::where(std::size_t row) const { return path + ": line " + std::to_string(line_numbers.at(row)); }

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream s(line);
  while (std::getline(s, field, ',')) {
    const auto a = field.find_first_not_of(" \t\r"), b = field.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : field.substr(a, b - a + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string csv_quoted(const std::string& field) {
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

csv_table read_csv_table(const std::string& path) {
  csv_table t;
  t.path = path;
  std::istringstream in(read_text_file(path));
  std::string line;
  int line_no = 0;
  while (t.header.empty() && std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") != std::string::npos) t.header = split_csv_line(line);
  }
  if (t.header.empty()) throw input_error(path + ": empty CSV (expected a header row of column names)");
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = split_csv_line(line);
    const std::string where = path + ": line " + std::to_string(line_no);
    if (fields.size() != t.header.size())
      throw input_error(where + ": " + std::to_string(fields.size()) + " fields, the header has " +
                        std::to_string(t.header.size()));
    std::vector<double> row;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (f.empty() || end != f.c_str() + f.size())
        throw input_error(where + ": " + t.header[c] + ": '" + f + "' is not a number");
      if (!std::isfinite(v)) throw input_error(where + ": " + t.header[c] + ": '" + f + "' is not a finite number");
      row.push_back(v);
    }
    t.rows.push_back(std::move(row));
    t.line_numbers.push_back(line_no);
  }
  return t;
}

}  // namespace airr
