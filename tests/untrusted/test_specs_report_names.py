"""Figures carry the robot's names (a sensor's in its key and label, a link's in a
source): `mcar diff --specs` and `mcar specs --picture` must show them escaped, as every
other report does (mobile_car.names), so a name cannot forge a line of the review."""

from __future__ import annotations

import numpy as np
from PIL import Image

from mobile_car.diff import specs as diff_specs
from mobile_car.specs import picture
from mobile_car.specs.figures import Figure, Section

# A sensor name that ends its line and writes a reassuring one of its own, then recolours
# the terminal.
FORGED = "laser\n  tip-over left 19.3° → 24.1° (+4.8°)  [statics.tip.left]\x1b[8m"
KEY = f"sensors.{FORGED}.blocked_share"


def sections(share: float, source: str = "collision geometry") -> list[Section]:
    return [Section("sensors", [Figure(KEY, f"{FORGED} blocked share", share, "", source)])]


def test_a_name_cannot_forge_a_line_of_the_text_report():
    diff = diff_specs.compare_specs(sections(0.1), sections(0.3, f"link {FORGED}"))
    report = diff_specs.text(diff)
    lines = report.splitlines()
    assert len(lines) == 2  # the summary and the one change
    assert not any(line.startswith("  tip-over") for line in lines)
    assert "\x1b" not in report and "\\x1b[8m" in report
    assert "laser\\n  tip-over left" in lines[1]
    # control: the raw label, written as a row is, would have forged the line
    raw = f"  {FORGED} blocked share 0.1 → 0.3 (+0.2)"
    assert any(line.startswith("  tip-over left 19.3° → 24.1°") for line in raw.splitlines())


def test_a_name_cannot_break_the_markdown_table_or_the_not_computed_reason():
    diff = diff_specs.compare_specs(sections(0.1), sections(None, f"no {FORGED} | x"))
    document = diff_specs.markdown(diff)
    rows = [line for line in document.splitlines() if line.startswith("| ")]
    assert len(rows) == 2  # the header and the one change
    assert "\\n" in rows[1] and "\x1b" not in document and "\\|" in rows[1]


def test_a_lidar_name_is_drawn_escaped_in_the_picture():
    hostile = f"{FORGED}\udc80\u202e"
    sensors = Section("sensors", [
        Figure(f"sensors.{hostile}.pose", "pose", [0.0, 0.0, 0.1, 0.0], "", "x"),
        Figure(f"sensors.{hostile}.blocked", "blocked", [[90.0, 270.0]], "", "x")])
    top, _ = picture.draw_views([sensors])
    assert picture.overlay_of([sensors]).lidars[0].name == hostile
    pixels = np.asarray(top.image.convert("RGB")).astype(int)
    purple = np.abs(pixels - np.array(picture.BLOCKED_COLOUR)).max(axis=2) <= 60
    assert purple.any()  # drawn, not refused
    assert isinstance(top.image, Image.Image)
