#!/usr/bin/env python3
"""Fails when a text file of the tree, outside third_party, is longer than 500 lines.

Files are those git tracks (or, outside a git work tree, every file under the given root); binary
files (images, models, fuzz inputs) are skipped.
"""
import pathlib
import subprocess
import sys
import tempfile

import tree_check

LIMIT = 500


def tracked_files(root: pathlib.Path):
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True, check=True).stdout
        return [root / p for p in out.decode().split("\0") if p]
    except (subprocess.CalledProcessError, FileNotFoundError):
        return [p for p in root.rglob("*") if p.is_file() and ".git" not in p.parts and "build" not in p.parts]


def check(root: pathlib.Path) -> int:
    long_files, counted = [], 0
    for f in tracked_files(root):
        rel = f.relative_to(root).as_posix()
        if rel.startswith("third_party/") or not f.is_file():
            continue
        data = f.read_bytes()
        if b"\0" in data[:8192]:
            continue  # binary
        counted += 1
        lines = data.count(b"\n") + (0 if data.endswith(b"\n") or not data else 1)
        if lines > LIMIT:
            long_files.append(f"{rel}: {lines} lines (the limit is {LIMIT}); split it by concept")
    for line in long_files:
        print(line, file=sys.stderr)
    print(f"file length: {counted} text files, {len(long_files)} over {LIMIT} lines")
    return 1 if long_files else 0


def self_test() -> None:
    """The check must catch a file of 501 lines, pass one of 500, and leave third_party alone."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "third_party").mkdir()
        (root / "third_party/big.cpp").write_text("x\n" * 900)
        (root / "ok.cpp").write_text("x\n" * LIMIT)
        if check(root) != 0:
            sys.exit("file length self-test: a file at the limit was refused")
        (root / "long.cpp").write_text("x\n" * (LIMIT + 1))
        if check(root) == 0:
            sys.exit("file length self-test: a file over the limit passed")


if __name__ == "__main__":
    sys.exit(tree_check.run(check, self_test))
