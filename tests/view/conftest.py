"""Fixtures for the mcar view tests: a private copy of the arm robot, and the bundled car,
each served on a free port of 127.0.0.1 by a real viser server that every test stops."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

ARM = Path(__file__).resolve().parent / "arm"


@pytest.fixture
def arm_copy(tmp_path) -> Path:
    """A copy of tests/view/arm, free to edit: returns its robot file."""
    copy = tmp_path / "arm"
    shutil.copytree(ARM, copy)
    return copy / "arm.urdf.xacro"


@pytest.fixture
def served(arm_copy):
    """A RobotView of the arm copy on 127.0.0.1, any free port; stopped after the test."""
    pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]"; '
                                        "`make test` installs it)")
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions
    from mobile_car.view.model import load_model
    from mobile_car.view.server import RobotView

    inp, options = RobotInput(arm_copy), LoadOptions()
    view = RobotView(load_model(inp, options), lambda: load_model(inp, options),
                     host="127.0.0.1", port=0)
    try:
        yield view
    finally:
        view.stop()


@pytest.fixture
def serve():
    """serve(RobotInput, LoadOptions): a RobotView as `mcar view` makes it (with dimension
    sliders when the robot is built from a config.xacro); each is stopped after the test."""
    pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]"; '
                                        "`make test` installs it)")
    from mobile_car.view.dimensions import robot_dimensions
    from mobile_car.view.model import load_model
    from mobile_car.view.server import RobotView

    views = []

    def start(inp, options):
        model = load_model(inp, options)
        dimensions = robot_dimensions(inp, options, model)
        reload = dimensions.load if dimensions else lambda: load_model(inp, options)
        views.append(RobotView(model, reload, host="127.0.0.1", port=0,
                               dimensions=dimensions))
        return views[-1]

    try:
        yield start
    finally:
        for view in views:
            view.stop()


@pytest.fixture
def car(serve, repo):
    """The bundled car (urdf/mobile_robot.xacro), served."""
    from mobile_car.load.inputs import RobotInput
    from mobile_car.load.robot import LoadOptions

    return serve(RobotInput(repo / "urdf" / "mobile_robot.xacro"), LoadOptions())
