"""The readers of a mesh's geometry alone (check's box, sim's and the export's MuJoCo copy,
specs' inertia, diff's bounds) do not read the textures it names. Curiosity's textured
COLLADA parts (space-ros/demos) took 15 s of CPU in a cold `mcar check` and 18 s in
`mcar specs --no-proof`, most of it trimesh packing their textures into one atlas that
nothing looked at; 2 s and 3 s without, every figure the same. A picture still draws them
(tests/untrusted/test_textures.py)."""

from __future__ import annotations

from pathlib import Path

from PIL import Image
from untrusted.test_textures import MTL, OBJ  # (the textured quad it draws)


def _textured(tmp: Path) -> Path:
    (tmp / "quad.obj").write_text(OBJ)
    (tmp / "quad.mtl").write_text(MTL)
    Image.new("RGB", (8, 8), (200, 30, 30)).save(tmp / "tex.png")
    return tmp / "quad.obj"


def test_the_geometry_is_read_without_its_texture(tmp_path):
    from mobile_car.load.mesh_reader import load_mesh

    mesh = _textured(tmp_path)
    drawn, read_drawn = load_mesh(mesh, force="mesh")
    shape, read_shape = load_mesh(mesh, textures=False, force="mesh")
    assert [p.name for p in read_drawn] == ["quad.mtl", "tex.png"]
    assert [p.name for p in read_shape] == ["quad.mtl"]
    assert shape.vertices.tolist() == drawn.vertices.tolist()
    assert shape.faces.tolist() == drawn.faces.tolist()
    assert getattr(shape.visual.material, "image", None) is None
    assert drawn.visual.material.image.size == (8, 8)


def test_checks_box_of_a_textured_mesh_keeps_the_texture_among_its_inputs(tmp_path,
                                                                          monkeypatch):
    # trimesh no longer opens it, but the mesh's measure names it: editing the texture
    # still makes a no-op check run again, as before
    from mobile_car.load import mesh_facts

    mesh = _textured(tmp_path)
    monkeypatch.setenv("MCAR_CACHE_DIR", str(tmp_path / "cache"))  # facts not yet known
    facts = mesh_facts.mesh_facts(mesh, str(mesh))
    assert facts.bounds == ((0.0, 0.0, 0.0), (1.0, 1.0, 0.0))
    assert sorted(Path(p).name for p in facts.reads) == ["quad.mtl", "tex.png"]
