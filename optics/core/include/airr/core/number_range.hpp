#pragma once
// Ranges typed on the command line as "start:end:step": evenly spaced values from start to end.
#include <string>
#include <vector>

namespace airr {

struct number_range {
  double start = 0, end = 0, step = 1;
};

// Parses "start:end:step" (start <= end, step > 0, at most `max_points` values). Throws
// input_error "<where>: <problem>", e.g. "--focus -20:x:2: end 'x' is not a number".
number_range parse_number_range(const std::string& text, const std::string& where, int max_points);

// start, start + step, ... up to end (end kept when a step lands on it up to rounding).
std::vector<double> range_values(const number_range& r);

}  // namespace airr
