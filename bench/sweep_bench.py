"""What the `sweep` section of bench/run.py needs besides timing whole commands: the
sweeps it runs, the Dask cluster it starts, the shell loop it compares against, and the
per-point times read back from a results file."""

from __future__ import annotations

import contextlib
import csv
import shlex
import statistics
from dataclasses import dataclass
from pathlib import Path

STAGES = ("validate_s", "build_s", "check_s", "sim_s")


@dataclass(frozen=True)
class Sweep:
    label: str
    varies: tuple[str, ...]
    points: int
    loop: bool  # also run the shell loop of `mcar sim` over these points

    def args(self) -> list[str]:
        return [arg for vary in self.varies for arg in ("--vary", vary)]


def sweeps(quick: bool) -> list[Sweep]:
    """Every point of the first is valid (built, checked, simulated); the second is the
    issue's 60-point grid, where the narrow and wide tracks are rejected by config.xacro."""
    if quick:  # a smoke test: two points for the two workers, and a rejection each side
        return [Sweep("all valid", ("wheel_radius=25mm,45mm", "track_width=0.16"), 2, True),
                Sweep("mixed", ("wheel_radius=35mm", "track_width=0.15,0.16,0.17"), 3, False)]
    return [Sweep("all valid", ("wheel_radius=25mm..45mm:12", "track_width=0.158,0.162"),
                  24, True),
            Sweep("mixed (issue 18's grid)",
                  ("wheel_radius=25mm..45mm:12", "track_width=0.15..0.17:5"), 60, False)]


def read_rows(path: Path) -> list[dict]:
    """The rows of a results CSV (empty if the sweep wrote none)."""
    if not path.is_file():
        return []
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def statuses(rows: list[dict]) -> str:
    """'24 ok', '24 ok, 36 rejected': what the points came to, in the sweep's status order."""
    counts: dict[str, int] = {}
    for row in rows:
        counts[row["status"]] = counts.get(row["status"], 0) + 1
    return ", ".join(f"{n} {status}" for status, n in sorted(counts.items(),
                                                            key=lambda item: -item[1]))


def seconds(rows: list[dict], column: str) -> list[float]:
    return [float(row[column]) for row in rows if row[column] not in ("", "nan")]


def median_ok_point(rows: list[dict]) -> float | None:
    values = seconds([row for row in rows if row["status"] == "ok"], "total_s")
    return statistics.median(values) if values else None


def split(rows: list[dict]) -> list[tuple[str, float, float]]:
    """(stage, median seconds per point, share of the sum of the points' total_s) for
    validate, build, check, sim, and what total_s holds besides them (the mass, the row)."""
    ok = [row for row in rows if row["status"] == "ok"]
    total = sum(seconds(ok, "total_s"))
    result = []
    for stage in STAGES:
        values = seconds(ok, stage)
        result.append((stage, statistics.median(values), sum(values) / total))
    other = [float(row["total_s"]) - sum(float(row[stage]) for stage in STAGES) for row in ok]
    result.append(("other", statistics.median(other), sum(other) / total))
    result.append(("total_s", statistics.median(seconds(ok, "total_s")), 1.0))
    return result


def loop_script(path: Path, mcar: str, robot: str, rows: list[dict]) -> list[str]:
    """A POSIX shell loop running one `mcar sim` per point of ``rows`` (the values exactly
    as the results file has them); it stops at the first failure, so its exit code is
    the first failing mcar's. Returns the command that runs it."""
    pairs = " ".join(f"{row['wheel_radius']},{row['track_width']}" for row in rows)
    path.write_text(
        "set -e\n"
        f"for point in {pairs}; do\n"
        f"  {shlex.quote(mcar)} sim {shlex.quote(robot)} --set wheel_radius=\"${{point%,*}}\" "
        "--set track_width=\"${point#*,}\" </dev/null\n"
        "done\n", encoding="utf-8")
    return ["sh", str(path)]


BURN = "sum(i * i for i in range(8_000_000))"  # about 0.5 s of one core, in pure Python


def burn_commands(python: str) -> tuple[list[str], list[str]]:
    """A CPU-bound Python process alone, and two of them at once (exit: both's): what this
    machine gives two busy processes, the ceiling of 2 workers' speed-up when it is run."""
    one = [python, "-c", BURN]
    quoted = " ".join(shlex.quote(arg) for arg in one)
    two = ["sh", "-c", f"{quoted} & first=$!; {quoted}; second=$?; wait $first; "
                       "exit $(( $? | second ))"]
    return one, two


@contextlib.contextmanager
def dask_cluster():
    """A Dask LocalCluster of 2 single-thread worker processes on 127.0.0.1, up for the
    whole block, so that only the sweeps are timed; yields its scheduler address, or
    None with the reason it could not start."""
    try:
        from distributed import LocalCluster
    except ImportError:
        yield None, "Dask distributed is not installed (pip install '.[sweep]')"
        return
    try:
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1",
                               dashboard_address=None)
    except (OSError, RuntimeError, TimeoutError) as error:
        yield None, f"the LocalCluster did not start: {error}"
        return
    with cluster:
        yield cluster.scheduler_address, ""
