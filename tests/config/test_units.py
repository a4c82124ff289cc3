"""Dimensions typed by people: bare SI numbers, or numbers with units converted to SI."""

from __future__ import annotations

import math

import pytest

from mobile_car.config.units import FAST_UNITS, parse_quantity
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


def _with_pint(number: float, word: str, unit: str) -> float:
    from mobile_car.config.units import _PINT_UNITS, _registry

    registry = _registry()
    quantity = registry.Quantity(number, registry.parse_units(word))
    return float(quantity.to(_PINT_UNITS.get(unit, unit)).magnitude)


@pytest.mark.parametrize("word", sorted(FAST_UNITS))
def test_units_read_without_pint_give_pints_very_float(word):
    """The same float to the last bit, for the numbers people and ranges write and many
    others: a sweep's points and a range's ends do not move by the change of path."""
    import random

    unit = FAST_UNITS[word][0]
    chance = random.Random(word)
    numbers = [0, 1, 2.5, 6.5, 25, 33, 45, 65, 90, 99.9, 280, 1e-3, 1.5e-7, 3e5,
               *(chance.uniform(0, 1000) for _ in range(500)),
               *(round(chance.uniform(0, 200), 1) for _ in range(500))]
    for number in numbers:
        for text in (f"{number!r}{word}", f"{number!r} {word}"):
            assert parse_quantity(text, unit, "x") == _with_pint(number, word, unit), text


def test_common_units_are_read_without_importing_pint():
    code = ("import sys; from mobile_car.config.units import parse_quantity as p; "
            "print(p('25mm', 'm', 'x'), p('90 deg', 'rad', 'x'), p('40g', 'kg', 'x'), "
            "'pint' in sys.modules); p('1in', 'm', 'x'); print('pint' in sys.modules)")
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    assert done.stdout.split() == ["0.025", repr(math.pi / 2), "0.04", "False", "True"]
