#!/usr/bin/env bash
# Fuzzes one loader for a bounded time in a clang tree built with AIRR_FUZZ (default build-fuzz/,
# configured and built here when needed), from the corpus kept in that tree and the seeds named in
# tests/fuzz/seeds.txt. A crash, leak, timeout or out-of-memory input is kept in
# tests/fuzz/regressions/<target>/ for the ordinary suite to replay; the run then fails.
# Usage: run_fuzz.sh TARGET SECONDS [BUILD_DIR]
set -euo pipefail
target=$1
seconds=$2
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build=${3:-$source_dir/build-fuzz}
if ! command -v clang++ >/dev/null || [ -z "$(ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a 2>/dev/null)" ]; then
  echo "fuzzing needs clang and libFuzzer: bash packaging/setup.sh --fuzz" >&2
  exit 2
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$source_dir" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAIRR_FUZZ=ON >/dev/null
fi
# Under ctest the tree is built already (and another fuzz test may be running beside this one).
if [ ! -x "$build/tests/fuzz_$target" ] || [ -z "${AIRR_FUZZ_BUILT:-}" ]; then
  cmake --build "$build" -j2 --target "fuzz_$target" >/dev/null
fi

corpus=$build/corpus/$target
mkdir -p "$corpus"
found=0
while read -r t where extension; do
  [ "$t" = "$target" ] || continue
  found=1
  if [ -d "$source_dir/$where" ]; then
    find "$source_dir/$where" -maxdepth 1 -type f -name "*${extension:-}" -exec cp {} "$corpus"/ \;
  else
    cp "$source_dir/$where" "$corpus"/
  fi
done < <(grep -v '^#' "$source_dir/tests/fuzz/seeds.txt")
[ "$found" = 1 ] || { echo "no seeds for $target in tests/fuzz/seeds.txt" >&2; exit 2; }

regressions=$source_dir/tests/fuzz/regressions/$target
mkdir -p "$regressions"
kept_before=$(ls "$regressions")
# OpenImageIO keeps the text of each refused file's error (a few bytes), so libFuzzer would scan the
# heap for leaks after almost every image input; the ordinary suite (under asan) checks leaks there.
leaks=1
[ "$target" = image ] && leaks=0
# Sanitizer reports go to files: while an image is read, the loader sends stderr elsewhere.
logs=$build/fuzz-logs/$target.$$  # this run's own: runs of one target may go side by side
rm -rf "$logs"
mkdir -p "$logs"
# The process prints its figures: executions (stat::number_of_executed_units) and coverage (cov:).
ASAN_OPTIONS="log_path=$logs/report" UBSAN_OPTIONS="log_path=$logs/report" \
  LSAN_OPTIONS="suppressions=$source_dir/tests/lsan_suppressions.txt" "$build/tests/fuzz_$target" "$corpus" \
  -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -max_len=262144 -detect_leaks=$leaks -artifact_prefix="$regressions/" \
  -print_final_stats=1 2>&1 | grep -E "^(#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|==[0-9]+==ERROR|SUMMARY|artifact)" || true
# libFuzzer names what it keeps crash-*, leak-*, timeout-*, oom-* or slow-unit-*.
new=$(comm -13 <(echo "$kept_before") <(ls "$regressions"))
if [ -n "$new" ]; then
  echo "findings kept in $regressions: $new" >&2
  cat "$logs"/report.* >&2 2>/dev/null || true
  exit 1
fi
