"""MCAR_* limits are validated as options are: a bad value is a usage error naming the
variable (exit 2), never ignored in silence nor an internal error (issue 13, item 6)."""

from __future__ import annotations

import pytest
from conftest import REPO

XACRO = str(REPO / "urdf" / "tutorial" / "04_xacro.xacro")
URDF = str(REPO / "urdf" / "tutorial" / "02_visual.urdf")


@pytest.mark.parametrize("name, value, args, message", [
    ("MCAR_XACRO_TIMEOUT", "abc", ["build", XACRO], "MCAR_XACRO_TIMEOUT='abc': expected a "
                                                     "number of seconds"),
    ("MCAR_XACRO_TIMEOUT", "nan", ["check", XACRO], "MCAR_XACRO_TIMEOUT=nan: must be "
                                                    "between 0.1 and 86400 seconds"),
    ("MCAR_XACRO_MEMORY_MB", "inf", ["build", XACRO], "MCAR_XACRO_MEMORY_MB=inf: must be "
                                                      "between 64 and 1e+07 MB"),
    ("MCAR_MAX_INPUT_MB", "-1", ["render", URDF, "--renderer", "raycast", "-o", "x.png"],
     "MCAR_MAX_INPUT_MB=-1: must be between 0.001 and 1e+06 MB"),
    ("MCAR_GL_TIMEOUT", "0", ["render", URDF, "--renderer", "gl", "-o", "x.png"],
     "MCAR_GL_TIMEOUT=0: must be between 0.1 and 600 seconds"),
])
def test_a_bad_limit_names_its_variable(name, value, args, message, run_mcar, tmp_path):
    result = run_mcar(*args, env={name: value}, cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert f"error: {message}" in result.stderr
    assert "internal error" not in result.stderr
    assert not (tmp_path / "x.png").exists()
