"""mcar specs prints what a description names (its links in the keys ``loads.<link>``,
labels and sources) in three formats, one of them Markdown meant to be pasted into a pull
request, where a reviewer trusts what renders. A link named by an attacker holds a line
break with a forged message after it, a bidi override, a cell separator, an HTML tag and
a Markdown link: the text table and stderr show them escaped, the Markdown renders them as
text in their one cell (no tag, no link, no extra cell), JSON keeps the name exact.
Control: the same row with the name left as it is renders the tag, the link and extra
cells."""

from __future__ import annotations

import json
from xml.sax.saxutils import quoteattr

import pytest
from markdown_it import MarkdownIt
from specs import robots
from untrusted.test_names import raw_controls

FORGED = "mcar: error: forged"
NAME = (f"castor\n{FORGED} | <img src=x onerror=alert(1)> [click](https://evil.example) "
        "\u202etxt.exe")


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    """The box on wheels, its castor link renamed NAME (XML character references for
    what an attribute cannot hold as is)."""
    attribute = quoteattr(NAME).replace("\n", "&#10;")
    text = robots.box_on_wheels().replace('"castor_link"', attribute)
    path = tmp_path_factory.mktemp("hostile_specs") / "hostile.urdf"
    path.write_text(text)
    return path


def _render(markdown_text: str) -> tuple[str, list]:
    parser = MarkdownIt("commonmark").enable(["table", "strikethrough"])
    return parser.render(markdown_text), parser.parse(markdown_text)


def _row_of(tokens, first_cell: str) -> list[str]:
    """The inline contents of the table row whose first cell starts with ``first_cell``."""
    rows, row = [], None
    for token in tokens:
        if token.type == "tr_open":
            row = []
        elif token.type == "inline" and row is not None:
            row.append(token.content)
        elif token.type == "tr_close":
            rows.append(row)
            row = None
    return next(r for r in rows if r[0].startswith(first_cell))


def test_json_keeps_the_name_exact(run_mcar, hostile):
    result = run_mcar("specs", hostile, "--format", "json", "--no-proof")
    assert result.returncode == 0, result.stderr
    assert raw_controls(result.stdout) == []  # \u202e written as an escape
    figures = json.loads(result.stdout)["files"][0]["figures"]
    assert figures[f"loads.{NAME}"]["value"] > 0  # the name reached the output whole


def test_text_shows_the_name_escaped_on_its_own_line(run_mcar, hostile):
    result = run_mcar("specs", hostile, "--no-proof")
    assert result.returncode == 0, result.stderr
    both = result.stdout + result.stderr
    assert raw_controls(both) == []
    assert not any(line.lstrip().startswith(FORGED) for line in both.splitlines())
    (row,) = [line for line in result.stdout.splitlines() if "load on castor" in line]
    assert f"castor\\n{FORGED} | <img" in row and "\\u202etxt.exe" in row


def test_markdown_renders_the_name_as_text_in_one_cell(run_mcar, hostile):
    result = run_mcar("specs", hostile, "--format", "markdown", "--no-proof")
    assert result.returncode == 0, result.stderr
    assert raw_controls(result.stdout) == []
    html, tokens = _render(result.stdout)
    assert "<img" not in html and "<a " not in html
    assert not any(line.startswith(FORGED) for line in result.stdout.splitlines())
    row = _row_of(tokens, "load on castor")
    assert len(row) == 5  # figure, key, value, source, assumes
    rendered = MarkdownIt("commonmark").renderInline(row[0])
    assert rendered == ("load on castor\\n" + FORGED + " | &lt;img src=x onerror=alert(1)&gt; "
                        "[click](https://evil.example) \\u202etxt.exe")


def test_control_the_name_left_as_it_is_would_inject():
    """The row the report writes, with the name as the description gives it: the name
    splits its cell (what follows lands in the key's column and the value in the
    source's), and the tag and the link render."""
    raw = f"| load on {' '.join(NAME.split())} | loads.castor | 1 N | statics |  |"
    html, tokens = _render("| figure | key | value | source | assumes |\n"
                           "|---|---|---|---|---|\n" + raw + "\n")
    row = _row_of(tokens, "load on castor")
    assert row[0] == f"load on castor {FORGED}" and row[2] == "loads.castor"
    assert "<img src=x onerror=alert(1)>" in html
    assert '<a href="https://evil.example">click</a>' in html
