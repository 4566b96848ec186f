#!/usr/bin/env bash
# Builds the threads stress test (tests/stress_threads.cpp) with ThreadSanitizer in its own build tree and runs it; any
# TSan report fails the test (halt_on_error).
set -euo pipefail
src="$1"
build="$2"
cmake -S "$src" -B "$build" -DAIRR_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target stress_threads -j2 >/dev/null
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$src/tests/tsan_suppressions.txt" "$build/tests/stress_threads" 10000
