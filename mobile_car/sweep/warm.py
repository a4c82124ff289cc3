"""Imported once in a local sweep's fork server (see execute._pool): what evaluating a
point imports, so that each worker forked from the server starts with it, instead of every
worker importing it again (~0.8 s of CPU each: lxml, xacro, numpy, MuJoCo)."""

from __future__ import annotations

from ..check import checker  # noqa: F401
from ..config import overrides  # noqa: F401
from ..load import robot  # noqa: F401
from ..sim import report  # noqa: F401
from ..sim.engine import mujoco
from . import point  # noqa: F401

mujoco()
