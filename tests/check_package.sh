#!/usr/bin/env bash
# Builds the Debian package with CPack and checks it: its control fields (the version the programs
# print, dependencies computed by dpkg-shlibdeps), its files (dpkg-deb --info and --contents), the
# menu entry (desktop-file-validate), the MIME type it opens, and the man pages.
set -euo pipefail
build_dir=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

(cd "$tmp" && cpack --config "$build_dir/CPackConfig.cmake" -B "$tmp/out" >cpack.log 2>&1) ||
  fail "cpack: $(cat "$tmp/cpack.log")"
debs=("$tmp"/out/*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || fail "cpack made no single .deb: ${debs[*]}"
deb=${debs[0]}
dpkg-deb --info "$deb" | tee "$tmp/info.txt"
dpkg-deb --contents "$deb" | awk '{ print $6 }' | tee "$tmp/contents.txt"

field() { dpkg-deb --field "$deb" "$1"; }
[ "$(field Package)" = airr-studio ] || fail "package name '$(field Package)'"
version=$("$build_dir/app/airr" --version)
[ "$(field Version)" = "${version#airr }" ] || fail "package version '$(field Version)', programs print '$version'"
depends=$(field Depends)
for lib in libc6 libstdc++6 libembree3 libglfw3 libopenimageio libtbb libopencv-core libgl1 python3-numpy; do
  grep -q "$lib" <<<"$depends" || fail "Depends lacks $lib (shlibdeps?): $depends"
done

for f in ./usr/bin/airr ./usr/bin/airr-studio ./usr/share/airr-studio/scenes/default.json \
  ./usr/share/airr-studio/scenes/ideal_bench.json \
  ./usr/share/airr-studio/presets/rf-an.json ./usr/share/airr-studio/presets/rf-ay.json \
  ./usr/share/airr-studio/shift_tables/corner_cube.json ./usr/share/applications/airr-studio.desktop \
  ./usr/share/mime/packages/airr-studio.xml ./usr/share/icons/hicolor/scalable/apps/airr-studio.svg \
  ./usr/share/man/man1/airr.1.gz ./usr/share/man/man1/airr-studio.1.gz ./usr/share/airr-studio/slurm/airr-array.sbatch \
  ./usr/share/airr-studio/blender/airr_studio_addon.py; do
  grep -qxF "$f" "$tmp/contents.txt" || fail "the package lacks $f"
done
for size in 16 22 24 32 48 64 128 256 512; do
  grep -qxF "./usr/share/icons/hicolor/${size}x${size}/apps/airr-studio.png" "$tmp/contents.txt" ||
    fail "the package lacks the ${size}x${size} icon"
done

dpkg-deb -x "$deb" "$tmp/root"
# The Python module: Debian's python3 imports it from the package's files and nothing else.
grep -qxF ./usr/lib/python3/dist-packages/airr/__init__.py "$tmp/contents.txt" || fail "the package lacks the Python module"
grep -q '^./usr/lib/python3/dist-packages/airr/_airr\..*\.so$' "$tmp/contents.txt" || fail "the package lacks airr/_airr*.so"
# (A sanitizer build's module needs its runtime preloaded into Python, AIRR_PYTHON_PRELOAD, and the
# interpreter keeps its objects at exit: no leaks are looked for there.)
(cd "$tmp" && env -u AIRR_ASSETS LD_PRELOAD="${AIRR_PYTHON_PRELOAD:-}" ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" \
  PYTHONPATH="$tmp/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  'import airr, sys; s = airr.Scene.load(airr.default_scene_path()); assert airr.asset_dir().startswith(sys.argv[1]), airr.asset_dir(); print("import airr from the package:", airr.__version__, s.get("tilt_deg"))' \
  "$tmp/root/usr/share/airr-studio") || fail "python3 cannot import airr from the package"
desktop-file-validate "$tmp/root/usr/share/applications/airr-studio.desktop" || fail "desktop-file-validate"
# The menu entry opens the scene files' MIME type, which the MIME package defines.
python3 - "$tmp/root/usr/share/applications/airr-studio.desktop" "$tmp/root/usr/share/mime/packages/airr-studio.xml" <<'PY'
import sys, xml.etree.ElementTree as ET
desktop, mime = sys.argv[1:3]
types = next(l for l in open(desktop) if l.startswith("MimeType=")).strip().split("=", 1)[1].split(";")
ns = {"m": "http://www.freedesktop.org/standards/shared-mime-info"}
defined = ET.parse(mime).getroot().find("m:mime-type", ns)
assert defined.get("type") in types, (defined.get("type"), types)
assert any(g.get("pattern") == "*.airr.json" for g in defined.findall("m:glob", ns))
PY
for page in airr airr-studio; do
  text=$(zcat "$tmp/root/usr/share/man/man1/$page.1.gz")
  grep -q "^\.TH \"\?$(tr a-z A-Z <<<"$page")" <<<"$text" || fail "$page.1 has no title"
  grep -q "^\.SH OPTIONS" <<<"$text" && grep -qF '\-\-version' <<<"$text" || fail "$page.1 lacks the options"
done
zcat "$tmp/root/usr/share/man/man1/airr.1.gz" | grep -q '^\.SS render' || fail "airr.1 lacks the render command"
echo "package: $(basename "$deb"), $(stat -c %s "$deb") bytes"
