"""``mcar build --format sdf``: the SDF Gazebo would spawn, written by libsdformat itself
(through the Gazebo helper, as ``gz sdf -p`` prints it), never by mcar.
"""

from __future__ import annotations

from ..errors import GazeboError
from .changes import MAX_NAMED, link_fates


def sdf_of(loaded) -> tuple[bytes, list[str]]:
    """(the SDF of a loaded robot, warnings to show): what libsdformat printed, and one
    per link it leaves out for want of mass (``mcar check --gazebo`` says what is lost).
    GazeboError (exit 1) where libsdformat cannot make a model of it; GazeboUnavailable
    (exit 2) without the helper."""
    from .helper import run_helper
    from .includes import refuse_includes

    refuse_includes(loaded.urdf, loaded.label, loaded.locate)  # E152, at its source line
    report = run_helper(loaded.urdf, loaded.label, with_sdf=True)
    if report.model is None or report.errors:
        first = report.errors[0].text.strip().splitlines()[0] if report.errors else \
            "no model"
        # the rest of its verdict, then what it printed: often the reason (urdfdom's)
        raise GazeboError(f"libsdformat {report.sdformat} cannot make a Gazebo model of "
                          f"it: {first[:300]}", file=loaded.label,
                          details=[f"{m.where}: {m.text.strip().splitlines()[0][:300]}"
                                   for m in dict.fromkeys((*report.errors[1:],
                                                           *report.console_errors))
                                   if m.text.strip()])
    # what it printed and loaded past (errors included: not its verdict), once each
    warnings = [f"libsdformat: {m.text.strip()} ({m.where})"
                for m in dict.fromkeys((*report.console_errors, *report.warnings))]
    _lumped, lost = link_fates(_link_names(loaded.urdf), report, None)
    if lost:
        warnings.append(f"Gazebo leaves out {len(lost)} link{'s' * (len(lost) != 1)} of the "
                        f"URDF ({', '.join(lost[:MAX_NAMED])}{', ...' * (len(lost) > MAX_NAMED)})"
                        ": a link without mass and everything that moves below it; "
                        "mcar check --gazebo says which and why")
    return report.sdf.encode("utf-8"), warnings


def _link_names(urdf: bytes) -> list[str]:
    """The names of the robot's links but "world" (the ground, never a Gazebo link)."""
    from ..check.urdf_model import XmlError, parse_xml

    try:
        root = parse_xml(urdf)
    except XmlError:  # libsdformat read it, lxml does not: no count of what is lost
        return []
    return [link.get("name") for link in root
            if link.tag == "link" and link.get("name") not in (None, "world")]
