"""``mcar ci``'s export step: the folders a package's ``mcar.yaml`` asks for (``export:
formats``, for the robots its ``export: robots`` globs take), written as `mcar export
--to FORMAT --verify` writes them, as build artefacts below ``BUILD/exports/``:
``build/mobile_robot.urdf`` -> ``build/exports/mobile_robot/mjcf/``.

Each export is verified; a failed one fails the step (exit 1, or 2 where the format's
engine is not installed: the usd extra, the Gazebo helper) and the others still run.
An item with exports is built again on every run: the record does not replay them.
"""

from __future__ import annotations

import time
from pathlib import Path

from ..errors import McarError
from ..load.inputs import display_path
from .pipeline import CiItem, Step
from .simulation import config_for


def formats_for(item: CiItem, configs: dict) -> tuple[str, ...]:
    """The formats the item's package asks for it (none without an ``export`` section)."""
    config = config_for(item, configs)
    return config.exports(item.source) if config is not None else ()


def export_folder(item: CiItem, build_dir: Path, to: str) -> Path:
    relative = Path(item.urdf).relative_to(build_dir)
    stem = relative.name[:-len(".urdf")] if relative.name.endswith(".urdf") else relative.name
    return build_dir / "exports" / relative.parent / stem / to


def export_step(item: CiItem, build_dir: Path) -> None:
    """Export an item that passed its check to each of ``item.exports``, verified."""
    from ..export.mjcf import MjcfOptions
    from ..export.run import export_robot
    from ..extras import require

    started = time.perf_counter()
    wrote, failures = [], []
    for to in item.exports:
        target = export_folder(item, build_dir, to)
        try:
            if to == "usd":
                require("mcar ci's usd export", "usd")
            report = export_robot(item.loaded, target, to, MjcfOptions(), verify=True)
        except McarError as error:
            failures.append((to, error))
            continue
        exported = report.exported
        wrote.append(f"{to} {display_path(target)}/ ({exported.model_mass:.6g} kg, "
                     f"{len(exported.moving_joints)} moving joints, verified)")
    seconds = time.perf_counter() - started
    if failures:
        to, error = failures[0]
        item.steps.append(Step("export", "failed", f"--to {to}: {error}", seconds=seconds,
                               exit_code=max(e.exit_code for _, e in failures), error=error,
                               problems=[f"--to {t}: {e}" for t, e in failures]))
        return
    item.steps.append(Step("export", message="exported " + "; ".join(wrote), seconds=seconds))
