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
    ("5 furlongs per", "m", "x: '5 furlongs per' has an unknown unit 'per'"),
])
def test_refuses_what_is_not_a_quantity_of_that_unit(text, unit, message):
    with pytest.raises(UsageError) as info:
        parse_quantity(text, unit, "x")
    assert message in str(info.value)


@pytest.mark.parametrize("text, message", [
    # pint alone reads "4 0mm" as 4 * 0 mm = 0 and "1/25" as a dimensionless 0.04
    ("4 0mm", "x: '4 0mm' is neither a number nor a number with a unit (e.g. 0.065, 65mm, "
              "6.5 cm)"),
    ("1/25", "x: '1/25' is an expression; give one number with an optional unit"),
    ("(40)mm", "x: '(40)mm' is an expression"),
    ("2*20mm", "x: '2*20mm' is an expression"),
    # YAML 1.1 number syntax is not ours: the same text means the same thing everywhere
    ("0x10", "x: '0x10' is neither a number nor a number with a unit"),
    ("1_000", "x: '1_000' is neither a number nor a number with a unit"),
    (".inf", "x: '.inf' is not a finite number"),
    ("40furlongz", "x: '40furlongz' has an unknown unit 'furlongz'"),
    ("40 percent", "x: '40 percent' has the wrong unit: expected m, got %"),
    ("1e306 km", "x: '1e306 km' is not a finite number"),
])
def test_one_number_with_one_unit_and_nothing_else(text, message):
    with pytest.raises(UsageError) as info:
        parse_quantity(text, "m", "x")
    assert str(info.value).startswith(message)


@pytest.mark.parametrize("text, unit, expected", [
    ("40furlongs", "m", 8046.736093472186), ("1.19 g/cm^3", "kg/m^3", 1190.0),
    ("-5 mm", "m", -0.005), ("90°", "rad", math.pi / 2), ("1e3mm", "m", 1.0),
    ("360", "count", 360.0), ("4.4 kgf*cm", "N*m", 0.4314926),
])
def test_units_pint_knows_are_converted(text, unit, expected):
    assert parse_quantity(text, unit, "x") == pytest.approx(expected, rel=1e-6)
