"""render.smoothing: trimesh's smooth_shade in one pass, the same corners, normals and
colours, without its submesh per piece (Husky A200's wheels: 25,000 pieces, 18 s)."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest
import trimesh

from mobile_car.render.smoothing import smooth_shade

ANGLE = math.radians(30)


def corners(mesh):
    index = mesh.faces.reshape(-1)
    return mesh.vertices[index], mesh.vertex_normals[index], mesh.visual.vertex_colors[index]


def tread(pieces: int) -> trimesh.Trimesh:
    """A strip of ``pieces`` ridges folded at 90°: every face its own smoothing piece but
    the flat pairs, as a CAD tyre's tread is, with a colour per face."""
    x = np.repeat(np.arange(pieces + 1, dtype=float), 2)
    z = np.tile([0.0, 1.0], pieces + 1) * (np.arange(2 * pieces + 2) // 2 % 2)
    top = np.column_stack([x, np.zeros_like(x), z])
    vertices = np.vstack([top, top + [0, 1, 0]])
    n = len(top)
    faces = [(i, i + 1, n + i) for i in range(n - 1)] + \
        [(i + 1, n + i + 1, n + i) for i in range(n - 1)]
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    colours = np.random.default_rng(7).integers(0, 256, (len(faces), 4), dtype=np.uint8)
    mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=colours)
    return mesh


def coloured_box(kind: str) -> trimesh.Trimesh:
    mesh = trimesh.creation.box((1, 2, 3))
    rng = np.random.default_rng(3)
    if kind == "vertex":
        mesh.visual = trimesh.visual.ColorVisuals(
            mesh, vertex_colors=rng.integers(0, 256, (8, 4), dtype=np.uint8))
    elif kind == "face":
        mesh.visual = trimesh.visual.ColorVisuals(
            mesh, face_colors=rng.integers(0, 256, (12, 4), dtype=np.uint8))
    return mesh


@pytest.mark.parametrize("mesh", [
    coloured_box("vertex"), coloured_box("face"), coloured_box("none"),
    trimesh.creation.cylinder(radius=0.5, height=0.2, sections=40),
    trimesh.creation.icosphere(subdivisions=2), tread(50),
], ids=["vertex colours", "face colours", "no colour", "cylinder", "sphere", "tread"])
def test_the_same_corners_normals_and_colours_as_trimesh(mesh):
    expected = corners(trimesh.graph.smooth_shade(mesh, angle=ANGLE, facet_minarea=None))
    got = corners(smooth_shade(mesh, ANGLE))
    for want, have in zip(expected, got, strict=True):
        assert want.shape == have.shape
        assert np.array_equal(want, have)


def test_a_mesh_of_thousands_of_pieces_is_smoothed_without_a_loop_over_them():
    mesh = tread(1000)

    def cpu(function) -> float:
        start = time.process_time()
        function(mesh.copy())
        return time.process_time() - start

    ours = cpu(lambda m: smooth_shade(m, ANGLE))
    theirs = cpu(lambda m: trimesh.graph.smooth_shade(m, angle=ANGLE, facet_minarea=None))
    assert ours * 5 < theirs, (ours, theirs)
