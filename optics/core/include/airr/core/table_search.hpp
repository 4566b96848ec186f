#pragma once
// Searches of ascending tables in the samplers' inner loops (a discrete distribution's cumulative
// table): std::upper_bound's answer without its unpredictable branches.
#include <cstddef>

namespace airr {

// The index of the first of data[0 .. n) greater than x (n when none is), data ascending. The
// candidates halve by a conditional move, not a branch: the samplers' draws are random, so a
// branch on each comparison is mispredicted half the time.
inline std::size_t first_greater(const double* data, std::size_t n, double x) {
  if (n == 0) return 0;
  const double* first = data;
  std::size_t len = n;
  // The answer stays within [first, first + len].
  while (len > 1) {
    const std::size_t half = len / 2;
    first = first[half - 1] <= x ? first + half : first;
    len -= half;
  }
  return std::size_t(first - data) + (*first <= x ? 1 : 0);
}

}  // namespace airr
