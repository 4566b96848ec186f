#!/usr/bin/env bash
# Installs what is needed, builds, and runs the whole test suite (but the `slow` label: the suite
# under AddressSanitizer, and `long`: the designer's soak run). Arguments go to ctest instead:
# `-L slow` runs the slow tests, `-L long` the soak run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2
if [ $# -eq 0 ]; then set -- -LE "slow|long"; fi
cd build && ctest --output-on-failure -j2 "$@"
