"""The plot of a sweep: the valid region over two dimensions, coloured by one figure, and
every rejected point marked by the constraint that refused it.

The table is the sweep's results (one row per point): the varied dimensions in their SI
unit, ``valid``, ``constraint``, ``status`` and the figures. :func:`draw_sweep` makes the
matplotlib Figure (for a test to inspect), :func:`plot_sweep` also writes it as a PNG.
Each drawn group of points carries a gid, so the Figure says what it shows:
``valid`` / ``valid unmeasured`` (a figure of NaN, drawn grey), ``rejected:CONSTRAINT``,
and ``failed:STATUS`` (a black mark drawn over a valid point whose build, check or sim
did not pass; not a point of its own).

matplotlib is imported only here, and through the Figure API with the Agg canvas, never
pyplot: no global figure state, no GUI backend, whatever MPLBACKEND says.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import dataclass

from ..errors import UsageError

# The columns every sweep table has besides its dimensions and figures.
REQUIRED = ("valid", "constraint", "status")

# A valid point's status when something after the config validator went wrong, and the
# mark drawn over it: black for a verdict on the robot, red for a run that broke.
FAILED_MARKS = {
    "check failed": ("x", "black"),
    "sim failed": ("+", "black"),
    "error": ("x", "#d62728"),
    "crashed": ("+", "#d62728"),
}
OTHER_FAILED_MARKS = [("1", "black"), ("2", "black"), ("3", "#d62728"), ("4", "#d62728")]

# Rejected points: hollow grey, one shape per constraint (cycled, then darker, if many).
REJECTED_SHAPES = ["s", "^", "D", "v", "p", "h", "<", ">"]
REJECTED_GREYS = ["#8c8c8c", "#4d4d4d"]

# A dimension's SI unit -> the unit its axis shows and the factor to it. Millimetres and
# degrees are what a builder measures a small robot in.
AXIS_UNITS = {"m": ("mm", 1000.0), "rad": ("°", 180.0 / math.pi), "1": ("", 1.0),
              "count": ("", 1.0)}
# A figure's column suffix -> its unit as shown and the factor to it. Longest first, so
# speed_m_s is a speed, not a length.
FIGURE_SUFFIXES = [("_rad_s", "rad/s", 1.0), ("_m_s", "m/s", 1.0), ("_deg", "°", 1.0),
                   ("_kg", "kg", 1.0), ("_m", "mm", 1000.0), ("_s", "s", 1.0)]

NEUTRAL = "#c8c8c8"  # a valid point whose colour figure was not measured
COLOURMAP = "viridis"
SIZE_INCHES = (9.0, 5.4)
DPI = 120
MARKER_AREA = 64
LEGEND_WIDTH = 30  # characters per line of a constraint's name in the legend


@dataclass(frozen=True)
class Axis:
    """How one column is drawn: its label and the factor from its SI value."""

    label: str
    factor: float


def plot_sweep(table, x: str, y: str, colour: str, units: dict[str, str], path):
    """Draw the sweep (see :func:`draw_sweep`) and write it to ``path`` as a PNG,
    atomically: a failure leaves an earlier plot there untouched. Returns the Figure."""
    import io

    from ..atomic import atomic_write

    figure = draw_sweep(table, x, y, colour, units)
    buffer = io.BytesIO()
    with _plain(_matplotlib()[0]):  # savefig reads rcParams too (transparent, bbox)
        # No "Software" stamp: the same table gives the same bytes under any matplotlib.
        figure.savefig(buffer, format="png", dpi=DPI, metadata={"Software": None})
    atomic_write(path, buffer.getvalue())
    return figure


def draw_sweep(table, x: str, y: str, colour: str, units: dict[str, str]):
    """The matplotlib Figure of the sweep ``table`` over dimensions ``x`` and ``y``,
    valid points coloured by the numeric column ``colour``. ``units`` maps dimension
    names to their SI unit ("m", "rad", "kg", ...); the table's dimensions are its columns
    named there. A table without a valid point draws its rejections and no colour bar.
    Raises UsageError, naming the columns there are, for a wrong x, y or colour."""
    check_columns(table, x, y, colour, units)
    matplotlib, Figure, FigureCanvasAgg = _matplotlib()
    with _plain(matplotlib):
        figure = Figure(figsize=SIZE_INCHES, dpi=DPI, layout="constrained")
        FigureCanvasAgg(figure)
        _draw(figure, table, x, y, colour, units)
    return figure


def _plain(matplotlib):
    """matplotlib's defaults, not the user's matplotlibrc (the plot looks the same
    everywhere), and its log kept off stderr."""
    import contextlib

    stack = contextlib.ExitStack()
    stack.enter_context(_quiet_matplotlib())
    stack.enter_context(matplotlib.style.context("default"))
    return stack


def _draw(figure, table, x, y, colour, units):
    import numpy as np
    from matplotlib.patheffects import withStroke

    axes = figure.add_subplot()
    x_axis = _dimension_axis(x, units[x])
    y_axis = _dimension_axis(y, units[y])
    xs = table[x].to_numpy(dtype=float) * x_axis.factor
    ys = table[y].to_numpy(dtype=float) * y_axis.factor
    valid = table["valid"].to_numpy(dtype=bool)
    status = table["status"].astype(str).to_numpy()
    values = table[colour].to_numpy(dtype=float) * _colour_axis(colour, units).factor
    handles, refusals = [], []

    measured = valid & np.isfinite(values)
    if measured.any():
        points = axes.scatter(xs[measured], ys[measured], c=values[measured], cmap=COLOURMAP,
                              s=MARKER_AREA, edgecolors="black", linewidths=0.5, zorder=3)
        points.set_gid("valid")
        figure.colorbar(points, ax=axes, label=_colour_axis(colour, units).label,
                        fraction=0.05, pad=0.02, aspect=30)
        handles.append(_handle("o", points.cmap(0.6), "black",
                               f"coloured by {_colour_name(colour)} ({int(measured.sum())})"))
    unmeasured = valid & ~np.isfinite(values)
    if unmeasured.any():
        grey = axes.scatter(xs[unmeasured], ys[unmeasured], color=NEUTRAL, s=MARKER_AREA,
                            edgecolors="black", linewidths=0.5, zorder=3)
        grey.set_gid("valid unmeasured")
        handles.append(_handle("o", NEUTRAL, "black",
                               f"{_colour_name(colour)} not measured "
                               f"({int(unmeasured.sum())})"))

    others = iter(OTHER_FAILED_MARKS)
    for name in _in_order(status[valid & (status != "ok")], list(FAILED_MARKS)):
        shape, ink = FAILED_MARKS.get(name) or next(others, ("1", "black"))
        failed = valid & (status == name)
        marks = axes.scatter(xs[failed], ys[failed], marker=shape, color=ink,
                             s=MARKER_AREA * 1.6, linewidths=1.6, zorder=4)
        marks.set_gid(f"failed:{name}")
        # A white rim: a black mark stays visible on viridis' darkest points.
        marks.set_path_effects([withStroke(linewidth=3.2, foreground="white")])
        handles.append(_handle(shape, ink, ink, f"{name} ({int(failed.sum())})"))

    constraints = table["constraint"].fillna("").astype(str).to_numpy()
    for index, name in enumerate(_by_count(constraints[~valid])):
        shape = REJECTED_SHAPES[index % len(REJECTED_SHAPES)]
        grey = REJECTED_GREYS[index // len(REJECTED_SHAPES) % len(REJECTED_GREYS)]
        refused = ~valid & (constraints == name)
        hollow = axes.scatter(xs[refused], ys[refused], marker=shape, facecolors="none",
                              edgecolors=grey, s=MARKER_AREA, linewidths=1.2, zorder=2)
        hollow.set_gid(f"rejected:{name}")
        shown = name or "rejected, constraint not named"
        refusals.append(_handle(shape, "none", grey,
                                _wrapped(f"{shown} ({int(refused.sum())})")))

    axes.set_xlabel(x_axis.label)
    axes.set_ylabel(y_axis.label)
    axes.set_title(_title(len(table), int(valid.sum()), int((valid & (status != "ok")).sum())))
    axes.grid(True, color="#e6e6e6", linewidth=0.8, zorder=0)
    axes.set_axisbelow(True)
    # One legend, outside the axes right of the colour bar (it never hides a point), in
    # two sections under bold headings: what became of the valid points, and why the
    # others were refused.
    entries = ([_heading("valid"), *handles] if handles else []) + (
        [_heading("rejected: the constraint"), *refusals] if refusals else [])
    if entries:
        legend = figure.legend(handles=entries, loc="outside right upper", frameon=False,
                               handletextpad=0.4, labelspacing=0.75)
        for handle, text in zip(entries, legend.get_texts(), strict=True):
            if handle.get_gid() == "heading":
                text.set_fontweight("bold")


def _title(points: int, valid: int, failed: int) -> str:
    failing = f" ({failed} failed)" if failed else ""
    noun = "point" if points == 1 else "points"
    return f"{points} {noun}: {valid} valid{failing}, {points - valid} rejected"


def _handle(shape, face, edge, label):
    from matplotlib.lines import Line2D

    return Line2D([], [], linestyle="none", marker=shape, markersize=8, label=label,
                  markerfacecolor=face, markeredgecolor=edge,
                  markeredgewidth=1.6 if shape in ("x", "+", "1", "2", "3", "4") else 1.0)


def _heading(text: str):
    from matplotlib.lines import Line2D

    return Line2D([], [], linestyle="none", label=text, gid="heading")


def _wrapped(text: str) -> str:
    """A constraint's name on a few short lines, cut with an ellipsis past three."""
    return "\n".join(textwrap.wrap(text, LEGEND_WIDTH, max_lines=3, placeholder=" …"))


def _in_order(names, known: list[str]) -> list[str]:
    """The distinct ``names``, those in ``known`` first in its order, then the rest sorted."""
    present = set(names.tolist())
    return [n for n in known if n in present] + sorted(present - set(known))


def _by_count(names) -> list[str]:
    """The distinct ``names``, the most frequent first (ties by name): the legend's order."""
    counts: dict[str, int] = {}
    for name in names.tolist():
        counts[name] = counts.get(name, 0) + 1
    return sorted(counts, key=lambda name: (-counts[name], name))


def _dimension_axis(name: str, unit: str) -> Axis:
    shown, factor = AXIS_UNITS.get(unit, (unit, 1.0))
    return Axis(f"{name} ({shown})" if shown else name, factor)


def _colour_axis(name: str, units: dict[str, str]) -> Axis:
    if name in units:
        return _dimension_axis(name, units[name])
    for suffix, shown, factor in FIGURE_SUFFIXES:
        if name.endswith(suffix) and len(name) > len(suffix):
            return Axis(f"{name[: -len(suffix)]} ({shown})", factor)
    return Axis(name, 1.0)


def _colour_name(name: str) -> str:
    return _colour_axis(name, {}).label.split(" (")[0]


def check_columns(table, x, y, colour, units) -> None:
    """UsageError, one line naming the columns there are, unless x and y are two of the
    table's dimensions and colour is one of its numeric columns."""
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    columns = [str(c) for c in table.columns]
    missing = [name for name in REQUIRED if name not in columns]
    if missing:
        raise UsageError(f"the sweep table has no column {', '.join(missing)}: it is not "
                         f"the results of mcar sweep (its columns: {', '.join(columns)})")
    dimensions = [c for c in columns if c in units and is_numeric_dtype(table[c])]
    listed = ", ".join(dimensions) or "none"
    for name in (x, y):
        if name not in dimensions:
            raise UsageError(f"cannot plot over {name!r}: it is not a dimension the sweep "
                             f"varied; its dimensions are {listed}")
    if x == y:
        if len(dimensions) < 2:
            raise UsageError(f"cannot plot the sweep over two dimensions: it varied only "
                             f"{listed}")
        raise UsageError(f"cannot plot {x} against itself: choose two of {listed}")
    numeric = [c for c in columns if is_numeric_dtype(table[c]) and not is_bool_dtype(table[c])]
    if colour not in numeric:
        what = "not a number column" if colour in columns else "not a column"
        raise UsageError(f"cannot colour the plot by {colour!r}: it is {what} of the sweep "
                         f"table; its number columns are {', '.join(numeric)}")


def _matplotlib():
    """matplotlib, its Figure and the Agg canvas; UsageError when the extra is missing."""
    try:
        with _quiet_matplotlib():
            import matplotlib
            import matplotlib.style
            from matplotlib.backends.backend_agg import FigureCanvasAgg
            from matplotlib.figure import Figure
    except ImportError:
        raise UsageError('the sweep plot needs matplotlib, which is not installed: '
                         'pip install "mcar[sweep]"') from None
    except OSError as exc:  # no writable HOME and no writable temporary folder either
        raise UsageError(f"matplotlib cannot start: {exc}") from None
    return matplotlib, Figure, FigureCanvasAgg


class _quiet_matplotlib:
    """Keep matplotlib's log off stderr while it runs here.

    With a HOME it cannot write (a CI container, a service account) matplotlib makes a
    temporary config folder, removed at exit, and says so on stderr through logging's
    last-resort handler; a plot costs ~0.1 s more for its font cache and is otherwise the
    same, so mcar prints nothing. An application that configured logging still sees it.
    """

    def __enter__(self):
        import logging

        self.logger = logging.getLogger("matplotlib")
        self.handler = logging.NullHandler()
        self.logger.addHandler(self.handler)
        return self

    def __exit__(self, *exc_info):
        self.logger.removeHandler(self.handler)
        return False

