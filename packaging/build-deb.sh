#!/usr/bin/env bash
# Installs what is needed, builds, and makes the Debian package of both programs with CPack.
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2
(cd build && cpack -G DEB >/dev/null)
deb=$(ls -t build/airr-studio_*.deb | head -n 1)
echo "Built $(pwd)/$deb; install it with: sudo apt install $(pwd)/$deb"
