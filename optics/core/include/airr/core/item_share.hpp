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

}  // namespace airr
