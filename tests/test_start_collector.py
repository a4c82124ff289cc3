"""mcar's start-up imports leave no work to Python's cyclic garbage collector: where mcar
is the program, the objects they make are frozen before the collector goes back on, so no
pass over them runs (cli/main.py). Real processes, each told of every pass."""

from __future__ import annotations

import subprocess
import sys

from conftest import clean_environ

# Writes one line on stderr at the start of every collection, then runs mcar's main() as
# the console script does, under the program name given.
_RUN = """
import gc, os, sys
gc.callbacks.append(lambda phase, info: phase == "start" and os.write(
    2, b"collector pass, generation %d\\n" % info["generation"]))
sys.argv = [sys.argv[1], *sys.argv[2:]]
from mobile_car.cli.main import main
main()
"""


def _passes(cwd, program: str, *args: str) -> list[str]:
    # Not in the checkout: `-c` puts the working folder first on the module path.
    done = subprocess.run([sys.executable, "-c", _RUN, program, *args], cwd=cwd,
                          capture_output=True, text=True, timeout=120, env=clean_environ())
    assert done.returncode == 0, done.stderr
    return [line for line in done.stderr.splitlines() if line.startswith("collector pass")]


def test_a_check_of_the_car_runs_no_collector_pass(tmp_path):
    car = tmp_path / "car.urdf"
    car.write_text('<robot name="r"><link name="base_link"/></robot>\n')
    assert _passes(tmp_path, "/usr/local/bin/mcar", "check", str(car)) == []
    # The control: imported by another program (a test run), nothing is frozen, and the
    # first objects of the run set off a pass over the imports' objects.
    assert _passes(tmp_path, "/usr/bin/other", "check", str(car))[:1] == [
        "collector pass, generation 0"]
