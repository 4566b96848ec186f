#!/bin/bash
# Renders the reference images with an older build's airr (issue 53's baseline: 96af0ca).
# Usage: make.sh OLD_AIRR ASSETS_DIR (the older tree's assets; the scenes are unchanged since).
set -euo pipefail
airr=$1
assets=$2
out=$(dirname "$0")
size=(--set observer.width=64 --set observer.height=64)
render() {  # NAME SCENE SPP [--set ...]
  local name=$1 scene=$2 spp=$3
  shift 3
  for i in 1 2; do
    "$airr" render "$assets/scenes/$scene" -o "$out/$name.tmp.exr" --spp "$spp" --seed $((100 + i)) "${size[@]}" "$@"
    # Half floats: a fraction of the noise at these counts, and a quarter of the bytes.
    oiiotool "$out/$name.tmp.exr" -d half --compression zip -o "$out/${name}_$i.exr"
    rm "$out/$name.tmp.exr"
  done
}
render default default.json 8192
render kiosk two_sheet_kiosk.json 8192
render prism_sheet default.json 4096 --set retroreflectors.0.model.type=prism_sheet
