"""What ``mcar ci`` prints: the table, each file's problems, the summary lines, or the
JUnit / GitHub forms of the same (cli/ci.py runs the steps)."""

from __future__ import annotations

import click

from mobile_car.errors import McarError
from mobile_car.load.inputs import display_path
from mobile_car.names import shown

from . import streams
from .common import print_diagnostic, report, severity_label


def emit(items, output_format: str, quiet: bool, seconds: float, no_render: bool,
          no_sim: bool, gazebo: bool, skipped: int, verbose: bool = False) -> None:
    if output_format == "junit":
        from mobile_car.ci.junit import junit_report

        streams.echo(junit_report(items), nl=False)
        return
    if output_format == "github":
        for item in items:
            for step in item.steps:
                for diagnostic in step.diagnostics:
                    if diagnostic.is_error or diagnostic.is_warning:
                        streams.echo(diagnostic.github())
                failed = step.problems if step.problems else [step.message] if \
                    step.status == "failed" and not step.diagnostics else []
                for message in failed:
                    from mobile_car.check.diagnostics import github_annotation

                    streams.echo(github_annotation("error", str(item.source), None,
                                                 f"mcar ci {step.name}", message))
    else:
        if not quiet:  # robots not simulated: why, one line per kind
            from mobile_car.ci.simulation import skip_lines

            for line in skip_lines(items):
                click.echo(f"mcar: {shown(line)}", err=True)
        for item in items:
            if not quiet:  # the folders exported; with -v, what Gazebo simulates
                shown_steps = ("gazebo", "export") if verbose else ("export",)
                for step in item.steps:
                    if step.name in shown_steps and step.status == "passed":
                        click.echo(f"mcar: {item.label}: {shown(step.message)}", err=True)
            for line in _problems(item):
                if isinstance(line, str):
                    click.echo(line, err=True)
                elif isinstance(line, McarError):
                    report(line)
                else:
                    print_diagnostic(line)
    if not quiet or output_format == "github":
        streams.echo("\n".join(_table(items)))
    passed = sum(item.ok for item in items)
    strict = {item.strict for item in items}
    steps = "build, " + ("check --strict" if strict == {True} else "check" if strict == {False}
                         else "check, --strict where mcar.yaml says") + \
        (", gazebo" if gazebo else "") + \
        ("" if no_sim else ", sim") + ("" if no_render else ", render") + \
        (", export" if any(item.exports for item in items) else "")
    if skipped:
        files = "file that is" if skipped == 1 else "files that are"
        click.echo(f"mcar ci: skipped {skipped} {files} not robots (-v lists them)", err=True)
    click.echo(f"mcar ci: {passed} of {len(items)} files passed ({steps}) in {seconds:.1f} s",
               err=True)


def _table(items) -> list[str]:
    header = ("FILE", "LINKS", "JOINTS", "WARN", "ERR", "SIM", "PNG", "RESULT")
    rows = []
    for item in items:
        failed = [step.name for step in item.steps if step.status == "failed"]
        png = display_path(item.png) if item.png and any(
            s.name == "render" and s.status == "passed" for s in item.steps) else "-"
        # the drive kind and its scenarios passed, or why it was not simulated
        sim = next((s.summary for s in item.steps if s.name == "sim" and s.summary), "-")
        rows.append((item.label, "-" if item.links is None else str(item.links),
                     "-" if item.joints is None else str(item.joints), str(item.warnings),
                     str(item.errors), sim, png, "ok" if item.ok else f"FAILED ({failed[0]})"))
    widths = [max(len(row[i]) for row in [header, *rows]) for i in range(len(header))]
    right = {1, 2, 3, 4}

    def line(row):
        return "  ".join(cell.rjust(widths[i]) if i in right else cell.ljust(widths[i])
                         for i, cell in enumerate(row)).rstrip()

    return [line(header), *map(line, rows)]


def _problems(item) -> list:
    """What to print for an item: diagnostics, and the errors of failed steps."""
    lines = []
    for step in item.steps:
        if step.status != "failed":
            # warnings of a passed step; notes (what Gazebo lumps) only in the JUnit report
            lines += [d for d in step.diagnostics if d.is_error or d.is_warning]
            continue
        if step.problems:  # sim: its rules' diagnostics, then each failed scenario
            lines += step.diagnostics
            lines += [f"{item.label}: {severity_label('error')} {step.name} {shown(problem)}"
                      for problem in step.problems]
            continue
        lines += [d for d in step.diagnostics if d.is_error or d.is_warning] or [
            step.error or f"{item.label}: {step.name} failed: {shown(step.message)}"]
    return lines
