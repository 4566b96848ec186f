#!/usr/bin/env bash
# Exports a layout with props as .glb and .gltf with `airr export-gltf`, exports the imported .glb
# again, exports the shipped kiosk (its display's chart embedded as a texture) as .glb and .gltf,
# and has the Khronos glTF-Validator judge all five and the tile sheet's shipped tile: no errors
# and no warnings.
set -euo pipefail
airr="$1"
source_dir="$2"
validator="$source_dir/tests/gltf_validator"
if [ ! -f "$validator/node_modules/gltf-validator/index.js" ]; then
  echo "the glTF-Validator is not installed: run packaging/setup.sh (npm ci --prefix tests/gltf_validator)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The default scene with two props: the shipped corner cube (a 1 m unit corner, scaled to 20 and
# 10 mm) as a diffuse block, and as a hidden mirror.
python3 - "$source_dir/assets" "$tmp/scene.json" <<'PY'
import json, sys
assets, out = sys.argv[1:3]
scene = json.load(open(f"{assets}/scenes/default.json"))
scene["source"]["image"] = f"{assets}/charts/test_chart.png"
cube = f"{assets}/models/corner_cube.gltf"
scene["props"] = [
    {"name": "block", "mesh": cube, "scale": 0.02, "surface": "diffuse", "albedo": [0.5, 0.4, 0.3],
     "pose": {"center_mm": [60, -140, 40], "yaw_deg": 30}},
    {"name": "shiny", "mesh": cube, "scale": 0.01, "surface": "mirror", "visible": False,
     "pose": {"center_mm": [-60, -140, 40]}},
]
json.dump(scene, open(out, "w"), indent=1)
PY
"$airr" export-gltf "$tmp/scene.json" -o "$tmp/layout.glb"
"$airr" export-gltf "$tmp/scene.json" -o "$tmp/layout.gltf"
"$airr" export-gltf "$tmp/layout.glb" -o "$tmp/again.glb"
"$airr" export-gltf "$source_dir/assets/scenes/two_sheet_kiosk.json" -o "$tmp/kiosk.glb"
"$airr" export-gltf "$source_dir/assets/scenes/two_sheet_kiosk.json" -o "$tmp/kiosk.gltf"
node "$validator/validate.mjs" --strict "$tmp/layout.glb" "$tmp/layout.gltf" "$tmp/again.glb" "$tmp/kiosk.glb" \
  "$tmp/kiosk.gltf" "$source_dir/assets/models/corner_cube_tile.gltf"
