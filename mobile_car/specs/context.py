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
    drive options (``left``, ``right``, ``kind``, ``fix_inertia``, ``setting``);
    ``sections`` the sections computed so far, body first (the stack reads the statics'
    top speed and the sensors' blocked sectors)."""

    checked: object
    sim: object
    options: dict = field(default_factory=dict)
    sections: list = field(default_factory=list)

    @property
    def body(self):
        """The body Section: the first computed, every other starts from it."""
        return self.sections[0]
