"""``mcar ci`` as a library: build, strictly check and render every robot file of a package.

The plan is every robot file of the package (parts, steps, complete robots) and, for each
variant file in ``urdf/variants/*.yaml``, the package's top-level robot files (those
directly in ``urdf/``) built with that variant's dimensions. Each item goes through three
steps; a failed step is recorded and the item's later steps are skipped, while the other
items go on. Nothing here prints: the command line formats the :class:`CiItem` list.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .atomic import atomic_write
from .build import build_file, display_path
from .config import CONFIG_ARG
from .diagnostics import Diagnostic
from .discover import output_name, require_robot_files, source_base
from .errors import McarError
from .packages import PackageSearch

STEPS = ("build", "check", "render")


@dataclass
class Step:
    """The outcome of one step: ``status`` is passed, failed or skipped."""

    name: str
    status: str = "passed"
    message: str = ""  # why it failed (first line), or what it wrote
    diagnostics: list[Diagnostic] = field(default_factory=list)
    seconds: float = 0.0
    exit_code: int = 0  # of a failed step: 1 problems in the input, 2 environment/usage


@dataclass
class CiItem:
    label: str  # e.g. "wheel/test_wheel.urdf.xacro" or "mobile_robot.xacro @ small"
    source: Path
    variant: Path | None
    urdf: Path
    png: Path | None
    steps: list[Step] = field(default_factory=list)
    links: int | None = None
    joints: int | None = None

    @property
    def ok(self) -> bool:
        return all(step.status == "passed" for step in self.steps)

    @property
    def errors(self) -> int:
        return sum(1 for step in self.steps for d in step.diagnostics if d.is_error) + \
            sum(1 for step in self.steps if step.status == "failed" and not step.diagnostics)

    @property
    def warnings(self) -> int:
        return sum(1 for step in self.steps for d in step.diagnostics if not d.is_error)


def variant_files(root: Path) -> list[Path]:
    return sorted((source_base(root) / "variants").glob("*.yaml"))


def plan(root: Path, build_dir: Path, render_dir: Path | None) -> list[CiItem]:
    """Every item of a package's CI run, in a stable order."""
    base = source_base(root)
    sources = require_robot_files(root)
    items = []

    def item(source: Path, variant: Path | None) -> CiItem:
        relative = output_name(source, base)
        prefix = Path("variants") / variant.stem if variant else Path()
        png = None
        if render_dir is not None:
            png = render_dir / prefix / relative.with_name(
                relative.name[: -len(".urdf")] + ".png")
        label = source.relative_to(base).as_posix() + (f" @ {variant.stem}" if variant else "")
        return CiItem(label, source, variant, build_dir / prefix / relative, png)

    items += [item(source, None) for source in sources]
    top_level = [s for s in sources if s.parent == base]
    for variant in variant_files(root):
        items += [item(source, variant) for source in top_level]
    return items


def _fail(item: CiItem, name: str, message: str, diagnostics=(), exit_code: int = 1) -> None:
    item.steps.append(Step(name, "failed", message, list(diagnostics), exit_code=exit_code))
    done = {step.name for step in item.steps}
    item.steps += [Step(rest, "skipped", f"skipped: {name} failed")
                   for rest in STEPS if rest not in done]


def build_and_check(item: CiItem, package_paths, overrides: dict[str, float],
                    strict: bool = True) -> str | None:
    """The build and check steps of one item; returns the built URDF text, or None."""
    import time

    from .checker import check_urdf_data
    from .config import override_mappings, resolve_overrides
    from .xacro_locate import SourceLocator

    search = PackageSearch(package_paths=list(package_paths), origin=item.source)
    started = time.perf_counter()
    try:
        effective = dict(overrides)
        if item.variant is not None:
            effective = {**resolve_overrides(search, [], [item.variant])[1], **overrides}
        with override_mappings(effective) as mappings:
            built = build_file(item.source, mappings, search,
                               optional_args=frozenset({CONFIG_ARG}))
        atomic_write(item.urdf, built.xml)
    except McarError as error:
        _fail(item, "build", str(error), exit_code=error.exit_code)
        return None
    item.steps.append(Step("build", message=f"wrote {display_path(item.urdf)}",
                           seconds=time.perf_counter() - started))
    started = time.perf_counter()
    result = check_urdf_data(built.xml.encode("utf-8"), display_path(item.source),
                             base=item.source.parent, search=search,
                             locate=SourceLocator(item.source, built.deps))
    if result.robot is not None:
        item.links, item.joints = len(result.robot.links), len(result.robot.joints)
    if result.failure is not None:
        _fail(item, "check", str(result.failure), exit_code=result.failure.exit_code)
        return None
    if result.errors or (strict and result.warnings):
        _fail(item, "check", result.diagnostics[0].text(), result.diagnostics)
        return None
    item.steps.append(Step("check", diagnostics=result.diagnostics,
                           seconds=time.perf_counter() - started))
    return built.xml


def render_step(item: CiItem, session, manifest) -> None:
    """Draw the built URDF of an item that passed build and check."""
    from .render.session import RenderJob

    if item.png is None:
        return
    result = session.render_one(RenderJob(item.urdf, item.png, item.label), manifest)
    if result.error is not None:
        _fail(item, "render", str(result.error), exit_code=result.error.exit_code)
        return
    verb = "unchanged" if result.status == "unchanged" else "wrote"
    item.steps.append(Step("render", message=f"{verb} {display_path(item.png)}",
                           seconds=result.seconds))


def exit_code(items: list[CiItem]) -> int:
    codes = {step.exit_code for item in items for step in item.steps if step.status == "failed"}
    return 2 if 2 in codes else (1 if codes else 0)
