"""Dimensions typed by people: bare SI numbers, or numbers with units converted to SI."""

from __future__ import annotations

import math

import pytest

from mobile_car.config.units import parse_quantity
from mobile_car.errors import UsageError


@pytest.mark.parametrize("text, unit, expected", [
    ("0.0325", "m", 0.0325), ("65mm", "m", 0.065), ("6.5 cm", "m", 0.065),
    ("1in", "m", 0.0254), ("40 g", "kg", 0.040), ("90deg", "rad", math.pi / 2),
    ("1.5e-3", "m", 0.0015), (0.2, "m", 0.2), (3, "kg", 3.0),
    ("280 rpm", "rad/s", 280 * math.pi / 30),
])
def test_converts_to_si(text, unit, expected):
    assert parse_quantity(text, unit, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text, unit, message", [
    ("3kg", "m", "x: '3kg' has the wrong unit: expected m, got kg"),
    ("abc", "m", "x: 'abc' is neither a number nor a number with a unit"),
    ("nan", "m", "is not a finite number"),
    ("inf mm", "m", "is not a finite number"),
    (True, "m", "expected a number in m"),
    ("5 furlongs per", "m", "is neither a number nor a number with a unit"),
])
def test_refuses_what_is_not_a_quantity_of_that_unit(text, unit, message):
    with pytest.raises(UsageError) as info:
        parse_quantity(text, unit, "x")
    assert message in str(info.value)
