#!/usr/bin/env python3
"""Make the meshes of mobile_car_description from urdf/config.xacro.

    python scripts/make_meshes.py                 # rewrite meshes/motor.stl
    python scripts/make_meshes.py -o /tmp/meshes  # write them elsewhere (the tests do)

meshes/motor.stl is the JGA25-370 gear motor with its Hall encoder, at true size in
metres, as four stacked solid cylinders: output shaft, gearbox, motor can and encoder
disc. Mesh frame: the shaft axis is +z and the gearbox face (the face screwed to the
bracket) is z = 0; the shaft sticks out towards +z, the body lies towards -z. The sizes are
read from config.xacro with xacro itself, so the mesh and the collision cylinder built from
the same properties cannot disagree; rerun this script after editing them.

The output is deterministic (fixed tessellation, no timestamp in the binary STL header),
so the committed file can be checked by regenerating it and comparing bytes.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import trimesh
import xacro

PACKAGE = Path(__file__).resolve().parent.parent
CONFIG = PACKAGE / "urdf" / "config.xacro"
# Facets around each cylinder: round at the size the motor is seen, still a small file.
SECTIONS = 64

MOTOR_PROPERTIES = (
    "motor_shaft_radius", "motor_shaft_length",
    "motor_gearbox_radius", "motor_gearbox_length",
    "motor_can_radius", "motor_can_length",
    "motor_encoder_radius", "motor_encoder_length",
)


def read_properties(config: Path, names: tuple[str, ...]) -> dict[str, float]:
    """The values (floats) of the named xacro properties, evaluated by xacro."""
    attributes = " ".join(f'{name}="${{{name}}}"' for name in names)
    text = (f'<robot name="values" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            f'<xacro:include filename="{config}"/><values {attributes}/></robot>')
    doc = xacro.parse(text)
    xacro.process_doc(doc)
    element = doc.getElementsByTagName("values")[0]
    return {name: float(element.getAttribute(name)) for name in names}


def z_cylinder(radius: float, z_from: float, z_to: float) -> trimesh.Trimesh:
    """A closed cylinder on the z axis spanning z_from..z_to (m)."""
    transform = trimesh.transformations.translation_matrix([0.0, 0.0, (z_from + z_to) / 2])
    return trimesh.creation.cylinder(radius=radius, height=z_to - z_from, sections=SECTIONS,
                                     transform=transform)


def motor_mesh(dims: dict[str, float]) -> trimesh.Trimesh:
    """The motor as touching, non-overlapping solids: watertight, volume = sum of parts."""
    gearbox_end = -dims["motor_gearbox_length"]
    can_end = gearbox_end - dims["motor_can_length"]
    encoder_end = can_end - dims["motor_encoder_length"]
    parts = [
        z_cylinder(dims["motor_shaft_radius"], 0.0, dims["motor_shaft_length"]),
        z_cylinder(dims["motor_gearbox_radius"], gearbox_end, 0.0),
        z_cylinder(dims["motor_can_radius"], can_end, gearbox_end),
        z_cylinder(dims["motor_encoder_radius"], encoder_end, can_end),
    ]
    return trimesh.util.concatenate(parts)


def write_atomically(path: Path, data: bytes) -> None:
    """Write via a temporary file and rename, so a failure never leaves half a mesh."""
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_bytes(data)
    temporary.replace(path)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output-dir", type=Path, default=PACKAGE / "meshes",
                        help="folder to write the meshes into (default: the package's meshes/)")
    args = parser.parse_args(argv)
    mesh = motor_mesh(read_properties(CONFIG, MOTOR_PROPERTIES))
    target = args.output_dir / "motor.stl"
    write_atomically(target, trimesh.exchange.stl.export_stl(mesh))
    print(f"wrote {target} ({len(mesh.faces)} triangles)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
