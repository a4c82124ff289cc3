"""tests/zygote.py, which starts the suite's mcar runs: a run through it prints, exits and
reads what a new `mcar` process does, in its own process, folder and environment."""

from __future__ import annotations

import re
import subprocess

import pytest
from conftest import MCAR, REPO, clean_environ, mcar_process

CAR = REPO / "urdf" / "mobile_robot.xacro"
BROKEN = '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>' \
         '<child link="b"/></joint></robot>'
RUNAWAY = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
           '<link name="${9**9**9}"/></robot>')


def _real(*args, cwd, input=None):
    return subprocess.run([str(MCAR), *map(str, args)], cwd=cwd, input=input,
                          env=clean_environ(), capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("args, stdin", [
    (["check", CAR], None),
    (["tree", CAR], None),
    (["build", "-"], (REPO / "urdf" / "tutorial" / "01_skeleton.urdf").read_text()),
    (["check", "broken.urdf"], None),
    (["render", "broken.urdf", "-o", "out.png"], None),
    (["chek"], None),
    (["config", "--set", "wheel_radius=40mm", "--format", "json"], None),
], ids=["check", "tree", "build-stdin", "check-error", "render-error", "typo", "config"])
def test_a_run_prints_and_exits_as_a_new_process_does(tmp_path, args, stdin):
    (tmp_path / "broken.urdf").write_text(BROKEN)
    ours = mcar_process(*args, cwd=tmp_path, input=stdin)
    real = _real(*args, cwd=tmp_path, input=stdin)
    assert (ours.returncode, ours.stdout, _untimed(ours.stderr)) == (
        real.returncode, real.stdout, _untimed(real.stderr))


def _untimed(text: str) -> str:
    return re.sub(r"\(\d+\.\d\d s\)", "(T s)", text)


def test_a_run_has_its_own_environment_and_leaves_the_launchers_alone(tmp_path):
    env = {**clean_environ(), "MCAR_MAX_INPUT_MB": "-1"}
    refused = mcar_process("check", CAR, cwd=tmp_path, env=env)
    assert refused.returncode == 2
    assert "MCAR_MAX_INPUT_MB=-1: must be between" in refused.stderr
    again = mcar_process("check", "-q", CAR, cwd=tmp_path)  # the variable went with the run
    assert again.returncode == 0, again.stderr


def test_a_run_past_its_timeout_is_killed_and_the_next_one_runs(tmp_path):
    (tmp_path / "slow.xacro").write_text(RUNAWAY)
    env = {**clean_environ(), "MCAR_XACRO_TIMEOUT": "600"}
    with pytest.raises(subprocess.TimeoutExpired):
        mcar_process("build", "slow.xacro", "-o", "out.urdf", cwd=tmp_path, env=env, timeout=2)
    assert mcar_process("check", "-q", CAR, cwd=tmp_path).returncode == 0


def test_variables_read_as_python_starts_get_a_new_interpreter(tmp_path):
    """A PYTHONPATH the launcher did not start with: a new interpreter, which runs the
    sitecustomize.py found there."""
    (tmp_path / "sitecustomize.py").write_text(
        f"open({str(tmp_path / 'started')!r}, 'w').close()\n")
    env = {**clean_environ(), "PYTHONPATH": str(tmp_path)}
    done = mcar_process("check", "-q", CAR, cwd=tmp_path, env=env)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "started").exists()


def test_a_library_set_up_by_a_variable_is_preloaded_as_mcar_would_set_it(tmp_path):
    """MuJoCo reads MUJOCO_GL as it is imported: the launcher imports it as mcar does (EGL,
    so that `sim --record` renders), and a run asking for another backend gets a new
    interpreter."""
    import zygote

    mcar_process("--version", cwd=tmp_path)
    launcher = zygote._shared[0]
    assert launcher.usable({**clean_environ(), "MUJOCO_GL": "egl"})
    assert not launcher.usable({**clean_environ(), "MUJOCO_GL": "osmesa"})
    assert not launcher.usable({**clean_environ(), "LC_ALL": "C.UTF-8x"})


def test_what_a_dask_cluster_sets_in_its_maker_keeps_runs_launched(tmp_path):
    """A LocalCluster sets PYTHONHASHSEED and the OMP/OpenBLAS thread counts in the test
    process that makes it; mcar's runs after it still come from the launcher."""
    import zygote

    distributed = pytest.importorskip("distributed", reason="the sweep extra installs Dask")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None):
        drifted = clean_environ()
    mcar_process("--version", cwd=tmp_path)
    assert zygote._shared[0].usable(drifted)
