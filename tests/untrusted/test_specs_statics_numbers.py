"""The figures of a description reach mcar specs' statics and the MuJoCo runs that prove
them (mobile_car/specs/statics.py, proof_tilt.py, proof_climb.py): a hostile file gives
its tyres a friction (<mu1> 1e300) and its motors an effort (1e300) no robot has, so that
every slope holds and the proofs would tilt and climb for ever, and MuJoCo's state turns
to NaN in its first step. A μ over 10 is no tyre's: not used (MuJoCo's default 1, a note
says why); the slopes are searched up to 89° only, and every tilt stops 4° past the
angle it proves: the figures stay numbers, every run ends, and MuJoCo warns of nothing.
The controls: the hostile μ reaches the statics (the note names it), and the effort is
used as written (the climb is the 89° cap)."""

from __future__ import annotations

import math

from specs.statics_robots import box_on_wheels, checked_and_sim

from mobile_car.sim.engine import WARNINGS
from mobile_car.specs import proof_tilt
from mobile_car.specs.statics import statics_section

# s simulated: the settle, 10°/s to 85°, 2°/s over the last 8°: the longest tilt there is
LONGEST_TILT = proof_tilt.SETTLE + math.radians(85) / proof_tilt.FAST_RATE + \
    2 * proof_tilt.WINDOW / proof_tilt.SLOW_RATE


def test_a_friction_and_effort_no_robot_has_end_in_bounded_runs(tmp_path, monkeypatch):
    path = tmp_path / "hostile.urdf"
    path.write_text(box_on_wheels(lift=0.02, mu=1e300, effort=1e300, velocity=10))
    checked, sim = checked_and_sim(path)
    tilts = []
    real_tilt = proof_tilt.tilt

    def counted(*args, **kwargs):
        tilts.append(real_tilt(*args, **kwargs))
        return tilts[-1]

    monkeypatch.setattr(proof_tilt, "tilt", counted)
    WARNINGS.clear()
    section = statics_section(checked, sim, {})
    fig = {f.key: f for f in section.figures}
    assert "link front_left_wheel_link: <mu1> 1e+300 is no tyre's (over 10): not used" \
        in section.notes
    assert "μ 1 (MuJoCo's default 1 (its <mu1> not used))" in fig["statics.slide"].source
    assert fig["statics.slide"].value == 45.0 and fig["statics.climb"].value == 45.0
    for figure in section.figures:
        for number in _numbers(figure.value):
            assert math.isfinite(number), figure.key
    # four directions (stand's and slide's azimuths among them), each ended in time
    assert len(tilts) == 4 and all(t.seconds <= LONGEST_TILT for t in tilts), tilts
    assert not WARNINGS


def _numbers(value):
    if isinstance(value, (int, float)):
        yield float(value)
    elif isinstance(value, list):
        for item in value:
            yield from _numbers(item)
