"""What the tree checks share: each proves on a made-up tree that it catches what it looks for
(quietly), then checks the tree given on the command line (default: the current folder)."""
import contextlib
import io
import pathlib
import sys


def run(check, self_test) -> int:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        self_test()  # exits with its reason when the check misses what it should catch
    return check(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "."))
