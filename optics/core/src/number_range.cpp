#include "airr/core/number_range.hpp"

#include <cmath>
#include <stdexcept>

#include "airr/core/error.hpp"

namespace airr {

static double parse_number(const std::string& text, const std::string& where, const char* what) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw input_error(where + ": " + what + " '" + text + "' is not a number");
  return v;
}

static int point_count(const number_range& r) { return int(std::floor((r.end - r.start) / r.step + 1e-9)) + 1; }

number_range parse_number_range(const std::string& text, const std::string& where, int max_points) {
  const auto c1 = text.find(':'), c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  if (c2 == std::string::npos || text.find(':', c2 + 1) != std::string::npos)
    throw input_error(where + ": expected start:end:step");
  number_range r;
  r.start = parse_number(text.substr(0, c1), where, "start");
  r.end = parse_number(text.substr(c1 + 1, c2 - c1 - 1), where, "end");
  r.step = parse_number(text.substr(c2 + 1), where, "step");
  if (r.start > r.end) throw input_error(where + ": start is above end");
  if (!(r.step > 0)) throw input_error(where + ": step must be positive");
  // Counted in doubles first: a huge range must not overflow the count.
  if (std::floor((r.end - r.start) / r.step + 1e-9) + 1 > max_points)
    throw input_error(where + ": more than " + std::to_string(max_points) + " points");
  return r;
}

std::vector<double> range_values(const number_range& r) {
  // A small tolerance keeps the end point when start + k * step lands on it up to rounding.
  std::vector<double> v;
  for (int i = 0, n = point_count(r); i < n; ++i) v.push_back(r.start + i * r.step);
  return v;
}

}  // namespace airr
