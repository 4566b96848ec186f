#!/usr/bin/env bash
# Installs everything AIRR Studio needs to build, test, package and run, from Debian 12 packages.
# Idempotent: packages already present are left alone; safe to run repeatedly as root.
# --fuzz also installs clang and libFuzzer for the fuzz harnesses (tests/fuzz).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libembree-dev libtbb-dev libglm-dev
  libopenimageio-dev openimageio-tools libtinygltf-dev nlohmann-json3-dev libcli11-dev
  libopencv-dev libfftw3-dev libnlopt-cxx-dev openmpi-bin libopenmpi-dev
  libglfw3-dev libimgui-dev libgl-dev libgl1-mesa-dri xvfb xauth x11-xserver-utils fonts-dejavu-core
  libgtest-dev libgmock-dev clang-format python3
  python3-dev pybind11-dev python3-numpy python3-pytest blender
  libocct-data-exchange-dev libocct-modeling-algorithms-dev freecad
  librsvg2-bin help2man file desktop-file-utils procps slurm-wlm munge
)
if [ "${1:-}" = "--fuzz" ]; then packages+=(clang libclang-rt-14-dev); fi
# The Khronos glTF-Validator (npm) judges the glTF files the tests write; it needs Node.js.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed" >&2
else
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

validator="$(dirname "$0")/../tests/gltf_validator"
if [ ! -d "$validator/node_modules/gltf-validator" ]; then
  echo "setup: installing the glTF-Validator for the tests (npm)" >&2
  npm ci --prefix "$validator" --no-audit --no-fund --loglevel=error >&2
fi
