"""mcar sim reads a robot's control package's YAML files for a mecanum_drive_controller
(sim/mecanum.py, issue 40 item 4): files a pull request commits. The attack: a
``config/*.yaml`` that is a link to a file outside the package, which mcar would read and,
where it does not parse as YAML, quote in the "not read (...)" line it prints. A secret
planted outside the package must not reach the output; the link is said, not followed.
The control commits the same bytes as a regular file inside the package: its parse error
then quotes them, so the test can fail."""

from __future__ import annotations

import json

import pytest
from hostile import files_holding
from sim.robot_makers import PLANAR_MOVE, mecanum_wheels

MARK = "MCAR-SECRET-5d1e0b"
# A file that names the controller (so it is parsed) and does not parse, its first bad
# line holding the secret: PyYAML's error quotes that line.
SECRET = f"mecanum_drive_controller: x\n{MARK}: : bad\n"
PACKAGE_XML = ('<?xml version="1.0"?><package format="3"><name>{}</name><version>0.0.1'
               '</version><description>d</description><maintainer email="t@example.com">t'
               '</maintainer><license>BSD</license></package>\n')


def plant(tmp_path, linked: bool):
    """atk_description (a mecanum base, declared by planar_move on sliding wheels, so that
    only the mecanum reader reads the control package) and atk_control, whose
    config/evil.yaml is a link to the secret outside (or, ``linked`` false, a copy)."""
    outside = tmp_path / "outside"
    outside.mkdir()
    secret = outside / "secret.yaml"
    secret.write_text(SECRET)
    work = tmp_path / "ws"
    for name in ("atk_description", "atk_control"):
        (work / name).mkdir(parents=True)
        (work / name / "package.xml").write_text(PACKAGE_XML.format(name))
    (work / "atk_description" / "robot.urdf").write_text(
        mecanum_wheels(wheel_mu=0.01, extra=PLANAR_MOVE))
    (work / "atk_control" / "config").mkdir()
    evil = work / "atk_control" / "config" / "evil.yaml"
    if linked:
        evil.symlink_to(secret)
    else:
        evil.write_text(SECRET)
    return work


@pytest.mark.parametrize("linked", [True, False], ids=["link-out", "control-inside"])
def test_a_control_yaml_linked_out_of_its_package_is_not_read(cli, tmp_path, monkeypatch,
                                                               linked):
    work = plant(tmp_path, linked)
    monkeypatch.chdir(work)
    out = tmp_path / "out"
    out.mkdir()
    result = cli("sim", "atk_description/robot.urdf", "--package-path", work, "--scenario",
                 "drop", "--format", "json")
    assert result.exit_code == 0, result.stderr
    (out / "stdout.json").write_text(result.stdout)
    (out / "stderr.txt").write_text(result.stderr)
    entry = json.loads(result.stdout)["files"][0]
    assert entry["drive"]["kind"] == "mecanum"
    notes = entry["notes"]
    if linked:
        assert files_holding(out, MARK.encode()) == []
        assert notes == ["atk_control/config/evil.yaml: not read (a link to "
                         f"{(tmp_path / 'outside' / 'secret.yaml').resolve()}, outside "
                         f"{(work / 'atk_control').resolve()})"]
    else:  # the same bytes inside the package: read, and their error quoted
        assert notes[0].startswith("atk_control/config/evil.yaml: not read (mapping values ")
        assert files_holding(out, MARK.encode()) == ["stdout.json"]
