#pragma once
// The processes of an MPI job when `airr` runs under mpirun or srun (a build with AIRR_MPI), or
// this process alone. MPI starts only under a launcher, so `airr` alone never needs one.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "airr/core/item_share.hpp"
#include "airr/formats/image.hpp"

struct mpi_job {
  int rank = 0;
  int size = 1;
  bool root() const { return rank == 0; }
};

// This process's place in its job (MPI initialised on first call when launched by mpirun or srun,
// and finalised at exit).
const mpi_job& this_job();

// The job's item_share (airr/core/item_share.hpp): item i computed by rank i % size, on its
// threads, and every rank given all n x width numbers, in item order. The ranks take their items in
// 20 rounds and count the job's finished items after each, for rank 0's `progress(done, n)`.
std::vector<double> share_items(std::size_t n, std::size_t width, const airr::item_compute& compute,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

// share_items as an item_share when this process is one rank of several; else empty (the items
// then run on this machine's cores).
airr::item_share job_share(const std::function<void(std::size_t, std::size_t)>& progress = {});

// Where this rank keeps files that rank 0 writes to `folder` and the command reads back (a fit's
// data): `folder` itself on rank 0 (and alone), else a temporary folder of its own, removed when
// this ends, so the job writes the user's files once.
class rank_folder {
 public:
  explicit rank_folder(const std::string& folder);
  ~rank_folder();
  rank_folder(const rank_folder&) = delete;
  rank_folder& operator=(const rank_folder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool temporary_ = false;
};

// The smallest of the ranks' values, on every rank (every rank must call it).
std::uint64_t job_min(std::uint64_t mine);

// Every rank's floats at rank 0, in rank order (the other ranks get nothing back).
std::vector<float> gather_floats(const std::vector<float>& mine);

// The whole image at rank 0, from each rank's rows [first_row, end_row) of its `whole`-sized
// image (the ranks' rows in rank order, together every row); the other ranks get an empty image.
airr::image_rgb gather_rows(const airr::image_rgb& whole, int first_row, int end_row);

// Ends every rank of the job with `code`: one rank's error must not leave the others waiting.
[[noreturn]] void abort_job(int code);
