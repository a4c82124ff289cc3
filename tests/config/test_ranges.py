"""The range grammar of config.xacro's comments ("m 5mm..0.5m; listing: ..."), and what
mcar does with it: values outside are refused with the range and a unit hint."""

from __future__ import annotations

import pytest
from conftest import REPO

from mobile_car.config.ranges import KINDS, outside_message, parse_range
from mobile_car.config.spec import load_spec, parse_set_options
from mobile_car.errors import BuildError, InputError, UsageError

CONFIG = REPO / "urdf" / "config.xacro"


@pytest.mark.parametrize("text, unit, low, high, shown", [
    ("5mm..0.5m", "m", 0.005, 0.5, "5 mm..0.5 m"),
    ("0..20mm", "m", 0.0, 0.02, "0 m..20 mm"),
    ("-0.5m..0.5m", "m", -0.5, 0.5, "-0.5 m..0.5 m"),
    ("1..100000", "count", 1, 100000, "1..100000"),
    ("0..1", "1", 0, 1, "0..1"),
    ("1g..5kg", "kg", 0.001, 5.0, "1 g..5 kg"),
    ("10rpm..20000rpm", "rad/s", 1.0471975511965976, 2094.3951023931954,
     "10 rpm..20000 rpm"),
])
def test_a_range_is_two_values_in_the_set_grammar(text, unit, low, high, shown):
    plausible = parse_range(text, unit)
    assert (plausible.low, plausible.high, plausible.shown) == \
        (pytest.approx(low), pytest.approx(high), shown)
    assert low in plausible and high in plausible  # both ends included
    assert high * 1.001 + 1e-9 not in plausible


@pytest.mark.parametrize("text, unit, message", [
    ("5mm", "m", "range '5mm' is not LO..HI (e.g. 5mm..0.5m)"),
    ("..5mm", "m", "range '..5mm' is not LO..HI"),
    ("0.5m..5mm", "m", "range '0.5m..5mm' is empty: 0.5 > 0.005 m"),
    ("5mm..1kg", "m", "range '5mm..1kg': its high end: '1kg' has the wrong unit: expected m"),
    ("5mm..1/2", "m", "range '5mm..1/2': its high end: '1/2' is an expression"),
    ("1.5..10", "count", "range '1.5..10': a count's range has whole ends"),
])
def test_a_bad_range_says_what_is_wrong(text, unit, message):
    with pytest.raises(ValueError) as info:
        parse_range(text, unit)
    assert str(info.value).startswith(message)


@pytest.mark.parametrize("raw, unit, text, expected", [
    ("40", "m", "5mm..0.5m", "r = 40 m is outside 5 mm..0.5 m; did you mean 40mm?"),
    ("400", "m", "5mm..0.5m", "r = 400 m is outside 5 mm..0.5 m; did you mean 400mm?"),
    ("4000", "m", "5mm..0.5m", "r = 4000 m is outside 5 mm..0.5 m"),  # 4 m, 40 m: no unit fits
    # Just past an end: meant as written, a bit too big or small; 0.6cm would fit, but
    # a unit slip is 10-1000 times off, so it is not offered.
    ("0.6", "m", "5mm..0.5m", "r = 0.6 m is outside 5 mm..0.5 m"),
    ("0.003", "m", "5mm..0.5m", "r = 0.003 m is outside 5 mm..0.5 m"),
    ("1.1", "m", "-0.5m..0.5m", "r = 1.1 m is outside -0.5 m..0.5 m; did you mean 1.1mm?"),
    ("-0.7", "m", "-0.5m..0.5m", "r = -0.7 m is outside -0.5 m..0.5 m"),
    (40, "kg", "1g..5kg", "r = 40 kg is outside 1 g..5 kg; did you mean 40g?"),
    ("40furlongs", "m", "5mm..0.5m", "r = 40furlongs (8046.74 m) is outside 5 mm..0.5 m"),
    ("1e308", "m", "5mm..0.5m", "r = 1e+308 m is outside 5 mm..0.5 m"),
    ("0", "count", "1..100000", "r = 0 is outside 1..100000"),
])
def test_outside_the_range_names_it_and_hints_a_unit_for_bare_numbers(raw, unit, text,
                                                                       expected):
    from mobile_car.config.units import parse_quantity

    value = parse_quantity(raw, unit, "r")
    assert outside_message("r", raw, value, unit, parse_range(text, unit)) == expected


def test_every_dimension_of_the_car_has_a_range_and_a_kind():
    spec = load_spec(CONFIG)  # would raise if a default were outside its own range
    assert spec.base() and all(d.range is not None for d in spec.base())
    assert all(d.range is None for d in spec.derived())
    assert {d.kind for d in spec.base()} <= set(KINDS.values())
    assert {"length", "mass", "count", "rate"} <= {d.kind for d in spec.base()}
    samples = spec.dimensions["laser_samples"]
    assert (samples.unit, samples.range.low, type(samples.range.high)) == ("count", 1, int)


def _config(tmp_path, *properties: str):
    path = tmp_path / "config.xacro"
    path.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                    + "\n".join(properties) + "\n</robot>\n")
    return path


@pytest.mark.parametrize("prop, message", [
    ('<xacro:property name="a" value="0.1"/> <!-- m 0..1m (>=0); design: size -->',
     "config.xacro:2: property 'a': the range 0..1m already bounds it; drop (>=0)"),
    ('<xacro:property name="a" value="${1}"/> <!-- m 0..1m; derived: size -->',
     "config.xacro:2: property 'a': a derived value has no range: give ranges to what it is "
     "computed from"),
    ('<xacro:property name="a" value="0.1"/> <!-- m 1m..0m; design: size -->',
     "config.xacro:2: property 'a': range '1m..0m' is empty: 1 > 0 m"),
])
def test_a_range_that_cannot_hold_is_refused_where_it_is_written(tmp_path, prop, message):
    path = _config(tmp_path, prop)
    with pytest.raises(InputError) as info:
        load_spec(path)
    assert str(info.value) == f"{tmp_path}/{message}"


@pytest.mark.parametrize("value, hint", [
    ("0.9", ""),  # less than twice the top: too big as written, not cm (see unit hints)
    ("4", "; did you mean 4 cm (written 0.04)?"),
    ("40", "; did you mean 40 mm (written 0.04)?"),
    ("0.001", ""),  # no common unit brings it inside: no guess
])
def test_a_value_outside_its_own_range_is_a_problem_of_the_robot(tmp_path, value, hint):
    """Exit 1 (BuildError), as any slip in the description: every command that loads a
    robot including this config.xacro says the same (tests/config/test_own_ranges_everywhere.py)."""
    path = _config(tmp_path, f'<xacro:property name="a" value="{value}"/> '
                             "<!-- m 5mm..0.5m; design: size -->")
    with pytest.raises(BuildError) as info:
        load_spec(path)
    assert str(info.value) == (f"{tmp_path}/config.xacro:2: property 'a': its value {value} "
                               f"is outside its own range 5 mm..0.5 m{hint}")


def test_a_config_without_ranges_keeps_the_old_bounds(tmp_path):
    spec = load_spec(_config(
        tmp_path, '<xacro:property name="a" value="0.1"/> <!-- m; design: size -->',
        '<xacro:property name="b" value="0"/> <!-- m (>=0); design: size -->'))
    assert parse_set_options(spec, ["a=40", "b=0"]) == {"a": 40.0, "b": 0.0}
    with pytest.raises(UsageError, match="a = -1 m: a length must be > 0"):
        parse_set_options(spec, ["a=-1"])


def test_a_count_is_whole_and_written_as_an_integer():
    spec = load_spec(CONFIG)
    assert parse_set_options(spec, ["laser_samples=720.0"]) == {"laser_samples": 720}
    assert type(parse_set_options(spec, ["laser_samples=720"])["laser_samples"]) is int
    with pytest.raises(UsageError, match=r"laser_samples = 360\.5: a count is a whole number"):
        parse_set_options(spec, ["laser_samples=360.5"])



def test_mcar_config_shows_the_range(run_mcar):
    table = __import__("json").loads(run_mcar("config", "--format", "json").stdout)
    radius = table["dimensions"]["wheel_radius"]
    assert (radius["range"], radius["range_text"], radius["kind"]) == \
        ([0.005, 0.5], "5mm..0.5m", "length")
    assert "range" not in table["derived"]["axle_height"]
    rows = {line.split()[0]: line.split() for line in run_mcar("config").stdout.splitlines()
            if line.strip()}
    assert rows["wheel_radius"][1:5] == ["0.0325", "m", "listing", "5mm..0.5m"]


def test_a_derived_value_that_overflows_is_refused(run_mcar, tmp_path):
    """Finite, in-range inputs can still overflow an expression: the probe refuses "inf"
    before it reaches a URDF (exit 2 for an override, 1 for config.xacro's own numbers)."""
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    config = tmp_path / "demo" / "urdf" / "config.xacro"
    text = config.read_text()
    anchor = "<!-- kg 10g..500kg; estimate: mass of the base -->\n"
    config.write_text(text.replace(anchor, anchor + (
        '  <xacro:property name="a" value="1"/> <!-- m; design: no range, so > 0 -->\n'
        '  <xacro:property name="a_cubed" value="${a * a * a}"/> <!-- m; derived: cube -->\n')))
    ok = run_mcar("config", "--set", "a=1e100", cwd=tmp_path / "demo")
    assert ok.returncode == 0, ok.stderr
    bad = run_mcar("config", "--set", "a=1e200", cwd=tmp_path / "demo")
    assert (bad.returncode, bad.stderr.splitlines()[-1]) == (2, (
        "mcar: error: the dimensions do not fit together: a_cubed = a * a * a comes out as "
        "inf, not a finite number"))
    config.write_text(config.read_text().replace('name="a" value="1"', 'name="a" value="1e200"'))
    own = run_mcar("config", cwd=tmp_path / "demo")
    assert own.returncode == 1
    line = config.read_text().splitlines().index(
        '  <xacro:property name="a_cubed" value="${a * a * a}"/> <!-- m; derived: cube -->') + 1
    assert own.stderr.splitlines()[-1].endswith(
        f"config.xacro:{line}: error: config: a_cubed = a * a * a comes out as inf, not a finite "
        "number"), own.stderr


def test_the_quick_range_check_never_passes_what_the_exact_one_refuses():
    """The loader judges config.xacro's values without pint where it can (its import
    costs every command ~0.25 s): wherever that quick look says "inside", the exact
    check (pint) must agree; near an end it defers to the exact one."""
    from mobile_car.config.spec import COMMENT_RE, _clearly_inside

    spec = load_spec(CONFIG)
    ranged = [d for d in spec.base() if d.range is not None]
    assert {d.unit for d in ranged} >= {"m", "kg", "rad/s"}
    for dimension in ranged:
        match = COMMENT_RE.match(f" {dimension.unit} {dimension.range.text}; design: size ")
        low, high = dimension.range.low, dimension.range.high
        for value in (low, high, (low + high) / 2, low - abs(low) * 1e-6 - 1e-12,
                      high + abs(high) * 1e-6, low + abs(low) * 1e-12):
            if _clearly_inside(repr(value), match):
                assert value in dimension.range, (dimension.name, value)
        assert _clearly_inside(repr((low + high) / 2), match), dimension.name
