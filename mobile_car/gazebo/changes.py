"""What Gazebo changes in a robot: the URDF mcar checked, set against what libsdformat made
of it (a checked :class:`~.wire.GazeboReport`), as located diagnostics (``mcar check
--gazebo``).

Nothing of the conversion is redone here: which links Gazebo has, which it lumped and
which it left out are libsdformat's answer; the URDF only says where each thing was
written, what it weighed, and which links lie below which. A URDF link is

* *kept*: a link of the Gazebo model;
* *lumped*: libsdformat says it lumped it into its parent by a fixed joint (or, in later
  releases, made it a frame), and the chain of those ends at a kept link: N401;
* *lost*: anything else. The cause of a loss is the nearest link at or above it that
  libsdformat says it left out for want of mass (a massless link lumped away still stops
  everything that moves below it): one E150 per cause, naming every link lost with it
  and their mass.

Then ``<gazebo reference>`` blocks (W231 when Gazebo has no such link or joint, N402 when
the link is lumped: the block goes to the link it is lumped into), joint names in
``<gazebo>`` plugins (W232), libsdformat's verdict and what it printed (below) and the
total mass (N403). Masses in kg.

libsdformat's verdict is its own: an error (E151) is only what its load returned in its
Errors list, and each names the libsdformat that said it (with the known bug of that
release it matches, :mod:`.versions`). What it printed on its console while loading is
not a verdict: sdformat 12 prints some errors and then loads the robot anyway, returning
none (its own tests expect none), so a printed error is a note (N404) and a printed
warning a warning (W230).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ..check.context import Reporter
from ..check.diagnostics import Diagnostic
from ..check.urdf_model import parse_number
from .versions import known_bug
from .wire import GazeboReport

MAX_NAMED = 12  # links named in one message; the rest are counted
# Plugin parameters that name joints: <joint>, <joint_name>, <left_joint> (gz-sim, ROS 2),
# <leftJoint>, <jointName> (ROS 1 plugins; a list separated by commas or spaces).
_JOINT_TAG = re.compile(r"joints?|joint_names?|jointNames?|[a-z0-9_]*_joint|[a-z][A-Za-z0-9]*Joint")
_NAME_SEPARATOR = re.compile(r"[\s,]+")


@dataclass
class GazeboView:
    """The robot as Gazebo has it, in the URDF's terms, and what was said about it."""

    sdformat: str
    links: list[str]                                      # Gazebo's links, its order
    lumped: dict[str, str] = field(default_factory=dict)  # URDF link -> Gazebo link
    lost: dict[str, str | None] = field(default_factory=dict)  # URDF link -> its cause
    urdf_mass: float = 0.0
    gazebo_mass: float = 0.0
    loaded: bool = True
    diagnostics: list[Diagnostic] = field(default_factory=list)

    def summary(self) -> str:
        """One line: "3 links of 16 (13 lumped), 0.7056 kg, as in the URDF (libsdformat
        12.3.0)"."""
        if not self.loaded:
            return f"libsdformat {self.sdformat} could not load it"
        total = len(self.links) + len(self.lumped) + len(self.lost)
        parts = [f"{len(self.lumped)} lumped"] + (
            [f"{len(self.lost)} left out"] if self.lost else [])
        return (f"{len(self.links)} link{'s' * (len(self.links) != 1)} of {total} "
                f"({', '.join(parts)}), {_mass_words(self.gazebo_mass, self.urdf_mass)} "
                f"(libsdformat {self.sdformat})")

    def as_json(self) -> dict:
        return {"sdformat": self.sdformat, "loaded": self.loaded, "links": self.links,
                "lumped": self.lumped, "lost": self.lost, "urdf_mass": self.urdf_mass,
                "gazebo_mass": self.gazebo_mass}


def gazebo_view(result, report: GazeboReport) -> GazeboView:
    """What Gazebo changes in a checked robot (a sound CheckResult)."""
    robot, tree = result.robot, result.tree
    diagnostics = Reporter(result.file, result.where)
    view = GazeboView(report.sdformat, [], urdf_mass=math.fsum(_mass(link) for link in
                                                                robot.links))
    said = f"libsdformat {report.sdformat}"
    hinted = set()  # a known bug is named once, at the first error it may explain
    for message in dict.fromkeys(report.errors):
        hint = known_bug(report, message, robot.element)
        diagnostics.add("E151", robot.element, f"{said}: {_first_line(message.text)} "
                                               f"({message.where}){'' if hint in hinted else hint}")
        hinted.add(hint)
    for message in dict.fromkeys(report.console_errors):
        diagnostics.add("N404", robot.element, f"{said} printed an error it did not return, "
                        f"and loaded the robot past it: {_first_line(message.text)} "
                        f"({message.where})")
    for message in dict.fromkeys(report.warnings):
        diagnostics.add("W230", robot.element, f"libsdformat: {_first_line(message.text)} "
                                               f"({message.where})")
    model = report.model
    if model is None:
        if not report.errors:  # no model is a failed load, whatever it returned
            diagnostics.add("E151", robot.element, f"{said} made no model of the robot "
                                                   "and returned no error")
        view.loaded = False
        view.diagnostics = diagnostics.diagnostics
        return view
    view.links = [link.name for link in model.links]
    view.gazebo_mass = model.mass
    links = {link.name: link for link in robot.links}
    parent_joint = {child: joints[0] for child, joints in tree.parent_joints.items()}
    _classify(view, report, links, parent_joint, tree.root)
    gazebo_links = {link.name: link for link in model.links}
    for name, into in view.lumped.items():
        body = gazebo_links[into]
        joint = parent_joint[name].name if name in parent_joint else "?"
        diagnostics.add("N401", links[name].element, f"link '{name}' is lumped into "
                        f"'{into}' by its fixed joint '{joint}': Gazebo simulates them as one "
                        f"body ('{into}': {body.mass or 0:.4g} kg, {body.collisions} "
                        f"collision{'s' * (body.collisions != 1)})")
    _report_losses(view, report, links, parent_joint, diagnostics)
    joints = {joint.name for joint in model.joints}
    _references(robot, view, links, parent_joint, joints, diagnostics)
    _plugin_joints(robot, view, parent_joint, joints, diagnostics)
    diagnostics.add("N403", robot.element, f"Gazebo simulates {len(view.links)} "
                    f"link{'s' * (len(view.links) != 1)}: "
                    f"{_mass_words(view.gazebo_mass, view.urdf_mass)} ({said})")
    view.diagnostics = sorted(set(diagnostics.diagnostics), key=Diagnostic.sort_key)
    return view


def link_fates(names, report: GazeboReport, root: str | None) -> tuple[dict, list]:
    """(URDF link -> the Gazebo link it is lumped into, the URDF links Gazebo lost) of
    the links ``names``; those kept are in neither. ``root`` named "world" is the ground,
    never a link."""
    kept = {link.name for link in report.model.links}
    into = dict(report.lumped)
    for frame in report.model.frames:  # later releases keep a lumped link as a frame
        if frame.name not in kept and frame.body in kept:
            into[frame.name] = frame.body
    lumped, lost = {}, []
    for name in names:
        if name in kept or (name == "world" and name == root):
            continue
        body, steps = into.get(name), 0
        while body is not None and body not in kept and steps < len(into):
            body, steps = into.get(body), steps + 1
        if body in kept:
            lumped[name] = body
        else:
            lost.append(name)
    return lumped, lost


def _classify(view: GazeboView, report: GazeboReport, links: dict, parent_joint: dict,
              root: str | None) -> None:
    view.lumped, lost = link_fates(list(links), report, root)
    causes = {link for link, _words in report.dropped} - set(view.links)
    for name in lost:
        link = name
        while link is not None and link not in causes:
            joint = parent_joint.get(link)
            link = joint.parent if joint is not None else None
        view.lost[name] = link


def _report_losses(view: GazeboView, report: GazeboReport, links: dict, parent_joint: dict,
                   diagnostics: Reporter) -> None:
    words = dict(report.dropped)
    by_cause: dict[str | None, list[str]] = {}
    for name, cause in view.lost.items():
        by_cause.setdefault(cause, []).append(name)
    for cause, names in by_cause.items():
        lost_mass = math.fsum(_mass(links[name]) for name in names)
        others = [name for name in names if name != cause]
        listed = _listed([f"{name} ({_mass(links[name]):.4g} kg)" for name in others])
        if cause is None:  # libsdformat said nothing: name the topmost lost link
            top = next(name for name in names
                       if parent_joint.get(name) is None
                       or parent_joint[name].parent not in view.lost)
            diagnostics.add("E150", links[top].element, f"Gazebo does not have link '{top}' "
                            f"and libsdformat does not say why; lost: "
                            f"{_listed([f'{n} ({_mass(links[n]):.4g} kg)' for n in names])}; "
                            f"{lost_mass:.4g} kg not simulated")
            continue
        why = _why_massless(links[cause])
        joint = parent_joint.get(cause)
        below = f": {listed}; {lost_mass:.4g} kg not simulated" if others else ""
        if cause in view.lost:
            own = f"with its joint '{joint.name}'" if joint is not None else "the root"
            head = (f"Gazebo leaves out link '{cause}' ({why}), {own}"
                    + (", and everything that moves below it" if others else ""))
        else:
            head = (f"link '{cause}' has {why}: Gazebo lumps it into "
                    f"'{view.lumped[cause]}' but leaves out everything that moves below it")
        diagnostics.add("E150", links[cause].element,
                        f"{head}{below} (libsdformat: \"{_first_line(words[cause])}\"); "
                        "give it an <inertial> with a mass")


def _references(robot, view: GazeboView, links: dict, parent_joint: dict, joints: set,
                diagnostics: Reporter) -> None:
    """``<gazebo reference="NAME">``: a link or joint Gazebo has, or say what became of it."""
    urdf_joints = {joint.name: joint for joint in robot.joints}
    for block in robot.others:
        name = block.get("reference") if block.tag == "gazebo" else None
        if name is None or name in view.links or name in joints:
            continue
        where = f'<gazebo reference="{name}">'
        if name in view.lumped:
            diagnostics.add("N402", block, f"{where}: Gazebo lumps link '{name}' into "
                            f"'{view.lumped[name]}', so what this block sets, sensors "
                            f"included, goes to '{view.lumped[name]}'")
        elif name in view.lost:
            diagnostics.add("W231", block, f"{where}: Gazebo leaves out link '{name}' "
                            "(see E150), so this block applies to nothing")
        elif name in urdf_joints:
            diagnostics.add("W231", block, f"{where}: Gazebo has no joint '{name}' "
                            f"({_joint_fate(urdf_joints[name], view)}), so this block "
                            "applies to nothing")
        else:
            diagnostics.add("W231", block, f"{where}: the robot has no link or joint "
                            f"'{name}', so this block applies to nothing")


def _plugin_joints(robot, view: GazeboView, parent_joint: dict, joints: set,
                   diagnostics: Reporter) -> None:
    """Joint names in the parameters of ``<gazebo>`` plugins that Gazebo does not have."""
    urdf_joints = {joint.name: joint for joint in robot.joints}
    for block in robot.others:
        if block.tag != "gazebo":
            continue
        for plugin in block.iter("plugin"):
            label = plugin.get("name") or plugin.get("filename") or "?"
            for parameter in plugin.iter():
                if parameter is plugin or not isinstance(parameter.tag, str) or \
                        not _JOINT_TAG.fullmatch(parameter.tag):
                    continue
                for name in _NAME_SEPARATOR.split((parameter.text or "").strip()):
                    if not name or name in joints:
                        continue
                    fate = (_joint_fate(urdf_joints[name], view) if name in urdf_joints
                            else "the robot has no such joint")
                    diagnostics.add("W232", parameter, f"plugin '{label}': "
                                    f"<{parameter.tag}> names joint '{name}', which Gazebo "
                                    f"does not have ({fate})")


def _joint_fate(joint, view: GazeboView) -> str:
    if joint.child in view.lost:
        return f"left out with link '{joint.child}'"
    if joint.child in view.lumped:
        return f"a fixed joint, lumped away with link '{joint.child}'"
    return "libsdformat did not keep it"


def _mass(link) -> float:
    inertial = link.inertial
    mass = inertial.get("mass") if inertial is not None else None
    value = parse_number(mass.get("value")) if mass is not None else None
    return value if value is not None and value > 0 else 0.0


def _why_massless(link) -> str:
    if link.inertial is None:
        return "no <inertial>"
    return "mass 0"


def _mass_words(gazebo: float, urdf: float) -> str:
    if math.isclose(gazebo, urdf, rel_tol=1e-6, abs_tol=1e-9):
        return f"{gazebo:.4g} kg, as in the URDF"
    return f"{gazebo:.4g} kg of the URDF's {urdf:.4g} kg ({urdf - gazebo:.4g} kg left out)"


def _listed(items: list[str]) -> str:
    if len(items) <= MAX_NAMED:
        return ", ".join(items)
    return ", ".join(items[:MAX_NAMED]) + f" and {len(items) - MAX_NAMED} more"


def _first_line(text: str) -> str:
    line = text.strip().splitlines()[0] if text.strip() else ""
    return line if len(line) <= 200 else line[:197] + "..."
