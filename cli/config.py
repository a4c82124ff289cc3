"""``mcar config``: every dimension of the robot, its unit, source and where it is defined."""

from __future__ import annotations

import json
from pathlib import Path

import click

from mobile_car.errors import UsageError
from mobile_car.load.inputs import display_path
from mobile_car.names import shown_lines

from . import streams
from .common import handle_errors, load_inputs, robot_options

HELP = """Show the robot's dimensions: value, unit, source, range, meaning, FILE:LINE.

\b
  mcar config                               the table, then the derived values
  mcar config --set wheel_radius=40mm       effective values; overrides marked *
  mcar config --format json > car.json      a document --config reads back

The dimensions live once, in urdf/config.xacro (one <xacro:property> each, with a
"UNIT LO..HI; SOURCE: meaning" comment: --set/--config values outside the plausible
range LO..HI are refused); derived ones are xacro expressions of the others,
evaluated here by xacro itself. The config is urdf/config.xacro of the package found
from INPUT (a robot .xacro, a folder or part of the package), else of the package you
stand in, else the bundled mobile car's. A URDF has no dimensions to show.

\b
INPUT (optional) names the package whose config.xacro to show: a robot .xacro file,
a folder, or a part name of the package. Not stdin, not a URDF, and no NAME:=VALUE
words: dimensions change with --set and --config.

\b
Exit codes:
  0  the table was printed
  1  config.xacro's own values are outside their ranges or do not fit together
  2  usage or I/O error: an unknown or invalid --set/--config value, dimensions that
     do not fit together, a URDF or macro file as INPUT, unknown package
  130  interrupted (Ctrl-C); 143 terminated
"""


def _text(table: dict) -> str:
    rows = []
    for section, title in (("dimensions", "Dimensions"), ("derived", "Derived")):
        entries = table[section]
        if not entries:  # a package may derive nothing
            continue
        rows.append(f"{title}:")
        rows += _columns([_cells(name, item) for name, item in entries.items()])
        rows.append("")
    if any(item.get("overridden") for item in table["dimensions"].values()):
        rows.append("* overridden by --set or --config: its description is of the default "
                    "value")
    rows.append(f"Defined in {display_path(table['config'])}")
    return "\n".join(rows)


def _cells(name: str, item: dict) -> list[str]:
    """One row: mark and name, value, unit, source, range, where defined, meaning."""
    note = item["meaning"]
    if item.get("overridden"):  # the meaning describes the default, not this value
        unit = "" if item["unit"] in ("1", "count") else f" {item['unit']}"
        default = item["default"]
        shown = f"{default:.6g}{unit}" if isinstance(default, float) else default
        note += f" (this describes the default, {shown})"
    if "expression" in item:
        note += f"  = {item['expression']}"
    path, _, line = item["defined"].rpartition(":")
    mark = "*" if item.get("overridden") else " "
    return [mark + name, f"{item['value']:.6g}", item["unit"], item["source"],
            item.get("range_text", ""), f"{Path(path).name}:{line}", note]


def _columns(rows: list[list[str]]) -> list[str]:
    """Rows aligned in columns as wide as their widest cell, two spaces apart, so no two
    columns ever touch; the value column right-aligned, the last left ragged."""
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]) - 1)]
    lines = []
    for row in rows:
        cells = [cell.rjust(width) if i == 1 else cell.ljust(width)
                 for i, (cell, width) in enumerate(zip(row, widths, strict=False))]
        lines.append("  ".join([*cells, row[-1]]).rstrip())
    return lines


@click.command("config", help=HELP, short_help="Show the robot's dimensions.")
@click.argument("words", nargs=-1, metavar="[INPUT]...")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "yaml"]), default="text",
              show_default=True, help="Output format; json and yaml can be read by --config.")
@robot_options
@handle_errors
def command(words, fmt, sets, config_files, package_paths):
    from mobile_car.config.overrides import config_table, resolve_overrides
    from mobile_car.load.robot import load_robot, require_robot_file
    from mobile_car.packages.search import PackageSearch

    with load_inputs(words, package_paths, sets, config_files) as (selection, options):
        if options.mappings:
            raise UsageError("NAME:=VALUE does not change dimensions: use --set NAME=VALUE")
        if selection.reads_stdin:
            raise UsageError("config reads the package's config.xacro, not stdin")
        for inp in selection.inputs if selection.kind == "files" else ():
            require_robot_file(inp)
            if not inp.is_xacro:
                raise UsageError("a URDF has no dimensions to show: give the .xacro it was "
                                 "built from", file=inp.label)
            load_robot(inp, options)  # refuses what every command refuses for this file
        if options.overrides is not None:
            spec, overrides = options.overrides.spec, options.overrides.values
            values = options.overrides.effective
        else:
            origin = selection.inputs[0].path if selection.kind == "files" else \
                (selection.root or Path.cwd())
            search = PackageSearch(package_paths=list(package_paths), origin=origin)
            spec, overrides, values = resolve_overrides(search, (), ())
    table = config_table(spec, values, overrides)
    if fmt == "json":
        streams.echo(json.dumps(table, indent=2))
    elif fmt == "yaml":
        import yaml

        streams.echo(yaml.safe_dump(table, sort_keys=False), nl=False)
    else:
        streams.echo(shown_lines(_text(table)))  # names are data: mobile_car.names
