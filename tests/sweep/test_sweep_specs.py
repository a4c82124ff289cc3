"""`mcar sweep --specs`: figures of mcar specs as columns of each point's row. mcar specs'
computation is replaced by hand-built Sections that follow the point's wheel radius, so
each cell is known; the point itself is built, checked and simulated for real."""

from __future__ import annotations

import math

import pytest
from conftest import REPO

from mobile_car.errors import McarError, UsageError
from mobile_car.specs.figures import Figure, Section
from mobile_car.sweep import specs
from mobile_car.sweep.plan import Point
from mobile_car.sweep.point import SweepJob, evaluate_point

pd = pytest.importorskip("pandas", reason="the sweep extra (pip install 'mcar[sweep]')")

ROBOT = str(REPO / "urdf" / "mobile_robot.xacro")
KEYS = ("statics.tip.left", "body.mass", "statics.climb", "statics.top_speed")


def hand_sections(radius: float) -> list[Section]:
    """A tip-over angle that grows with the wheels, a mass, a figure not computed, a
    list where a number was asked for; statics.top_speed absent."""
    return [Section("body", [Figure("body.mass", "mass", 0.7 + radius, "kg", "inertials")]),
            Section("statics", [
                Figure("statics.tip.left", "tip-over left", 1000 * radius, "deg", "geometry"),
                Figure("statics.climb", "climb", None, "deg", "no drive: no driven wheels")])]


def test_keys_are_parsed_in_order_once_each():
    assert specs.parse_keys("statics.tip.left, body.mass,statics.tip.left") == (
        "statics.tip.left", "body.mass")
    assert specs.parse_keys(None) == ()


@pytest.mark.parametrize(("text", "message"), [
    ("body.footprint", "--specs body.footprint: body.footprint is a list, not a number; a "
     "column holds one number per point (e.g. statics.tip.min, body.mass)"),
    ("body.mass,sensors.front_laser.blocked", "--specs body.mass,sensors.front_laser.blocked: "
     "sensors.front_laser.blocked is a list, not a number; a column holds one number per "
     "point (e.g. statics.tip.min, body.mass)"),
    ("mass_kg", "--specs mass_kg: 'mass_kg' is not a figure key (dotted, like "
     "statics.tip.left or body.mass; the list: mcar specs --format json)"),
])
def test_a_key_that_cannot_be_a_column_is_refused(text, message):
    with pytest.raises(UsageError) as caught:
        specs.parse_keys(text)
    assert caught.value.message == message


def test_cells_hold_numbers_and_say_why_a_cell_is_empty():
    sections = hand_sections(0.03)
    sections[0].figures.append(Figure("body.com", "centre of mass", [0, 0, 0.1], "m", "x"))
    row = specs.cells(sections, (*KEYS, "body.com"))
    assert row["statics.tip.left"] == 30.0 and row["body.mass"] == pytest.approx(0.73)
    assert math.isnan(row["statics.climb"]) and math.isnan(row["statics.top_speed"])
    assert row["specs_notes"] == (
        "statics.climb: not computed (no drive: no driven wheels); "
        "statics.top_speed: this robot has no such figure; body.com: not a number (list)")


def _fake_sections(checked, options=None):
    base = next(j for j in checked.robot.joints if j.name == "base_joint")
    radius = float(base.parts["origin"].get("xyz").split()[2])  # the axle height: r
    return hand_sections(radius)


@pytest.fixture
def job(monkeypatch):
    monkeypatch.setattr(specs, "specs_sections", _fake_sections)
    return SweepJob(ROBOT, None, scenarios=("drop",), specs=KEYS)


@pytest.fixture(scope="module")
def rows():
    """Two points evaluated once for the tests that read them: 40 mm and 30 mm wheels."""
    job = SweepJob(ROBOT, None, scenarios=("drop",), specs=KEYS)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(specs, "specs_sections", _fake_sections)
        return [evaluate_point(job, i, {"wheel_radius": r, "track_width": 0.16})
                for i, r in enumerate((0.04, 0.03))]


def test_a_point_row_has_the_figures_as_columns(rows):
    row = rows[0]
    assert row["status"] == "ok", row["reason"]
    assert row["statics.tip.left"] == pytest.approx(40.0, abs=1e-6)
    assert row["body.mass"] == pytest.approx(0.74, abs=1e-6)
    assert math.isnan(row["statics.climb"])
    assert row["specs_notes"] == ("statics.climb: not computed (no drive: no driven wheels); "
                                  "statics.top_speed: this robot has no such figure")
    assert not math.isnan(row["rest_height_m"])  # the scenarios ran as before


def test_a_point_whose_specs_fail_keeps_its_row(job, monkeypatch):
    def broken(checked, options=None):
        raise McarError("the model does not compile")

    monkeypatch.setattr(specs, "specs_sections", broken)
    row = evaluate_point(job, 3, {"wheel_radius": 0.04})
    assert row["status"] == "ok"
    assert all(math.isnan(row[key]) for key in KEYS)
    assert row["specs_notes"] == "specs not computed: the model does not compile"


def test_a_rejected_point_computes_nothing(job):
    row = evaluate_point(job, 1, {"wheel_radius": 5.0})
    assert row["status"] == "rejected"
    assert all(math.isnan(row[key]) for key in KEYS) and row["specs_notes"] == ""


def test_the_table_keeps_the_columns_through_csv_and_resume(job, rows, tmp_path):
    from mobile_car.sweep import results
    from mobile_car.sweep.execute import crashed_row

    names = ["wheel_radius", "track_width"]
    table_rows = [rows[0], crashed_row(Point(1, {"wheel_radius": 0.03, "track_width": 0.16}),
                                       "died twice", job.specs)]
    fingerprint = job.fingerprint(names)
    frame = results.table(table_rows, names, fingerprint, job.specs)
    assert list(frame.columns).index("statics.tip.left") > list(frame.columns).index(
        "centre_moved_m")
    path = tmp_path / "results.csv"
    results.write(frame, str(path))
    back = results.read(str(path))
    assert back["statics.tip.left"].tolist()[0] == pytest.approx(40.0)
    assert math.isnan(back["statics.tip.left"].tolist()[1])
    assert back["specs_notes"].tolist()[1] == ""
    points = [Point(0, {"wheel_radius": 0.04, "track_width": 0.16}),
              Point(1, {"wheel_radius": 0.03, "track_width": 0.16})]
    kept = results.resumed_rows(str(path), points, names, fingerprint, job.specs)
    assert [row["point"] for row in kept] == [0]  # the crashed one runs again


def test_a_sweep_with_other_specs_is_another_sweep(job):
    names = ["wheel_radius"]
    without = SweepJob(ROBOT, None, scenarios=("drop",))
    assert job.fingerprint(names) != without.fingerprint(names)
    # without --specs, the fingerprint an earlier mcar gave (results files stay resumable)
    assert without.fingerprint(names) == SweepJob(ROBOT, None, scenarios=("drop",),
                                                  specs=()).fingerprint(names)


def test_the_plot_is_coloured_by_a_specs_figure(job, rows):
    pytest.importorskip("matplotlib", reason="the sweep extra (pip install 'mcar[sweep]')")
    from mobile_car.sweep import results
    from mobile_car.sweep.plot import draw_sweep

    frame = results.table(rows, ["wheel_radius", "track_width"], "x", job.specs)
    figure = draw_sweep(frame, "wheel_radius", "track_width", "statics.tip.left",
                        {"wheel_radius": "m", "track_width": "m"})
    colour_bar = figure.axes[1]
    assert colour_bar.get_ylabel() == "statics.tip.left"
    valid = next(c for c in figure.axes[0].collections if c.get_gid() == "valid")
    assert valid.get_array().tolist() == pytest.approx([40.0, 30.0])


def test_the_command_refuses_a_list_figure_before_it_runs(run_mcar, tmp_path):
    done = run_mcar("sweep", ROBOT, "--vary", "wheel_radius=25mm,30mm", "--specs",
                    "statics.support", "-o", "r.csv", cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr == ("mcar: error: --specs statics.support: statics.support is a list, "
                           "not a number; a column holds one number per point (e.g. "
                           "statics.tip.min, body.mass)\n")
    assert not (tmp_path / "r.csv").exists()
