"""The sandboxed xacro child's way back: whatever it writes into the result pipe, the
parent runs none of it, reads no more than its bound, and ends in one located error.

Each attack is a xacro whose expression reaches the real builtins (through a class's
``__init__.__globals__``, which xacro's ``__`` guard does not see), runs a Python program
with ``exec``, finds the result pipe among its open descriptors and writes its own bytes
into it, then leaves at once so that nothing genuine follows. Where code could run, it
would ``touch`` a marker file: the marker must never appear.
"""

from __future__ import annotations

import json
import os
import pickle
import struct
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mobile_car.expand import wire

# xacro ends ``${`` at the first ``}``: the program comes hex-encoded, run with os's globals.
_REACH_OS = ("[c.__init__.__globals__ for x in [()] for c in x.__class__.__base__"
             ".__subclasses__() if c.__name__ == '_wrap_close']")
_ATTACK = ("<?xml version=\"1.0\"?>\n"
           "<robot name=\"attack\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
           "  <link name=\"base_link\"/>\n"
           "  <link name=\"${[B['exec'](B['bytes'].fromhex('PROGRAM').decode(), g) "
           f"for g in {_REACH_OS} for B in [g['__builtins__']]][0]}}\"/>\n"
           "</robot>\n")

# Runs in the child: finds the pipe(s) it may write, writes DATA (or floods), and leaves.
_PROGRAM = """
import os, stat
def pipes():
    for fd in range(3, 4096):
        try:
            if stat.S_ISFIFO(os.fstat(fd).st_mode):
                yield fd
        except OSError:
            pass
def send(data):
    for fd in pipes():
        view = memoryview(data)
        try:
            while view:
                view = view[os.write(fd, view):]
        except OSError:
            pass
{body}
os._exit(0)
"""


class _Rce:
    """Unpickling this runs a shell command: what the old channel did with pickle.loads."""

    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"touch {self.marker}",))


def _frame(header: dict | bytes, body: bytes = b"", body_size: int | None = None) -> bytes:
    raw = header if isinstance(header, bytes) else json.dumps(header).encode()
    size = len(body) if body_size is None else body_size
    return wire.MAGIC + struct.pack(">IQ", len(raw), size) + raw + body


def _send(data: bytes) -> str:
    return f"send(bytes.fromhex({data.hex()!r}))"


def _attack_file(tmp_path: Path, body: str) -> Path:
    program = _PROGRAM.format(body=body).encode().hex()
    path = tmp_path / "attack.urdf.xacro"
    path.write_text(_ATTACK.replace("PROGRAM", program))
    return path


# Well-formed origins of the forged URDF below (one file, the stdin label, which a
# build from a file never reads: each case breaks one field).
_ORIGINS = {"files": ["<stdin>"], "names": ["m"], "calls": [], "sites": [0, 1, -1],
            "of": [0, 0]}


def _cases(marker: Path) -> dict[str, tuple[str, str]]:
    """name -> (the child's program body, the reason the parent gives)."""
    ok = {"ok": True, "deps": [], "warnings": [], "known_args": [], "origins": None}
    urdf = b'<robot name="forged"><link name="a"/></robot>'
    return {
        "pickle_that_runs_a_command": (_send(pickle.dumps(_Rce(marker))),
                                       "it does not start as a result does"),
        "garbage_before_a_result": (_send(b"\x80\x04junk" + _frame(ok, urdf)),
                                    "it does not start as a result does"),
        "error_of_a_chosen_class": (
            _send(_frame({"ok": False, "error": {"kind": "posix.system", "message": "x"}})),
            "its error is of no known kind ('posix.system')"),
        "error_with_extra_fields": (
            _send(_frame({"ok": False, "error": {"kind": "BuildError", "message": "m",
                                                 "file": None, "line": None, "details": [],
                                                 "__reduce__": "os.system"}})),
            "its error has the wrong fields (__reduce__)"),
        "result_naming_a_secret_as_read": (
            _send(_frame({**ok, "deps": ["/etc/passwd"]}, urdf)),
            "read /etc/passwd, outside the folders a xacro may read (its own folder, the "
            "packages it finds and the files given as arguments)"),
        "header_nested_past_the_stack": (_send(_frame(b"[" * 200_000 + b"]" * 200_000)),
                                         "its header is not JSON (RecursionError)"),
        "number_that_is_not_one": (_send(_frame(b'{"ok": NaN}')),
                                   "its header is not JSON (ValueError)"),
        "key_given_twice": (_send(_frame(b'{"ok": true, "ok": false}')),
                            "its header is not JSON (ValueError)"),
        "urdf_not_utf8": (_send(_frame(ok, b"\xff\xfe<robot/>")), "its URDF is not UTF-8"),
        # Where each element was written (expand/origins.py): only files it read, and
        # indices that point at what was sent, outer calls before inner ones.
        "origins_naming_a_secret": (
            _send(_frame({**ok, "origins": {**_ORIGINS, "files": ["/etc/passwd"]}}, urdf)),
            "its origins name a file the build did not read"),
        # Compared as files, not spellings: a name that resolves elsewhere is refused too.
        "origins_naming_a_secret_by_another_spelling": (
            _send(_frame({**ok, "origins": {**_ORIGINS, "files": [
                "./" + "../" * 40 + "etc//passwd"]}}, urdf)),
            "its origins name a file the build did not read"),
        "origins_with_a_call_loop": (
            _send(_frame({**ok, "origins": {**_ORIGINS, "calls": [0, 1, 0, 0]}}, urdf)),
            "its origins hold a call out of range"),
        "origins_past_their_sites": (
            _send(_frame({**ok, "origins": {**_ORIGINS, "of": [0, 7]}}, urdf)),
            "its origins point at no site"),
        "origins_not_integers": (
            _send(_frame({**ok, "origins": {**_ORIGINS, "sites": [0, 1.5, -1]}}, urdf)),
            "its origins are not lists of integers"),
        "shorter_than_it_says": (_send(_frame(ok, urdf, body_size=len(urdf) + 10)),
                                 "it ended before the length it declared"),
        "ten_gigabytes_declared": (_send(_frame(ok, b"", body_size=10 << 30)),
                                   "it declares 10240.0 MB, more than MCAR_XACRO_OUTPUT_MB=256"),
    }


CASE_NAMES = list(_cases(Path("m")))


def _expected_line(reason: str) -> str:
    if reason.startswith("read /etc/passwd"):
        return f"attack.urdf.xacro: error: {reason}"
    return ("attack.urdf.xacro: error: the sandboxed xacro sent back something that is not "
            f"a result ({reason}); nothing of it was used")


@pytest.mark.parametrize("command", ["build", "check"])
@pytest.mark.parametrize("case", CASE_NAMES)
def test_nothing_the_child_writes_is_run_or_used(run_mcar, tmp_path, case, command):
    marker = tmp_path / "PWNED"
    body, reason = _cases(marker)[case]
    attack = _attack_file(tmp_path, body)
    before = attack.read_bytes()
    extra = ["-o", "out.urdf"] if command == "build" else []
    result = run_mcar(command, attack.name, *extra, cwd=tmp_path, timeout=60)
    assert result.returncode == 1, result.stderr
    rule = " [E140]" if command == "check" else ""  # check names its rule
    assert result.stderr.splitlines()[0] == _expected_line(reason) + rule, result.stderr
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    assert not marker.exists()
    assert attack.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["attack.urdf.xacro"]  # no output


@pytest.mark.parametrize("command", ["tree", "render", "ci"])
def test_the_pickle_attack_fails_in_every_command(run_mcar, tmp_path, command):
    marker = tmp_path / "PWNED"
    attack = _attack_file(tmp_path, _cases(marker)["pickle_that_runs_a_command"][0])
    args = [attack.name] if command != "ci" else []
    if command == "render":
        args += ["-o", "out.png"]
    if command == "ci":
        (tmp_path / "package.xml").write_text("<package><name>attack</name></package>\n")
    result = run_mcar(command, *args, cwd=tmp_path, timeout=120)
    assert result.returncode == 1, result.stdout + result.stderr
    assert "sent back something that is not a result" in result.stdout + result.stderr
    assert "Traceback" not in result.stderr
    assert not marker.exists()


def test_the_pickle_is_a_real_attack(tmp_path):
    """The control: the bytes the attack writes do run a command when unpickled, as the
    old channel did; so the tests above can fail."""
    marker = tmp_path / "PWNED"
    payload = pickle.dumps(_Rce(marker))
    subprocess.run([sys.executable, "-c", "import pickle,sys; "
                    "pickle.loads(sys.stdin.buffer.read())"], input=payload, check=True)
    assert marker.exists()


def _peak_kb(command: list[str], cwd: Path, env: dict) -> tuple[subprocess.CompletedProcess,
                                                               int, float]:
    """Run ``command``; its result, the peak memory (KB) of it and its children, seconds."""
    probe = ("import resource, subprocess, sys, json\n"
             "r = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
             "print(json.dumps([r.returncode, r.stderr, "
             "resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss]))\n")
    start = time.monotonic()
    out = subprocess.run([sys.executable, "-c", probe, *command], cwd=cwd, env=env,
                         capture_output=True, text=True, timeout=120, check=True)
    code, stderr, peak = json.loads(out.stdout)
    return subprocess.CompletedProcess(command, code, "", stderr), peak, \
        time.monotonic() - start


def test_a_flood_is_cut_off_within_its_bound(mcar_bin, tmp_path):
    """A child that declares 8 MB and writes without end is stopped just past 8 MB: the
    parent's memory stays near what a normal build takes, and the run ends at once."""
    env = {**os.environ, "MCAR_XACRO_OUTPUT_MB": "8"}
    ok = {"ok": True, "deps": [], "warnings": [], "known_args": [], "origins": None}
    prefix = _frame(ok, b"", body_size=8 << 20)
    flood = (f"{_send(prefix)}\nchunk = b'x' * (1 << 20)\n"
             "for fd in pipes():\n"
             "    try:\n"
             "        while True:\n"
             "            os.write(fd, chunk)\n"
             "    except OSError:\n"
             "        pass\n")
    attack = _attack_file(tmp_path, flood)
    plain = tmp_path / "plain.urdf.xacro"
    plain.write_text('<robot name="plain"><link name="a"/></robot>\n')
    _, normal_kb, _ = _peak_kb([str(mcar_bin), "build", plain.name, "-o", "p.urdf"],
                               tmp_path, env)
    result, flood_kb, seconds = _peak_kb([str(mcar_bin), "build", attack.name, "-o", "o.urdf"],
                                         tmp_path, env)
    assert result.returncode == 1, result.stderr
    assert result.stderr.splitlines()[0] == _expected_line("more bytes followed the result")
    assert flood_kb < normal_kb + 64 * 1024, (flood_kb, normal_kb)
    assert seconds < 20
    assert not (tmp_path / "o.urdf").exists()


@pytest.mark.parametrize("data, reason", [
    (b"", "it ended before the length it declared"),
    (wire.MAGIC[:5], "it ended before the length it declared"),
    (b"cos\nsystem\n(S'touch x'\ntR.", "it does not start as a result does"),
    (wire.MAGIC + struct.pack(">IQ", wire.MAX_HEADER_BYTES + 1, 0),
     f"its header claims {wire.MAX_HEADER_BYTES + 1} bytes (at most {wire.MAX_HEADER_BYTES})"),
    (_frame({"ok": True}) + b"!", "more bytes followed the result"),
    (_frame(b"\xff"), "its header is not JSON (UnicodeDecodeError)"),
    (_frame([1, 2]), "its header is not a result"),
    (_frame({"ok": 1}), "its header is not a result"),
])
def test_malformed_frames_are_named(data, reason):
    with pytest.raises(wire.MalformedResult) as info:
        wire.unframe(data)
    assert info.value.reason == reason


@pytest.mark.parametrize("error, reason", [
    ({"kind": "BuildError", "message": 3, "file": None, "line": None, "details": []},
     "its error field 'message' is not str"),
    ({"kind": "BuildError", "message": "m", "file": None, "line": True, "details": []},
     "its error field 'line' is not line"),
    ({"kind": "BuildError", "message": "m", "file": None, "line": -1, "details": []},
     "its error field 'line' is not line"),
    ({"kind": "BuildError", "message": "m", "file": "a\0b", "line": None, "details": []},
     "its error field 'file' is not str?"),
    ({"kind": "InputError", "message": "m", "file": None, "line": None,
      "details": ["x"] * (wire.MAX_LIST_ITEMS + 1)}, "its error field 'details' is not [str]"),
    ({"kind": "crashed", "type": "ValueError"}, "its error has the wrong fields (message)"),
    ({"message": "m"}, "its error has no kind"),
])
def test_malformed_errors_are_named(error, reason):
    with pytest.raises(wire.MalformedResult) as info:
        wire.raise_error({"ok": False, "error": error})
    assert info.value.reason == reason


def test_a_well_formed_error_comes_back_as_its_allowed_kind():
    from mobile_car.errors import PackageNotFoundError

    header, body = wire.unframe(wire.error_frame(
        PackageNotFoundError("no package 'x'", file="a.xacro", line=2, details=["d"])))
    with pytest.raises(PackageNotFoundError) as info:
        wire.raise_error(header)
    assert (str(info.value), info.value.details, body) == ("a.xacro:2: no package 'x'", ["d"], b"")
