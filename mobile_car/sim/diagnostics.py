"""The sim rules and their diagnostics, apart from the lint that finds them, so that
``mcar ci`` replays a recorded sim step without importing lxml or the engine."""

from __future__ import annotations

from ..check.diagnostics import Diagnostic

ERROR, WARNING = "error", "warning"
# id -> (name, summary), for docs/sim.md and --format json.
SIM_RULES = {
    "E301": ("diffdrive-separation", "the DiffDrive plugin's wheel separation differs from "
             "the distance between the drive wheels by more than 1% (not for a skid-steer "
             "robot, whose plugin may rightly hold its effective track)"),
    "E302": ("diffdrive-radius", "the DiffDrive plugin's wheel radius (or diameter) differs "
             "from the drive wheels' collision radius by more than 1%"),
    "E303": ("diffdrive-joint", "the DiffDrive plugin names a joint that is not a drive "
             "wheel of the robot, or puts the left wheel on the right"),
    "E305": ("moving-link-massless", "a moving link without mass: MuJoCo refuses to "
             "simulate it, Gazebo leaves it out with what moves below it"),
    "E306": ("drive-joint-fixed", "a drive declaration (a Gazebo drive plugin, a controller "
             "in the robot's control package) names a joint that is fixed or missing: the "
             "robot cannot be driven as its package says"),
    "E310": ("inertia-refused", "an inertia tensor MuJoCo refuses: not positive definite, "
             "principal moments that break the triangle inequality (check warns: W204, "
             "W205), or all zeros on a moving link with a mass; `--fix-inertia` puts the "
             "nearest physical tensor in its place (a small sphere's for zeros)"),
    "W304": ("mass-invented", "a link with collision geometry and no `<inertial>`: Gazebo "
             "leaves it out if it moves, MuJoCo gives it a mass from its volume; mcar sim "
             "keeps it massless, as URDF says"),
}


class SimDiagnostic(Diagnostic):
    """A sim rule broken at FILE:LINE; prints exactly as check's Diagnostic does, from
    the sim rules' table."""

    __slots__ = ()

    @property
    def severity(self) -> str:
        return ERROR if self.rule.startswith("E") else WARNING

    def rule_name(self) -> str:
        return SIM_RULES[self.rule][0]

    @classmethod
    def knows(cls, rule: str) -> bool:
        return rule in SIM_RULES
