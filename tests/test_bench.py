"""`bench/run.py` (what `make bench` runs) works: a quick section writes its table.

Timings are not asserted (they belong to the benchmark, not to tests); what is checked is
that the runner measures real, successful runs of both tools and compares their outputs.
"""

from __future__ import annotations

import re
import subprocess
import sys

import pytest
from conftest import REPO


def quick_section(tmp_path, section: str, timeout: int) -> str:
    """The document `bench/run.py --quick SECTION` writes, after a run that exited 0."""
    output = tmp_path / "bench.md"
    done = subprocess.run([sys.executable, str(REPO / "bench" / "run.py"), "--quick", section,
                           "-o", str(output)], capture_output=True, text=True, timeout=timeout)
    assert done.returncode == 0, done.stderr
    return output.read_text(encoding="utf-8")


def test_quick_build_section_writes_a_table_of_real_runs(tmp_path, mcar_bin):
    text = quick_section(tmp_path, "build", timeout=120)
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
    text = quick_section(tmp_path, "sim", timeout=180)
    row = next(line for line in text.splitlines()
               if line.startswith("| `mcar sim mobile_robot.xacro` (drop, drive, spin)"))
    cells = row.strip("| ").split(" | ")
    # It ran and exited 0 every time, with a peak memory and a ratio to --version.
    assert re.fullmatch(r"[\d.]+ ms", cells[1]) and re.fullmatch(r"\d+ MiB|-", cells[2])
    assert re.fullmatch(r"\d+\.\d", cells[3]) and cells[4] == "0"
    assert cells[5] in ("met", "**missed**")


def test_quick_sweep_section_times_sweeps_whose_points_all_ran(tmp_path, mcar_bin):
    pytest.importorskip("distributed", reason="the sweep extra (pip install '.[sweep]')")
    text = quick_section(tmp_path, "sweep", timeout=400)
    assert "## `mcar sweep`" in text
    table = {tuple(cells[:2]): cells for cells in
             (line.strip("| ").split(" | ") for line in text.splitlines()
              if line.startswith("| all valid |") or line.startswith("| mixed |"))}
    runners = ["`--jobs 1`", "`--jobs 2`", "`--scheduler`, Dask (2 workers)"]
    assert sorted(table) == sorted([*((sweep, runner) for sweep in ("all valid", "mixed")
                                      for runner in runners),
                                    ("all valid", "shell loop of `mcar sim`, one per point")])
    for (sweep, runner), cells in table.items():
        # Every run exited 0 (a failure shows "(exit N)" next to the time, and no rate).
        assert re.fullmatch(r"[\d.]+ m?s", cells[3]) and cells[9] == "0", cells
        assert re.fullmatch(r"\d+\.\d\d", cells[4]), cells  # points per second
        if runner.startswith("shell loop"):
            continue
        # The results file of the timed run had one row per point, with what they came to:
        # the all-valid sweep's 2 points were both built, checked and simulated.
        assert cells[2] == ("2 ok" if sweep == "all valid" else "2 rejected, 1 ok"), cells
        assert re.fullmatch(r"[\d.]+ ms", cells[7]), cells  # median of the ok points
        assert re.fullmatch(r"[\d.]+ m?s \(\d+%\)", cells[8]), cells  # outside the points
        if runner != "`--jobs 1`":
            assert re.fullmatch(r"\d+\.\d\dx", cells[5]), cells  # over 1 worker
        if sweep == "all valid":
            assert re.fullmatch(r"\d+\.\d\dx", cells[6]), cells  # loop / this sweep
        assert cells[10] in (("met", "**missed**") if runner == "`--jobs 2`" else ("-",))
    # The per-point split of the --jobs 1 run: every stage timed, the shares add up.
    split = re.search(r"\| stage \| median per point \| share \|\n\|---\|---:\|---:\|\n"
                      r"((?:\|.*\n)+)", text)
    assert split, text
    stages = [line.strip("| ").split(" | ") for line in split.group(1).splitlines()]
    assert [cells[0].split(" ")[0] for cells in stages] == [
        "validate", "build", "check", "sim", "other", "**total**"]
    for cells in stages:
        assert re.fullmatch(r"\d+\.\d ms", cells[1]) and re.fullmatch(r"-?\d+%", cells[2])
    assert stages[-1][2] == "100%"
    assert 98 <= sum(int(cells[2].rstrip("%")) for cells in stages[:-1]) <= 102
    assert re.search(r"two busy processes get \d+\.\d\dx the throughput of one", text)


def test_quick_folder_section_times_check_and_build_of_two_sizes(tmp_path, mcar_bin):
    text = quick_section(tmp_path, "folder", timeout=300)
    assert "## A folder of robots" in text
    rows = [line.strip("| ").split(" | ") for line in text.splitlines()
            if re.match(r"\| \d+ (URDF|xacro) \|", line)]
    assert [row[0] for row in rows] == ["25 URDF", "50 URDF", "25 xacro", "50 xacro"]
    for cells in rows:
        # Both commands exited 0 every time (else "(exit N)" next to the time, no ratio).
        assert re.fullmatch(r"[\d.]+ m?s", cells[1]) and re.fullmatch(r"[\d.]+ m?s", cells[2])
        assert re.fullmatch(r"\d+\.\d", cells[3]) and cells[5] == "0 / 0", cells
    assert all(cells[6] in ("met", "**missed**") for cells in rows[1::2])  # 2N vs N


def _rows_by_command(text: str) -> dict[str, list[str]]:
    """A section's table rows whose first cell is a command (`mcar ...`), by that cell."""
    return {cells[0]: cells for cells in (line.strip("| ").split(" | ")
                                          for line in text.splitlines()
                                          if line.startswith("| `"))}


def test_quick_robots_section_times_sim_on_real_robots_next_to_the_car(tmp_path, mcar_bin):
    from sim.test_sim_real_robots import FOLDER

    if FOLDER is None:
        pytest.skip("the shared real-robots folder is absent (set MCAR_REAL_ROBOTS)")
    text = quick_section(tmp_path, "robots", timeout=600)
    assert "## `mcar sim` on real robots" in text
    rows = _rows_by_command(text)
    sims = ["`mcar sim` bundled car (mobile_robot.xacro)",
            "`mcar sim` TurtleBot3 burger (built URDF)", "`mcar sim` Husky (husky.urdf.xacro)"]
    assert list(rows)[:3] == sims
    for label in sims:
        cells = rows[label]
        # Every run exited 0, with a peak memory, a ratio to the car's time and a verdict.
        assert re.fullmatch(r"[\d.]+ m?s", cells[1]) and cells[4] == "0", cells
        assert re.fullmatch(r"\d+ MiB|-", cells[2]) and re.fullmatch(r"\d+\.\d\d", cells[3])
        assert cells[5] in ("met", "**missed**")
    assert rows[sims[0]][3] == "1.00"
    assert rows["`mcar check` Husky (husky.urdf.xacro)"][4] == "0"


def test_quick_specs_section_times_specs_with_and_without_proofs_beside_sim(tmp_path,
                                                                           mcar_bin):
    from sim.test_sim_real_robots import FOLDER

    if FOLDER is None:
        pytest.skip("the shared real-robots folder is absent (set MCAR_REAL_ROBOTS)")
    text = quick_section(tmp_path, "specs", timeout=600)
    assert "## `mcar specs`" in text
    rows = _rows_by_command(text)
    names = ("TurtleBot3 burger", "the bundled car")
    assert list(rows) == [label for name in names for label in (
        f"`mcar specs --no-proof` {name}", f"`mcar specs` {name} (with its proofs)",
        f"`mcar sim --scenario drop` {name}", f"`mcar sim` {name}")]
    for cells in rows.values():
        # Every run exited 0 (every proof agreeing), with a peak memory and a ratio to sim's.
        assert re.fullmatch(r"[\d.]+ m?s", cells[1]) and cells[4] == "0", cells
        assert re.fullmatch(r"\d+ MiB|-", cells[2]) and re.fullmatch(r"\d+\.\d\d", cells[3])
    assert rows["`mcar sim` TurtleBot3 burger"][3] == "1.00"
    assert rows["`mcar specs --no-proof` TurtleBot3 burger"][5] in ("met", "**missed**")


def test_quick_gazebo_section_times_check_gazebo_and_the_helper(tmp_path, mcar_bin,
                                                                gazebo):
    text = quick_section(tmp_path, "gazebo", timeout=300)
    rows = [line.strip("| ").split(" | ") for line in text.splitlines()
            if line.startswith("| the car") or line.startswith("| tree")]
    assert [row[0] for row in rows] == ["the car (xacro, 16 links)",
                                        "tree, every number distinct, 100 links"]
    for cells in rows:
        # check, check --gazebo and the helper alone all ran and exited 0
        assert all(re.fullmatch(r"[\d.]+ (ms|s)", cell) for cell in cells[1:5]), cells
        assert cells[6] == "0" and cells[7] in ("met", "**missed**")


def test_quick_meshes_section_sets_a_mesh_robot_beside_its_boxes(tmp_path, mcar_bin):
    text = quick_section(tmp_path, "meshes", timeout=600)
    assert "## `mcar check` of a mesh-heavy robot" in text
    rows = [line.strip("| ").split(" | ") for line in text.splitlines()
            if line.startswith(("| boxes", "| meshes"))]
    assert [row[0] for row in rows] == ["boxes", "meshes, cache kept", "meshes, empty cache"]
    for row in rows:  # real runs: a time, a ratio to the boxes, a peak, exit 0 every time
        assert re.fullmatch(r"[\d.]+ m?s", row[1]) and re.fullmatch(r"[\d.]+x", row[2])
        assert re.fullmatch(r"\d+ MiB", row[3]) and row[4] == "0"


def test_quick_export_section_times_each_format_next_to_check(tmp_path, mcar_bin):
    from sim.test_sim_real_robots import FOLDER

    if FOLDER is None:
        pytest.skip("the shared real-robots folder is absent (set MCAR_REAL_ROBOTS)")
    text = quick_section(tmp_path, "export", timeout=600)
    assert "## `mcar export`" in text
    rows = [line.strip("| ").split(" | ") for line in text.splitlines()
            if line.startswith("| TurtleBot3 burger")]
    assert rows[0][1:4] == ["(`mcar check`)", rows[0][2], "1.00"]
    formats = [row[1] for row in rows[1:]]
    assert "mjcf" in formats and "urdf" in formats  # usd, sdf where their engines are
    for cells in rows[1:]:  # every run of both commands exited 0, with ratios to check
        assert re.fullmatch(r"[\d.]+ m?s", cells[2]) and re.fullmatch(r"[\d.]+ m?s", cells[4])
        assert re.fullmatch(r"\d+\.\d\d", cells[3]) and re.fullmatch(r"\d+\.\d\d", cells[5])
        assert cells[7] == "0", cells


def test_quick_floor_section_gives_each_ratio_from_real_runs(tmp_path, mcar_bin):
    text = quick_section(tmp_path, "floor", timeout=180)
    assert "## At the floor: mcar beside its yardsticks" in text
    rows = [line.strip("| ").split(" | ") for line in text.splitlines()
            if line.startswith("| `mcar ")]
    labels = [cells[0] for cells in rows]
    assert labels[:3] == ["`mcar check` the car (mobile_robot.urdf)",
                          "`mcar check` 500-link tree, distinct",
                          "`mcar check` 500-link tree, repeated"]
    assert all(label.startswith("`mcar build` ") for label in labels[3:])
    for cells in rows:
        # Both sides ran and exited 0 (else "exit N / M" and no ratio), and the CPU
        # ratio, from wait4, is judged against the row's target.
        assert re.fullmatch(r"[\d.]+ ms / [\d.]+ ms", cells[2]), cells
        assert re.fullmatch(r"\*\*\d+\.\d\dx\*\*", cells[3]), cells
        verdict = r"(met|\*\*missed\*\*) \(<= 1\.\d+x\)"
        if cells[0].startswith("`mcar build` "):  # mcar's own overhead said after it
            verdict += r"; \d+\.\d\dx the click \+ xacro floor"
        assert re.fullmatch(verdict, cells[7]), cells
    # Each build is followed by the floor of any click tool that runs xacro and by that of
    # any runner that keeps the sandbox on, each over xacro, from real runs (an exit other
    # than 0 leaves no ratio), and judged on nothing.
    for floor in ("| click + xacro, unsandboxed", "| xacro in mcar's sandbox, no click"):
        floors = [line.strip("| ").split(" | ") for line in text.splitlines()
                  if line.startswith(floor)]
        assert len(floors) == len(labels) - 3, floor
        for cells, build in zip(floors, labels[3:], strict=True):
            assert cells[0].endswith(build.removeprefix("`mcar build` ").split(" (")[0]), cells
            assert cells[1] == "`xacro`" and cells[7] == "-", cells
            assert re.fullmatch(r"\*\*\d+\.\d\dx\*\*", cells[3]), cells
