#!/usr/bin/env python3
"""Fails when a library includes a header of a library above it.

Each folder below is one library; a file may include the project headers (airr/NAME/...) of its
own library and of those the table allows, and private headers of its own folder. The order is the
one docs/architecture.md draws: core -> models -> layout -> formats -> analysis | render ->
measure -> ui -> app.
"""
import pathlib
import re
import sys
import tempfile

import tree_check

# Library folder, its include name, and the include names it may use besides its own.
LIBRARIES = [
    ("optics/core", "core", []),
    ("optics/models", "models", ["core"]),
    ("optics/layout", "layout", ["core", "models"]),
    ("optics/formats", "formats", ["core", "models", "layout"]),
    ("optics/analysis", "analysis", ["core", "models", "layout", "formats"]),
    ("render/measure", "measure", ["core", "models", "layout", "formats", "analysis", "render"]),
    ("render", "render", ["core", "models", "layout", "formats"]),
    ("ui", "ui", ["core", "models", "layout", "formats", "analysis", "render", "measure"]),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]airr/([a-z_]+)/', re.M)


def library_of(path: str):
    for folder, name, allowed in LIBRARIES:  # render/measure before render
        if path.startswith(folder + "/"):
            return name, set(allowed) | {name}
    return None, None


def check(root: pathlib.Path) -> int:
    known = {name for _, name, _ in LIBRARIES}
    bad, checked = [], 0
    for f in sorted(root.rglob("*")):
        if f.suffix not in (".cpp", ".hpp", ".h") or not f.is_file():
            continue
        rel = f.relative_to(root).as_posix()
        name, allowed = library_of(rel)
        if name is None:
            continue
        checked += 1
        for m in INCLUDE.finditer(f.read_text(errors="replace")):
            used = m.group(1)
            if used not in known:
                bad.append(f"{rel}: includes airr/{used}/, which is no library")
            elif used not in allowed:
                bad.append(f"{rel}: {name} includes airr/{used}/, a library above it")
    for line in bad:
        print(line, file=sys.stderr)
    if checked == 0:
        print(f"layering: no library file found under {root}", file=sys.stderr)
        return 1
    print(f"layering: {checked} files of {len(LIBRARIES)} libraries, {len(bad)} wrong includes")
    return 1 if bad else 0


def self_test() -> None:
    """The check must catch an upward include and pass a downward one."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "optics/layout/src").mkdir(parents=True)
        (root / "optics/models/src").mkdir(parents=True)
        (root / "optics/layout/src/down.cpp").write_text('#include "airr/models/retro_model.hpp"\n')
        if check(root) != 0:
            sys.exit("layering self-test: a downward include was refused")
        (root / "optics/models/src/up.cpp").write_text('#include "airr/layout/scene.hpp"\n')
        if check(root) == 0:
            sys.exit("layering self-test: an upward include passed")


if __name__ == "__main__":
    sys.exit(tree_check.run(check, self_test))
