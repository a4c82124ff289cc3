"""What every command shares: the package-path option and turning errors into exit codes."""

from __future__ import annotations

import contextlib
import functools
import os
import sys
from pathlib import Path

import click

from mobile_car.errors import EXIT_USAGE, McarError

package_path_option = click.option(
    "--package-path", "package_paths", multiple=True, metavar="DIR",
    type=click.Path(file_okay=False, exists=True),
    help="Also look for ROS packages (package.xml) under DIR; repeatable. Searched after the "
         "package holding INPUT and before ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and the "
         "bundled mobile_car_description.")


def config_options(func):
    """--set and --config: override the robot's dimensions (see `mcar config`)."""
    func = click.option(
        "--config", "config_files", multiple=True, metavar="FILE.yaml",
        type=click.Path(dir_okay=True),
        help="Dimension overrides from a YAML/JSON file: `name: value` pairs (only what "
             "differs), or a document `mcar config --format json` wrote. Repeatable; "
             "--set wins.")(func)
    func = click.option(
        "--set", "sets", multiple=True, metavar="NAME=VALUE",
        help="Override one dimension of config.xacro, e.g. --set wheel_radius=40mm. A bare "
             "number is SI (m, kg); units like mm, cm, in, g, deg are converted. Repeatable.")(
        func)
    return func


# The xacro argument config.xacro reads overrides from; kept here, not imported from
# mobile_car.config, so that commands run without overrides never import it.
CONFIG_ARG = "config"


def default_package(package_paths) -> Path:
    """The mobile_car_description a command without INPUT works on: the checkout the user
    stands in wins over ROS paths and the copy bundled with mcar."""
    from mobile_car.packages import PackageSearch
    from mobile_car.resources import PACKAGE_NAME

    return PackageSearch(package_paths=list(package_paths), origin=Path.cwd()).find(PACKAGE_NAME)


def dimension_overrides(origin: Path, package_paths, sets, config_files) -> dict[str, float]:
    """Validated --set/--config overrides for inputs at origin ({} when none are given)."""
    if not sets and not config_files:
        return {}
    from mobile_car.config import resolve_overrides
    from mobile_car.packages import PackageSearch

    search = PackageSearch(package_paths=list(package_paths), origin=origin)
    return resolve_overrides(search, sets, config_files)[1]


def override_context(overrides: dict[str, float]):
    """A context yielding the xacro arguments that apply the overrides ({} for none)."""
    if not overrides:
        return contextlib.nullcontext({})
    from mobile_car.config import override_mappings

    return override_mappings(overrides)


def use_color() -> bool | None:
    """False with NO_COLOR set (https://no-color.org); else None: click colours a TTY only."""
    return False if os.environ.get("NO_COLOR") else None


def severity_label(severity: str) -> str:
    """``error:`` in red, ``warning:`` in yellow (the styling is dropped off a TTY)."""
    return click.style(f"{severity}:", fg="red" if severity == "error" else "yellow", bold=True)


def report(error: McarError) -> None:
    """Print an error as one `FILE:LINE: error: message` line, then its context lines."""
    where = error.location()
    prefix = f"{where}: " if where else "mcar: "
    click.echo(f"{prefix}{severity_label('error')} {error.message}", err=True, color=use_color())
    for line in error.details:
        click.echo(f"  {line}", err=True)


def handle_errors(func):
    """Run a command body; McarError becomes its message and exit code, Ctrl-C exits 130."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except McarError as error:
            report(error)
            sys.exit(error.exit_code)
        except KeyboardInterrupt:
            click.echo("mcar: interrupted", err=True)
            sys.exit(130)
        except BrokenPipeError:
            # The reader (head, a closed pipe) went away: not our failure to report.
            sys.stderr.close()
            sys.exit(0)
        except Exception as error:  # a bug in mcar: say so in one line, no traceback
            if os.environ.get("MCAR_DEBUG"):
                raise
            click.echo(f"mcar: internal error: {type(error).__name__}: {error} "
                       "(set MCAR_DEBUG=1 for a traceback, and please report it)", err=True)
            sys.exit(EXIT_USAGE)

    return wrapper
