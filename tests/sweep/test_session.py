"""The summary a sweep ends with names what could not be evaluated, but not endlessly."""

from __future__ import annotations

from mobile_car.sweep.execute import crashed_row
from mobile_car.sweep.plan import Point
from mobile_car.sweep.point import SweepJob, empty_row
from mobile_car.sweep.session import SHOWN_FAILURES, Session


def test_the_summary_names_ten_failures_and_counts_the_rest():
    points = [Point(i, {"wheel_radius": 0.03}) for i in range(25)]
    session = Session(SweepJob("/robot.xacro", None), ["wheel_radius"], points, None)
    for point in points[:12]:
        session.add(crashed_row(point, "it died"))
    for point in points[12:]:
        row = empty_row(point.index, point.values)
        row.update(status="rejected", constraint="the wheels overlap the chassis")
        session.add(row)
    lines = session.summary("2 local workers")
    assert lines[0].endswith("(2 local workers): 0 ok, 13 rejected, 12 crashed")
    assert lines[1:] == [
        "  rejected 13x: the wheels overlap the chassis",
        *[f"  point {i} crashed: it died" for i in range(SHOWN_FAILURES)],
        "  ... and 2 more (status and reason in the results)"]
    assert session.exit_code() == 1
