"""One export, start to end: a checked robot in, a folder out (written whole or not at all,
:mod:`.folder`), with its manifest, :data:`~.folder.MANIFEST`, and, when asked, the proof
that its engine loads it back as the description says (:mod:`.verify`).

The manifest is JSON: the format, the robot file, the masses (kg), the moving joints, the
drive, every file written and every mesh converted, and the warnings; ``mcar ci`` and a
later export read it (an earlier export is the one folder an export replaces).
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from ..load.inputs import display_path
from .folder import MANIFEST, staged_folder

MANIFEST_VERSION = 1


@dataclass
class ExportReport:
    format: str
    folder: Path
    exported: object              # the format's Exported
    proven: list[str] = field(default_factory=list)  # --verify: what was shown, in words


def export_robot(loaded, target: Path, to: str, options, verify: bool = False) -> ExportReport:
    """Export a loaded robot (a LoadedRobot that passed ``mcar check``) to ``target`` in
    format ``to``; ExportError when it cannot be made or, with ``verify``, does not load
    back as the description says (then nothing is written)."""
    protected = [loaded.input.path, *loaded.deps, *mesh_sources(loaded)]
    with staged_folder(target, protected) as staging:
        exported, proven = _write(loaded, staging, to, options, verify, display_path(target))
        document = {"mcar_export": MANIFEST_VERSION, "format": to, "source": loaded.label,
                    **asdict(exported), "verified": proven if verify else None}
        (staging / MANIFEST).write_text(json.dumps(document, indent=1, ensure_ascii=False)
                                        + "\n", encoding="utf-8")
    return ExportReport(to, target, exported, proven)


def _write(loaded, staging: Path, to: str, options, verify: bool, shown: str):
    if to == "mjcf":
        from .mjcf import export_mjcf
        from .verify import verify_mjcf

        exported = export_mjcf(loaded, staging, options)
        return exported, verify_mjcf(staging, exported, shown) if verify else []
    if to == "usd":
        from .usd import export_usd
        from .verify import verify_usd

        exported = export_usd(loaded, staging, options)
        return exported, verify_usd(staging, exported, shown) if verify else []
    if to in ("urdf", "sdf"):
        from . import urdf, verify_portable

        exported = (urdf.export_urdf if to == "urdf" else urdf.export_sdf)(loaded, staging,
                                                                            options)
        check = verify_portable.verify_urdf if to == "urdf" else verify_portable.verify_sdf
        return exported, check(staging, exported, shown) if verify else []
    raise ValueError(f"unknown export format {to!r}")  # pragma: no cover - click's choice


def mesh_sources(loaded) -> list[Path]:
    """The mesh files the robot names that exist (an export must not replace a folder
    holding one of them)."""
    from ..errors import McarError
    from .mjcf import parse_robot

    found = []
    for mesh in parse_robot(loaded.urdf, loaded.label).iter("mesh"):
        try:
            path = loaded.search.resolve_uri(mesh.get("filename") or "", loaded.base)
        except McarError:  # a package that cannot be found: reported when it is copied
            continue
        if path.is_file():
            found.append(path)
    return found
