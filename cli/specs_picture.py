"""``mcar specs --picture FILE.png``: the options and the writing, for cli/specs.py.

The command registers the options with :func:`picture_options`, refuses a bad name with
:func:`check_picture_name` before any work, may start the renderer early with
:func:`.common.start_probe` (as mcar diff does), and calls :func:`write_picture` with the
Sections it computed. Nothing heavy
is imported until a picture is asked for.
"""

from __future__ import annotations

from pathlib import Path

import click

from mobile_car.errors import UsageError
from mobile_car.render.options import RENDERER_ENV, RENDERERS

from .common import print_warning

PICTURE_HELP = ("Also draw the figures over the robot: a top view (footprint, support "
                "polygon, centre of mass, lidars' blocked sectors, scale bar) and a side "
                "view (floor, centre of mass, forward and backward tip angles), side by "
                "side, as PNG.")


def picture_options(command):
    """``--picture FILE.png`` and ``--renderer`` (as for mcar render), for a click command:
    its function takes ``picture`` and ``renderer``."""
    command = click.option("--renderer", type=click.Choice(RENDERERS), default="auto",
                           show_default=True, envvar=RENDERER_ENV, show_envvar=True,
                           help="For --picture: as for mcar render.")(command)
    return click.option("--picture", metavar="FILE.png", type=click.Path(dir_okay=False),
                        help=PICTURE_HELP)(command)


def check_picture_name(picture: str | None) -> None:
    """UsageError for a --picture that is not a .png name, before any work is done."""
    if picture is None:
        return
    suffix = Path(picture).suffix
    if suffix.lower() != ".png":
        shown = suffix or "a name without .png"
        raise UsageError(f"--picture {picture}: mcar specs draws PNG pictures, not {shown}; "
                         f"name it {Path(picture).with_suffix('.png')}")



def write_picture(picture: str, sections, checked=None, renderer: str = "auto",
                  probe=None) -> None:
    """Draw the Sections over the checked robot and write the PNG atomically (an earlier
    picture stays whole if anything fails); never over one of the robot's own files."""
    from mobile_car.atomic import atomic_write
    from mobile_car.load.outputs import refuse_overwriting
    from mobile_car.specs.picture import specs_picture

    loaded = getattr(checked, "loaded", None)
    if loaded is not None:
        refuse_overwriting(picture, [loaded.input.path, *loaded.deps])
    png, notes = specs_picture(sections, checked, renderer, probe)
    for note in notes:
        print_warning("mcar", note)
    atomic_write(picture, png)
