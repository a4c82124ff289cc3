"""Where the bundled ``mobile_car_description`` package lives.

In an installed wheel the description sits at ``mobile_car/description``; in a source
checkout (tests run against the wheel, but tools like ``bench/`` may import from the tree)
it is the repository root. Both hold ``package.xml``, ``urdf/`` and ``meshes/``.
"""

from __future__ import annotations

from pathlib import Path

PACKAGE_NAME = "mobile_car_description"


def description_dir() -> Path:
    """The directory holding the bundled package's ``package.xml``."""
    here = Path(__file__).resolve().parent.parent  # mobile_car/
    for candidate in (here / "description", here.parent):
        if (candidate / "package.xml").is_file() and (candidate / "urdf").is_dir():
            return candidate
    raise FileNotFoundError(f"bundled {PACKAGE_NAME} not found next to {here}")


def urdf_dir() -> Path:
    return description_dir() / "urdf"
