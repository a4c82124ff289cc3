"""Scale: `mcar build FOLDER` does work linear in its files.

The output-clash check resolved every input for every output: 1,000 one-link robots
made a million realpath() calls (~45 s, against 0.4 s for `mcar check` of the folder).
Times belong to the benchmark (bench/run.py, section "folder"); here the work itself is
counted, in-process and deterministically: every realpath() (Path.resolve() included)
the build makes in mcar's own process, for folders of N, 2N and 4N robots.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

N = 8


def _folder(tmp_path: Path, count: int) -> Path:
    folder = tmp_path / f"robots_{count}"
    folder.mkdir()
    for i in range(count):
        (folder / f"r{i:03d}.urdf").write_text(f'<robot name="r{i}">\n  <link name="a"/>\n'
                                               "</robot>\n")
    return folder


@pytest.fixture
def realpath_calls(monkeypatch):
    """A counter of os.path.realpath calls in this process (the xacro children's are
    their own: they run nothing of the clash check)."""
    real = os.path.realpath
    count = [0]

    def counting(*args, **kwargs):
        count[0] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(os.path, "realpath", counting)
    return count


def test_building_a_folder_resolves_paths_a_linear_number_of_times(cli, tmp_path,
                                                                   realpath_calls):
    calls = {}
    for count in (N, 2 * N, 4 * N):
        folder = _folder(tmp_path, count)
        realpath_calls[0] = 0
        result = cli("build", folder, "-o", f"{tmp_path / 'out' / folder.name}/", "-q")
        calls[count] = realpath_calls[0]
        assert result.exit_code == 0, result.output
        assert len(list((tmp_path / "out" / folder.name).glob("*.urdf"))) == count
    assert calls[N] > 0  # the counter sees the build's calls
    # Linear: doubling the files about doubles the extra work. Checking each output
    # against every input added N*N calls: 8 -> 16 -> 32 robots made 138 -> 402 -> 1314
    # calls, an increment of 912 against twice 264 (3.5 times). Now 51 -> 98 -> 194: six
    # per robot, and a couple more for the longer names of the larger folder, so the
    # bound leaves a quarter of slack, far below what quadratic work gives.
    assert calls[4 * N] - calls[2 * N] <= 2.5 * (calls[2 * N] - calls[N]), calls


def test_an_output_over_an_input_is_still_refused(cli, tmp_path, monkeypatch):
    """The linear check refuses what the quadratic one did: a folder built into itself
    would write each URDF over itself. Nothing is written."""
    monkeypatch.chdir(tmp_path)
    folder = _folder(tmp_path, 3)
    before = {path: path.read_bytes() for path in folder.iterdir()}
    result = cli("build", folder.name, "-o", f"{folder.name}/")
    assert result.exit_code == 2
    assert (f"{folder.name}/r000.urdf: error: would overwrite {folder.name}/r000.urdf, a "
            "file this run reads; write the output somewhere else") in result.output
    assert {path: path.read_bytes() for path in folder.iterdir()} == before
