#!/usr/bin/env bash
# Installs AIRR Studio into a temporary prefix and moves the prefix elsewhere (the programs find
# their assets relative to themselves). Then, from an unrelated directory with a fresh home and no
# AIRR_ASSETS: renders a scene saved there, runs `airr psf` with a preset by name and on the shipped
# scenes, and starts airr-studio under Xvfb for a screenshot. Nothing may be written into the
# prefix; the designer's settings go under the XDG directories; without its share/ the installed
# program names where it looked for the assets (it never falls back to the source tree).
set -euo pipefail
build_dir=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cmake --install "$build_dir" --prefix "$tmp/staging" >/dev/null
mv "$tmp/staging" "$tmp/moved-prefix"
prefix=$tmp/moved-prefix
for f in bin/airr bin/airr-studio share/airr-studio/scenes/default.json share/airr-studio/scenes/ideal_bench.json \
  share/airr-studio/presets/rf-ay.json \
  share/airr-studio/charts/test_chart.png share/applications/airr-studio.desktop \
  share/mime/packages/airr-studio.xml share/icons/hicolor/scalable/apps/airr-studio.svg \
  share/icons/hicolor/16x16/apps/airr-studio.png share/icons/hicolor/256x256/apps/airr-studio.png \
  share/man/man1/airr.1.gz share/man/man1/airr-studio.1.gz; do
  [ -f "$prefix/$f" ] || fail "the install lacks $f"
done
listing() { (cd "$prefix" && find . -printf '%p %s %T@\n' | sort); }
listing >"$tmp/prefix-before.txt"

unset AIRR_ASSETS
export HOME=$tmp/home XDG_CONFIG_HOME=$tmp/home/config XDG_STATE_HOME=$tmp/home/state
mkdir -p "$tmp/designs" "$HOME"
cd "$tmp/designs"

# A scene saved in an unrelated directory: the shipped default with its chart beside it and the
# sheet's model from a shipped preset, by name.
cp "$prefix/share/airr-studio/charts/test_chart.png" chart.png
python3 - "$prefix/share/airr-studio/scenes/default.json" bench.airr.json <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["source"]["image"] = "chart.png"
scene["observer"]["width"], scene["observer"]["height"] = 96, 64
scene["retroreflectors"][0]["model"] = {"type": "sinc_shift", "preset": "rf-ay"}
json.dump(scene, open(sys.argv[2], "w"), indent=2)
PY
"$prefix/bin/airr" render bench.airr.json -o render.png --spp 4 >/dev/null
[ -s render.png ] || fail "airr render wrote no image"

"$prefix/bin/airr" psf bench.airr.json --samples 20000 -o psf.csv
rows=$(tail -n +2 psf.csv | wc -l)
[ "$rows" -ge 50 ] || fail "airr psf wrote $rows rows"
# The shipped scenes as installed: the default's sheet names its preset (RF-Ay) by name.
for s in default ideal_bench; do
  "$prefix/bin/airr" psf "$prefix/share/airr-studio/scenes/$s.json" --samples 2000 -o psf.csv >/dev/null ||
    fail "airr psf on the installed scenes/$s.json failed"
done
# A preset name that is not shipped is refused, naming the installed presets' folder.
if "$prefix/bin/airr" psf bench.airr.json --set retroreflectors.0.model.preset=no-such-sheet -o x.csv 2>err.txt; then
  fail "an unknown preset was accepted"
fi
grep -q "$prefix/share/airr-studio/presets" err.txt || fail "the error does not name the installed presets: $(cat err.txt)"

xvfb-run -a -s "-screen 0 1280x800x24" "$prefix/bin/airr-studio" bench.airr.json --frames 10 --screenshot shot.png \
  >studio.log 2>&1 || fail "airr-studio failed: $(cat studio.log)"
[ "$(stat -c %s shot.png)" -gt 20000 ] || fail "the screenshot is (nearly) empty"
# What the designer kept (its window layout) is under the XDG directories, and nothing else of it
# is anywhere in the home or here.
[ -f "$XDG_CONFIG_HOME/airr-studio/imgui.ini" ] || fail "no window layout under XDG_CONFIG_HOME"
stray=$(find "$HOME" . -type f ! -path "$XDG_CONFIG_HOME/*" ! -path "$XDG_STATE_HOME/*" \
  ! -name 'shot.png*' ! -name '*.log' ! -name 'psf.csv' ! -name 'render.png' ! -name 'err.txt' \
  ! -name 'chart.png' ! -name 'bench.airr.json')
[ -z "$stray" ] || fail "files written outside the XDG directories: $stray"
if [ -n "${AIRR_INSTALL_SHOT:-}" ]; then cp shot.png "$AIRR_INSTALL_SHOT"; fi

v1=$("$prefix/bin/airr" --version)
v2=$("$prefix/bin/airr-studio" --version)
[ "${v1#airr }" = "${v2#airr-studio }" ] || fail "versions differ: '$v1' and '$v2'"
[[ "$v1" =~ ^airr\ [0-9]+\.[0-9]+\.[0-9]+ ]] || fail "airr --version printed '$v1'"

# The Python module from the moved prefix alone (PYTHONPATH into it): it renders the scene saved
# here with the prefix's assets, as the installed `airr` renders it. (A sanitizer build's module
# needs its runtime preloaded into Python, AIRR_PYTHON_PRELOAD, and the interpreter keeps its
# objects at exit: no leaks are looked for there.)
"$prefix/bin/airr" render bench.airr.json -o render.exr --spp 2 --seed 5 >/dev/null 2>&1
LD_PRELOAD="${AIRR_PYTHON_PRELOAD:-}" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" PYTHONPATH="$prefix/lib/python3/dist-packages" PYTHONDONTWRITEBYTECODE=1 \
  /usr/bin/python3 - "$prefix" <<'PY' ||
import sys, numpy, airr
prefix = sys.argv[1]
assert airr.__file__.startswith(prefix), airr.__file__
assert airr.asset_dir().startswith(prefix + "/share/airr-studio"), airr.asset_dir()
image = airr.render(airr.Scene.load("bench.airr.json"), spp=2, seed=5)
assert numpy.array_equal(image, airr.read_image("render.exr")["pixels"]), "the module's render differs from airr's"
print("import airr from the prefix:", airr.__version__)
PY
  fail "python3 cannot import and run airr from the prefix"
rm render.exr
listing >"$tmp/prefix-after.txt"
diff "$tmp/prefix-before.txt" "$tmp/prefix-after.txt" >&2 || fail "something was written into the prefix"

# Without its assets the installed program says where it looked, and that is in the prefix.
mv "$prefix/share/airr-studio" "$tmp/assets-away"
if "$prefix/bin/airr" psf bench.airr.json -o x.csv 2>err.txt; then
  fail "the installed airr found assets without its share/ folder"
fi
grep -q "$prefix/share/airr-studio" err.txt || fail "the error does not name the prefix: $(cat err.txt)"
echo "installed, moved and ran: $v1"
