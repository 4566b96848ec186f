#pragma once
// Runs body(y0, y1) over rows [0, rows) on `threads` workers (0: all cores). TBB normally; the
// ThreadSanitizer build uses std::thread, because TSan cannot see the synchronisation inside the
// uninstrumented TBB library and would report its hand-overs as races.
#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#ifndef AIRR_PLAIN_THREADS
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

namespace airr::detail {

// body(y0, y1) over rows [0, rows) on `threads` threads started for the loop (0: one per core),
// at the caller's priority.
template <class Body>
void plain_parallel_rows(int rows, int threads, const Body& body) {
  // No more threads than rows: a loop of one row (a bin's kernels from one block) starts one.
  const int n = std::min(rows, threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())));
  std::atomic<int> next{0};
  std::exception_ptr failure;  // the first body's exception, thrown here as TBB would
  std::atomic<bool> failed{false};
  std::vector<std::thread> workers;
  for (int t = 0; t < n; ++t) {
    workers.emplace_back([&] {
      try {
        for (int y; !failed && (y = next.fetch_add(1)) < rows;) body(y, y + 1);
      } catch (...) {
        if (!failed.exchange(true)) failure = std::current_exception();
      }
    });
  }
  for (auto& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
}

template <class Body>
void parallel_rows(int rows, int threads, const Body& body) {
#ifdef AIRR_PLAIN_THREADS
  plain_parallel_rows(rows, threads, body);
#else
  // Isolated: while it waits, the calling thread runs only this loop's rows, never a long task of
  // other work sharing the pool (the tracer's waves beside the model image's bins).
  auto run = [&] {
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, rows, 1),
                        [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    });
  };
  if (threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(run);
  } else {
    run();
  }
#endif
}

// Which workers a loop runs on: the pool's (parallel_rows), or threads of its own
// (plain_parallel_rows): a loop that must not wait on the pool's threads when a background render
// has lowered their priority (a starved worker holding rows it stole would hold the loop up).
struct row_workers {
  int threads = 0;  // 0: all cores
  bool own = false;
};

template <class Body>
void parallel_rows(int rows, row_workers w, const Body& body) {
  if (w.own && w.threads != 1)
    plain_parallel_rows(rows, w.threads, body);
  else
    parallel_rows(rows, w.threads, body);
}

}  // namespace airr::detail
