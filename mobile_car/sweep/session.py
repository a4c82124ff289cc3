"""One ``mcar sweep`` run as the command line drives it: the robot it sweeps, the rows as
they come (saved with the first and then every few seconds, so an interrupted or killed
sweep keeps them), the summary of the outcome."""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass, field

from ..errors import UsageError
from ..load.inputs import RobotInput
from .plan import Point
from .point import SweepJob

SAVE_EVERY = 5.0  # seconds between saves of the results file while the sweep runs
SHOWN_FAILURES = 10  # the points that could not be evaluated, named in the summary


def swept_robot(selection) -> RobotInput:
    """The one robot file a sweep varies: the file named, or a package's only top-level
    robot file (directly in urdf/); stdin is refused (every worker reads the file)."""
    if selection.reads_stdin:
        raise UsageError("mcar sweep reads the robot in every worker: give a file, not - "
                         "(stdin)")
    inputs = selection.inputs
    if selection.kind in ("package", "folder", "parts") and len(inputs) > 1:
        top = [inp for inp in inputs if inp.base is not None and len(inp.relative.parts) == 1
               and inp.is_xacro and ".gazebo." not in inp.path.name]
        inputs = top or inputs
    if len(inputs) != 1:
        names = ", ".join(inp.label for inp in inputs[:5])
        raise UsageError(f"mcar sweep varies one robot, and there are {len(inputs)} "
                         f"({names}{', ...' if len(inputs) > 5 else ''}): name one INPUT")
    return inputs[0]


@dataclass
class Session:
    job: SweepJob
    names: list[str]
    points: list[Point]
    output: str | None  # the results file; None: written once at the end (stdout)
    units: dict[str, str] = field(default_factory=dict)  # of the varied dimensions
    rows: list[dict] = field(default_factory=list)
    resumed: int = 0
    started: float = field(default_factory=time.perf_counter)
    _saved: float = field(default_factory=time.perf_counter)
    _dirty: bool = False

    @property
    def fingerprint(self) -> str:
        return self.job.fingerprint(self.names)

    def resume(self) -> list[Point]:
        """The rows an earlier run of this sweep left in the output, kept; the points left."""
        from .results import resumed_rows

        self.rows = resumed_rows(self.output, self.points, self.names, self.fingerprint,
                                 self.job.specs)
        self.resumed = len(self.rows)
        done = {int(row["point"]) for row in self.rows}
        return [point for point in self.points if point.index not in done]

    def add(self, row: dict) -> None:
        self.rows.append(row)
        self._dirty = True
        # The first row at once: the file shows the sweep under way, and a sweep killed
        # (SIGKILL, a crash) in its first seconds keeps it.
        first = len(self.rows) == self.resumed + 1
        if self.output and (first or time.perf_counter() - self._saved >= SAVE_EVERY):
            self.save()

    def table(self):
        from .results import table

        return table(self.rows, self.names, self.fingerprint, self.job.specs)

    def save(self, table=None) -> None:
        """Write the rows so far (``table``: them, already made), replacing the file at
        once (never half a file)."""
        from .results import write

        if self.output and self.rows:
            write(self.table() if table is None else table, self.output)
        self._saved, self._dirty = time.perf_counter(), False

    @property
    def complete(self) -> bool:
        return len({int(row["point"]) for row in self.rows}) == len(self.points)

    def exit_code(self) -> int:
        """1 when a point could not be evaluated (error, crashed), else 0: rejected points
        and failed checks or scenarios are what a sweep is there to find."""
        return 1 if any(row["status"] in ("error", "crashed") for row in self.rows) else 0

    def summary(self, workers: str) -> list[str]:
        counts = Counter(row["status"] for row in self.rows)
        constraints = Counter(row["constraint"] for row in self.rows
                              if row["status"] == "rejected")
        seconds = time.perf_counter() - self.started
        parts = [f"{counts[s]} {s}" for s in ("ok", "rejected", "check failed", "sim failed",
                                               "error", "crashed") if counts[s] or s == "ok"]
        lines = [f"mcar sweep: {len(self.rows)} points in {seconds:.1f} s ({workers}"
                 f"{f', {self.resumed} from the earlier run' if self.resumed else ''}): "
                 + ", ".join(parts)]
        lines += [f"  rejected {n}x: {name}" for name, n in constraints.most_common()]
        failed = [row for row in sorted(self.rows, key=lambda r: int(r["point"]))
                  if row["status"] in ("error", "crashed")]
        lines += [f"  point {row['point']} {row['status']}: {row['reason']}"
                  for row in failed[:SHOWN_FAILURES]]
        if len(failed) > SHOWN_FAILURES:
            lines.append(f"  ... and {len(failed) - SHOWN_FAILURES} more (status and reason "
                         "in the results)")
        return lines
