"""Read and check what is inside the links (inertials, visuals, collisions): most of a
robot's elements, read only by ``mcar check`` (``mcar tree`` needs none of it)."""

from __future__ import annotations

from .check_context import Reporter
from .check_inertia import check_inertia
from .check_links import check_links
from .check_schema import report_anomalies
from .urdf_reader import Anomalies, Link, read_links


def check_link_bodies(links: list[Link], report: Reporter, materials: set[str],
                      top_level: set, moving: set[str], root: str | None) -> None:
    """Read ``links`` and check their geometry, materials, inertia and vocabulary."""
    notes = Anomalies()
    read_links(links, notes)
    check_links(links, report, materials, top_level)
    check_inertia(links, report, moving, root)
    report_anomalies(notes, report)
