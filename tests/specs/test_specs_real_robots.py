"""mcar specs on the bundled car and on robots people ship (TurtleBot3 burger, Husky,
Jackal, read in place from the shared real-robots folder: skipped where it is absent):
every body figure is there with a source, the wheels are those SOURCES.md gives, and the
loads on the wheels and castors carry the robot's weight."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from conftest import REPO
from sim.test_sim_real_robots import FOLDER, needs_folder

G = 9.81
BODY_KEYS = ("body.mass", "body.com", "body.com_height", "body.footprint",
             "body.radius.circumscribed", "body.radius.inscribed", "body.clearance",
             "wheels.radius", "wheels.track", "wheels.wheelbase")
# robot -> (file, mass kg, wheel radius, track, wheelbase, how its loads are found), as
# SOURCES.md and the bundled car's config.xacro give them
ROBOTS = {
    "car": (REPO / "urdf" / "mobile_robot.xacro", 0.7056, 0.0325, 0.165, None, "statics"),
    "burger": ("turtlebot3_description/urdf/turtlebot3_burger.urdf", 1.002, 0.033, 0.160,
               None, "statics"),
    "husky": ("husky_description/urdf/husky.urdf.xacro", 56.58, 0.1651, 0.5708, 0.512,
              "MuJoCo"),
    "jackal": ("jackal_description/urdf/jackal.urdf.xacro", 18.43, 0.098, 0.37559, 0.262,
               "MuJoCo"),
}


def _specs(name: str) -> dict:
    """The robot's JSON entry (mcar specs --no-proof --format json, in process)."""
    from mobile_car.cli.main import main

    file = ROBOTS[name][0]
    words = [str(file)] if name == "car" else ["--package-path", str(FOLDER),
                                               str(FOLDER / file)]
    result = CliRunner().invoke(main, ["specs", "--no-proof", "--format", "json", *words],
                                catch_exceptions=False)
    assert result.exit_code == 0, result.output
    (entry,) = json.loads(result.stdout)["files"]
    return entry


@pytest.fixture(scope="module")
def specs_of():
    """name -> its JSON entry, each robot run once for the module's tests."""
    done = {}

    def get(name: str) -> dict:
        if name not in done:
            done[name] = _specs(name)
        return done[name]

    return get


@pytest.mark.parametrize("name", [
    "car", *(pytest.param(n, marks=needs_folder) for n in ("burger", "husky", "jackal"))])
def test_every_body_figure_is_there_with_a_source(specs_of, name):
    figures = specs_of(name)["figures"]
    _, mass, radius, track, wheelbase, loads_from = ROBOTS[name]
    for key in BODY_KEYS:
        assert figures[key]["source"], key
        if key != "wheels.wheelbase":
            assert figures[key]["value"] is not None, (key, figures[key]["source"])
    assert figures["body.mass"]["value"] == pytest.approx(mass, abs=5e-3)  # as rounded
    assert figures["wheels.radius"]["value"] == pytest.approx(radius, rel=1e-3)
    assert figures["wheels.track"]["value"] == pytest.approx(track, rel=1e-3)
    if wheelbase is None:
        assert figures["wheels.wheelbase"]["value"] is None
    else:
        assert figures["wheels.wheelbase"]["value"] == pytest.approx(wheelbase, rel=1e-3)
    loads = {k: f for k, f in figures.items() if k.startswith("loads.")}
    assert len(loads) == (3 if loads_from == "statics" else 4)
    assert all(f["source"].startswith(loads_from) for f in loads.values())
    assert sum(f["value"] for f in loads.values()) == pytest.approx(mass * G, rel=0.01)
    # the footprint holds the wheels' contact points, and the floor frame's origin
    outer = figures["body.radius.circumscribed"]["value"]
    assert figures["body.radius.inscribed"]["value"] > 0
    assert outer >= max(abs(p) for point in figures["body.footprint"]["value"]
                        for p in point)


@needs_folder
def test_burger_rests_leaning_on_its_caster_and_says_so(specs_of):
    figures = specs_of("burger")["figures"]
    assert figures["body.com_height"]["assumption"].startswith("leaning as its geometry rests")
    # Its wheels stand out of its 140 mm box: 80 mm out, 18 mm wide, 33 mm in radius, on
    # joints at rpy="-1.57 0 0", so each disc leans π/2 - 1.57 rad out of the vertical.
    lean = math.pi / 2 - 1.57
    side = 0.08 + 0.009 * math.cos(lean) + 0.033 * math.sin(lean)
    ys = [y for _, y in figures["body.footprint"]["value"]]
    assert (min(ys), max(ys)) == pytest.approx((-side, side), abs=1e-9)
