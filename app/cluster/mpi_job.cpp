#include "cluster/mpi_job.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include <unistd.h>

#include <tbb/parallel_for.h>

#ifdef AIRR_WITH_MPI
#include <mpi.h>
#endif

namespace {

// Whether an MPI launcher started this process: Open MPI's mpirun, or srun with PMI or PMIx.
bool launched_by_mpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(var)) return true;
  return false;
}

}  // namespace

const mpi_job& this_job() {
  static const mpi_job job = [] {
    mpi_job j;
#ifdef AIRR_WITH_MPI
    if (launched_by_mpi()) {
      MPI_Init(nullptr, nullptr);
      std::atexit([] { MPI_Finalize(); });
      MPI_Comm_rank(MPI_COMM_WORLD, &j.rank);
      MPI_Comm_size(MPI_COMM_WORLD, &j.size);
    }
#else
    (void)launched_by_mpi;
#endif
    return j;
  }();
  return job;
}

std::vector<float> gather_floats(const std::vector<float>& mine) {
  const mpi_job& job = this_job();
  if (job.size == 1) return mine;
#ifdef AIRR_WITH_MPI
  const int count = int(mine.size());
  std::vector<int> counts(job.root() ? job.size : 0), offsets(counts.size());
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<float> all;
  if (job.root()) {
    std::size_t total = 0;
    for (int r = 0; r < job.size; ++r) {
      offsets[std::size_t(r)] = int(total);
      total += std::size_t(counts[std::size_t(r)]);
    }
    all.resize(total);
  }
  MPI_Gatherv(mine.data(), count, MPI_FLOAT, all.data(), counts.data(), offsets.data(), MPI_FLOAT, 0, MPI_COMM_WORLD);
  return all;
#else
  throw std::logic_error("an MPI job in a build without MPI");
#endif
}

std::uint64_t job_min(std::uint64_t mine) {
  if (this_job().size == 1) return mine;
#ifdef AIRR_WITH_MPI
  unsigned long long v = mine, least = 0;
  MPI_Allreduce(&v, &least, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
  return least;
#else
  throw std::logic_error("an MPI job in a build without MPI");
#endif
}

std::vector<double> share_items(std::size_t n, std::size_t width, const airr::item_compute& compute,
                                const std::function<void(std::size_t, std::size_t)>& progress) {
  const mpi_job& job = this_job();
  const std::size_t ranks = std::size_t(job.size), rank = std::size_t(job.rank);
  const auto items_of = [&](std::size_t r) { return r < n ? (n - r + ranks - 1) / ranks : 0; };
  std::vector<double> mine(items_of(rank) * width);
  // The same rounds on every rank (rank 0 has the most items), each ended by counting the job's.
  const std::size_t rounds = 20, slice = (items_of(0) + rounds - 1) / rounds;
  for (std::size_t round = 0; round < rounds; ++round) {
    const std::size_t first = std::min(items_of(rank), round * slice), end = std::min(items_of(rank), first + slice);
    tbb::parallel_for(first, end, [&](std::size_t k) { compute(rank + k * ranks, mine.data() + k * width); });
    if (ranks == 1) {
      if (progress) progress(end, n);
      continue;
    }
#ifdef AIRR_WITH_MPI
    unsigned long long done = end, total = 0;
    MPI_Allreduce(&done, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (progress && job.root()) progress(std::size_t(total), n);
#endif
  }
  if (ranks == 1) return mine;
#ifdef AIRR_WITH_MPI
  std::vector<int> counts(ranks), offsets(ranks);
  for (std::size_t r = 0, at = 0; r < ranks; at += counts[r], ++r) {
    counts[r] = int(items_of(r) * width);
    offsets[r] = int(at);
  }
  std::vector<double> by_rank(n * width), all(n * width);
  MPI_Allgatherv(mine.data(), int(mine.size()), MPI_DOUBLE, by_rank.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD);
  for (std::size_t i = 0; i < n; ++i) {
    const double* from = by_rank.data() + std::size_t(offsets[i % ranks]) + (i / ranks) * width;
    std::copy(from, from + width, all.data() + i * width);
  }
  return all;
#else
  throw std::logic_error("an MPI job in a build without MPI");
#endif
}

airr::item_share job_share(const std::function<void(std::size_t, std::size_t)>& progress) {
  if (this_job().size == 1) return {};
  return [progress](std::size_t n, std::size_t width, const airr::item_compute& compute) {
    return share_items(n, width, compute, progress);
  };
}

rank_folder::rank_folder(const std::string& folder) : path_(folder) {
  const mpi_job& job = this_job();
  if (job.root()) return;
  const auto dir = std::filesystem::temp_directory_path() /
                   ("airr-rank-" + std::to_string(job.rank) + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  path_ = dir.string();
  temporary_ = true;
}

rank_folder::~rank_folder() {
  std::error_code ignored;
  if (temporary_) std::filesystem::remove_all(path_, ignored);
}

airr::image_rgb gather_rows(const airr::image_rgb& whole, int first_row, int end_row) {
  airr::image_rgb out;
  out.rgb = gather_floats(airr::image_rows(whole, first_row, end_row).rgb);
  if (!this_job().root()) return {};
  if (out.rgb.size() != whole.rgb.size()) throw std::logic_error("the ranks' rows do not make up the image");
  out.width = whole.width;
  out.height = whole.height;
  return out;
}

void abort_job(int code) {
#ifdef AIRR_WITH_MPI
  if (this_job().size > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}
