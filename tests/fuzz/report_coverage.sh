#!/usr/bin/env bash
# Runs one target's corpus once (no fuzzing) and prints the coverage it reaches: libFuzzer's edge
# count, then per project source file the code edges covered, for files the corpus reaches at all.
# Usage: report_coverage.sh TARGET [BUILD_DIR]
set -euo pipefail
target=$1
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build=${2:-$source_dir/build-fuzz}
out=$(mktemp)
trap 'rm -f "$out"' EXIT
LSAN_OPTIONS="suppressions=$source_dir/tests/lsan_suppressions.txt" "$build/tests/fuzz_$target" "$build/corpus/$target" \
  -runs=0 -print_coverage=1 -rss_limit_mb=4096 -detect_leaks=0 >"$out" 2>&1 || true
grep -E "INITED" "$out" | sed -E 's/.*INITED (cov: [0-9]+ ft: [0-9]+ corp: [^ ]+).*/\1/'
# COVERED_FUNC: hits: H edges: C/T NAME FILE:LINE (UNCOVERED_FUNC lines count their edges as 0/T)
awk -v src="$source_dir/" '
  /^(UN)?COVERED_FUNC:/ {
    split($5, e, "/"); file = $NF; sub(/:[0-9]+$/, "", file)
    if (index(file, src) != 1 || index(file, src "tests/") == 1) next
    file = substr(file, length(src) + 1); covered[file] += e[1]; total[file] += e[2]
  }
  END { for (f in covered) if (covered[f] > 0) printf "%6d / %-6d edges  %s\n", covered[f], total[f], f }
' "$out" | sort -k5
