#!/usr/bin/env bash
# Writes a program's man page (gzipped, for share/man/man1) from its --help and --version with
# help2man; a program with subcommands gets each one's --help in a COMMANDS section.
# Both pages share the ENVIRONMENT and FILES sections in desktop/man-common.h2m.
# Usage: make-man.sh PROGRAM "one-line description" OUTPUT.1.gz
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
program=$1
description=$2
output=$3
# Run by name, so that the usage lines say "airr", not the build tree's path.
export PATH="$(cd "$(dirname "$program")" && pwd):$PATH"
program=$(basename "$program")
include=$(mktemp)
trap 'rm -f "$include"' EXIT
cat "$here/desktop/man-common.h2m" >"$include"

subcommands=$("$program" --help | awk '/^[A-Za-z]+:$/ { on = ($1 == "Subcommands:"); next } on && /^  [a-z]/ { print $1 }')
if [ -n "$subcommands" ]; then
  echo "[COMMANDS]" >>"$include"
  for command in $subcommands; do
    echo ".SS $command"
    echo ".nf"
    # Backslashes and leading dots are roff syntax: escape them.
    "$program" "$command" --help | sed -e 's/\\/\\e/g' -e 's/^\([.'"'"']\)/\\\&\1/'
    echo ".fi"
  done >>"$include"
fi
help2man --no-info --name="$description" --include="$include" "$program" | gzip -n -9 >"$output"
