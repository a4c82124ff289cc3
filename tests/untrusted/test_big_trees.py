"""Scale: a deep tree's text is written as it is made, never held whole.

Each generation of a chain is indented four more spaces, by `mcar tree` as by check_urdf,
so the text grows with the square of the depth: a 10,000-link chain prints 200 MB, nearly
all of it spaces. `mcar tree` joined it into one string (and encoded a copy) and peaked
at 1.26 GB; now both commands write it line by line, in chunks, and stay near what the
robot itself takes (~90-120 MB here). Each run below is the installed `mcar` as its own
process, its peak memory read from its rusage, its stdout read and counted as it comes
rather than kept. The control: the text is larger than the bound, so nothing that holds
it could pass.

A write that fails half-way (the reader gone, a file size limit) ends the run as a
failed first write does: quietly, or with one line and exit 2.
"""

from __future__ import annotations

import subprocess
import sys
import tracemalloc
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import MCAR, clean_environ

DEPTH = 10_000  # links
PEAK_LIMIT_MB = 200
JOINT = ('  <joint name="j{i:05d}" type="revolute"><parent link="l{p}"/><child link="l{i}"/>'
         '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>'
         '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n')
SUMMARY = "xyz 0 0 0.1, rpy 0 0 0, axis 0 0 1, limits -1..1"


def _chain(path: Path, depth: int) -> Path:
    path.write_text('<robot name="chain">\n'
                    + "".join(f'  <link name="l{i}"/>\n' for i in range(depth))
                    + "".join(JOINT.format(i=i, p=i - 1) for i in range(1, depth))
                    + "</robot>\n")
    return path


@pytest.fixture(scope="module")
def chain(tmp_path_factory) -> Path:
    """A 10,000-link chain of revolute joints (2 MB of URDF, 200 MB of tree text)."""
    return _chain(tmp_path_factory.mktemp("chain") / "chain.urdf", DEPTH)


@pytest.fixture(scope="module")
def short_chain(tmp_path_factory) -> Path:
    """2,000 links: 8 MB of tree text, far more than a pipe or the file limit below hold."""
    return _chain(tmp_path_factory.mktemp("short") / "chain.urdf", 2000)


@dataclass
class Streamed:
    exit_code: int
    size: int          # bytes on stdout
    lines: int
    first_line: bytes
    last_line: bytes
    stderr: str
    peak_mb: float     # the child's peak resident memory


# The child's peak is read by a small process that starts it, not by the test worker:
# Linux carries the resident size of the process that forked a child over its exec into
# the child's ru_maxrss, and a worker that has run many tests is itself hundreds of MB.
_MEASURE = """
import os, subprocess, sys
child = subprocess.Popen(sys.argv[2:])
_pid, status, usage = os.wait4(child.pid, 0)
with open(sys.argv[1], "w") as out:
    out.write(f"{os.waitstatus_to_exitcode(status)} {usage.ru_maxrss}")
"""


def _stream(args, tmp_path: Path) -> Streamed:
    """Run `mcar ARGS`, reading its stdout as it comes: counted, its first and last lines
    kept, nothing else (stderr, which check fills with thousands of warnings, goes to a
    file so that neither pipe can block the other)."""
    measured = tmp_path / "measured"
    with open(tmp_path / "stderr", "w+b") as err:
        process = subprocess.Popen([sys.executable, "-c", _MEASURE, str(measured), str(MCAR),
                                    *map(str, args)], stdout=subprocess.PIPE, stderr=err,
                                   stdin=subprocess.DEVNULL, env=clean_environ(), cwd=tmp_path)
        size = lines = 0
        head = tail = b""
        while chunk := process.stdout.read(1 << 20):
            size += len(chunk)
            lines += chunk.count(b"\n")
            head = head or chunk
            # The last 256 KB: longer than the longest line (40 KB).
            tail = chunk if len(chunk) >= 1 << 18 else (tail + chunk)[-(1 << 18):]
        process.stdout.close()
        assert process.wait(timeout=60) == 0, err.read().decode()
        err.seek(0)
        stderr = err.read().decode()
    exit_code, peak_kib = map(int, measured.read_text().split())
    return Streamed(exit_code, size, lines, head.split(b"\n", 1)[0],
                    tail.rstrip(b"\n").rsplit(b"\n", 1)[-1], stderr,
                    peak_kib / 1024)  # ru_maxrss is in KiB on Linux


def _tree_line(i: int) -> bytes:
    """`mcar tree`'s line for link ``i`` of the chain (i >= 1), without its indentation
    of 4 * (i - 1) spaces."""
    return f"└── l{i}  (j{i:05d}: revolute, {SUMMARY})\n".encode()


def test_tree_of_a_deep_chain_is_streamed(chain, tmp_path):
    done = _stream(["tree", chain], tmp_path)
    assert (done.exit_code, done.stderr) == (0, "")
    assert done.lines == DEPTH
    assert done.first_line == b"l0"
    assert done.last_line + b"\n" == b" " * 4 * (DEPTH - 2) + _tree_line(DEPTH - 1)
    assert done.size == len(b"l0\n") + sum(4 * (i - 1) + len(_tree_line(i))
                                           for i in range(1, DEPTH))
    assert done.size > PEAK_LIMIT_MB * 1_000_000  # the control: no room to hold the text
    assert done.peak_mb < PEAK_LIMIT_MB, f"mcar tree peaked at {done.peak_mb:.0f} MB"


def test_check_of_a_deep_chain_is_streamed_and_a_later_error_still_fails(chain, tmp_path):
    """check prints each sound input's tree as check_urdf does, then its problems; an
    input after it that does not parse prints no tree (as check_urdf prints nothing of
    one) and still makes the run fail, its one line and the summary last on stderr."""
    broken = tmp_path / "broken.urdf"
    broken.write_text('<robot name="b">\n  <link name="a">\n</robot>\n')
    done = _stream(["check", chain, broken.name], tmp_path)
    assert done.exit_code == 1
    assert done.first_line == f"==> {chain} <==".encode()
    assert done.lines == 1 + 3 + (DEPTH - 1)
    assert done.last_line == b" " * 4 * (DEPTH - 1) + f"child(1):  l{DEPTH - 1}".encode()
    assert done.size > PEAK_LIMIT_MB * 1_000_000
    assert done.peak_mb < PEAK_LIMIT_MB, f"mcar check peaked at {done.peak_mb:.0f} MB"
    errors = done.stderr.splitlines()
    assert len(errors) == (DEPTH - 1) + 2  # a W206 per moving link, broken's line, summary
    assert errors[-2:] == [
        "broken.urdf:3: error: not well-formed XML: Opening and ending tag mismatch: link "
        "line 2 and robot [E100]",
        f"mcar check: 1 error, {DEPTH - 1} warnings in 2 files"]


@pytest.mark.parametrize("command", ["tree", "check"])
def test_reader_gone_mid_tree_ends_quietly(short_chain, tmp_path, command):
    """`mcar tree big.urdf | head`: the reader leaves after the first lines; the rest is
    not written, and the run ends at once with exit 0 and not a word."""
    process = subprocess.Popen([str(MCAR), command, str(short_chain)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               stdin=subprocess.DEVNULL, env=clean_environ(), cwd=tmp_path)
    first = process.stdout.read(4096)
    process.stdout.close()  # the reader goes, with ~8 MB still to come
    stderr = process.stderr.read().decode()
    assert process.wait(timeout=60) == 0
    assert first.startswith(b"l0\n" if command == "tree" else b"robot name is: chain\n")
    # check's warnings come after the tree, which was never finished: none is said.
    assert stderr == ""


@pytest.mark.parametrize("command", ["tree", "check"])
def test_write_failing_mid_tree_is_one_line(short_chain, tmp_path, command):
    """stdout a file that may not grow past 1 MB (ulimit -f; SIGXFSZ ignored, so the
    write fails with EFBIG rather than killing mcar): the first megabyte is written,
    then one line, exit 2, no traceback."""
    out = tmp_path / "out.txt"
    done = subprocess.run(["sh", "-c", 'ulimit -f 2048; trap "" XFSZ; exec "$@" > "$OUT"',
                           "sh", str(MCAR), command, str(short_chain)],
                          capture_output=True, env={**clean_environ(), "OUT": str(out)},
                          cwd=tmp_path, timeout=60)
    assert done.stderr.decode() == "mcar: error: cannot write <stdout>: File too large\n"
    assert done.returncode == 2
    assert out.stat().st_size == 2048 * 512  # dash's ulimit -f counts 512-byte blocks
    assert out.read_bytes().startswith(b"l0\n" if command == "tree"
                                       else b"robot name is: chain\n")


def _comb(depth: int):
    """A spine of ``depth`` links with a leaf on each: the spine's joint sorts first, so
    while the walk goes down, every level has a sibling waiting to be drawn."""
    from mobile_car.check.tree import build_tree
    from mobile_car.check.urdf_model import parse_xml
    from mobile_car.check.urdf_reader import read_robot

    text = ["<robot name='comb'>"]
    text += [f"<link name='s{i}'/><link name='f{i}'/>" for i in range(depth)]
    text += [f"<joint name='a{i:05d}' type='fixed'><parent link='s{i - 1}'/>"
             f"<child link='s{i}'/></joint>" for i in range(1, depth)]
    text += [f"<joint name='b{i:05d}' type='fixed'><parent link='s{i}'/>"
             f"<child link='f{i}'/></joint>" for i in range(depth)]
    text.append("</robot>")
    tree = build_tree(read_robot(parse_xml("".join(text).encode())))
    assert tree.is_sound
    return tree


@pytest.mark.parametrize("view", ["rich_lines", "check_urdf_lines"])
def test_waiting_siblings_hold_no_copy_of_the_drawing(view):
    """In a comb, a sibling waits at every level; a drawn prefix kept per waiting sibling
    (what `mcar tree` kept) adds up to the square of the depth. The walk holds only one
    prefix and its stack: its peak is a small part of the text it makes."""
    from mobile_car.check import tree as views

    depth = 1500
    comb = _comb(depth)
    lines = views.rich_lines(comb) if view == "rich_lines" else \
        views.check_urdf_lines("comb", comb)
    tracemalloc.start()
    try:
        size = count = 0
        for line in lines:
            size += len(line)
            count += 1
        _current, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert count == 2 * depth + (0 if view == "rich_lines" else 2)
    # The control: the text is ~9 MB, the prefixes once held per waiting sibling ~4.5 MB.
    assert size > 8_000_000
    assert peak < 1_000_000, f"{view} held {peak / 1e6:.1f} MB"
