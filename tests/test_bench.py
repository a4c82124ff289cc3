"""`bench/run.py` (what `make bench` runs) works: a quick section writes its table.

Timings are not asserted (they belong to the benchmark, not to tests); what is checked is
that the runner measures real, successful runs of both tools and compares their outputs.
"""

from __future__ import annotations

import re
import subprocess
import sys

from conftest import REPO


def test_quick_build_section_writes_a_table_of_real_runs(tmp_path, mcar_bin):
    output = tmp_path / "bench.md"
    done = subprocess.run([sys.executable, str(REPO / "bench" / "run.py"), "--quick", "build",
                           "-o", str(output)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    text = output.read_text(encoding="utf-8")
    assert text.startswith("# Benchmarks\n")
    assert "## `mcar build` vs `xacro`" in text
    rows = [line for line in text.splitlines() if line.startswith("| ") and " ms |" in line]
    assert [row.split(" | ")[0] for row in rows] == [
        "| complete robot (mobile_robot.xacro)", "| tutorial car (tutorial/04_xacro.xacro)",
        "| 500 macro calls (generated)"]
    for row in rows:
        cells = row.strip("| ").split(" | ")
        # Both tools ran and exited 0 (a failure would show "(exit N)" next to the time),
        # their URDFs are the same, and a ratio was computed from the two medians.
        assert re.fullmatch(r"[\d.]+ ms", cells[1]) and re.fullmatch(r"[\d.]+ ms", cells[2])
        assert re.fullmatch(r"\d+\.\d\d", cells[3])
        assert cells[6] == "yes"
        assert cells[7] in ("met", "**missed**")


def test_quick_sim_section_times_a_passing_simulation(tmp_path, mcar_bin):
    output = tmp_path / "bench.md"
    done = subprocess.run([sys.executable, str(REPO / "bench" / "run.py"), "--quick", "sim",
                           "-o", str(output)], capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr
    text = output.read_text(encoding="utf-8")
    row = next(line for line in text.splitlines()
               if line.startswith("| `mcar sim mobile_robot.xacro` (drop, drive, spin)"))
    cells = row.strip("| ").split(" | ")
    # It ran and exited 0 every time, with a peak memory and a ratio to --version.
    assert re.fullmatch(r"[\d.]+ ms", cells[1]) and re.fullmatch(r"\d+ MiB|-", cells[2])
    assert re.fullmatch(r"\d+\.\d", cells[3]) and cells[4] == "0"
    assert cells[5] in ("met", "**missed**")
