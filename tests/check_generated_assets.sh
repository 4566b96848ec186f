#!/usr/bin/env bash
# Regenerates the shipped generated assets into a temporary directory and compares them with the
# shipped ones: models and scenes (the default and the ideal bench) byte for byte, charts pixel for
# pixel, and the corner-cube shift table (at a reduced grid) by total-variation distance per
# incidence angle.
set -euo pipefail
airr="$1"
assets="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$airr" make-assets --dir "$tmp"
status=0
for f in models/panel.gltf models/corner_cube.gltf models/corner_cube_tile.gltf scenes/default.json scenes/ideal_bench.json; do
  if cmp -s "$tmp/$f" "$assets/$f"; then echo "same: $f"; else echo "DIFFERS: $f" >&2; diff "$tmp/$f" "$assets/$f" | head -20 >&2; status=1; fi
done
for f in charts/test_chart.png charts/slanted_edge.png; do
  if idiff -fail 0 -warn 0 "$tmp/$f" "$assets/$f" >/dev/null; then echo "same pixels: $f"; else echo "DIFFERS: $f" >&2; status=1; fi
done

"$airr" shift-table -o "$tmp/shift.json" --grid 300 --model "$assets/models/corner_cube.gltf" >/dev/null 2>&1
python3 - "$tmp/shift.json" "$assets/shift_tables/corner_cube.json" <<'PY' || status=1
import json, sys
new, old = (json.load(open(p)) for p in sys.argv[1:3])
assert new["theta_deg"] == old["theta_deg"], "angles differ"
worst = 0.0
for theta, a, b in zip(old["theta_deg"], new["probability"], old["probability"]):
    tv = 0.5 * sum(abs(x - y) for x, y in zip(a, b))
    worst = max(worst, tv)
    print(f"shift table theta {theta:4.0f}: total variation {tv:.4f}")
fractions = max(abs(x - y) for x, y in zip(new["retro_fraction"], old["retro_fraction"]))
print(f"retro fraction: largest difference {fractions:.5f}")
# A 300-ray grid against the shipped 1500-ray grid: sampling noise stays well under these limits.
if worst > 0.03 or fractions > 0.002:
    sys.exit("the regenerated shift table differs from the shipped one")
PY
exit $status
