"""Benchmark of `mcar render` (a measurement to record in the README, not a test).

    .venv/bin/python bench/render_bench.py [PACKAGE_DIR] [--runs N]

1. Whole set: `mcar render PACKAGE_DIR --force` in a fresh output folder, each run a new
   process (cold Python, warm disk cache), N runs; default PACKAGE_DIR is the bundled
   mobile_car_description (every part test file, chassis step and the complete robot).
2. Pieces, in this process: importing the render stack, making the GL context, and the
   time per 800x600 picture of the tutorial car with OpenGL and with the ray caster.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
MCAR = Path(sys.executable).parent / "mcar"


def whole_set(package: Path, runs: int) -> None:
    walls = []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as out:
            started = time.perf_counter()
            result = subprocess.run([str(MCAR), "render", str(package), "-o", out, "--force"],
                                    capture_output=True, text=True, check=False)
            walls.append(time.perf_counter() - started)
            if result.returncode != 0:
                sys.exit(f"mcar render failed:\n{result.stderr}")
            pictures = len(list(Path(out).rglob("*.png"))) - 1  # less the contact sheet
    print(f"whole set: {pictures} pictures + contact sheet at 800x600 from {package}")
    print(f"  wall per run (new process each): min {min(walls):.2f} s, "
          f"median {statistics.median(walls):.2f} s over {runs} runs")
    print(f"  summary line of the last run: {result.stderr.strip().splitlines()[-1]}")


def pieces(frames: int) -> None:
    started = time.perf_counter()
    import numpy  # noqa: F401  (what the render stack pulls in, timed together)
    import trimesh  # noqa: F401
    import yourdfpy  # noqa: F401

    from mobile_car.packages import PackageSearch
    from mobile_car.render.camera import fit_camera
    from mobile_car.render.compose import compose, png_bytes
    from mobile_car.render.options import RenderOptions
    from mobile_car.render.scene import ModelSource, load_scene
    imported = time.perf_counter()
    print(f"import numpy + trimesh + yourdfpy + mcar.render: {imported - started:.3f} s")

    from mobile_car.render.gl import GLRenderer
    started = time.perf_counter()
    gl = GLRenderer()
    print(f"GL context (in process, after the probe): {time.perf_counter() - started:.3f} s"
          f"  [{gl.description}]")
    from mobile_car.render.raycast import RaycastRenderer

    car = REPO / "urdf/tutorial/03_color.urdf"
    started = time.perf_counter()
    scene = load_scene(ModelSource(car.read_bytes(), car, True), PackageSearch(origin=car))
    print(f"load tutorial car ({scene.triangle_count} triangles): "
          f"{time.perf_counter() - started:.3f} s")
    options = RenderOptions()
    camera = fit_camera("iso", scene.positions, 800, 600)
    for renderer in (gl, RaycastRenderer()):
        renderer.draw(scene, camera)  # first frame compiles shaders / builds the BVH
        draws, totals = [], []
        for _ in range(frames):
            t0 = time.perf_counter()
            model = renderer.draw(scene, camera)
            t1 = time.perf_counter()
            png_bytes(compose(model, camera, scene.bounds, options))
            t2 = time.perf_counter()
            draws.append(t1 - t0)
            totals.append(t2 - t0)
        print(f"{renderer.name:>8}: draw {statistics.median(draws) * 1000:6.1f} ms, "
              f"draw + overlays + PNG {statistics.median(totals) * 1000:6.1f} ms per 800x600 "
              f"picture (median of {frames})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("package", nargs="?", type=Path, default=REPO,
                        help="a description package folder (default: this repository)")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--frames", type=int, default=10)
    args = parser.parse_args()
    whole_set(args.package, args.runs)
    pieces(args.frames)


if __name__ == "__main__":
    main()
