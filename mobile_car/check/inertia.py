"""Inertia rules: an ``<inertial>`` must be complete (E115), and should be physical.

A negative mass on any link is an error (E118). A mass of 0 on a moving link, a tensor
that is not positive definite, principal moments that break the triangle inequality (no
rigid body has them), a moving link with no inertia at all, and an inertia on the root
link (KDL ignores it) are warnings: the file is valid URDF, but a simulator or a dynamics
library will misbehave on it.
"""

from __future__ import annotations

import math

from .context import MAX_INERTIA, MAX_MASS, Reporter, within
from .urdf_reader import Link

INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def check_inertia(links: list[Link], report: Reporter, moving: set[str],
                  root: str | None) -> None:
    """``moving`` holds the links carried by a non-fixed joint; ``root`` the root, if one."""
    for link in links:
        owner = f"link '{link.name}'" if link.name else "link"
        is_moving = link.name in moving
        if link.inertial is None:
            if is_moving:
                report.add("W206", link.element, f"{owner} moves but has no <inertial>; "
                           "Gazebo leaves it out, with everything that moves below it "
                           "(mcar check --gazebo)")
            continue
        inertial = link.parts["inertial"]
        parts = link.inertial
        report.origin(parts.get("origin"), owner)
        mass, inertia = parts.get("mass"), parts.get("inertia")
        # The verdict depends on these values only: check each distinct set once.
        key = ("inertial", is_moving, None if mass is None else mass.get("value"),
               None if inertia is None else tuple(inertia.items()))
        report.once_clean(key, _check_mass_inertia, inertial, parts, owner, is_moving, report)
        if link.name == root and root is not None:
            report.add("W208", inertial, f"{owner} is the root and has an inertia, which KDL "
                                         "ignores; add a massless root link (base_footprint) "
                                         "above it")


def _check_mass_inertia(inertial, parts: dict, owner: str, moving: bool,
                        report: Reporter) -> None:
    mass_element = parts.get("mass")
    if mass_element is None or mass_element.get("value") is None:
        report.add("E115", inertial if mass_element is None else mass_element,
                   f"{owner}: <inertial> has no <mass value=.../>")
    else:
        mass = report.number(mass_element, "value", owner)
        sane = report.bounded(mass_element, "value", None if mass is None else (mass,),
                              MAX_MASS, " kg", owner)
        # A fixed link may be a massless frame (0), but no body weighs less than nothing:
        # the negative test used to sit behind the moving one, so fixed links escaped it.
        if sane and mass is not None and mass < 0:
            report.add("E118", mass_element, f"{owner}: mass {mass:g} kg is negative; no body "
                       "has a negative mass")
        elif sane and mass is not None and mass == 0 and moving:
            report.add("W203", mass_element, f"{owner} moves but its mass is {mass:g}")
    inertia = parts.get("inertia")
    if inertia is None:
        report.add("E115", inertial, f"{owner}: <inertial> has no <inertia .../>")
        return
    missing = [name for name in INERTIA if inertia.get(name) is None]
    if missing:
        report.add("E115", inertia, f"{owner}: <inertia> is missing "
                   f"{', '.join(missing)}")
        return
    values = [report.number(inertia, name, owner) for name in INERTIA]
    if None in values:
        return
    if not within(values, MAX_INERTIA):  # (the eigenvalues would overflow, too)
        for name, value in zip(INERTIA, values, strict=True):
            report.bounded(inertia, name, (value,), MAX_INERTIA, " kg m²", owner)
        return
    problem = tensor_problem(*values)
    if problem is not None:
        rule, text = problem
        report.add(rule, inertia, f"{owner}: {text}")


def tensor_problem(ixx, ixy, ixz, iyy, iyz, izz) -> tuple[str, str] | None:
    """(rule, message) if the inertia tensor is not physical, else None."""
    moments = principal_moments(ixx, ixy, ixz, iyy, iyz, izz)
    a, b, c = moments
    scale = max(-a, c) or 1.0  # the largest magnitude: a <= b <= c
    if a <= 1e-12 * scale:
        # a moment within round-off of 0 is shown as 0: Unitree B1's base, every entry
        # 1e-6, has moments 0, 0, 3e-06, which the closed form gives as ±4.2e-22
        shown = tuple(0.0 if abs(m) <= 1e-12 * scale else m for m in moments)
        return "W204", f"inertia is not positive definite (principal moments {_show(shown)})"
    if a + b < c * (1 - 1e-6):
        return "W205", (f"principal moments {_show(moments)} break the triangle inequality "
                        "(no rigid body has them)")
    return None


def _show(moments) -> str:
    return ", ".join(f"{m:.4g}" for m in moments)


def principal_moments(ixx, ixy, ixz, iyy, iyz, izz) -> tuple[float, float, float]:
    """Eigenvalues of the symmetric inertia tensor, ascending, in closed form (no numpy)."""
    off = ixy * ixy + ixz * ixz + iyz * iyz
    if off == 0:
        return tuple(sorted((ixx, iyy, izz)))
    q = (ixx + iyy + izz) / 3
    p = math.sqrt(((ixx - q) ** 2 + (iyy - q) ** 2 + (izz - q) ** 2 + 2 * off) / 6)
    b = [[(ixx - q) / p, ixy / p, ixz / p], [ixy / p, (iyy - q) / p, iyz / p],
         [ixz / p, iyz / p, (izz - q) / p]]
    det = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
           - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
           + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]))
    phi = math.acos(max(-1.0, min(1.0, det / 2))) / 3
    largest = q + 2 * p * math.cos(phi)
    smallest = q + 2 * p * math.cos(phi + 2 * math.pi / 3)
    return tuple(sorted((smallest, 3 * q - largest - smallest, largest)))
