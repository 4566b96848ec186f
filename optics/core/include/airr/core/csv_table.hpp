#pragma once
// Numeric CSV files: a header row of column names, then rows of finite numbers. Errors name the
// file, the line and the column.
#include <string>
#include <vector>

namespace airr {

struct csv_table {
  std::string path;
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<int> line_numbers;  // of each row, for messages

  // Index of a column, or -1.
  int column(const std::string& name) const;
  // "<path>: line <n>" for row i.
  std::string where(std::size_t row) const;
};

// Splits one line at commas, trimming blanks around each field.
std::vector<std::string> split_csv_line(const std::string& line);

// A text field as a CSV file holds it: in double quotes, each quote doubled.
std::string csv_quoted(const std::string& field);

// Reads a file; blank lines are skipped. Throws input_error for a missing or empty file, a row
// whose field count differs from the header's, or a field that is not a finite number.
csv_table read_csv_table(const std::string& path);

}  // namespace airr
