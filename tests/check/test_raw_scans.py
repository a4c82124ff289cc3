"""The raw-text scans' quick forms find what their plain forms find (document.py)."""

from __future__ import annotations

import random
import re

from mobile_car.check import document
from mobile_car.check.context import Reporter

# The search as it was written first, without possessive runs: the reference.
_PLAIN_LINE_BREAK = re.compile(rb"\n[^\"'\n<>]*[\"'](?=[\s/>])")
_PIECES = [b"\n", b" ", b"  ", b'"', b"'", b"<", b">", b"/", b"=", b"\t", b"\r", b"a",
           b"1 2", b'xyz="', b'"/>', b"<!-- ", b" -->"]


def test_the_line_break_search_finds_what_the_plain_pattern_finds():
    rng = random.Random(41)
    found = 0
    for _ in range(20000):
        text = b"".join(rng.choice(_PIECES) for _ in range(rng.randint(1, 14)))
        plain = _PLAIN_LINE_BREAK.search(text)
        quick = document._LINE_BREAK_IN_VALUE_RE.search(text)
        assert (quick and quick.span()) == (plain and plain.span()), text
        found += plain is not None
    assert 1000 < found < 19000  # both outcomes were tried, many times


def test_a_value_over_two_lines_is_found_and_an_indented_file_is_not():
    assert document._LINE_BREAK_IN_VALUE_RE.search(b'<origin xyz="0 0\n    1"/>')
    assert document._LINE_BREAK_IN_VALUE_RE.search(b"<origin xyz='0\n1' />")
    indented = b'<robot name="r">\n  <link name="a">\n    <visual/>\n  </link>\n</robot>\n'
    assert not document._LINE_BREAK_IN_VALUE_RE.search(indented)


def _doctype_lines(data: bytes) -> list:
    report = Reporter("r.urdf")
    document.check_doctype(data, report)
    return [(d.rule, d.line) for d in report.diagnostics]


def test_a_doctype_subset_is_found_and_a_file_without_a_bang_is_passed():
    assert _doctype_lines(b'<?xml version="1.0"?>\n<!DOCTYPE robot [\n<!ENTITY a "1">\n]>\n'
                          b'<robot name="r"/>') == [("E104", 2)]
    assert _doctype_lines(b'<!DOCTYPE robot>\n<robot name="r"/>') == []
    assert _doctype_lines(b'<robot name="r"><link name="DOCTYPE ["/></robot>') == []
