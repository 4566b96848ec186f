#!/usr/bin/env bash
# The Blender add-on (packaging/blender) in Debian's blender, in background mode: a layout exported
# by `airr export-gltf`, its AIRR roles stripped, gets them back through the add-on, whose render
# of the scene equals `airr render` of the GLB Blender exported, pixel for pixel.
# Arguments: the airr program, the source tree, the folder holding the built airr package.
set -euo pipefail
airr="$1"
source_dir="$2"
package_dir="$3"
command -v blender >/dev/null || { echo "blender is not installed (packaging/setup.sh installs it)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export HOME=$tmp/home PYTHONDONTWRITEBYTECODE=1
mkdir -p "$HOME"

"$airr" export-gltf "$source_dir/assets/scenes/default.json" -o "$tmp/source.glb" >/dev/null 2>&1
blender -b --factory-startup --python-exit-code 1 --python "$source_dir/tests/blender/addon_in_blender.py" -- \
  "$source_dir/packaging/blender/airr_studio_addon.py" "$package_dir" "$tmp/source.glb" "$tmp" >"$tmp/blender.log" 2>&1 ||
  { cat "$tmp/blender.log"; echo "FAIL: the add-on's run in blender"; exit 1; }
grep "roles set\|aerial image" "$tmp/blender.log"

"$airr" render "$tmp/blender.glb" -o "$tmp/cli.exr" --spp 4 --seed 3 --set observer.width=64 --set observer.height=48 \
  2>"$tmp/render.log" || { cat "$tmp/render.log"; exit 1; }
PYTHONPATH="$package_dir" /usr/bin/python3 - "$tmp" <<'PY'
import sys
import numpy as np
import airr
tmp = sys.argv[1]
addon = np.load(f"{tmp}/addon.npy")
cli = airr.read_image(f"{tmp}/cli.exr")["pixels"]
assert addon.shape == cli.shape, (addon.shape, cli.shape)
assert cli.max() > 0, "an empty render"
assert np.array_equal(addon, cli), f"the add-on's image differs: max |difference| {np.abs(addon - cli).max()}"
print(f"the add-on's image equals airr render of the GLB Blender exported ({cli.shape[1]} x {cli.shape[0]})")
PY
