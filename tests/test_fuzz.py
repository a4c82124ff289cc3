"""Property-based fuzzing: mutated URDF and xacro files never crash `mcar check` or
`mcar build`: they exit 0, 1 or 2 with a message, never a traceback, in bounded time."""

from __future__ import annotations

import random

import pytest
from conftest import REPO
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

SEEDS = sorted([*(REPO / "urdf" / "tutorial").glob("*"),
                REPO / "urdf" / "wheel" / "test_wheel.urdf.xacro",
                REPO / "urdf" / "chassis" / "steps" / "02_brackets.xacro",
                REPO / "tests" / "check_corpus" / "valid" / "every_joint_type.urdf"])
ODD_VALUES = ["", "0", "-1", "nan", "inf", "1e309", "1 2", "1 2 3 4", "${x}", "$(arg y)",
              "${1/0}", "package://nowhere/x.stl", "../../../etc/passwd", "é", "🦾" * 50,
              "a" * 5000, "0x10", "1,5", " 1  2\t3 "]
FUZZ = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])


def mutate(data: bytes, rng: random.Random, steps: int) -> bytes:
    """Drop, duplicate, rename and corrupt elements and attributes; sometimes the bytes."""
    try:
        root = etree.fromstring(data, etree.XMLParser(resolve_entities=False))
    except etree.XMLSyntaxError:
        return data
    for _ in range(steps):
        elements = [e for e in root.iter() if isinstance(e.tag, str)]
        element = rng.choice(elements)
        action = rng.randrange(7)
        parent = element.getparent()
        if action == 0 and parent is not None:
            parent.remove(element)
        elif action == 1 and parent is not None:
            parent.insert(parent.index(element), etree.fromstring(etree.tostring(element)))
        elif action == 2 and element.attrib:
            del element.attrib[rng.choice(sorted(element.attrib))]
        elif action == 3:
            name = rng.choice(sorted(element.attrib) or ["name", "xyz", "size"])
            element.set(name, rng.choice(ODD_VALUES))
        elif action == 4:
            element.tag = rng.choice(["link", "joint", "visul", "geometry", "box", "origin",
                                      "mesh", "inertia", "robot", "xacro_macro"])
        elif action == 5 and parent is not None:  # move it somewhere else
            parent.remove(element)
            rng.choice([e for e in root.iter() if isinstance(e.tag, str)]).append(element)
        else:
            element.text = rng.choice(ODD_VALUES)
    out = etree.tostring(root, xml_declaration=True, encoding="utf-8")
    if rng.random() < 0.15:  # and now and then, raw byte damage
        cut = rng.randrange(len(out))
        out = out[:cut] + bytes([rng.randrange(256)]) + out[cut + rng.randrange(3):]
    return out


def assert_clean(result) -> None:
    assert result.exit_code in (0, 1, 2), result.output
    assert "Traceback" not in result.output
    assert "internal error" not in result.output, result.output


@pytest.mark.parametrize("command", ["check", "build"])
@FUZZ
@given(seed=st.sampled_from(SEEDS), salt=st.integers(0, 2**32), steps=st.integers(1, 6))
def test_mutated_files_never_crash(cli, tmp_path, command, seed, salt, steps):
    rng = random.Random(salt)
    mutated = mutate(seed.read_bytes(), rng, steps)
    # Keep the seed's folder for xacro's relative includes: write next to a copy's name.
    path = tmp_path / f"fuzz{''.join(seed.suffixes)}"
    path.write_bytes(mutated)
    args = ["-q"] if command == "check" else ["-o", str(tmp_path / "out.urdf")]
    result = cli(command, str(path), *args)
    assert_clean(result)
