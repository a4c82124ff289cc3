"""The sim rules and their diagnostics, apart from the lint that finds them, so that
``mcar ci`` replays a recorded sim step without importing lxml or the engine."""

from __future__ import annotations

from dataclasses import dataclass

ERROR, WARNING = "error", "warning"
# id -> (name, summary), for the README and --format json.
SIM_RULES = {
    "E301": ("diffdrive-separation", "the DiffDrive plugin's wheel separation differs from "
             "the distance between the drive wheels by more than 1%"),
    "E302": ("diffdrive-radius", "the DiffDrive plugin's wheel radius (or diameter) differs "
             "from the drive wheels' collision radius by more than 1%"),
    "E303": ("diffdrive-joint", "the DiffDrive plugin names a joint that is not a drive "
             "wheel of the robot, or puts the left wheel on the right"),
    "E305": ("moving-link-massless", "a moving link without mass: MuJoCo refuses to "
             "simulate it, Gazebo gives it 1 kg"),
    "W304": ("mass-invented", "a link with collision geometry and no `<inertial>`: Gazebo "
             "gives it 1 kg and a unit inertia, MuJoCo a mass from its volume; mcar sim "
             "keeps it massless, as URDF says"),
}


@dataclass(frozen=True)
class SimDiagnostic:
    """A sim rule broken at FILE:LINE; prints like check's Diagnostic."""

    rule: str
    file: str
    line: int | None
    message: str

    @property
    def severity(self) -> str:
        return ERROR if self.rule.startswith("E") else WARNING

    @property
    def is_error(self) -> bool:
        return self.severity == ERROR

    def location(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file

    def text(self) -> str:
        return f"{self.location()}: {self.severity}: {self.message} [{self.rule}]"

    def github(self) -> str:
        """A GitHub Actions annotation on the line, as check's Diagnostic makes it."""
        from ..check.diagnostics import github_annotation

        return github_annotation(self.severity, self.file, self.line,
                                 f"{self.rule} {SIM_RULES[self.rule][0]}", self.message)

    def as_json(self) -> dict:
        return {"rule": self.rule, "severity": self.severity, "file": self.file,
                "line": self.line, "message": self.message}
