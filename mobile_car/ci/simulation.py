"""The sim step of ``mcar ci``: a green CI never passes a vehicle nobody watched move.

Each robot that passed its check is simulated as ``mcar sim`` does the files of a package,
with its drive kind's scenarios. Then:

* a robot that is not a vehicle (no wheels, one wheel, nothing but its wheels to stand
  on: :func:`mobile_car.sim.vehicle.not_a_vehicle`) is skipped, saying so;
* a vehicle sim cannot drive (mecanum rollers, wheels on one side, a steering layout
  that is no Ackermann pair) *fails*, with the reason, as in ``mcar sim``
  (:func:`mobile_car.sim.report.undriven`), unless its package opts it out:
  ``sim: skip: {GLOB: REASON}`` in the package's ``mcar.yaml``
  (:mod:`mobile_car.packages.package_config`), whose reason ci prints;
* any other vehicle fails on any failed scenario or sim rule.

Skips are printed one line per kind (:func:`skip_lines`), not one per file.
"""

from __future__ import annotations

import time
from pathlib import Path

from ..errors import EXIT_PROBLEMS, McarError
from ..packages.package_config import FILE_NAME, PackageConfig, load_package_config
from .pipeline import CiItem, Step

OPT_OUT = f"{FILE_NAME} sim: skip: {{GLOB: REASON}} opts a robot out"


def package_configs(items: list[CiItem], root: Path | None) -> dict[Path, PackageConfig]:
    """The settings of each package the items lie in (the selection's ``root`` for a
    folder that is no package), read before anything is built: a mistake in one is a
    usage error that stops the run."""
    configs: dict[Path, PackageConfig] = {}
    for item in items:
        home = _package_root(item.source, root)
        if home is not None and home not in configs:
            configs[home] = load_package_config(home)
    return configs


def strictness(item: CiItem, configs: dict[Path, PackageConfig], flag: bool | None) -> bool:
    """Whether a warning fails the item: --strict/--no-strict when given, else its
    package's ``ci: strict``, else not (a package that has not said so is held to errors:
    another team's released robot, whose warnings ci shows without failing it)."""
    if flag is not None:
        return flag
    config = config_for(item, configs)
    return bool(config is not None and config.strict)


def config_for(item: CiItem, configs: dict[Path, PackageConfig]) -> PackageConfig | None:
    """The settings of the package (or folder) the item lies in, of those ``configs``
    package_configs read."""
    for home, config in configs.items():
        if item.source.resolve().is_relative_to(Path(home).resolve()):
            return config
    return None


def skip_reason(item: CiItem, configs: dict[Path, PackageConfig]) -> str | None:
    """The reason the item's package gives for not simulating it, or None."""
    for home, config in configs.items():
        if item.source.resolve().is_relative_to(home.resolve()):
            reason = config.sim_skip_reason(item.source)
            if reason is not None:
                line = config.lines.get(("sim", "skip"))
                return f"{reason} ({FILE_NAME}{f':{line}' if line else ''})"
    return None


def drive_setting(item: CiItem, configs: dict[Path, PackageConfig]):
    """({kind, left, right}, where) the item's package sets in ``sim.drive``, or None."""
    config = config_for(item, configs)
    return config.sim_drive_for(item.source) if config is not None else None


def sim_step(item: CiItem, skip: str | None = None, setting=None) -> None:
    """Simulate an item that passed its check; ``skip``: its package's reason not to;
    ``setting``: its package's ``sim.drive`` (:func:`drive_setting`)."""
    from ..sim.report import failure_lines, junit_cases, simulate

    started = time.perf_counter()
    if skip is not None:
        item.steps.append(Step("sim", "skipped", f"not simulated: {skip}", skip_kind=skip,
                               summary="opted out"))
        return
    try:
        result = simulate(item.checked, only_if_drives=True, setting=setting)
    except McarError as error:  # no engine, or drive wheels named that cannot drive
        item.steps.append(Step("sim", "failed", str(error), exit_code=error.exit_code,
                               error=error, seconds=time.perf_counter() - started))
        return
    seconds = time.perf_counter() - started
    if not result.simulated:
        why = result.not_a_vehicle
        item.steps.append(Step("sim", "skipped", f"not simulated: {why}", seconds=seconds,
                               skip_kind=f"not a vehicle: {why.kind}", summary="not a vehicle"))
        return
    cases, problems, code = junit_cases(result), failure_lines(result), result.exit_code
    if result.drive is None and not result.error:  # a vehicle that only stood
        # (sim failed its drive scenarios already, as mcar sim does: one line says why)
        why = (f"cannot drive this vehicle: {result.why_no_drive}; only drop ran ({OPT_OUT} "
               "that is not meant to drive)")
        for case in cases[1:]:
            if case["status"] == "skipped":
                case.update(status="failed", message=why)
        problems = [p for p in problems if "cannot drive this vehicle: " not in p] + [why]
        code = code or EXIT_PROBLEMS
    failed = [case["name"] for case in cases if case["status"] == "failed"]
    ran = ", ".join(case["name"] for case in cases[1:])
    message = f"{', '.join(failed)} failed" if failed else f"{ran} passed"
    passed = sum(case["status"] == "passed" for case in cases[1:])
    summary = (f"{result.drive['kind']} {passed}/{len(cases) - 1}" if result.drive else
               "cannot drive" if not result.error else "failed")
    item.steps.append(Step("sim", "failed" if code else "passed", message,
                           list(result.diagnostics), seconds, code, cases=cases,
                           problems=problems, reads=list(result.reads), summary=summary))


def skip_lines(items: list[CiItem]) -> list[str]:
    """One line per kind of skipped simulation: ``LABEL: not simulated: WHY`` for a kind
    only one file has, else ``not simulated, KIND: N files: A, B, ...``."""
    groups: dict[str, list[tuple[str, str]]] = {}
    for item in items:
        for step in item.steps:
            if step.name == "sim" and step.status == "skipped" and step.skip_kind:
                groups.setdefault(step.skip_kind, []).append((item.label, step.message))
    lines = []
    for kind, entries in groups.items():
        if len(entries) == 1:
            lines.append(f"{entries[0][0]}: {entries[0][1]}")
        else:
            lines.append(f"not simulated, {kind}: {len(entries)} files: "
                         + ", ".join(label for label, _ in entries))
    return lines


def _package_root(path: Path, root: Path | None) -> Path | None:
    from ..packages.search import enclosing_package

    found = enclosing_package(path)
    return found[1] if found is not None else root
