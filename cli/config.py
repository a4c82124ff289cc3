"""``mcar config``: every dimension of the robot, its unit, source and where it is defined."""

from __future__ import annotations

import json
from pathlib import Path

import click

from mobile_car.build import display_path
from mobile_car.config import config_table, resolve_overrides
from mobile_car.packages import PackageSearch

from .common import config_options, handle_errors, package_path_option

HELP = """Show the robot's dimensions: value, unit, source, meaning, FILE:LINE.

\b
  mcar config                               the table, then the derived values
  mcar config --set wheel_radius=40mm       effective values; overrides marked *
  mcar config --format json > car.json      a document --config reads back

The dimensions live once, in urdf/config.xacro (one <xacro:property> each, with a
"UNIT; SOURCE: meaning" comment); derived ones are xacro expressions of the others,
evaluated here by xacro itself. The config is that of the mobile_car_description
package found from the current folder (a checkout you stand in, else the bundled one).
"""


def _text(table: dict) -> str:
    rows = []
    for section, title in (("dimensions", "Dimensions"), ("derived", "Derived")):
        rows.append(f"{title}:")
        entries = table[section]
        width = max(len(name) for name in entries) + 2
        for name, item in entries.items():
            mark = "*" if item.get("overridden") else " "
            value = f"{item['value']:.6g}"
            note = item["meaning"]
            if item.get("overridden"):
                note += f" (default {item['default']:.6g})"
            if "expression" in item:
                note += f"  = {item['expression']}"
            path, _, line = item["defined"].rpartition(":")
            where = f"{Path(path).name}:{line}"
            rows.append(f"{mark}{name:<{width}}{value:>10} {item['unit']:<7} "
                        f"{item['source']:<10}{where:<18}{note}")
        rows.append("")
    rows.append(f"* overridden. Defined in {display_path(table['config'])}")
    return "\n".join(rows)


@click.command("config", help=HELP, short_help="Show the robot's dimensions.")
@click.option("--format", "fmt", type=click.Choice(["text", "json", "yaml"]), default="text",
              show_default=True, help="Output format; json and yaml can be read by --config.")
@config_options
@package_path_option
@handle_errors
def command(fmt, sets, config_files, package_paths):
    search = PackageSearch(package_paths=list(package_paths), origin=Path.cwd())
    spec, overrides, values = resolve_overrides(search, sets, config_files)
    table = config_table(spec, values, overrides)
    if fmt == "json":
        click.echo(json.dumps(table, indent=2))
    elif fmt == "yaml":
        import yaml

        click.echo(yaml.safe_dump(table, sort_keys=False), nl=False)
    else:
        click.echo(_text(table))
