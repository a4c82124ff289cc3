"""What every section of ``mcar specs`` starts from: the checked robot, sim's model of it
at rest, the body figures (computed first: mass, centre of mass, footprint, wheels) and
the command's options."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(eq=False)
class SpecsContext:
    """``checked`` the CheckResult (:func:`mobile_car.check.checker.check_input`); ``sim``
    the SimModel (:func:`.model.specs_model`), None where MuJoCo cannot model the robot;
    ``body`` the body Section; ``options``: ``friction`` (mu, None: the description's),
    ``effort`` (N·m), ``speed`` (rad/s), ``proof`` (False: no MuJoCo runs), and sim's
    drive options (``left``, ``right``, ``kind``, ``fix_inertia``, ``setting``)."""

    checked: object
    sim: object
    body: object = None
    options: dict = field(default_factory=dict)
