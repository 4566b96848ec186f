#!/usr/bin/env bash
# Fuzzes one loader for a bounded time, from seeds out of the shipped assets, in a clang tree built
# with AIRR_FUZZ (build-fuzz/, made here when missing). A crash input is kept in
# tests/fuzz/regressions/<target>/ for the ordinary suite to replay; the run then fails.
# Usage: run_fuzz.sh TARGET SECONDS [SOURCE_DIR]
set -euo pipefail
target=$1
seconds=$2
source_dir=$(cd "${3:-$(dirname "$0")/../..}" && pwd)
build=$source_dir/build-fuzz
if ! command -v clang++ >/dev/null || [ -z "$(ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a 2>/dev/null)" ]; then
  echo "fuzzing needs clang and libFuzzer: apt-get install clang libclang-rt-14-dev" >&2
  exit 2
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$source_dir" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAIRR_FUZZ=ON >/dev/null
fi
cmake --build "$build" -j2 --target "fuzz_$target" >/dev/null

assets=$source_dir/assets
case $target in
  scene_json) seeds=("$assets"/scenes/*.json "$assets"/fit_example/setup.json) ;;
  gltf) seeds=("$assets"/models/*.gltf) ;;
  preset) seeds=("$assets"/presets/*.json) ;;
  shift_table) seeds=("$assets"/shift_tables/*.json) ;;
  fit_json) seeds=("$assets"/fit_example/fit.json) ;;
  csv) seeds=("$assets"/fit_example/*.csv "$assets"/displays/*.csv) ;;
  image) seeds=("$assets"/charts/*.png "$assets"/fit_example/white_00.exr) ;;
  *) echo "unknown target $target" >&2; exit 2 ;;
esac
corpus=$source_dir/build-fuzz/corpus/$target
mkdir -p "$corpus"
cp "${seeds[@]}" "$corpus"/
regressions=$source_dir/tests/fuzz/regressions/$target
mkdir -p "$regressions"
LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz/lsan.supp" "$build/tests/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 \
  -max_len=262144 -artifact_prefix="$regressions/" -print_final_stats=1 2>&1 | grep -E "^(#[0-9]+ +DONE|stat::|==|SUMMARY|artifact)" || true
# libFuzzer writes crash-*, leak-*, timeout-*, oom-* into the regressions folder.
if ls "$regressions"/{crash,leak,timeout,oom}-* >/dev/null 2>&1; then
  echo "findings kept in $regressions" >&2
  exit 1
fi
