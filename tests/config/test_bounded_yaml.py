"""The config-file YAML reader: keys given twice are an error, and numbers stay text so
that a file's values go through the grammar of --set."""

from __future__ import annotations

import pytest
import yaml

from mobile_car.config.bounded_yaml import DuplicateKey, compose_and_load


@pytest.mark.parametrize("text, line, message", [
    ("wheel_radius: 0.04\ntrack_width: 0.17\nwheel_radius: 0.05\n", 3,
     "duplicate key 'wheel_radius' (first given on line 1)"),
    ("dimensions:\n  a: {value: 1}\n  a: {value: 2}\n", 3,
     "duplicate key 'a' (first given on line 2)"),
    ('{"a": 1, "a": 2}', 1, "duplicate key 'a' (first given on line 1)"),
])
def test_a_key_given_twice_is_refused_at_its_second_line(text, line, message):
    with pytest.raises(DuplicateKey) as info:
        compose_and_load(text)
    assert (info.value.problem, info.value.problem_mark.line + 1) == (message, line)


def test_merge_keys_may_still_override():
    _node, data = compose_and_load("base: &b {a: 1}\nmine:\n  <<: *b\n  a: 2\n")
    assert data["mine"] == {"a": 2}


def test_numbers_stay_text_when_asked():
    text = "a: 0x10\nb: 1_000\nc: .inf\nd: 0.04\ne: 40\nf: true\ng: ~\nh: 45mm\n"
    _node, data = compose_and_load(text, numbers_as_text=True)
    assert data == {"a": "0x10", "b": "1_000", "c": ".inf", "d": "0.04", "e": "40",
                    "f": True, "g": None, "h": "45mm"}
    _node, plain = compose_and_load(text)
    assert (plain["a"], plain["b"], plain["d"]) == (16, 1000, 0.04)  # YAML 1.1's own reading


def test_the_default_loader_keeps_its_number_resolvers():
    compose_and_load("a: 1", numbers_as_text=True)
    assert compose_and_load("a: 1")[1] == {"a": 1}
    assert isinstance(DuplicateKey(None, None, "x", None), yaml.YAMLError)
