"""Running `mcar sim --format json` in-process, as the sim tests read it."""

from __future__ import annotations

import json


def sim(cli, path, *options):
    """(exit code, stderr, the JSON entry) of ``mcar sim PATH OPTIONS --format json``."""
    result = cli("sim", path, *options, "--format", "json")
    files = json.loads(result.stdout)["files"] if result.stdout.strip() else [None]
    return result.exit_code, result.stderr, files[0]
