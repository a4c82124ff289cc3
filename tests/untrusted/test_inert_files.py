"""A file in which xacro can evaluate nothing (a plain URDF) is expanded without the
sandboxed child (mobile_car/expand/xacro_build.py: is_inert); everything else goes through
the child, however it hides its code from a look at its bytes.

Each attack below runs ``os.system`` to touch a marker when xacro evaluates it in an
unconfined process (the control test shows it does, with --no-sandbox); through mcar it
must end in the sandbox's refusal, the marker absent.
"""

from __future__ import annotations

import pytest

from mobile_car.expand.xacro_build import is_inert

_REACH = ("[g['system']('touch PWNED') for g in [c.__init__.__globals__ for x in [()] "
          "for c in x.__class__.__base__.__subclasses__() if c.__name__ == '_wrap_close']]")


def _attacks() -> dict[str, bytes]:
    expression = "${" + _REACH + "}"
    plain = f'<robot name="r"><link name="{expression}"/></robot>\n'
    by_reference = expression.replace("$", "&#36;")
    return {
        # '$' and 'xacro' are not ASCII bytes in UTF-16
        "utf16": ('<?xml version="1.0" encoding="UTF-16"?>\n' + plain).encode("utf-16"),
        # a character reference is '$' once parsed
        "character_reference": f'<robot name="r"><link name="{by_reference}"/></robot>\n'
        .encode(),
        # so is an internal entity
        "entity": ('<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY d "&#36;">]>\n'
                   f'<robot name="r"><link name="{expression.replace("$", "&d;")}"/>'
                   "</robot>\n").encode(),
    }


ATTACKS = _attacks()


@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_code_hidden_from_the_bytes_still_runs_in_the_sandbox(run_mcar, tmp_path, name):
    source = tmp_path / "r.urdf"
    source.write_bytes(ATTACKS[name])
    assert not is_inert(source)
    result = run_mcar("build", source.name, "-o", "out.urdf", cwd=tmp_path)
    assert not (tmp_path / "PWNED").exists()
    assert result.returncode == 1, result.stderr
    assert "the xacro sandbox forbids running programs (os.system)" in result.stderr, \
        result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "out.urdf").exists()


@pytest.mark.parametrize("command", ["check", "tree"])
@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_every_command_expands_a_urdf_that_uses_xacro_in_the_sandbox(run_mcar, tmp_path,
                                                                    name, command):
    """A .urdf that uses xacro is expanded by every command, not only build
    (docs/discovery.md); deciding that it does never runs it unconfined."""
    source = tmp_path / "r.urdf"
    source.write_bytes(ATTACKS[name])
    result = run_mcar(command, source.name, cwd=tmp_path)
    assert not (tmp_path / "PWNED").exists()
    assert result.returncode == 1, result.stderr
    assert "the xacro sandbox forbids running programs (os.system)" in result.stderr
    assert "r.urdf: uses xacro (" in result.stderr


@pytest.mark.parametrize("name", sorted(ATTACKS))
def test_control_the_attacks_run_unconfined(run_mcar, tmp_path, name):
    """With the sandbox off, xacro evaluates each: the attacks are real ones."""
    source = tmp_path / "r.urdf"
    source.write_bytes(ATTACKS[name])
    result = run_mcar("build", source.name, "-o", "out.urdf", "--no-sandbox", cwd=tmp_path)
    assert (tmp_path / "PWNED").exists(), result.stderr


@pytest.mark.parametrize("text, inert", [
    ('<robot name="r"><link name="a"/><!-- a comment --></robot>', True),
    ('<robot name="r"><link name="a">text</link></robot>', True),
    ('<robot name="r"><link name="a"/></robot><!-- $ -->', False),
    ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>',
     False),
    ('<robot name="r"><link name="a"/><?xacro x?></robot>', False),
    ('<robot name="r"><link name="a"/><![CDATA[ $ ]]></robot>', False),
    ('<robot name="r"><link name="a"', False),  # broken: the child reports it
    # EBCDIC hides '$' and 'xacro' from the bytes; expat cannot read it: the child says so
    (('<?xml version="1.0" encoding="cp037"?>\n<robot name="r"><link name="${1}"/></robot>'
      ).encode("cp037"), False),
])
def test_what_counts_as_inert(tmp_path, text, inert):
    path = tmp_path / "r.urdf"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    assert is_inert(path) is inert


def test_an_inert_file_builds_as_the_child_builds_it(run_mcar, tmp_path, repo):
    """The bundled skeleton (no xacro in it) comes out byte for byte as the same file
    made to go through the child (by an xacro namespace, which xacro drops) does."""
    skeleton = repo / "urdf" / "tutorial" / "01_skeleton.urdf"
    text = skeleton.read_text()
    (tmp_path / "fast").mkdir()
    (tmp_path / "child").mkdir()
    (tmp_path / "fast" / "r.urdf").write_text(text)
    (tmp_path / "child" / "r.urdf").write_text(text.replace(
        '<robot name=', '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name=', 1))
    assert is_inert(tmp_path / "fast" / "r.urdf")
    assert not is_inert(tmp_path / "child" / "r.urdf")
    fast = run_mcar("build", "fast/r.urdf", cwd=tmp_path)
    child = run_mcar("build", "child/r.urdf", cwd=tmp_path)
    assert fast.returncode == child.returncode == 0, fast.stderr + child.stderr
    assert fast.stdout == child.stdout and "<link" in fast.stdout
