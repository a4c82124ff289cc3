"""`mcar ci` draws a robot whose simulation failed: its picture is what shows why (before,
a package whose every robot failed sim got no picture at all: the renders were drawn
only when some robot passed)."""

from __future__ import annotations

from ci.test_ci_vehicles import make_package
from PIL import Image
from sim.robot_makers import skid_plate


def test_a_robot_that_fails_sim_keeps_its_picture(run_mcar, tmp_path):
    package = make_package(tmp_path / "belly_description", "belly_description",
                           {"belly.urdf": skid_plate(sag=0.004)})
    result = run_mcar("ci", package, "--build-dir", tmp_path / "build", "--render-dir",
                      tmp_path / "renders", "--no-gazebo", cwd=tmp_path, timeout=300)
    assert result.returncode == 1
    assert "drop failed: not touching the floor: wheel_left_link, wheel_right_link (drive " \
           "wheels); resting on plate_link: not a wheel or castor" in result.stderr
    picture = tmp_path / "renders" / "belly.png"
    assert picture.is_file(), sorted(p.name for p in (tmp_path / "renders").rglob("*"))
    with Image.open(picture) as image:
        low, high = image.convert("L").getextrema()
        assert image.size[0] >= 320 and high - low > 50  # a drawing, not a blank
    assert (tmp_path / "renders" / "index.png").is_file()  # the contact sheet too
