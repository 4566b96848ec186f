#!/usr/bin/env bash
# The unit, render, designer (gui) and Python suites built with AddressSanitizer +
# UndefinedBehaviorSanitizer (the asan preset: build-asan/) and run with both halting on their
# first report, so any report fails.
# Usage: run_asan_suite.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"
cmake --preset asan >/dev/null
cmake --build --preset asan >/dev/null
ctest --preset asan -L "unit|render|gui|python"
