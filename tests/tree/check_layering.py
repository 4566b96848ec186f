#!/usr/bin/env python3
"""Fails when a room includes a header of a room above it, or a room has no README.

Each folder below is one room (a library, or a folder of a library or program); a file may include
the project headers of its own room and of those the table allows, and private headers of its own
folder. Library headers are named by their include path: `airr/NAME/...` (`airr/ui/ROOM/...` for the
designer's rooms); app/'s rooms include each other as `ROOM/...` from app/. The order is the one
docs/architecture.md draws: core -> models -> layout -> formats -> analysis | render -> measure ->
design -> ui (platform -> jobs -> studio -> views -> panels -> window) -> app (cluster -> cli ->
bench -> main; python). Every room has a README.md saying what lives there and what must not.
"""
import pathlib
import re
import sys
import tempfile

import tree_check

OPTICS = ["core", "models", "layout", "formats", "analysis"]
RENDER = ["core", "models", "layout", "formats", "render"]
MEASURE = OPTICS + ["render", "measure"]
DESIGN = MEASURE + ["design"]
UI_ROOMS = ["ui/platform", "ui/jobs", "ui/studio", "ui/views", "ui/panels", "ui/window"]


def stacked(base, rooms):
    """Each room of `rooms` may use `base` and the rooms before it."""
    return [(room, base + rooms[:i]) for i, room in enumerate(rooms)]


# Folder, its include name, and the include names it may use besides its own. A folder inside
# another comes first (render/measure before render).
LIBRARIES = [
    ("optics/core", "core", []),
    ("optics/models", "models", OPTICS[:1]),
    ("optics/layout", "layout", OPTICS[:2]),
    ("optics/formats", "formats", OPTICS[:3]),
    ("optics/analysis", "analysis", OPTICS[:4]),
    ("render/measure", "measure", MEASURE[:-1]),
    ("render/design", "design", DESIGN[:-1]),
    ("render", "render", RENDER[:-1]),
] + [(room, room, allowed) for room, allowed in stacked(DESIGN, UI_ROOMS)] + [
    ("app/cluster", "app/cluster", DESIGN),
    ("app/cli", "app/cli", DESIGN + ["app/cluster"]),
    ("app/bench", "app/bench", DESIGN + ["app/cluster", "app/cli"]),
    ("app/main", "app/main", DESIGN + UI_ROOMS + ["app/cluster", "app/cli", "app/bench"]),
    ("app/python", "app/python", DESIGN),
]
LIBRARY_INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]airr/(ui/[a-z_]+|[a-z_]+)/', re.M)
APP_INCLUDE = re.compile(r'^\s*#\s*include\s*"(cluster|cli|bench|main|python)/', re.M)


def library_of(path: str):
    for folder, name, allowed in LIBRARIES:
        if path.startswith(folder + "/"):
            return name, set(allowed) | {name}
    return None, None


def includes(text: str):
    yield from (m.group(1) for m in LIBRARY_INCLUDE.finditer(text))
    yield from ("app/" + m.group(1) for m in APP_INCLUDE.finditer(text))


def missing_readmes(root: pathlib.Path):
    """Rooms present in the tree without a README.md that says something."""
    bad = []
    for folder, _, _ in LIBRARIES:
        if not (root / folder).is_dir():
            continue
        readme = root / folder / "README.md"
        if not readme.is_file():
            bad.append(f"{folder}: no README.md saying what lives there and what must not")
            continue
        text = [p for p in re.split(r"\n\s*\n", readme.read_text()) if p.strip() and not p.startswith("#")]
        if not text:
            bad.append(f"{folder}/README.md: nothing below its title; a paragraph says what lives there")
    return bad


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
        for used in includes(f.read_text(errors="replace")):
            if used not in known:
                bad.append(f"{rel}: includes {used}/, which is no room")
            elif used not in allowed:
                bad.append(f"{rel}: {name} includes {used}/, a room above it")
    bad += missing_readmes(root)
    for line in bad:
        print(line, file=sys.stderr)
    if checked == 0:
        print(f"layering: no library file found under {root}", file=sys.stderr)
        return 1
    print(f"layering: {checked} files of {len(LIBRARIES)} rooms, {len(bad)} problems")
    return 1 if bad else 0


def self_test() -> None:
    """The check must catch an upward include (across libraries, ui rooms and app rooms) and a
    missing README, and pass downward includes."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for folder in ("optics/layout", "optics/models", "ui/views", "ui/jobs", "app/cli", "app/cluster"):
            (root / folder / "src").mkdir(parents=True)
            (root / folder / "README.md").write_text("# x\n\nWhat lives here, and what must not.\n")
        (root / "optics/layout/src/down.cpp").write_text('#include "airr/models/retro_model.hpp"\n')
        (root / "ui/views/src/down.cpp").write_text('#include "airr/ui/jobs/fit_job.hpp"\n')
        (root / "app/cli/down.cpp").write_text('#include "cluster/mpi_job.hpp"\n')
        if check(root) != 0:
            sys.exit("layering self-test: a downward include was refused")
        for up in (
            ("optics/models/src/up.cpp", '#include "airr/layout/scene.hpp"\n'),
            ("ui/jobs/src/up.cpp", '#include "airr/ui/views/views.hpp"\n'),
            ("app/cluster/up.cpp", '#include "cli/commands.hpp"\n'),
        ):
            path = root / up[0]
            path.write_text(up[1])
            if check(root) == 0:
                sys.exit(f"layering self-test: an upward include passed ({up[0]})")
            path.unlink()
        (root / "ui/jobs/README.md").unlink()
        if check(root) == 0:
            sys.exit("layering self-test: a room without a README passed")


if __name__ == "__main__":
    sys.exit(tree_check.run(check, self_test))
