"""`mcar check` of a mesh-heavy robot against the same robot with boxes (bench/run.py's
section "meshes"; issue 26: check needs a mesh's box, not its triangles).

The robot: 40 links, each with a visual and a collision mesh of its own, a binary STL of
about 200,000 triangles (10 MB: 400 MB of meshes in all), written by trimesh into the
bench's folder; the peer is the same robot with a box in place of each mesh. Measured
side by side, interleaved, in fresh processes:

* boxes;
* meshes, the user's cache kept (what every check after the first does, and a CI job
  that keeps ``~/.cache/mcar``): nothing but a stat and a sealed record per mesh;
* meshes, an empty cache each run (the first check of a clone): every mesh read once.

Targets: the meshes within 1.5x of the boxes with the cache kept; under 200 MB of memory
either way (GNU time's peak resident set).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

LINKS = 40
SPHERE = (224, 224)  # trimesh's uv_sphere count: 198,912 triangles
TARGET_RATIO = 1.5
TARGET_MIB = 200


def make_robot(work: Path, links: int = LINKS) -> tuple[Path, Path, int]:
    """(robot with meshes, the same with boxes, triangles a mesh) in ``work``; each mesh
    distinct."""
    import trimesh

    base = trimesh.creation.uv_sphere(count=SPHERE)
    boxes, meshes = [], []
    for i in range(links):
        size = (0.05 + 0.001 * i, 0.04, 0.03)
        mesh = base.copy()
        mesh.apply_scale([v / 2 for v in size])
        (work / f"part_{i}.stl").write_bytes(mesh.export(file_type="stl"))
        meshes.append(f'<mesh filename="part_{i}.stl"/>')
        boxes.append(f'<box size="{size[0]:g} {size[1]:g} {size[2]:g}"/>')
    paths = []
    for name, shapes in (("meshes", meshes), ("boxes", boxes)):
        out = [f'<?xml version="1.0"?>\n<robot name="{name}">\n  <link name="base_link"/>\n']
        for i, shape in enumerate(shapes):
            mass, (x, y, z) = 0.5, (0.05 + 0.001 * i, 0.04, 0.03)
            out.append(
                f'  <link name="part_{i}">\n    <inertial><mass value="{mass}"/><inertia '
                f'ixx="{mass * (y * y + z * z) / 20:.6g}" ixy="0" ixz="0" '
                f'iyy="{mass * (x * x + z * z) / 20:.6g}" iyz="0" '
                f'izz="{mass * (x * x + y * y) / 20:.6g}"/></inertial>\n'
                f'    <visual><geometry>{shape}</geometry></visual>\n'
                f'    <collision><geometry>{shape}</geometry></collision>\n  </link>\n'
                f'  <joint name="joint_{i}" type="revolute"><parent link="base_link"/>'
                f'<child link="part_{i}"/><origin xyz="{0.1 * (i % 8):g} '
                f'{0.1 * (i // 8):g} 0.05"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" '
                'effort="1" velocity="1"/></joint>\n')
        out.append("</robot>\n")
        paths.append(work / f"{name}.urdf")
        paths[-1].write_text("".join(out))
    return paths[0], paths[1], len(base.faces)


def section(rows: list[str], work: Path, quick: bool, runner) -> None:
    """The "meshes" section; ``runner`` is bench/measure.py (its helpers and Result)."""
    folder = work / "meshes"
    folder.mkdir()
    meshes, boxes, triangles = make_robot(folder, 8 if quick else LINKS)
    links = 8 if quick else LINKS
    megabytes = sum(p.stat().st_size for p in folder.glob("*.stl")) / 1e6
    kept = work / "cache-kept"
    env = {**os.environ, "MCAR_CACHE_DIR": str(kept)}
    fresh = iter(range(10**6))

    def empty_cache() -> dict:
        path = work / f"cache-{next(fresh)}"
        return {**os.environ, "MCAR_CACHE_DIR": str(path)}

    commands = {"boxes": ([runner.MCAR, "check", "-q", str(boxes)], lambda: env),
                "meshes, cache kept": ([runner.MCAR, "check", "-q", str(meshes)], lambda: env),
                "meshes, empty cache": ([runner.MCAR, "check", "-q", str(meshes)], empty_cache)}
    results = {key: runner.Result() for key in commands}
    runner.run_timed(commands["meshes, cache kept"][0], env=env)  # fills the kept cache
    for key, (cmd, make_env) in commands.items():
        peak, code, _digest = runner.run_watched(cmd, env=make_env())
        results[key].peak_mib = peak
        results[key].codes.append(code)
    for _ in range(1 if quick else 9):  # interleaved: a change of load falls on all three
        for key, (cmd, make_env) in commands.items():
            wall, code = runner.run_timed(cmd, env=make_env())
            results[key].walls.append(wall)
            results[key].codes.append(code)
    box = results["boxes"]
    rows += ["## `mcar check` of a mesh-heavy robot", "",
             f"{links} links, each with its own binary STL of {triangles:,} triangles as "
             "visual and collision "
             f"({megabytes:.0f} MB of meshes), against the same robot with a box for each mesh "
             "(`bench/mesh_check_bench.py`). check needs each mesh's box, not its triangles: "
             "it reads a mesh once and keeps what it found in the user's cache "
             "(`~/.cache/mcar/mesh-facts`, sealed). Target: within 1.5x of the boxes with "
             "the cache kept, under 200 MB either way.", "",
             "| robot | median | ratio to boxes | peak memory | exit | target |",
             "|---|---:|---:|---:|---|---|"]
    for key, result in results.items():
        ratio = result.wall / box.wall if result.ok and box.ok else None
        within = result.peak_mib is None or result.peak_mib < TARGET_MIB
        target = None if key == "boxes" else (
            result.ok and within and (key != "meshes, cache kept" or ratio <= TARGET_RATIO))
        rows.append(f"| {key} | {runner.time_cell(result)} | "
                    f"{'-' if ratio is None else f'{ratio:.2f}x'} | {runner.fmt_peak(result)} | "
                    f"{runner.exit_text(result.codes)} | {runner.verdict(target)} |")
        runner.progress(f"meshes: {key} {runner.fmt_time(result.wall)} (runs from "
                        f"{runner.fmt_time(min(result.walls))} to "
                        f"{runner.fmt_time(max(result.walls))})")
    rows.append("")
    rows += runner.notes_for("meshes")
    shutil.rmtree(folder, ignore_errors=True)
