"""Where `mcar render`'s time goes, measured inside one fresh process (bench/run.py runs it).

    .venv/bin/python bench/render_bench.py [PACKAGE_DIR] [--runs N] [--json]

1. Importing the render stack (numpy, trimesh, yourdfpy, mcar's render modules), then
   making the OpenGL context (EGL; Mesa's llvmpipe on a machine without a GPU).
2. For every robot file of the package (default: this repository's description), the time
   per 800x600 picture with the context made and the modules loaded: expanding the xacro,
   loading the meshes into a scene, drawing, and overlays + PNG encoding; median of N.
3. Drawing the package's biggest scene with the ray-casting fallback instead (trimesh +
   embreex, used where no OpenGL context can be made).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def measure(package: Path, runs: int) -> dict:
    started = time.perf_counter()
    import numpy  # noqa: F401  (what the render stack pulls in, timed together)
    import trimesh  # noqa: F401
    import yourdfpy  # noqa: F401

    from mobile_car.load.robot import LoadOptions, load_robot
    from mobile_car.load.selection import select
    from mobile_car.packages.search import PackageSearch
    from mobile_car.render.compose import png_bytes
    from mobile_car.render.options import RenderOptions
    from mobile_car.render.picture import draw_views, finish_picture
    from mobile_car.render.scene import load_scene
    from mobile_car.render.session import model_source, selection_jobs

    def load_source(inp, search):
        return model_source(load_robot(inp, LoadOptions())), []

    def package_jobs(root, outdir):
        return selection_jobs(select([str(root)], None), outdir)
    imported = time.perf_counter() - started

    from mobile_car.render.backend import open_renderer
    started = time.perf_counter()
    renderer, notes = open_renderer("auto")
    context = time.perf_counter() - started

    options = RenderOptions()
    files = []
    for job in package_jobs(package, Path("unused")):
        stages: dict[str, list[float]] = {"expand": [], "load": [], "draw": [], "finish": []}
        for _ in range(runs):
            search = PackageSearch(origin=job.input.path)
            t0 = time.perf_counter()
            source, _warnings = load_source(job.input, search)
            t1 = time.perf_counter()
            scene = load_scene(source, search)
            t2 = time.perf_counter()
            views = draw_views(renderer, scene, options)
            t3 = time.perf_counter()
            png_bytes(finish_picture(views, scene.bounds, options))
            t4 = time.perf_counter()
            for stage, seconds in zip(stages, (t1 - t0, t2 - t1, t3 - t2, t4 - t3), strict=True):
                stages[stage].append(seconds)
        medians = {stage: statistics.median(values) for stage, values in stages.items()}
        files.append({"file": job.caption, "triangles": scene.triangle_count, **medians,
                      "total": sum(medians.values())})
    from mobile_car.render.raycast import RaycastRenderer

    biggest = max(package_jobs(package, Path("unused")),
                  key=lambda job: next(f["triangles"] for f in files
                                       if f["file"] == job.caption))
    search = PackageSearch(origin=biggest.input.path)
    scene = load_scene(load_source(biggest.input, search)[0], search)
    raycaster = RaycastRenderer()
    draw_views(raycaster, scene, options)  # the first draw builds the ray tracer's BVH
    raycast = []
    for _ in range(runs):
        started = time.perf_counter()
        draw_views(raycaster, scene, options)
        raycast.append(time.perf_counter() - started)
    return {"import": imported, "context": context, "renderer": renderer.description,
            "notes": notes, "files": files,
            "raycast": {"file": biggest.caption, "draw": statistics.median(raycast)}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("package", nargs="?", type=Path, default=REPO,
                        help="a description package folder (default: this repository)")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--json", action="store_true", help="one JSON document on stdout")
    args = parser.parse_args()
    result = measure(args.package, args.runs)
    if args.json:
        json.dump(result, sys.stdout, indent=1)
        return
    print(f"import numpy + trimesh + yourdfpy + mcar.render: {result['import']:.3f} s")
    print(f"renderer ({result['renderer']}): {result['context']:.3f} s")
    for entry in result["files"]:
        print(f"{entry['file']:40s} {entry['triangles']:7d} triangles  "
              + "  ".join(f"{stage} {entry[stage] * 1000:6.1f} ms"
                          for stage in ("expand", "load", "draw", "finish", "total")))
    raycast = result["raycast"]
    print(f"ray-casting fallback, {raycast['file']}: draw {raycast['draw'] * 1000:.1f} ms")


if __name__ == "__main__":
    main()
