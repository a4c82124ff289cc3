"""Fixtures for the render tests: draw in-process, read pictures as arrays, compare baselines.

Baselines are small PNGs under tests/render/baselines/. A mismatch writes the actual
picture and an amplified difference image under tests/_output/render/ for a person to look
at; MCAR_UPDATE_BASELINES=1 rewrites the baselines instead (then look at them and commit).
"""

from __future__ import annotations

import io
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

RENDER_TESTS = Path(__file__).resolve().parent
REPO = RENDER_TESTS.parent.parent
PKG = RENDER_TESTS / "pkg"
BASELINES = RENDER_TESTS / "baselines"
OUTPUT = REPO / "tests" / "_output" / "render"
UPDATE_BASELINES = os.environ.get("MCAR_UPDATE_BASELINES") == "1"

# A pixel "differs" when a channel is off by more than this many levels (of 255) ...
PIXEL_TOLERANCE = 16
# ... and a picture matches its baseline when at most this fraction of pixels differ.
GL_MISMATCH_FRACTION = 0.005
RAYCAST_MISMATCH_FRACTION = 0.03


def read_png(data: bytes | Path) -> np.ndarray:
    """A PNG (bytes or path) as an (H, W, 3) uint8 array."""
    if isinstance(data, (str, Path)):
        data = Path(data).read_bytes()
    with Image.open(io.BytesIO(data)) as image:
        assert image.format == "PNG"
        return np.asarray(image.convert("RGB"))


def differing_pixels(a: np.ndarray, b: np.ndarray, tolerance: int = PIXEL_TOLERANCE):
    """Boolean (H, W) mask of pixels where any channel differs by more than ``tolerance``."""
    return np.abs(a.astype(int) - b.astype(int)).max(axis=2) > tolerance


def foreground(image: np.ndarray, background=(255, 255, 255), tolerance: int = 12):
    """Mask of pixels that are not the (plain) background colour."""
    return np.abs(image.astype(int) - np.array(background)).max(axis=2) > tolerance


def silhouette_box(mask: np.ndarray) -> tuple[int, int, int, int]:
    """(left, top, width, height) of the True pixels."""
    rows, cols = np.nonzero(mask)
    assert len(rows), "nothing drawn"
    return cols.min(), rows.min(), cols.max() - cols.min() + 1, rows.max() - rows.min() + 1


@pytest.fixture
def in_repo(monkeypatch):
    """Run with the repository as working directory (paths in cases are relative to it)."""
    monkeypatch.chdir(REPO)
    return REPO


@pytest.fixture
def render(cli, in_repo, tmp_path):
    """render(*args) -> (H, W, 3) array: `mcar render ARGS -o tmp.png` in-process."""
    counter = iter(range(10**6))

    def run(*args, expect_exit=0):
        out = tmp_path / f"picture_{next(counter)}.png"
        result = cli("render", *args, "-o", out, "--force")
        assert result.exit_code == expect_exit, result.output
        return read_png(out) if expect_exit == 0 else result

    return run


def compare_with_baseline(name: str, actual: np.ndarray, max_fraction: float) -> None:
    """Fail, leaving actual and diff images for a person, if ``actual`` strays from the baseline."""
    baseline_path = BASELINES / f"{name}.png"
    if UPDATE_BASELINES:
        BASELINES.mkdir(exist_ok=True)
        Image.fromarray(actual).save(baseline_path)
        return
    if not baseline_path.exists():
        pytest.fail(f"no baseline {baseline_path.relative_to(REPO)}; run with "
                    "MCAR_UPDATE_BASELINES=1, look at the picture, and commit it")
    expected = read_png(baseline_path)
    message = None
    if expected.shape != actual.shape:
        message = f"size {actual.shape[1]}x{actual.shape[0]} != baseline " \
                  f"{expected.shape[1]}x{expected.shape[0]}"
    else:
        mask = differing_pixels(expected, actual)
        if mask.mean() > max_fraction:
            message = f"{mask.mean():.2%} of pixels differ (allowed {max_fraction:.2%})"
    if message is not None:
        OUTPUT.mkdir(parents=True, exist_ok=True)
        Image.fromarray(actual).save(OUTPUT / f"{name}.actual.png")
        shutil.copyfile(baseline_path, OUTPUT / f"{name}.baseline.png")
        if expected.shape == actual.shape:
            diff = np.abs(expected.astype(int) - actual.astype(int)).max(axis=2)
            Image.fromarray(np.clip(diff * 4, 0, 255).astype(np.uint8)).save(
                OUTPUT / f"{name}.diff.png")
        pytest.fail(f"{name}: {message}; see {OUTPUT.relative_to(REPO)}/{name}.*.png")


class PixelTools:
    """The helpers above, handed to test modules as the ``px`` fixture (test modules
    cannot import conftest under --import-mode=importlib)."""

    read_png = staticmethod(read_png)
    differing_pixels = staticmethod(differing_pixels)
    foreground = staticmethod(foreground)
    silhouette_box = staticmethod(silhouette_box)
    compare_with_baseline = staticmethod(compare_with_baseline)
    REPO = REPO
    PKG = PKG
    GL_MISMATCH_FRACTION = GL_MISMATCH_FRACTION
    RAYCAST_MISMATCH_FRACTION = RAYCAST_MISMATCH_FRACTION
    UPDATE_BASELINES = UPDATE_BASELINES


@pytest.fixture(scope="session")
def px() -> type[PixelTools]:
    return PixelTools


@pytest.fixture
def needs_gl(gl_reason):
    """Skip a test that is about the OpenGL renderer where there is none."""
    if gl_reason is not None:
        pytest.skip(f"OpenGL (EGL) is not available: {gl_reason} (Debian packages libegl1 "
                    "libegl-mesa0 libgl1-mesa-dri libgl1; `make test` installs them)")
