"""The second reading behind a nesting mistake's line (mobile_car/expand/unclosed.py): to
say where a tag left open opened, mcar parses the failing file again. That reading must
read only the file xacro was parsing, and must not expand what xacro's did not.
"""

from __future__ import annotations

import time

SECRET_TAG = "planted_secret_7f3a"
# The same shape as the planted file: opened on line 2, noticed on line 3.
STDIN_TEXT = '<robot name="r">\n <link name="a">\n</robot>\n'
PLANTED = f'<robot name="r">\n <{SECRET_TAG}>\n</robot>\n'


def test_a_robot_from_stdin_never_rereads_a_file_called_stdin(run_mcar, tmp_path):
    # Errors in text read from a pipe are labelled "<stdin>": a file of that name in the
    # working folder is the attacker's, and must not be what the message is made of.
    (tmp_path / "<stdin>").write_text(PLANTED)
    result = run_mcar("build", "-", "-o", "out.urdf", cwd=tmp_path, input=STDIN_TEXT)
    assert result.returncode == 1
    assert result.stderr == "<stdin>:3: error: XML parse error: mismatched tag (column 3)\n"
    assert SECRET_TAG not in result.stderr


def test_control_the_second_reading_quotes_the_file_it_reads(run_mcar, tmp_path):
    # The re-reading quotes the tag of the file it is pointed at: pointed at the planted
    # file by the "<stdin>" label (as it was before the guard), it would say this.
    (tmp_path / "planted.xacro").write_text(PLANTED)
    result = run_mcar("build", "planted.xacro", "-o", "out.urdf", cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == (
        f"planted.xacro:2: error: XML parse error: <{SECRET_TAG}> opened here is never "
        "closed (the parser noticed at line 3: mismatched tag)")


def test_entities_are_not_expanded_by_the_second_reading(run_mcar, tmp_path):
    # A "billion laughs" name on the element left open: the reading that finds its line
    # leaves entities unexpanded, so the message comes at once and names the line.
    levels = ['<!ENTITY e0 "' + "a" * 64 + '">']
    levels += [f'<!ENTITY e{i} "' + f"&e{i - 1};" * 16 + '">' for i in range(1, 5)]
    text = ('<?xml version="1.0"?>\n<!DOCTYPE robot [\n' + "\n".join(levels) + "\n]>\n"
            '<robot name="r">\n <link name="&e4;">\n</robot>\n')
    (tmp_path / "laughs.urdf").write_text(text)
    started = time.monotonic()
    result = run_mcar("build", "laughs.urdf", "-o", "out.urdf", cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == (
        "laughs.urdf:10: error: XML parse error: <link> opened here is never closed (the "
        "parser noticed at line 11: mismatched tag)")
    assert time.monotonic() - started < 30
