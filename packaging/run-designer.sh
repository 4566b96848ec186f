#!/usr/bin/env bash
# Installs what is needed, builds, and shows the default scene: the designer window when there
# is a display, otherwise a render of the default scene written to a file.
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j2
if [ -x build/app/airr-studio ] && [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec build/app/airr-studio assets/scenes/default.json
fi
mkdir -p out
build/app/airr render assets/scenes/default.json -o out/default.png --spp 64
echo "No display: rendered the default scene to $(pwd)/out/default.png"
