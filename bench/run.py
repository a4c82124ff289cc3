"""mcar against the tools a user would use instead, on the same inputs, in one run.

    python bench/run.py [--quick] [-o docs/benchmarks.md] [SECTION...]

Every time is the median wall time of several runs of a whole command (a fresh process,
as in a shell script or CI) with its output going to /dev/null, and every ratio compares
two commands measured in the same run. Before the timed runs, each command runs once more
under GNU time for its peak resident memory, with its output piped into a hash, so the
table can say whether the peer and mcar printed the same bytes; every exit code is shown.
Peers: urdfdom's C++ check_urdf (Debian liburdfdom-tools) and the plain `xacro` command
(PyPI xacro, the same library mcar calls). The inputs are generated (bench/generate.py).
bench/notes.md holds the explanations printed under the tables (profiles of the misses).
"""

from __future__ import annotations

import argparse
import datetime
import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from floor_section import section_floor  # noqa: E402
from measure import HAVE_GNU_TIME, REPO, machine, progress, versions  # noqa: E402
from runtime_sections import (  # noqa: E402
    section_noop,
    section_render,
    section_robots,
    section_sim,
)
from static_sections import (  # noqa: E402
    section_batch,
    section_build,
    section_check,
    section_folder,
    section_startup,
)
from sweep_section import section_sweep  # noqa: E402


def section_gazebo(rows: list[str], work: Path, quick: bool) -> None:
    import gazebo_bench
    import measure

    gazebo_bench.section(rows, work, quick, measure)


def section_export(rows: list[str], work: Path, quick: bool) -> None:
    import export_bench
    import measure

    export_bench.section(rows, work, quick, measure)


def section_specs(rows: list[str], work: Path, quick: bool) -> None:
    import measure
    import specs_bench

    specs_bench.section(rows, work, quick, measure)


def section_meshes(rows: list[str], work: Path, quick: bool) -> None:
    import measure
    import mesh_check_bench

    mesh_check_bench.section(rows, work, quick, measure)


SECTIONS = {"check": section_check, "build": section_build, "startup": section_startup,
            "batch": section_batch, "folder": section_folder, "render": section_render,
            "noop": section_noop, "sim": section_sim, "robots": section_robots,
            "sweep": section_sweep, "gazebo": section_gazebo, "meshes": section_meshes,
            "export": section_export, "floor": section_floor,
            "specs": section_specs}
NEEDS_CHECK_URDF = {"check", "startup", "batch", "floor"}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="smaller inputs, fewer runs (a smoke test; numbers are rough)")
    parser.add_argument("-o", "--output", type=Path,
                        help="where to write the tables (default: docs/benchmarks.md; with "
                             "--quick, build/benchmarks-quick.md)")
    parser.add_argument("sections", nargs="*", metavar="SECTION",
                        help=f"only these sections ({', '.join(SECTIONS)}); default all")
    args = parser.parse_args()
    unknown = [s for s in args.sections if s not in SECTIONS]
    if unknown:
        parser.error(f"unknown section(s) {', '.join(unknown)}; choose from {', '.join(SECTIONS)}")
    chosen = args.sections or list(SECTIONS)
    if NEEDS_CHECK_URDF & set(chosen) and shutil.which("check_urdf") is None:
        print("bench: check_urdf not found (Debian package liburdfdom-tools; `make bench` "
              "installs it)", file=sys.stderr)
        return 2
    output = args.output or (REPO / "build" / "benchmarks-quick.md" if args.quick
                             else REPO / "docs" / "benchmarks.md")
    rows = ["# Benchmarks", "",
            f"Measured {datetime.date.today().isoformat()} by `make bench` "
            f"(`bench/run.py{' --quick' if args.quick else ''}"
            f"{' ' + ' '.join(args.sections) if args.sections else ''}`) on: {machine()}.",
            "", f"Versions: {versions()}.", "",
            "Times are medians of repeated whole-process runs, output to /dev/null. Peak "
            "memory is the process's maximum resident set (GNU time). Speed-up = peer time / "
            "mcar time (above 1: mcar is faster). An exit code other than 0 is shown next to "
            "the time, and no ratio is computed from a failed run.", ""]
    if not HAVE_GNU_TIME:
        rows += ["(GNU time was not found at /usr/bin/time: no peak memory.)", ""]
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="mcar-bench-") as tmp:
        for name in chosen:
            section_start = time.perf_counter()
            folder = Path(tmp) / name
            folder.mkdir()
            SECTIONS[name](rows, folder, args.quick)
            progress(f"{name} done in {time.perf_counter() - section_start:.0f} s")
    rows.append(f"Whole run: {time.perf_counter() - started:.0f} s.")
    text = "\n".join(rows) + "\n"
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(text, encoding="utf-8")
    print(text)
    progress(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
