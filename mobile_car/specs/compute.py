"""Every section of ``mcar specs`` for one checked robot, in order: body first (every
other part starts from its figures), then statics, joints, sensors, stack, inertia, each
a module of this package with ``section(context) -> Section``."""

from __future__ import annotations

import importlib

from . import body
from .context import SpecsContext
from .model import specs_model

# The parts after body, in the order they are computed and printed.
PARTS = ("statics", "joints", "sensors", "stack", "inertia")
# sim's drive options, passed to specs_model from ``options``
MODEL_OPTIONS = ("left", "right", "kind", "effort", "speed", "fix_inertia", "setting")


def compute(checked, options: dict | None = None) -> list:
    """The Sections of a robot that passed ``mcar check`` (a CheckResult); ``options``
    as :class:`~.context.SpecsContext` documents."""
    return computed(checked, options).sections


def computed(checked, options: dict | None = None) -> SpecsContext:
    """:func:`compute`'s context once every section is in it (``sections``), with sim's
    model (``sim``) the stack's files are written from. sim's notes on the model (what it
    changed, or why there is none) open the body section's notes."""
    from ..load.mesh_cache import kept

    options = dict(options or {})
    with kept():  # sim's model, the sensors' scenes and the proofs read the same meshes
        sim, notes = specs_model(checked, **{k: options[k] for k in MODEL_OPTIONS
                                             if k in options})
        context = SpecsContext(checked, sim, options)
        context.sections = [body.section(context)]
        context.body.notes[:0] = notes
        for name in PARTS:
            context.sections.append(_part(name).section(context))
    return context


def _part(name: str):
    """The module of part ``name``, imported when the command runs (each brings numpy,
    MuJoCo or trimesh with it; tests stand in for them through sys.modules)."""
    return importlib.import_module(f"{__package__}.{name}")
