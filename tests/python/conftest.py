"""The Python module's tests: `airr` imported from the build tree (PYTHONPATH), and the `airr`
program of the same build ($AIRR_CLI) for the results it must equal."""
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `airr ARGS`; returns (exit code, stdout, stderr)."""
    program = os.environ["AIRR_CLI"]

    def run(*args, cwd=None):
        p = subprocess.run([program, *map(str, args)], capture_output=True, text=True, cwd=cwd)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture
def small_scene():
    """The default scene at 64 x 48 pixels."""
    import airr

    scene = airr.Scene.load(airr.default_scene_path())
    scene.set("observer.width", 64)
    scene.set("observer.height", 48)
    return scene
