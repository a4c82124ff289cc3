"""The sweep plot (mobile_car.sweep.plot): what the Figure draws (axes, points, legend,
colour bar), the PNG it writes, and the one-line errors for a wrong x, y or colour."""

from __future__ import annotations

import importlib.util
import math
import os
import subprocess
import sys

import pytest

NO_EXTRA = 'the sweep extra is not installed: pip install "mcar[sweep]"'
pd = pytest.importorskip("pandas", reason=NO_EXTRA)
# Looked for, not imported: the child process below imports this module, and its
# matplotlib must start inside plot_sweep, as it does in mcar.
if importlib.util.find_spec("matplotlib") is None:
    pytest.skip(NO_EXTRA, allow_module_level=True)
from PIL import Image  # noqa: E402

from mobile_car.errors import UsageError  # noqa: E402
from mobile_car.sweep.plot import draw_sweep, plot_sweep  # noqa: E402

OVERLAP = "the wheels overlap the chassis"
BRACKETS = "the motor brackets stick out of the plate"
# As long as the config's own messages: the legend has to shorten it.
CASTOR = ("the castor does not reach the ground: the plate's underside at z = wheel_radius "
          "- axle_height_offset is above the castor ball's top")
UNITS = {"wheel_radius": "m", "track_width": "m", "wheel_mass": "kg"}
FIGURES = ["mass_kg", "rest_height_m", "tilt_deg", "speed_ratio", "speed_m_s", "yaw_ratio",
           "yaw_rate_rad_s", "lateral_drift_m", "heading_change_deg", "centre_moved_m"]
# Valid points (in plan order) that did not pass: every failing status, check failed twice.
FAILURES = {1: "check failed", 4: "sim failed", 7: "error", 10: "crashed", 13: "check failed"}


def refusal(wheel_radius: float, track_width: float) -> str:
    """The constraint that refuses a point, as the car's config does ("" when none)."""
    if track_width <= 0.156:
        return OVERLAP
    if track_width > 0.166:
        return BRACKETS
    if wheel_radius >= 0.0575:
        return CASTOR
    return ""


def sweep_table(radii=None, tracks=None):
    """A results table as mcar sweep writes it: 10 wheel radii x 6 track widths = 60
    points, 16 valid (5 of them failing), 44 refused by three constraints."""
    radii = radii if radii is not None else [0.020 + 0.005 * i for i in range(10)]
    tracks = tracks if tracks is not None else [0.150 + 0.005 * i for i in range(6)]
    rows, valid_seen = [], 0
    for r in radii:
        for track in tracks:
            refused = refusal(r, track)
            row = {"point": len(rows), "wheel_radius": r, "track_width": track,
                   "valid": not refused, "constraint": refused,
                   "status": "rejected" if refused else "ok",
                   **dict.fromkeys(FIGURES, math.nan),
                   "build_s": 0.4, "attempts": 1, "worker": "local-1", "reason": ""}
            if not refused:
                row["status"] = FAILURES.get(valid_seen, "ok")
                if row["status"] in ("ok", "sim failed"):  # simulated: figures measured
                    row.update(mass_kg=0.55 + 4 * r, rest_height_m=r + 0.003,
                               tilt_deg=0.2 + 100 * (r - 0.02), speed_ratio=1.0 - 3 * (r - 0.02),
                               speed_m_s=5 * r, yaw_ratio=0.9 - (track - 0.16),
                               yaw_rate_rad_s=10 * r / track, lateral_drift_m=0.1 * r,
                               heading_change_deg=0.5, centre_moved_m=0.01 * r)
                valid_seen += 1
            rows.append(row)
    table = pd.DataFrame(rows)
    return table.astype({"point": "int64", "wheel_radius": "float64", "track_width": "float64"})


def groups(figure) -> dict[str, int]:
    """gid -> number of points of each scatter the figure's axes draw."""
    (axes,) = [a for a in figure.axes if a.get_label() != "<colorbar>"]
    return {c.get_gid(): len(c.get_offsets()) for c in axes.collections}


def legend_texts(figure) -> list[str]:
    (legend,) = figure.legends
    return [" ".join(text.get_text().split()) for text in legend.get_texts()]


def test_every_point_is_drawn_once_valid_coloured_rejections_by_constraint():
    table = sweep_table()
    figure = draw_sweep(table, "wheel_radius", "track_width", "speed_ratio", UNITS)
    drawn = groups(figure)
    points = {gid: n for gid, n in drawn.items() if not gid.startswith("failed:")}
    assert sum(points.values()) == len(table) == 60
    assert drawn["valid"] + drawn["valid unmeasured"] == table["valid"].sum() == 16
    assert drawn["valid"] == table["speed_ratio"].notna().sum() == 12
    # Valid but not measured (the check failed, the run broke): drawn neutral grey.
    (unmeasured,) = [c for c in figure.axes[0].collections if c.get_gid() == "valid unmeasured"]
    (red, green, blue, _), = unmeasured.get_facecolors()
    assert red == green == blue and 0.6 < red < 0.9
    assert {gid: n for gid, n in drawn.items() if gid.startswith("rejected:")} == {
        f"rejected:{OVERLAP}": 20, f"rejected:{BRACKETS}": 20, f"rejected:{CASTOR}": 4}
    assert {gid: n for gid, n in drawn.items() if gid.startswith("failed:")} == {
        "failed:check failed": 2, "failed:sim failed": 1, "failed:error": 1,
        "failed:crashed": 1}


def test_axes_title_colour_bar_and_legend_say_what_is_drawn():
    figure = draw_sweep(sweep_table(), "wheel_radius", "track_width", "speed_ratio", UNITS)
    axes, colour_bar = figure.axes
    assert axes.get_xlabel() == "wheel_radius (mm)"
    assert axes.get_ylabel() == "track_width (mm)"
    assert axes.get_title() == "60 points: 16 valid (5 failed), 44 rejected"
    assert colour_bar.get_ylabel() == "speed_ratio"
    # Lengths in millimetres: the points sit at 20..65 mm and 150..175 mm.
    offsets = [c.get_offsets() for c in axes.collections]
    assert min(o[:, 0].min() for o in offsets) == pytest.approx(20.0)
    assert max(o[:, 1].max() for o in offsets) == pytest.approx(175.0)
    texts = legend_texts(figure)
    assert texts[:7] == ["valid", "coloured by speed_ratio (12)",
                         "speed_ratio not measured (4)", "check failed (2)", "sim failed (1)",
                         "error (1)", "crashed (1)"]
    assert texts[7:10] == ["rejected: the constraint", f"{BRACKETS} (20)", f"{OVERLAP} (20)"]
    # The long constraint is cut to three lines, its start kept.
    assert texts[10].endswith(" …") and CASTOR.startswith(texts[10][:-2])
    assert len(figure.legends[0].get_texts()[10].get_text().splitlines()) == 3
    bold = [t.get_text() for t in figure.legends[0].get_texts() if t.get_fontweight() == "bold"]
    assert bold == ["valid", "rejected: the constraint"]


@pytest.mark.parametrize("colour, label", [
    ("rest_height_m", "rest_height (mm)"), ("tilt_deg", "tilt (°)"), ("mass_kg", "mass (kg)"),
    ("speed_m_s", "speed (m/s)"), ("yaw_rate_rad_s", "yaw_rate (rad/s)"),
    ("build_s", "build (s)"), ("track_width", "track_width (mm)")])
def test_the_colour_bar_names_the_figure_and_its_unit(colour, label):
    figure = draw_sweep(sweep_table(), "wheel_radius", "track_width", colour, UNITS)
    assert figure.axes[1].get_ylabel() == label


def test_the_png_is_written_at_its_size_with_the_colours_it_draws(tmp_path):
    out = tmp_path / "plots" / "sweep.png"
    plot_sweep(sweep_table(), "wheel_radius", "track_width", "speed_ratio", UNITS, out)
    with Image.open(out) as image:
        assert image.format == "PNG" and image.size == (1080, 648)
        pixels = image.convert("RGB")
        colours = pixels.getcolors(maxcolors=1 << 20)
    # Not blank: white paper, black ink, viridis' ends, the grey of rejections.
    assert len(colours) > 100
    ranked = [rgb for _, rgb in sorted(colours, reverse=True)]
    assert ranked[0] == (255, 255, 255)
    assert any(near(rgb, (68, 1, 84)) for rgb in ranked)  # viridis' dark end (colour bar)
    assert any(near(rgb, (253, 231, 37)) for rgb in ranked)  # viridis' light end
    assert any(near(rgb, (140, 140, 140)) for rgb in ranked)  # hollow grey markers


def near(rgb, reference) -> bool:
    return sum(abs(a - b) for a, b in zip(rgb, reference, strict=True)) < 40


def test_the_same_table_gives_the_same_png(tmp_path):
    first, second = tmp_path / "a.png", tmp_path / "b.png"
    for out in (first, second):
        plot_sweep(sweep_table(), "wheel_radius", "track_width", "tilt_deg", UNITS, out)
    assert first.read_bytes() == second.read_bytes()


def test_a_table_without_a_valid_point_draws_its_rejections_and_no_colour_bar(tmp_path):
    table = sweep_table(tracks=[0.150, 0.155, 0.170])
    out = tmp_path / "refused.png"
    figure = plot_sweep(table, "track_width", "wheel_radius", "speed_ratio", UNITS, out)
    assert len(figure.axes) == 1  # no colour bar: nothing valid to colour
    assert groups(figure) == {f"rejected:{OVERLAP}": 20, f"rejected:{BRACKETS}": 10}
    assert figure.axes[0].get_title() == "30 points: 0 valid, 30 rejected"
    assert legend_texts(figure) == ["rejected: the constraint", f"{OVERLAP} (20)",
                                    f"{BRACKETS} (10)"]
    with Image.open(out) as image:
        assert image.size == (1080, 648)


def test_a_failed_write_keeps_the_earlier_plot(tmp_path):
    out = tmp_path / "sweep.png"
    out.write_bytes(b"earlier plot")
    with pytest.raises(UsageError):
        plot_sweep(sweep_table(), "wheel_radius", "status", "speed_ratio", UNITS, out)
    assert out.read_bytes() == b"earlier plot"


def test_a_plot_that_breaks_while_being_written_keeps_the_earlier_one(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def half_a_png(figure, target, **options):
        target.write(b"\x89PNG half")
        raise MemoryError("out of memory while encoding")

    out = tmp_path / "sweep.png"
    out.write_bytes(b"earlier plot")
    monkeypatch.setattr(Figure, "savefig", half_a_png)
    with pytest.raises(MemoryError):
        plot_sweep(sweep_table(), "wheel_radius", "track_width", "speed_ratio", UNITS, out)
    assert out.read_bytes() == b"earlier plot"
    assert [p.name for p in tmp_path.iterdir()] == ["sweep.png"]


@pytest.mark.parametrize("x, y, colour, message", [
    ("wheel_width", "track_width", "speed_ratio",
     "cannot plot over 'wheel_width': it is not a dimension the sweep varied; its dimensions "
     "are wheel_radius, track_width"),
    ("wheel_radius", "mass_kg", "speed_ratio",
     "cannot plot over 'mass_kg': it is not a dimension the sweep varied; its dimensions are "
     "wheel_radius, track_width"),
    ("wheel_radius", "wheel_radius", "speed_ratio",
     "cannot plot wheel_radius against itself: choose two of wheel_radius, track_width"),
    ("wheel_radius", "track_width", "status",
     "cannot colour the plot by 'status': it is not a number column of the sweep table; its "
     "number columns are point, wheel_radius, track_width, " + ", ".join(FIGURES)
     + ", build_s, attempts"),
    ("wheel_radius", "track_width", "valid",
     "cannot colour the plot by 'valid': it is not a number column of the sweep table; its "
     "number columns are point, wheel_radius, track_width, " + ", ".join(FIGURES)
     + ", build_s, attempts"),
    ("wheel_radius", "track_width", "speed",
     "cannot colour the plot by 'speed': it is not a column of the sweep table; its number "
     "columns are point, wheel_radius, track_width, " + ", ".join(FIGURES)
     + ", build_s, attempts"),
])
def test_a_wrong_column_is_a_one_line_usage_error_naming_the_columns(x, y, colour, message):
    with pytest.raises(UsageError) as raised:
        draw_sweep(sweep_table(), x, y, colour, UNITS)
    assert str(raised.value) == message


def test_a_sweep_over_one_dimension_cannot_be_plotted_over_two():
    table = sweep_table(tracks=[0.160]).drop(columns="track_width")
    with pytest.raises(UsageError) as raised:
        draw_sweep(table, "wheel_radius", "wheel_radius", "speed_ratio", UNITS)
    assert str(raised.value) == ("cannot plot the sweep over two dimensions: it varied only "
                                 "wheel_radius")


def test_a_table_that_is_not_sweep_results_is_refused():
    table = sweep_table().drop(columns=["status", "valid"])
    with pytest.raises(UsageError) as raised:
        draw_sweep(table, "wheel_radius", "track_width", "speed_ratio", UNITS)
    assert str(raised.value).startswith("the sweep table has no column valid, status: it is "
                                        "not the results of mcar sweep (its columns: point, ")


PLOT_IN_A_CHILD = """
import sys
sys.path.insert(0, sys.argv[2])
from test_plot import UNITS, sweep_table
from mobile_car.sweep.plot import plot_sweep
plot_sweep(sweep_table(), "wheel_radius", "track_width", "speed_ratio", UNITS, sys.argv[1])
"""


# A user's matplotlibrc that would change every pixel if it were read.
HOSTILE_RC = """axes.facecolor: black
figure.facecolor: 0.2
font.size: 20
lines.markersize: 20
savefig.transparent: True
savefig.bbox: tight
image.cmap: jet
"""


@pytest.mark.parametrize("setting", ["unwritable home", "own matplotlibrc"])
def test_a_child_process_draws_the_same_png_quietly_whatever_its_matplotlib_home(
        setting, tmp_path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME", "XDG_CACHE_HOME", "MPLBACKEND")}
    env["TMPDIR"] = str(tmp_path)
    if setting == "unwritable home":
        home = tmp_path / "home"
        home.write_text("a file, so not even root can make ~/.config under it")
        env["HOME"] = str(home)
    else:
        config = tmp_path / "config"
        config.mkdir()
        (config / "matplotlibrc").write_text(HOSTILE_RC)
        env["MPLCONFIGDIR"] = str(config)
    out = tmp_path / "sweep.png"
    # Run from tmp_path: from the repository, `python -c` would import its source tree.
    result = subprocess.run([sys.executable, "-c", PLOT_IN_A_CHILD, str(out),
                             os.path.dirname(__file__)], cwd=tmp_path,
                            capture_output=True, text=True, env=env, timeout=120)
    assert (result.returncode, result.stderr) == (0, "")
    here = tmp_path / "here.png"
    plot_sweep(sweep_table(), "wheel_radius", "track_width", "speed_ratio", UNITS, here)
    assert out.read_bytes() == here.read_bytes()
    # matplotlib's temporary config folder went at exit.
    assert not list(tmp_path.glob("matplotlib-*"))
