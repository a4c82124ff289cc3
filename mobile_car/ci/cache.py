"""Reuse the build and check of robot files whose inputs did not change (``mcar ci``).

The record (``.mcar-ci.json`` in the build folder) holds per built file the key of its
settings and the stamps of every file it was made from (see :mod:`mobile_car.freshness`),
the stamp of the URDF written, the check's verdict, counts and diagnostics, and the sim
step's outcome (status, message, testcases, error lines and diagnostics), and the gazebo
step's (status, message, diagnostics; the helper's path and identity are part of the
key, so a rebuilt helper is asked again). An item
whose key, inputs and output are unchanged, and whose picture the render manifest finds
current, is *replayed*: its steps are made from the record, so the report (text, JUnit,
exit code) is the one a full run prints, without expanding or checking anything. An item
whose URDF or picture was deleted or edited since is built again. Build failures are not
recorded: they are built again every time, and so is an item whose sim could not run
(exit 2: no engine), or which is now to be simulated and was recorded without.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..freshness import (
    Basis,
    Stamper,
    diagnostics_data,
    diagnostics_from,
    file_sha256,
    identity,
    key_of,
    output_current,
    output_stamp,
    read_record,
    stamps_current,
    write_record,
)
from ..load.inputs import display_path
from .pipeline import CiItem, Step, fail

CACHE_NAME = ".mcar-ci.json"


def item_basis(item: CiItem, basis: Basis) -> Basis:
    """The run's basis plus the item's variant file, read as --config is."""
    return basis.with_file(item.variant, "variant")


class CiCache:
    def __init__(self, build_dir: Path, gazebo_helper: Path | None = None):
        self.folder = Path(build_dir)
        self.gazebo = _helper_stamp(gazebo_helper)
        self.path = self.folder / CACHE_NAME
        self.entries: dict[str, dict] = read_record(self.path, "items")
        self.stamper = Stamper()
        self._changed = False

    def _name(self, item: CiItem) -> str:
        return Path(os.path.relpath(os.path.abspath(item.urdf),
                                    os.path.abspath(self.folder))).as_posix()

    def _key(self, item: CiItem, basis: Basis, strict: bool) -> str:
        return key_of("ci", item_basis(item, basis).settings, strict, self.gazebo)

    def replay(self, item: CiItem, basis: Basis, strict: bool, picture_fresh,
               sim: bool = True) -> bool:
        """Fill in the item's steps from the record if nothing it depends on changed;
        ``picture_fresh(item)`` says whether its picture (if it has one) is current;
        ``sim``: the run simulates (not --no-sim)."""
        name = self._name(item)
        entry = self.entries.get(name)
        if not entry or entry.get("key") != self._key(item, basis, strict):
            return False
        try:
            passed, diagnostics, simulated = _recorded(entry)
            gazebo = _gazebo_step(entry["gazebo"]) if "gazebo" in entry else None
        except ValueError:  # damaged or forged: built again and recorded anew
            del self.entries[name]
            self._changed = True
            return False
        current, refreshed = stamps_current(entry.get("files"))
        if not current:
            return False
        written, touched = output_current(item.urdf, entry.get("urdf"))
        if not written:
            return False
        self._changed = self._changed or refreshed or touched
        if passed and item.png is not None and not picture_fresh(item):
            return False
        if passed and sim and simulated is None:
            return False
        if passed and item.gazebo and gazebo is None:
            return False
        item.links, item.joints = entry.get("links"), entry.get("joints")
        item.deps = [Path(p) for p in entry.get("deps") or []]
        item.steps.append(Step("build", message=f"wrote {display_path(item.urdf)}"))
        if not passed:
            fail(item, "check", diagnostics[0].text(), diagnostics)
            return True
        item.steps.append(Step("check", diagnostics=diagnostics))
        if item.gazebo:
            item.steps.append(gazebo)
        if sim:
            item.steps.append(simulated)
        if item.png is not None:
            item.steps.append(Step("render", message=f"unchanged {display_path(item.png)}"))
        return True

    def record(self, item: CiItem, basis: Basis, strict: bool) -> None:
        """Remember an item just built and checked (a failed build is forgotten)."""
        name = self._name(item)
        self._changed = True
        check = next((step for step in item.steps if step.name == "check"), None)
        if check is None or check.status == "skipped":
            self.entries.pop(name, None)
            return
        # and what its sim step read (a control package's YAML), and the meshes its check
        # read: a mesh edited is checked again (with --no-render nothing else stamps it)
        reads = [path for step in item.steps for path in step.reads]
        meshes, missing = _mesh_inputs(item.check_result)
        files = self.stamper.stamps([*item.deps, *item_basis(item, basis).files, *reads,
                                     *meshes], skip=item.generated, absent=missing)
        try:
            urdf = output_stamp(item.urdf, file_sha256(item.urdf))
        except OSError:
            urdf = None
        if files is None or urdf is None:
            self.entries.pop(name, None)
            return
        self.entries[name] = {
            "key": self._key(item, basis, strict), "files": files, "urdf": urdf,
            "deps": [os.path.abspath(p) for p in item.deps],
            "links": item.links, "joints": item.joints,
            "check": {"passed": check.status == "passed",
                      "diagnostics": diagnostics_data(check.diagnostics)}}
        gazebo = next((step for step in item.steps if step.name == "gazebo"), None)
        if check.status == "passed" and gazebo is not None:
            self.entries[name]["gazebo"] = {
                "status": gazebo.status, "message": gazebo.message,
                "diagnostics": diagnostics_data(gazebo.diagnostics)}
        simulated = next((step for step in item.steps if step.name == "sim"), None)
        if check.status == "passed" and simulated is not None:  # it ran (or was declined)
            if simulated.exit_code > 1:  # the engine could not run: try again next time
                self.entries.pop(name, None)
                return
            self.entries[name]["sim"] = {
                "status": simulated.status, "message": simulated.message,
                "exit_code": simulated.exit_code, "cases": simulated.cases,
                "problems": simulated.problems, "skip_kind": simulated.skip_kind,
                "summary": simulated.summary,
                "diagnostics": diagnostics_data(simulated.diagnostics)}

    def save(self) -> None:
        if self._changed:
            write_record(self.path, "items", self.entries)
            self._changed = False


def _recorded(entry: dict) -> tuple[bool, list, Step | None]:
    """What replaying an entry needs, checked to be what :meth:`CiCache.record` writes:
    (check passed, its diagnostics, the sim step or None); ValueError if it is not."""
    check = entry.get("check")
    deps = entry.get("deps") or []
    if not isinstance(check, dict) or not isinstance(check.get("passed"), bool):
        raise ValueError("no check verdict")
    if not all(value is None or type(value) is int
               for value in (entry.get("links"), entry.get("joints"))):
        raise ValueError("link or joint count not a number")
    if not isinstance(deps, list) or not all(isinstance(p, str) and "\0" not in p
                                             for p in deps):
        raise ValueError("dependencies not a list of paths")
    diagnostics = diagnostics_from(check.get("diagnostics") or [])
    if not check["passed"] and not diagnostics:
        raise ValueError("a failed check without its diagnostics")
    simulated = entry.get("sim")
    return check["passed"], diagnostics, None if simulated is None else _sim_step(simulated)


_STATUSES = ("passed", "failed", "skipped")


def _mesh_inputs(result) -> tuple[list, list]:
    """(the mesh files a check read and the files they pull in: materials, textures; the
    meshes it found missing, W207: the verdict holds while they are missing)."""
    meshes = [m for m in getattr(result, "mesh_files", None) or [] if m.path is not None]
    missing = [m.path for m in meshes if not os.path.lexists(m.path)]
    return [*(m.path for m in meshes if m.path not in missing),
            *(path for m in meshes for path in m.reads)], missing


def _helper_stamp(helper: Path | None):
    """What identifies the Gazebo helper a run used (None: no gazebo step)."""
    if helper is None:
        return None
    try:
        stat = os.stat(helper)
    except OSError:
        return str(helper)
    return [os.path.abspath(helper), *identity(stat)]


def _gazebo_step(data: dict) -> Step:
    """The gazebo step a run recorded; ValueError if it is not one."""
    if not isinstance(data, dict) or data.get("status") not in _STATUSES or \
            not isinstance(data.get("message"), str):
        raise ValueError("gazebo step without status or message")
    diagnostics = diagnostics_from(data.get("diagnostics") or [])
    if data["status"] == "failed" and not diagnostics:
        raise ValueError("a failed gazebo step without its diagnostics")
    return Step("gazebo", data["status"], data["message"], diagnostics,
                exit_code=1 if data["status"] == "failed" else 0)


def _sim_step(data: dict) -> Step:
    """The sim step a run recorded (see :meth:`CiCache.record`); ValueError if it is not
    one."""
    from ..sim.diagnostics import SimDiagnostic

    if not isinstance(data, dict):
        raise ValueError("sim step not a record")
    status, message, code = data.get("status"), data.get("message"), data.get("exit_code")
    cases, problems = data.get("cases") or [], data.get("problems") or []
    if status not in _STATUSES or not isinstance(message, str) or type(code) is not int:
        raise ValueError("sim step without status, message or exit code")
    if not isinstance(cases, list) or not all(_is_case(case) for case in cases):
        raise ValueError("sim testcases damaged")
    if not isinstance(problems, list) or not all(isinstance(p, str) for p in problems):
        raise ValueError("sim problems not lines")
    skip_kind, summary = data.get("skip_kind") or "", data.get("summary") or ""
    if not isinstance(skip_kind, str) or not isinstance(summary, str):
        raise ValueError("sim skip kind or summary not text")
    diagnostics = diagnostics_from(data.get("diagnostics") or [], SimDiagnostic)
    return Step("sim", status, message, diagnostics, exit_code=code, cases=list(cases),
                problems=list(problems), skip_kind=skip_kind, summary=summary)


def _is_case(case) -> bool:
    """A testcase as mobile_car.sim.report.junit_cases makes it."""
    return isinstance(case, dict) and case.get("status") in _STATUSES and all(
        isinstance(case.get(key), str) for key in ("name", "message", "text"))
