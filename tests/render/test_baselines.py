"""Every case under tests/render/cases/ against its committed baseline picture.

A case is one file, NAME.args, holding the arguments of `mcar render` (paths relative to
the repository); the picture is drawn at 200x150 unless the case says --size, and compared
with baselines/NAME.png pixel by pixel with a tolerance, by both renderers.
"""

from __future__ import annotations

import shlex
from pathlib import Path

import pytest

CASES = sorted((Path(__file__).parent / "cases").glob("*.args"))


def case_args(path: Path) -> list[str]:
    args = shlex.split(path.read_text(encoding="utf-8"), comments=True)
    return args if "--size" in args else args + ["--size", "200x150"]


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_gl_picture_matches_baseline(case, render, px, needs_gl):
    picture = render(*case_args(case), "--renderer", "gl")
    px.compare_with_baseline(case.stem, picture, px.GL_MISMATCH_FRACTION)


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_raycast_fallback_matches_the_same_baseline(case, render, px):
    picture = render(*case_args(case), "--renderer", "raycast")
    if px.UPDATE_BASELINES:
        pytest.skip("baselines are made with the OpenGL renderer")
    px.compare_with_baseline(case.stem, picture, px.RAYCAST_MISMATCH_FRACTION)


def test_there_are_cases():
    assert len(CASES) >= 10
