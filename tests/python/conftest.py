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


def ctrl_c_latency(seconds, call):
    """Sends SIGINT to this process after `seconds` while `call()` runs, which must end in
    KeyboardInterrupt; returns the time from the signal to that."""
    import signal
    import threading
    import time

    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Timer(seconds, interrupt).start()
    with pytest.raises(KeyboardInterrupt):
        call()
    return time.monotonic() - sent[0]


def cpu_seconds_while_idle(seconds=0.5):
    """The process's CPU time over `seconds` of sleep: near 0 when no work of it runs on."""
    import time

    before = time.process_time()
    time.sleep(seconds)
    return time.process_time() - before
