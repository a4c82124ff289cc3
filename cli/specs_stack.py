"""``mcar specs ROBOT --stack DIR``: the options that write the stack's YAML (Nav2,
ros2_controllers, laser_filters) and the call that writes it, kept apart from the specs
command so that it registers them with one decorator and one call:

    @stack_options
    def command(..., stack_dir, stack_distro):
        ...
        write_stack_files(stack_dir, stack_distro, sections, context.sim, context.checked)

The writing itself is the library's (:func:`mobile_car.specs.stack.write_stack`)."""

from __future__ import annotations

import click

from mobile_car.specs.stack import DISTROS

STACK_HELP = ("Also write the figures the ROS 2 stack needs into DIR: nav2.yaml (costmap "
              "footprint and robot_radius), controllers.yaml (the drive's ros2_controllers "
              "controller) and, when a lidar's view is blocked by the robot, "
              "laser_filters.yaml. Each file is written whole or not at all.")


def stack_options(func):
    """--stack DIR and --stack-distro."""
    func = click.option(
        "--stack-distro", type=click.Choice(DISTROS), default=DISTROS[0], show_default=True,
        help="ROS 2 release whose ros2_controllers parameter names --stack writes (jazzy: "
             "also Kilted and Rolling).")(func)
    func = click.option("--stack", "stack_dir", metavar="DIR",
                        type=click.Path(file_okay=False), help=STACK_HELP)(func)
    return func


def write_stack_files(stack_dir, stack_distro: str, sections, sim, checked) -> list:
    """Write the stack's YAML into ``stack_dir`` (nothing when it is None) and say each
    file written on stderr; the package's own YAML, which check compared, is never
    written over."""
    if stack_dir is None:
        return []
    from mobile_car.load.inputs import display_path
    from mobile_car.specs.stack import write_stack
    from mobile_car.specs.stack_check import find_package_yaml, package_control

    inputs = find_package_yaml(checked.loaded).read if checked.loaded is not None else []
    if checked.loaded is not None:
        inputs += list(checked.loaded.deps)
    written = write_stack(stack_dir, sections, sim, stack_distro,
                          package_control(checked, sim), inputs)
    for path in written:
        click.echo(f"wrote {display_path(path)}", err=True)
    return written
