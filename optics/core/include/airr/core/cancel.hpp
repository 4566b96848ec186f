#pragma once
// A long computation's stop request: a flag the caller may set from another thread (the designer's
// next edit, Ctrl+C in Python), polled between pieces of work; none given, nothing stops it.
#include <atomic>

namespace airr {

inline bool cancel_requested(const std::atomic<bool>* cancel) {
  return cancel && cancel->load(std::memory_order_relaxed);
}

}  // namespace airr
