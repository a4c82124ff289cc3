"""A sweep's rows as a table: written as Parquet or CSV (atomically, as often as wanted, so
an interrupted sweep keeps what it finished), read back by ``--resume``."""

from __future__ import annotations

import io
from pathlib import Path

from ..errors import InputError, UsageError
from .plan import Point
from .point import FIGURES, TIMINGS
from .specs import NOTES as SPECS_NOTES
from .specs import empty_cells

FORMATS = (".parquet", ".csv")
TEXT_COLUMNS = ("constraint", "status", "reason", "failed_scenarios", "worker", "sweep")


def results_format(path: str) -> str:
    """".parquet" or ".csv" (also "-": CSV on stdout); UsageError for anything else."""
    if path == "-":
        return ".csv"
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise UsageError(f"-o {path}: results are written as .parquet or .csv")
    return suffix


def columns(names, specs=()) -> list[str]:
    """The table's columns; ``specs`` (--specs keys) after the figures, with their notes."""
    figures = [*FIGURES, *specs, SPECS_NOTES] if specs else list(FIGURES)
    return ["point", *names, "valid", "constraint", "status", "reason", "check_errors",
            "check_warnings", "failed_scenarios", *figures, *TIMINGS, "attempts", "worker",
            "sweep"]


def table(rows: list[dict], names, fingerprint: str, specs=()):
    """The rows as a DataFrame in plan order, columns in a fixed order."""
    import pandas as pd

    defaults = empty_cells(specs)  # (a crashed row has no cells of its own)
    frame = pd.DataFrame([{**defaults, **row, "sweep": fingerprint} for row in rows],
                         columns=columns(names, specs))
    frame = frame.sort_values("point", kind="stable").reset_index(drop=True)
    frame = frame.astype({"point": "int64", "valid": "bool", "check_errors": "int64",
                          "check_warnings": "int64", "attempts": "int64",
                          **{name: "float64" for name in [*names, *FIGURES, *specs,
                                                          *TIMINGS]}})
    texts = [*TEXT_COLUMNS, SPECS_NOTES] if specs else TEXT_COLUMNS
    return frame.astype({name: "string" for name in texts})


def encode(frame, suffix: str) -> bytes:
    buffer = io.BytesIO()
    if suffix == ".parquet":
        frame.to_parquet(buffer, index=False)
    else:
        frame.to_csv(buffer, index=False)
    return buffer.getvalue()


def write(frame, path: str) -> None:
    from ..atomic import atomic_write

    atomic_write(path, encode(frame, results_format(path)))


def read(path: str):
    """A results file as a DataFrame; InputError/UsageError naming the file otherwise."""
    import pandas as pd

    suffix = results_format(path)
    try:
        if suffix == ".parquet":
            frame = pd.read_parquet(path)
        else:
            frame = pd.read_csv(path, keep_default_na=False, na_values=[""],
                                dtype={name: "string" for name in
                                       (*TEXT_COLUMNS, SPECS_NOTES)})
    except FileNotFoundError:
        raise InputError("no such file", file=path) from None
    except (OSError, ValueError, UnicodeDecodeError) as error:
        first = str(error).splitlines()[0] if str(error) else type(error).__name__
        raise InputError(f"not a results file mcar sweep wrote: {first}", file=path) from None
    for name in (*TEXT_COLUMNS, SPECS_NOTES):
        if name in frame:
            frame[name] = frame[name].fillna("").astype("string")
    return frame


def resumed_rows(path: str, points: list[Point], names, fingerprint: str,
                 specs=()) -> list[dict]:
    """The rows of an earlier run of this same sweep that need not run again: those whose
    point is in the plan with the same values, and did not crash."""
    import math

    frame = read(path)
    missing = [name for name in columns(names, specs) if name not in frame]
    if missing:
        raise UsageError(f"cannot resume: it has no column {missing[0]} (another sweep's "
                         "dimensions, or not mcar sweep's results)", file=path)
    others = set(frame["sweep"]) - {fingerprint}
    if others:
        raise UsageError("cannot resume: it holds another sweep (its INPUT, --set, --config, "
                         "--scenario or --vary names differ)", file=path)
    planned = {point.index: point for point in points}
    kept = []
    for row in frame.to_dict("records"):
        point = planned.get(int(row["point"]))
        if point is None or row["status"] == "crashed":
            continue
        if all(math.isclose(float(row[name]), value, rel_tol=1e-9, abs_tol=1e-12)
               for name, value in point.values.items()):
            row.pop("sweep", None)
            kept.append(row)
    return kept
