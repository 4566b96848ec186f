#!/usr/bin/env bash
# Fails when a C++ file of the tree is not formatted by the project's .clang-format.
set -euo pipefail
src="$1"
cd "$src"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- '*.cpp' '*.hpp' '*.h')
else
  mapfile -t files < <(find app optics render ui tests -name '*.cpp' -o -name '*.hpp' -o -name '*.h')
fi
present=()
for f in "${files[@]}"; do [ -f "$f" ] && present+=("$f"); done
# One clang-format for all files (one a file spends most of its time starting up); each place it
# would change is reported as "FILE:LINE:COL: error: code should be clang-formatted".
report=$(clang-format --dry-run -Werror "${present[@]}" 2>&1) && status=0 || status=$?
mapfile -t bad < <(printf '%s\n' "$report" | sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: .*/\1/p' | sort -u)
if [ ${#bad[@]} -gt 0 ]; then
  printf 'not formatted (run: clang-format -i FILE):\n' >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  printf 'clang-format failed:\n%s\n' "$report" >&2
  exit 1
fi
echo "format: ${#present[@]} files formatted"
