"""One point of a sweep, start to end, in whichever process runs it: validated by the config
validator (ranges, then config.xacro's own cross-checks), built, checked, simulated. The
result is a row: a flat dict of plain values, the same on a local worker or a Dask one.
Nothing here raises for a bad point: what went wrong is in the row.
"""

from __future__ import annotations

import contextlib
import math
import os
import socket
import time
from dataclasses import dataclass
from pathlib import Path

# The figures every row has (NaN when not measured), from the scenarios' raw measurements.
FIGURES = ("mass_kg", "rest_height_m", "height_error_m", "tilt_deg", "speed_ratio",
           "speed_m_s", "lateral_drift_m", "heading_change_deg", "yaw_ratio",
           "yaw_rate_rad_s", "centre_moved_m")
TIMINGS = ("validate_s", "build_s", "check_s", "sim_s", "total_s")
STATUSES = ("ok", "rejected", "check failed", "sim failed", "error", "crashed")
FIT_PREFIX = "the dimensions do not fit together: "


@dataclass(frozen=True)
class SweepJob:
    """What every point of a sweep shares; plain values, as it travels to the workers."""

    input: str                              # the robot file (absolute)
    base: str | None                        # what its label is relative to
    package_paths: tuple[str, ...] = ()
    mappings: tuple[tuple[str, str], ...] = ()   # NAME:=VALUE
    fixed: tuple[tuple[str, float], ...] = ()    # --set/--config, validated
    scenarios: tuple[str, ...] = ("drop", "drive", "spin")
    left: str | None = None
    right: str | None = None
    trusted: bool = False                   # --no-sandbox
    asset_paths: tuple[str, ...] = ()       # --asset-path
    specs: tuple[str, ...] = ()             # --specs: figure keys, columns of each row

    def fingerprint(self, names) -> str:
        """Identifies the sweep a results file belongs to (what --resume compares)."""
        import hashlib
        import json

        fields = [Path(self.input).name, sorted(self.mappings), sorted(self.fixed),
                  list(self.scenarios), self.left, self.right, list(names)]
        if self.specs:  # (a sweep without them keeps the fingerprint it had before)
            fields.append(list(self.specs))
        text = json.dumps(fields)
        return hashlib.sha256(text.encode()).hexdigest()[:12]


def empty_row(index: int, values: dict[str, float], specs=()) -> dict:
    from .specs import empty_cells

    row = {"point": index, **values, "valid": False, "constraint": "", "status": "error",
           "reason": "", "check_errors": 0, "check_warnings": 0, "failed_scenarios": ""}
    row.update({name: math.nan for name in FIGURES + TIMINGS})
    row.update(empty_cells(specs))
    row.update({"attempts": 1, "worker": f"{socket.gethostname()}:{os.getpid()}"})
    return row


def evaluate_point(job: SweepJob, index: int, values: dict[str, float]) -> dict:
    """The row of one point (see the module's docstring). A usage or input error (the
    robot does not take overrides, a file is missing) is the sweep's, not the point's:
    every point would fail alike, so it is raised, and ends the sweep."""
    from ..errors import InputError, McarError, UsageError

    started = time.perf_counter()
    row = empty_row(index, values, job.specs)
    if job.trusted:
        from ..expand.sandbox import trust_inputs

        trust_inputs()
    if job.asset_paths:  # a worker is a fresh process: the command line's choice again
        from ..packages.asset_roots import allow_asset_paths

        allow_asset_paths(job.asset_paths)
    try:
        _evaluate(job, values, row)
    except (UsageError, InputError):
        raise
    except McarError as error:
        row["status"], row["reason"] = "error", str(error)
    except Exception as error:  # noqa: BLE001 - one point's fault must not end the sweep
        row["status"], row["reason"] = "error", f"{type(error).__name__}: {error}"
    row["total_s"] = time.perf_counter() - started
    return row


def _evaluate(job: SweepJob, values: dict[str, float], row: dict) -> None:
    from ..config.overrides import applied_overrides
    from ..config.spec import config_file, load_spec
    from ..errors import UsageError
    from ..packages.search import PackageSearch

    clock = time.perf_counter()
    search = PackageSearch(package_paths=list(job.package_paths), origin=Path(job.input))
    spec = load_spec(config_file(search))
    refusal = out_of_range(spec, values)
    if refusal:
        row["status"], (row["constraint"], row["reason"]) = "rejected", refusal
        row["validate_s"] = time.perf_counter() - clock
        return
    overrides = dict(job.fixed)
    overrides.update({name: int(value) if spec.dimensions[name].unit == "count" else value
                      for name, value in values.items()})
    with contextlib.ExitStack() as stack:
        try:
            applied = stack.enter_context(applied_overrides(spec, overrides, search))
        except UsageError as error:  # config.xacro's cross-checks refused the combination
            row["status"] = "rejected"
            row["constraint"] = constraint_name(error.message)
            row["reason"] = error.message.removeprefix(FIT_PREFIX)
            row["validate_s"] = time.perf_counter() - clock
            return
        row["valid"] = True
        row["validate_s"] = time.perf_counter() - clock
        _build_check_sim(job, applied, row)


def _specs_cells(job: SweepJob, checked, row: dict) -> None:
    """The --specs columns of a point that passed its check; a figure that cannot be
    computed is an empty cell and a note, never the point's failure."""
    from ..errors import InputError, McarError, UsageError
    from . import specs

    try:
        sections = specs.specs_sections(checked)
    except (UsageError, InputError):
        raise  # the sweep's error (see evaluate_point)
    except McarError as error:
        row.update(specs.not_computed(job.specs, str(error)))
        return
    except Exception as error:  # noqa: BLE001 - one point's fault must not end the sweep
        row.update(specs.not_computed(job.specs, f"{type(error).__name__}: {error}"))
        return
    row.update(specs.cells(sections, job.specs))


def out_of_range(spec, values: dict[str, float]) -> tuple[str, str] | None:
    """(constraint, message) for the first value outside its dimension's range, or None."""
    from ..config.ranges import outside_message
    from ..config.spec import check_bound
    from ..errors import UsageError

    for name, value in values.items():
        dimension = spec.dimensions[name]
        if dimension.range is not None:
            if value not in dimension.range:
                return (f"{name} outside {dimension.range.shown}",
                        outside_message(name, value, value, dimension.unit, dimension.range))
            continue
        try:
            check_bound(dimension, value, name)
        except UsageError as error:
            return f"{name} {dimension.bound}", error.message
    return None


def constraint_name(message: str) -> str:
    """config.xacro's check message up to its explanation: "the wheels overlap the chassis"."""
    text = message.removeprefix(FIT_PREFIX)
    return text.split(":", 1)[0].strip()


def _build_check_sim(job: SweepJob, overrides, row: dict) -> None:
    from ..check.checker import check_loaded
    from ..load.inputs import RobotInput
    from ..load.robot import LoadOptions, load_robot

    options = LoadOptions(dict(job.mappings), [Path(p) for p in job.package_paths], overrides)
    inp = RobotInput(Path(job.input), Path(job.base) if job.base else None)
    clock = time.perf_counter()
    loaded = load_robot(inp, options)
    row["build_s"] = time.perf_counter() - clock
    clock = time.perf_counter()
    checked = check_loaded(loaded)
    row["check_s"] = time.perf_counter() - clock
    errors = [d for d in checked.diagnostics if d.is_error]
    warnings = [d for d in checked.diagnostics if d.is_warning]
    row["check_errors"], row["check_warnings"] = len(errors), len(warnings)
    if errors or warnings or not checked.tree_is_drawable:  # --strict: warnings fail too
        row["status"] = "check failed"
        row["reason"] = "; ".join(d.text() for d in (errors or warnings)[:3])
        if job.specs:
            from .specs import not_computed

            row.update(not_computed(job.specs, "the check failed"))
        return
    if job.specs:
        _specs_cells(job, checked, row)
    from ..sim.lint import link_mass
    from ..sim.report import simulate

    row["mass_kg"] = sum(link_mass(link) for link in checked.robot.links)
    clock = time.perf_counter()
    report = simulate(checked, list(job.scenarios), job.left, job.right)
    row["sim_s"] = time.perf_counter() - clock
    for scenario in report.scenarios:
        row.update(scenario.measured)
    failed = [s.name for s in report.scenarios if s.status == "failed"]
    row["failed_scenarios"] = ",".join(failed)
    problems = ([report.error] if report.error else []) + \
        [d.text() for d in report.lint_errors] + \
        [f"{s.name}: {s.message()}" for s in report.scenarios if s.status == "failed"]
    row["status"] = "sim failed" if problems else "ok"
    row["reason"] = "; ".join(problems)
