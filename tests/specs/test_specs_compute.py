"""compute() runs body first, then statics, joints, sensors, stack and inertia, each given
the context with the body figures and the command's options (the parts stand in here as
modules that record what they were given)."""

from __future__ import annotations

import importlib
import json
import sys
import types

import pytest
from specs import robots

from mobile_car.specs.compute import PARTS
from mobile_car.specs.figures import Section


@pytest.fixture
def recording_parts(monkeypatch) -> list:
    """Each part a module whose section() records (its name, the context) and returns an
    empty Section of its name; the rest of the module is the real one's (the command
    imports its constants)."""
    calls = []
    for name in PARTS:
        module = types.ModuleType(f"mobile_car.specs.{name}")
        module.__dict__.update(
            {k: v for k, v in vars(importlib.import_module(module.__name__)).items()
             if not k.startswith("__")})

        def section(context, name=name):
            calls.append((name, context))
            return Section(name)

        module.section = section
        monkeypatch.setitem(sys.modules, module.__name__, module)
    return calls


def test_the_parts_run_in_order_after_body_with_the_options(cli, tmp_path, recording_parts):
    path = tmp_path / "car.urdf"
    path.write_text(robots.box_on_wheels())
    result = cli("specs", path, "--no-proof", "--friction", "0.4", "--effort", "2",
                 "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert [name for name, _ in recording_parts] == list(PARTS)
    assert PARTS == ("statics", "joints", "sensors", "stack", "inertia")
    context = recording_parts[0][1]
    assert context.body.name == "body" and context.body.figure("body.mass").value == 5.2
    assert context.sim is not None and context.checked.robot.name == "box_on_wheels"
    assert {k: context.options[k] for k in ("proof", "friction", "effort", "speed")} == {
        "proof": False, "friction": 0.4, "effort": 2.0, "speed": None}
    sections = json.loads(result.stdout)["files"][0]["sections"]
    assert [s["name"] for s in sections] == ["body", *PARTS]


def test_the_proofs_are_asked_for_by_default(cli, tmp_path, recording_parts):
    path = tmp_path / "car.urdf"
    path.write_text(robots.box_on_wheels())
    assert cli("specs", path).exit_code == 0
    assert recording_parts[0][1].options["proof"] is True
