"""Commands that need an optional extra say which one to install, in one line (exit 2),
before they start, when a module of it is missing: never an internal error mid-run."""

from __future__ import annotations

import importlib.metadata
import re
import sys

import pytest
from conftest import REPO

from mobile_car.extras import EXTRAS

CAR = REPO / "urdf" / "mobile_robot.xacro"
VARY = ("--vary", "wheel_radius=0.03..0.04:2")


@pytest.mark.parametrize("hidden, args, named", [
    ("pandas", (), "pandas, which is"),
    ("pyarrow", (), "pyarrow, which is"),
    ("matplotlib", ("--plot", "p.png"), "matplotlib, which is"),
    ("distributed", ("--scheduler", "tcp://127.0.0.1:8786"), "distributed, which is"),
])
def test_sweep_without_its_extra_says_what_to_install(cli, monkeypatch, tmp_path, hidden,
                                                      args, named):
    monkeypatch.setitem(sys.modules, hidden, None)  # import fails, as when not installed
    monkeypatch.chdir(tmp_path)
    result = cli("sweep", CAR, *VARY, *args, "-o", tmp_path / "r.csv")
    assert result.exit_code == 2
    assert result.output == (f"mcar: error: mcar sweep needs {named} not installed: "
                             'pip install "mcar[sweep]"\n')
    assert list(tmp_path.iterdir()) == []  # nothing started, nothing written


def test_two_missing_modules_are_named_together(monkeypatch):
    from mobile_car import extras
    from mobile_car.errors import UsageError

    monkeypatch.setitem(sys.modules, "viser", None)
    monkeypatch.setitem(sys.modules, "websockets", None)
    with pytest.raises(UsageError) as caught:
        extras.require("mcar view", "view")
    assert caught.value.message == ('mcar view needs viser, websockets, which are not '
                                    'installed: pip install "mcar[view]"')


def test_the_extras_table_is_what_the_installed_mcar_declares():
    declared: dict[str, list[str]] = {}
    for requirement in importlib.metadata.requires("mcar"):  # 'pandas>=2; extra == "sweep"'
        extra = re.search(r"""extra\s*==\s*["']([^"']+)["']""", requirement)
        if extra:
            declared.setdefault(extra.group(1), []).append(requirement)
    assert set(EXTRAS) == set(declared) - {"test"}
    provided_by = importlib.metadata.packages_distributions()
    for extra, modules in EXTRAS.items():
        wanted = set()
        for requirement in declared[extra]:  # "dask[distributed]>=2024.1" brings both
            name = re.split(r"[<>=;]", requirement)[0].strip().lower()
            base, _, inner = name.partition("[")
            wanted |= {base.strip(), *filter(None, inner.rstrip("] ").split(","))}
        for module in modules:
            distributions = {name.lower() for name in provided_by.get(module, [])}
            assert distributions & wanted, f"{module} comes from none of {extra}'s {wanted}"
