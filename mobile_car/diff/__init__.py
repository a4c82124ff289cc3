"""``mcar diff`` as a library: what a change does to the robot.

:func:`describe` turns a loaded robot into :class:`~mobile_car.diff.facts.RobotFacts`
(joints, links, frames at joint zero, totals, config dimensions);
:func:`~mobile_car.diff.compare.compare` matches two of them by name;
:mod:`mobile_car.diff.report` writes the result as text, markdown or JSON.
"""

from __future__ import annotations

from ..errors import CheckFailed
from .compare import RobotDiff, compare
from .facts import RobotFacts, Value, robot_facts

__all__ = ["RobotDiff", "RobotFacts", "compare", "describe"]


def describe(loaded, label: str, mappings: dict[str, str] | None = None) -> RobotFacts:
    """The facts of a loaded robot, which must pass ``mcar check`` (else CheckFailed,
    with its diagnostics); ``mappings`` are the xacro arguments its dimensions were
    built with (the overrides' config:=)."""
    from ..check.checker import check_loaded

    result = check_loaded(loaded)
    if result.failure is not None:
        raise result.failure
    if result.errors or not result.tree_is_drawable:
        raise CheckFailed(label, result.diagnostics)
    facts = robot_facts(loaded.urdf, label, loaded.base, loaded.search)
    config = next((path for path in loaded.deps if path.name == "config.xacro"), None)
    if config is not None:
        facts.dimensions = _dimensions(config, mappings or {}, loaded.search)
    return facts


def _dimensions(config, mappings: dict[str, str], search) -> dict[str, Value]:
    from ..config.overrides import evaluate
    from ..config.spec import load_spec

    spec = load_spec(config)
    values = evaluate(spec, mappings, search)
    return {name: Value(f"unit:{spec.dimensions[name].unit}", (float(value),))
            for name, value in values.items()}
