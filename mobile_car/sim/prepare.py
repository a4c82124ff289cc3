"""A checked robot made into the SimModel sim runs its scenarios on: the inertias MuJoCo
refuses (refused, or mended with ``--fix-inertia``), the drive the package declares (its
plugins and controllers, its mecanum YAML, its mcar.yaml ``sim.drive``), then
:func:`.model.build_model`. ``mcar sim`` and ``mcar specs`` both start here, so the robot
``mcar specs`` describes is the one ``mcar sim`` drives."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import UsageError
from .lint import (
    SimDiagnostic,
    moving_links_without_mass,
    physical_urdf,
    refused_error,
    refused_inertias,
)


@dataclass
class Prepared:
    """``sim`` the model (None when it could not be made: ``error`` says why, and
    ``diagnostics`` holds the E305/E310 that refused it); ``declared`` what the package
    declares drives the robot (sim's lint compares it with the model); ``notes`` what was
    changed or left out; ``reads`` the control files looked at."""

    sim: object = None
    error: str | None = None
    diagnostics: list[SimDiagnostic] = field(default_factory=list)
    declared: list = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    reads: list = field(default_factory=list)


def prepare(checked, left=None, right=None, kind: str | None = None,
            effort: float | None = None, speed: float | None = None,
            fix_inertia: bool = False, setting=None) -> Prepared:
    """The SimModel of a robot that passed ``mcar check`` (arguments as
    :func:`.report.simulate`'s); a :class:`~mobile_car.errors.UsageError` for a drive the
    options or the package's ``sim.drive`` name wrongly."""
    from .model import SimModelError, build_model

    loaded = checked.loaded
    prepared = Prepared()
    urdf, fixed = loaded.urdf, []
    massless = moving_links_without_mass(checked)
    if fix_inertia:  # (a robot whose root has no mass is not one a token mass mends)
        prepared.diagnostics = [d for d in massless if d.message.startswith("root link")]
        if not prepared.diagnostics:
            urdf, fixed = physical_urdf(urdf)
    else:
        prepared.diagnostics = refused_inertias(checked) + massless
    if prepared.diagnostics:
        prepared.error = refused_error(prepared.diagnostics)
        return prepared
    declared, unread, prepared.reads = declarations(checked)
    prepared.declared = declared
    chosen_in = None  # where the package's mcar.yaml chose the drive
    if setting is not None and not (left or right or kind):
        (drive_set, chosen_in) = setting
        left, right, kind = drive_set.get("left"), drive_set.get("right"), drive_set.get("kind")
    from .mecanum import yaml_declarations

    mecanum, unread_mecanum = yaml_declarations(loaded)
    unread = list(dict.fromkeys(unread + unread_mecanum))
    try:
        sim = build_model(urdf, checked.file, loaded.base, loaded.search, left, right,
                          effort, speed, kind, declared, mecanum)
    except SimModelError as error:
        prepared.error = error.message
        return prepared
    except UsageError as error:
        if chosen_in is None:
            raise
        raise UsageError(f"sim.drive: {error.message}", file=chosen_in) from None
    if chosen_in is not None and sim.drive is not None:
        sim.drive.chosen = f"{chosen_in} sim.drive"
        sim.drive.sources = {joint: sim.drive.chosen for joint in sim.drive.sources}
    prepared.sim = sim
    prepared.notes = [f"--fix-inertia: {line}" for line in fixed] + list(sim.notes) + unread
    return prepared


def declarations(checked) -> tuple[list, list[str], list]:
    """(what the package declares drives the robot: its URDF's drive plugins, located in
    the sources, then its control package's controllers; the control files that could not
    be read; the control files looked at)."""
    from .control_config import find_controllers
    from .declared import in_urdf
    from .lint import Locator

    locate = Locator(checked)
    plugins = in_urdf(list(checked.robot.element), lambda e: locate(e))
    controllers, unread, read = find_controllers(checked.loaded)
    return plugins + controllers, unread, read
