#!/usr/bin/env bash
# The designer's soak run under Xvfb (airr-studio --soak): for SECONDS (default 600; an hour by
# hand: check_soak.sh STUDIO 3600) it cycles through drags, preset and model changes, fits, zone
# passes and optimisations opened and cancelled, undo and redo, saves and reopens, sampling the
# process once a cycle. After the first minute, none of its resident memory, open descriptors and
# threads may grow beyond its bound: 25% and 100 MB more memory than at one minute, 4 more
# descriptors, 4 more threads.
# Usage: check_soak.sh STUDIO [SECONDS]
set -euo pipefail
studio=$1
seconds=${2:-600}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_CONFIG_HOME=$dir/config XDG_STATE_HOME=$dir/state XDG_CACHE_HOME=$dir/cache
xvfb-run -a -s "-screen 0 1600x1000x24" "$studio" --soak "$seconds" --soak-log "$dir/soak.csv" --threads 2
python3 - "$dir/soak.csv" <<'PY'
import csv, sys
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(sys.argv[1]))]
after = [r for r in rows if r["seconds"] >= 60]
if len(after) < 2:
    sys.exit(f"soak: {len(rows)} samples, too few past the first minute")
base = after[0]
bounds = {"resident_mb": base["resident_mb"] * 1.25 + 100, "descriptors": base["descriptors"] + 4,
          "threads": base["threads"] + 4}
failed = False
for key, bound in bounds.items():
    worst = max(after, key=lambda r: r[key])
    print(f"{key}: start {rows[0][key]:g}, after 1 minute {base[key]:g}, end {rows[-1][key]:g}, "
          f"most {worst[key]:g} (at {worst['seconds']:g} s), bound {bound:g}")
    if worst[key] > bound:
        failed = True
print(f"{len(rows)} cycles in {rows[-1]['seconds']:g} s; the curve (seconds: resident MB, descriptors, threads):")
step = max(1, len(rows) // 10)
print("  " + "; ".join(f"{r['seconds']:.0f}: {r['resident_mb']:.0f}, {r['descriptors']:g}, {r['threads']:g}"
                       for r in rows[::step] + ([rows[-1]] if (len(rows) - 1) % step else [])))
sys.exit(1 if failed else 0)
PY
