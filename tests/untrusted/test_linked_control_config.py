"""A pull request attacks what ``mcar sim`` and ``mcar ci`` read of a robot's control
package (``X_control/config/*.yaml``, the controllers that declare its drive):

* ``atk_control/config/ctrl.yaml`` -> a file of the runner's (a credentials file): the
  YAML error quoting its first line (``while scanning a quoted scalar ... password:
  "..."``) printed the secret into the CI log.

The link is now refused unread, said in one line. The control puts the same bytes in the
control package as a plain file: they reach the message, so the test can see a leak.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from sim.robot_makers import two_wheeler

MARK = "MCAR-SECRET-5d21a9"
PACKAGE_XML = """<package format="2"><name>{}</name><version>0.0.0</version>
<description>x</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
</package>
"""


def _packages(root: Path, linked: bool) -> Path:
    """root/atk_description (the robot), root/atk_control (its controllers, the attack),
    root/outside/credentials (the runner's secret, planted outside both)."""
    for name in ("atk_description", "atk_control"):
        (root / name).mkdir()
        (root / name / "package.xml").write_text(PACKAGE_XML.format(name))
    (root / "atk_description" / "robot.urdf").write_text(two_wheeler())
    (root / "outside").mkdir()
    secret = root / "outside" / "credentials"
    secret.write_text(f'password: "{MARK}\n')
    (root / "atk_control" / "config").mkdir()
    config = root / "atk_control" / "config" / "ctrl.yaml"
    if linked:
        config.symlink_to(secret)
    else:
        config.write_bytes(secret.read_bytes())
    return config


@pytest.mark.parametrize("linked", [True, False])  # False: the control, a plain file
def test_a_control_yaml_linked_out_of_its_package_is_not_read(run_mcar, tmp_path, linked):
    config = _packages(tmp_path, linked)
    result = run_mcar("sim", tmp_path / "atk_description" / "robot.urdf", "--package-path",
                      tmp_path, "--scenario", "drop")
    assert result.returncode == 0, result.stdout + result.stderr
    if not linked:
        assert MARK in result.stderr  # the YAML error quotes the file
        return
    assert MARK not in result.stdout + result.stderr
    assert (f"{config}: not read (a link to {tmp_path / 'outside' / 'credentials'}, outside "
            f"{tmp_path / 'atk_control'})") in result.stderr
