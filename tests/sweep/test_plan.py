"""--vary words become points: ends included, units read as --set reads them, the first
--vary changing slowest; samples are the seed's."""

from __future__ import annotations

import itertools

import pytest
from conftest import REPO

from mobile_car.config.spec import load_spec
from mobile_car.errors import UsageError
from mobile_car.sweep.plan import grid, read_axes, samples


@pytest.fixture(scope="module")
def spec():
    return load_spec(REPO / "urdf" / "config.xacro")


def test_grid_includes_both_ends_in_si(spec):
    axes = read_axes(spec, ["wheel_radius=25mm..45mm:5", "track_width=0.15..0.17:3"], False)
    assert axes[0].values == (0.025, 0.03, 0.035, 0.04, 0.045)
    assert axes[1].values == (0.15, 0.16, 0.17)
    points = grid(axes)
    assert [p.index for p in points] == list(range(15))
    assert [tuple(p.values.values()) for p in points] == list(
        itertools.product(axes[0].values, axes[1].values))
    assert list(points[0].values) == ["wheel_radius", "track_width"]


def test_lists_units_and_duplicates(spec):
    axes = read_axes(spec, ["wheel_radius=2.5cm,30mm,0.03,1in", "motor_no_load_speed=280rpm"],
                     False)
    assert axes[0].values == (0.025, 0.03, 0.0254)
    assert axes[1].values == (pytest.approx(280 * 2 * 3.141592653589793 / 60),)


def test_a_count_takes_whole_values(spec):
    axes = read_axes(spec, ["laser_samples=100..200:4"], False)
    assert axes[0].values == (100.0, 133.0, 167.0, 200.0)


def test_samples_are_the_seeds(spec):
    axes = read_axes(spec, ["wheel_radius=25mm..45mm", "track_width=0.15,0.16"], True)
    first, again, other = samples(axes, 20, 3), samples(axes, 20, 3), samples(axes, 20, 4)
    assert [p.values for p in first] == [p.values for p in again]
    assert [p.values for p in first] != [p.values for p in other]
    assert all(0.025 <= p.values["wheel_radius"] <= 0.045 for p in first)
    assert {p.values["track_width"] for p in first} == {0.15, 0.16}


def test_values_outside_the_range_are_points_not_errors(spec):
    """A sweep shows where the range ends: those points become rejected rows."""
    axes = read_axes(spec, ["wheel_radius=1mm..9mm:3"], False)
    assert axes[0].values == (0.001, 0.005, 0.009)


@pytest.mark.parametrize("word, message", [
    ("wheel_radius=25mm..45mm:0",
     "--vary wheel_radius=25mm..45mm:0: the number of values must be 1..100000, not 0"),
    ("wheel_radius=25mm..45mm:1",
     "--vary wheel_radius=25mm..45mm:1: one value cannot span 0.025..0.045; give :2 or more"),
    ("wheel_radius=..45mm:3", "--vary wheel_radius=..45mm:3: a range is LO..HI, both ends given"),
    ("wheel_radius", "--vary wheel_radius: expected NAME=LO..HI:N or NAME=A,B,C, "
                     "e.g. wheel_radius=25mm..45mm:9"),
    ("wheel_radius=25mm,,30mm", "--vary wheel_radius=25mm,,30mm: wheel_radius: '' is neither "
                                "a number nor a number with a unit (e.g. 0.065, 65mm, 6.5 cm)"),
])
def test_malformed_words(spec, word, message):
    with pytest.raises(UsageError) as error:
        read_axes(spec, [word], False)
    assert error.value.message == message
