"""Numbers as urdfdom reads them, checked against the real check_urdf."""

from __future__ import annotations

import subprocess

import pytest

from mobile_car.check.urdf_model import parse_number, parse_numbers

SCALARS = ["1", " 1", "+1", "-1", "1.", ".5", "00.1", "1E5", "1e-400", "-0",
           "1 ", ".", "-", "1e", "1e+", "1e400", "0x10", "nan", "inf", "1,5", "", "1_0",
           "1e5.5", "+-1", "1d0", "1.5f", "\u0661", "\uff11"]
VECTORS = ["1 2 3", "1 2  3", " 1 2 3", "1 2 3 ", "+.5 -.5 1.", "1 2", "1 2 3 4", "1,2,3",
           "1e400 0 0", "nan 0 0"]


def _check_urdf_reads(check_urdf, tmp_path, joint: str) -> bool:
    path = tmp_path / "n.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/>' + joint + "</robot>",
                    encoding="utf-8")
    return subprocess.run([check_urdf, str(path)], capture_output=True, timeout=30).returncode == 0


@pytest.mark.parametrize("text", SCALARS, ids=repr)
def test_a_number_is_what_check_urdf_reads(text, check_urdf, tmp_path):
    joint = ('<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
             f'<limit effort="{text}" velocity="1"/></joint>')
    assert (parse_number(text) is not None) == _check_urdf_reads(check_urdf, tmp_path, joint)


@pytest.mark.parametrize("text", VECTORS, ids=repr)
def test_three_numbers_are_what_check_urdf_reads(text, check_urdf, tmp_path):
    joint = (f'<joint name="j" type="fixed"><origin xyz="{text}"/><parent link="a"/>'
             '<child link="b"/></joint>')
    assert isinstance(parse_numbers(text, 3), tuple) == \
        _check_urdf_reads(check_urdf, tmp_path, joint)


def test_parsed_values_and_messages():
    assert parse_numbers(" 1  -2.5e1 .5 ", 3) == (1.0, -25.0, 0.5)
    assert parse_numbers("1 2", 3) == "2 numbers where 3 are needed"
    assert parse_numbers("1 x 3", 3) == "'x' is not a number"
    assert parse_numbers("1\t2 3", 3) == ("'1\\t2' has a tab or line break between numbers "
                                          "(urdfdom separates numbers by spaces only)")
    assert parse_number("1e-400") == 0.0
