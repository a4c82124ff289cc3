"""The statics rules (docs/rules.md): a robot that tips on a slope its motors climb
(W502 facing up or down it, W504 across it), that cannot climb an easy slope (W503),
whose centre of mass is not inside what it stands on (W505), whose figure MuJoCo's proof
disagrees with (W506); and E503, motors that cannot move it on flat ground. Each message
gives the figures; the line is the first driven wheel's joint where it is known."""

from __future__ import annotations

from ..check.diagnostics import Diagnostic

EASY_SLOPE = 5.0  # deg


def judge(checked, sim, section) -> list[Diagnostic]:
    value = {f.key: f.value for f in section.figures}
    file, line = _where(checked, sim)
    found = []

    def say(rule, message):
        found.append(Diagnostic(rule, file, line, message))

    climb = value.get("statics.climb")
    if climb is not None:
        if climb <= 0:
            say("E503", f"the motors cannot move the robot on flat ground: "
                        f"{_source(section, 'statics.climb')}")
        elif climb < EASY_SLOPE:
            say("W503", f"it climbs {climb:.1f}° at most, less than a {EASY_SLOPE:g}° ramp: "
                        f"{_source(section, 'statics.climb')}")
        for name, facing in (("backward", "up"), ("forward", "down")):
            tip = value.get(f"statics.tip.{name}")
            if climb > 0 and tip is not None and climb >= tip:
                say("W502", f"its motors climb {climb:.1f}° but it tips over {name} at "
                            f"{tip:.1f}°: driving {facing} such a slope it falls")
                break
        across = [(value.get(f"statics.tip.{n}"), n) for n in ("left", "right")]
        across = [(t, n) for t, n in across if t is not None]
        if climb > 0 and across and min(across)[0] <= climb:
            tip, name = min(across)
            say("W504", f"its motors climb {climb:.1f}° but across a slope it tips over "
                        f"{name} at {tip:.1f}° (track too narrow or centre of mass too high)")
    least = value.get("statics.tip.min")
    if least is not None and least <= 0:
        say("W505", "its centre of mass is not inside the polygon it stands on "
                    f"({_source(section, 'statics.support')}): it stands only balanced")
    for figure in section.figures:
        if figure.proof is not None and not figure.proof.agrees:
            say("W506", f"{figure.key} {figure.value}{' ' + figure.unit} but MuJoCo measured "
                        f"{_shown(figure.proof.measured, figure.unit)} "
                        f"({figure.proof.tolerance}): {figure.proof.detail}")
    return found


def _where(checked, sim) -> tuple[str, int | None]:
    """The first driven wheel's joint in the sources (check's source map), else the file."""
    if sim.drive is None or not sim.drive.driven:
        return checked.file, None
    name = sim.drive.driven[0].joint
    joint = next((j for j in checked.robot.joints if j.name == name), None)
    if joint is None or checked.where is None:
        return checked.file, None
    file, line, _ = checked.where(joint.element)
    return file, line


def _source(section, key) -> str:
    figure = section.figure(key)
    return figure.source if figure is not None else ""


def _shown(value, unit) -> str:
    if value is None:
        return "nothing"
    return f"{value:.2f}{' ' + unit if unit else ''}" if isinstance(value, float) else str(value)
