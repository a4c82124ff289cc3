"""A description's spring figures reach the simulation (mobile_car/sim/springs.py): a
hostile file gives a wheel drop a stiffness, a reference or a travel no suspension has
(1e300), so that MuJoCo's state turns to NaN in one step and it prints its instability
warning thousands of times (4,000 lines for one drop). Such a figure is not used: the
spring is the default one, and the report says why; a joint limited wider than any
suspension travels is held still. Each attack has its control: the figure put into the
model as written makes the NaN."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from sim.robot_makers import sprung

HOSTILE = {
    "stiffness": ("<springStiffness>4000</springStiffness>",
                  "<springStiffness>1e300</springStiffness>"),
    "reference": ("<springReference>0.006</springReference>",
                  "<springReference>1e300</springReference>"),
}


def _hostile(name: str) -> str:
    old, new = HOSTILE[name]
    text = sprung(gazebo=True)
    assert text.count(old) == 2
    return text.replace(old, new)


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_a_spring_figure_no_step_can_follow_is_not_used(cli, tmp_path, name):
    path = tmp_path / f"{name}.urdf"
    path.write_text(_hostile(name))
    result = cli("sim", path, "--scenario", "drop", "--format", "json")
    assert result.exit_code == 0, result.stderr
    assert "WARNING" not in result.stdout + result.stderr
    (entry,) = json.loads(result.stdout)["files"]
    spring = entry["drive"]["sprung"][0]
    assert spring["source"].startswith("default: carries its share of the weight at "
                                       f"mid-travel (<gazebo> spring{name.title()} 1e+300 ")
    assert entry["scenarios"][0]["status"] == "passed"


def test_a_travel_no_suspension_has_is_held_still(cli, tmp_path):
    path = tmp_path / "travel.urdf"
    text = sprung()
    assert text.count('upper="0.006"') == 2
    path.write_text(text.replace('upper="0.006"', 'upper="1e300"'))
    result = cli("sim", path, "--scenario", "drop", "--format", "json")
    assert "WARNING" not in result.stdout + result.stderr
    (entry,) = json.loads(result.stdout)["files"]
    assert entry["held"] == ["wheel_drop_left_joint", "wheel_drop_right_joint"]
    assert entry["drive"]["sprung"] == []
    assert result.exit_code == 0, entry["scenarios"][0]["message"]


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_control_the_figure_as_written_makes_nan(name):
    """The defence is what keeps the state finite: the hostile figure written into the
    compiled model by hand, the drop's state is NaN."""
    from mobile_car.sim.model import build_model
    from mobile_car.sim.scenarios import run_scenarios

    sim = build_model(_hostile(name).encode(), "hostile.urdf", Path.cwd(), None)
    model = sim.model
    for spring in sim.springs:
        joint = model.joint(spring.joint).id
        if name == "stiffness":
            model.jnt_stiffness[joint] = 1e300
        else:
            model.qpos_spring[model.jnt_qposadr[joint]] = 1e300
    (drop,) = run_scenarios(sim, ["drop"])
    assert not math.isfinite(drop.measured["rest_height_m"])


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_an_export_writes_sims_spring_not_the_hostile_figure(cli, tmp_path, name):
    """``mcar export --to mjcf`` writes sim's springs into the file a MuJoCo user runs:
    the hostile figure is not in it, the default spring is, and --verify passes. Control:
    the figure put into the written file makes its drop fail."""
    import re

    from mobile_car.errors import McarError
    from mobile_car.export.mjcf import Exported
    from mobile_car.export.verify import verify_mjcf

    path = tmp_path / f"{name}.urdf"
    path.write_text(_hostile(name))
    result = cli("export", path, "--to", "mjcf", "-o", tmp_path / "out", "--verify")
    assert result.exit_code == 0, result.stderr
    assert "WARNING" not in result.stdout + result.stderr
    xml = tmp_path / "out/sprung.xml"
    text = xml.read_text()
    assert "e+300" not in text and "inf" not in text.lower()
    document = json.loads((tmp_path / "out/mcar-export.json").read_text())
    (left, _) = document["springs"]
    assert left["source"].startswith("default: carries its share of the weight at mid-travel")
    assert f'stiffness="{left["stiffness"]:g}"' in text
    attribute = "stiffness" if name == "stiffness" else "springref"
    xml.write_text(re.sub(rf' {attribute}="[^"]*"', f' {attribute}="1e300"', text))
    exported = Exported(**{k: document[k] for k in Exported.__dataclass_fields__})
    with pytest.raises(McarError, match="drop failed as mcar sim judges it: "):
        verify_mjcf(tmp_path / "out", exported)


def test_an_unstable_run_writes_no_log_into_the_working_folder(tmp_path, monkeypatch):
    """MuJoCo appends its warnings to MUJOCO_LOG.TXT in the working folder, the user's
    package, unless mcar takes them: it does, and keeps the latest."""
    from mobile_car.sim.engine import WARNINGS, mujoco

    monkeypatch.chdir(tmp_path)
    mj = mujoco()
    model = mj.MjModel.from_xml_string(
        '<mujoco><worldbody><body><freejoint/><geom size="0.1"/></body></worldbody></mujoco>')
    data = mj.MjData(model)
    data.qpos[0] = float("nan")
    mj.mj_step(model, data)
    assert list(tmp_path.iterdir()) == []
    assert WARNINGS[-1].startswith("Nan, Inf or huge value in QPOS")
