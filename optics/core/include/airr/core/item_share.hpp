#pragma once
// Work split into numbered items of a fixed count of numbers each, for whoever runs them: by
// default this machine's cores; in an MPI job (app/mpi_job.hpp) the ranks, each taking its share.
// Every caller gets every item's numbers, in item order, so each rank goes on the same.
#include <cstddef>
#include <functional>
#include <vector>

namespace airr {

// compute(i, out) writes item i's `width` numbers to out[0 .. width).
using item_compute = std::function<void(std::size_t i, double* out)>;
// Runs items 0 to n - 1 and returns their n x width numbers in item order.
using item_share = std::function<std::vector<double>(std::size_t n, std::size_t width, const item_compute& compute)>;

// The items through `share`, or without one here, one after another in item order, `after_each(i)`
// called after item i (for progress and cancelling).
inline std::vector<double> run_items(const item_share& share, std::size_t n, std::size_t width,
                                     const item_compute& compute,
                                     const std::function<void(std::size_t i)>& after_each = {}) {
  if (share) return share(n, width, compute);
  std::vector<double> all(n * width);
  for (std::size_t i = 0; i < n; ++i) {
    compute(i, all.data() + i * width);
    if (after_each) after_each(i);
  }
  return all;
}

}  // namespace airr
