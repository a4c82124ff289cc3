"""Choosing the renderer: OpenGL, the forced or automatic ray-cast fallback, and no renderer.

A machine without OpenGL is simulated by putting a stand-in ``moderngl`` first on
PYTHONPATH (one that fails to import, or one whose context never comes); a machine
without embreex likewise. Both the probe process and mcar itself see the stand-ins.
"""

from __future__ import annotations

import time

import pytest

MODEL = "urdf/tutorial/03_color.urdf"
SMALL = ("--size", "160x120")

NO_EGL = 'raise ImportError("libEGL.so.1: cannot open shared object file")\n'
HANGING_EGL = ("import time\n"
               "def create_context(*args, **kwargs):\n"
               "    time.sleep(3600)\n")
NO_EMBREE = 'raise ImportError("No module named embreex")\n'


@pytest.fixture
def shims(tmp_path):
    """shims(moderngl=CODE, embreex=CODE) -> env with those stand-in modules on PYTHONPATH."""

    def make(**modules):
        folder = tmp_path / "shims"
        for name, code in modules.items():
            (folder / name).mkdir(parents=True, exist_ok=True)
            (folder / name / "__init__.py").write_text(code)
        return {"PYTHONPATH": str(folder)}

    return make


def test_forced_raycast_renders_without_touching_opengl(run_mcar, repo, tmp_path, shims, px):
    env = shims(moderngl=NO_EGL)  # would fail if anything tried OpenGL
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, "--renderer", "raycast",
                      cwd=repo, env=env)
    assert result.returncode == 0, result.stderr
    assert "ray casting (trimesh + embreex)" in result.stderr and "warning" not in result.stderr
    assert px.foreground(px.read_png(tmp_path / "r.png"), background=(190, 196, 206)).mean() > 0.2


def test_renderer_can_be_chosen_by_environment_variable(run_mcar, repo, tmp_path):
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, cwd=repo,
                      env={"MCAR_RENDERER": "raycast"})
    assert result.returncode == 0 and "ray casting" in result.stderr


def test_auto_falls_back_to_ray_casting_and_says_why(run_mcar, repo, tmp_path, shims, px):
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, cwd=repo,
                      env=shims(moderngl=NO_EGL))
    assert result.returncode == 0, result.stderr
    warning, summary = result.stderr.splitlines()
    assert warning == ("mcar: warning: OpenGL (EGL) is not available: ImportError: libEGL.so.1: "
                       "cannot open shared object file. Install the Debian packages libegl1 "
                       "libegl-mesa0 libgl1-mesa-dri libgl1 (and the pip packages moderngl "
                       "glcontext); using the ray-casting fallback instead")
    assert summary.endswith(", ray casting (trimesh + embreex))")
    assert px.read_png(tmp_path / "r.png").shape == (120, 160, 3)


def test_a_hanging_gl_context_is_given_up_after_the_timeout(run_mcar, repo, tmp_path, shims):
    env = shims(moderngl=HANGING_EGL)
    env["MCAR_GL_TIMEOUT"] = "1"
    started = time.monotonic()
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, cwd=repo, env=env,
                      timeout=60)
    assert result.returncode == 0, result.stderr
    assert "making an EGL context did not finish within 1 s" in result.stderr
    assert time.monotonic() - started < 30  # bounded: the run did not wait for the context
    assert (tmp_path / "r.png").exists()


def test_forced_gl_without_opengl_exits_2_naming_the_packages(run_mcar, repo, tmp_path, shims):
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, "--renderer", "gl",
                      cwd=repo, env=shims(moderngl=NO_EGL))
    assert result.returncode == 2
    assert result.stderr.startswith("mcar: error: OpenGL (EGL) is not available: ")
    assert "libegl1 libegl-mesa0 libgl1-mesa-dri libgl1" in result.stderr
    assert "Traceback" not in result.stderr and not (tmp_path / "r.png").exists()


def test_no_renderer_at_all_exits_2_naming_what_to_install(run_mcar, repo, tmp_path, shims):
    result = run_mcar("render", MODEL, "-o", tmp_path / "r.png", *SMALL, cwd=repo,
                      env=shims(moderngl=NO_EGL, embreex=NO_EMBREE))
    assert result.returncode == 2
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("mcar: error: no renderer can run here.")
    assert "libegl1 libegl-mesa0 libgl1-mesa-dri libgl1" in lines[0]
    assert "pip install embreex" in lines[0]
    assert not (tmp_path / "r.png").exists()


def test_nothing_to_draw_never_opens_a_renderer(run_mcar, repo, tmp_path, shims, needs_gl):
    """An up-to-date picture is skipped before any renderer is needed."""
    out = tmp_path / "r.png"
    assert run_mcar("render", MODEL, "-o", out, *SMALL, cwd=repo).returncode == 0
    result = run_mcar("render", MODEL, "-o", out, *SMALL, "--renderer", "gl", cwd=repo,
                      env=shims(moderngl=NO_EGL))
    assert result.returncode == 0, result.stderr
    assert "0 rendered, 1 unchanged" in result.stderr


def test_a_picture_is_redrawn_when_another_renderer_is_required(run_mcar, repo, tmp_path,
                                                                 needs_gl):
    out = tmp_path / "r.png"
    assert run_mcar("render", MODEL, "-o", out, *SMALL, cwd=repo).returncode == 0  # auto: GL
    forced = run_mcar("render", MODEL, "-o", out, *SMALL, "--renderer", "raycast", cwd=repo)
    assert "1 rendered" in forced.stderr and "ray casting" in forced.stderr
    either = run_mcar("render", MODEL, "-o", out, *SMALL, cwd=repo)
    assert "0 rendered, 1 unchanged" in either.stderr
