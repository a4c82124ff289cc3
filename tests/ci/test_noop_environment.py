"""An environment variable a xacro reads ($(optenv NAME default), as Husky's and Jackal's
accessories are switched on) is an input like a file: with it changed, build, check,
render and ci do the work again and show the other robot; with it back as it was, each
is a no-op again (freshness.py stamps the variables a stamped file names)."""

from __future__ import annotations

import json

from ci.test_ci_vehicles import make_package

ROBOT = """<robot name="lamp" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link">
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="0.004" ixy="0" ixz="0" iyy="0.004" iyz="0"
      izz="0.0067"/></inertial>
  </link>
  <xacro:if value="$(optenv LAMP_MAST_ENABLED 0)">
    <link name="mast">
      <visual><geometry><box size="0.02 0.02 1.0"/></geometry></visual>
    </link>
    <joint name="mast_joint" type="fixed"><parent link="base_link"/><child link="mast"/>
      <origin xyz="0 0 0.55"/></joint>
  </xacro:if>
</robot>
"""


def package(tmp_path):
    return make_package(tmp_path / "lamp_description", "lamp_description",
                        {"lamp.urdf.xacro": ROBOT})


def extents(run_mcar, root, env, cache):
    done = run_mcar("check", "urdf/lamp.urdf.xacro", "--format", "json", cwd=root,
                    env={**env, "MCAR_CACHE_DIR": str(cache)})
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)["files"][0]["extents"]


def test_check_sees_the_variable(run_mcar, tmp_path):
    root, cache = package(tmp_path), tmp_path / "cache"
    low = extents(run_mcar, root, {}, cache)
    high = extents(run_mcar, root, {"LAMP_MAST_ENABLED": "1"}, cache)
    assert low[2] < 0.2 < high[2]  # the mast is there
    assert extents(run_mcar, root, {}, cache) == low
    assert extents(run_mcar, root, {"LAMP_MAST_ENABLED": "1"}, cache) == high


def test_build_render_and_ci_see_the_variable(run_mcar, tmp_path):
    root, cache = package(tmp_path), tmp_path / "cache"
    env = {"MCAR_CACHE_DIR": str(cache)}
    steps = ("--no-sim", "--no-gazebo")
    assert run_mcar("ci", *steps, cwd=root, env=env).returncode == 0
    built = root / "build" / "lamp.urdf"
    picture = root / "renders" / "lamp.png"
    plain, drawn = built.read_text(), picture.read_bytes()
    assert "mast" not in plain
    mast = {**env, "LAMP_MAST_ENABLED": "1"}
    build = run_mcar("build", cwd=root, env=mast)
    assert build.returncode == 0 and "1 of 1 files built into build" in build.stderr, \
        build.stderr
    assert "(1 unchanged)" not in build.stderr and "mast" in built.read_text()
    render = run_mcar("render", cwd=root, env=mast)
    assert render.returncode == 0 and picture.read_bytes() != drawn, render.stderr
    ci = run_mcar("ci", *steps, cwd=root, env=env)  # back without it: built again
    assert ci.returncode == 0 and "mast" not in built.read_text(), ci.stderr
    again = run_mcar("build", cwd=root, env=env)
    assert "(1 unchanged)" in again.stderr, again.stderr
