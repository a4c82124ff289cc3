"""``mcar ci`` as a library: build, strictly check and render every robot file of a package.

The plan is every robot file of the package (parts, steps, complete robots) and, for each
variant file in ``urdf/variants/*.yaml``, the package's top-level robot files (those
directly in ``urdf/``) built with that variant's dimensions. Each item goes through four
steps (build, check, sim (:mod:`.simulation`), render), five where the Gazebo helper is
installed (gazebo, after check: what libsdformat changes in a robot that has ``<gazebo>``
blocks), and export where the package's mcar.yaml asks (:mod:`.exports`); a failed build
or check is recorded and the item's later steps are skipped, while the other items go on
(a failed sim still lets the robot be drawn: the picture helps to see why). Nothing here
prints: the command line formats the :class:`CiItem` list.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, field
from pathlib import Path

from ..atomic import atomic_write
from ..check.diagnostics import Diagnostic
from ..errors import McarError, combine_exit_codes
from ..load.inputs import RobotInput, display_path
from ..load.robot import CONFIG_ARG, LoadOptions
from ..load.selection import Selection
from ..names import shown
from ..packages.discover import output_name, source_base

STEPS = ("build", "check", "gazebo", "sim", "render", "export")


@dataclass
class Step:
    """The outcome of one step: ``status`` is passed, failed or skipped."""

    name: str
    status: str = "passed"
    message: str = ""  # why it failed (first line), or what it wrote
    diagnostics: list[Diagnostic] = field(default_factory=list)
    seconds: float = 0.0
    exit_code: int = 0  # of a failed step: 1 problems in the input, 2 environment/usage
    error: McarError | None = None  # what failed a step that has no diagnostics
    # A step reported as several testcases (sim: lint and one per scenario): dicts of
    # name, status, message, text, as mobile_car.sim.report.junit_cases makes them.
    cases: list[dict] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)  # its error lines, without the file
    skip_kind: str = ""  # a skipped sim: the kind of reason, one line per kind in the report
    summary: str = ""  # sim: its cell in the report's table ("skid-steer 3/3", "not a vehicle")
    reads: list[Path] = field(default_factory=list)  # files read besides the build's


@dataclass
class CiItem:
    label: str  # e.g. "wheel/test_wheel.urdf.xacro" or "mobile_robot.xacro @ small"
    input: RobotInput
    variant: Path | None
    urdf: Path
    png: Path | None
    steps: list[Step] = field(default_factory=list)
    links: int | None = None
    joints: int | None = None
    checked: object = None  # the CheckResult of a passed check step, which render draws
    check_result: object = None  # the CheckResult of its check step, passed or not
    strict: bool = False  # a warning fails it (ci --strict, or its package's mcar.yaml)
    deps: list[Path] = field(default_factory=list)  # the files its build read
    expansion_warnings: list[str] = field(default_factory=list)  # xacro's, for the record
    generated: tuple[Path, ...] = ()  # files written for its build (overrides): no inputs
    diff: str | None = None  # with --against: what changed since then ("3 changes")
    gazebo: bool = False  # the gazebo step is part of its plan (the helper is installed)
    exports: tuple[str, ...] = ()  # formats its package's mcar.yaml exports it to (.exports)
    loaded: object = None  # the LoadedRobot of a passed build, which the export step reads

    @property
    def source(self) -> Path:
        return self.input.path

    @property
    def ok(self) -> bool:
        """No step failed (a robot that is not a vehicle skips sim and is still ok)."""
        return not any(step.status == "failed" for step in self.steps)

    @property
    def errors(self) -> int:
        return sum(1 for step in self.steps for d in step.diagnostics if d.is_error) + \
            sum(1 for step in self.steps if step.status == "failed" and not step.diagnostics)

    @property
    def warnings(self) -> int:
        return sum(1 for step in self.steps for d in step.diagnostics if d.is_warning)


def variant_files(root: Path) -> list[Path]:
    return sorted((source_base(root) / "variants").glob("*.yaml"))


def not_robots(selection: Selection) -> list:
    """The files found beside the robots that are not robots (Skipped, with why), but for
    the variant files this run applies."""
    variants = set(variant_files(selection.root)) \
        if selection.kind in ("package", "folder") and selection.root is not None else set()
    return [file for file in selection.skipped if file.path not in variants]


def plan(selection: Selection, build_dir: Path, render_dir: Path | None,
         gazebo: bool = False) -> list[CiItem]:
    """Every item of a CI run over the inputs, in a stable order: each input, then for a
    package (or folder) with variants, its top-level robot files once per variant;
    ``gazebo``: their plan has the gazebo step."""
    items = []

    def item(inp: RobotInput, variant: Path | None) -> CiItem:
        relative = output_name(inp.path, inp.base or inp.path.parent)
        prefix = Path("variants") / variant.stem if variant else Path()
        png = None
        if render_dir is not None:
            png = render_dir / prefix / relative.with_name(
                relative.name[: -len(".urdf")] + ".png")
        label = (shown(inp.relative.as_posix()) if inp.base is not None else inp.label) + \
            (f" @ {shown(variant.stem)}" if variant else "")
        return CiItem(label, inp, variant, build_dir / prefix / relative, png, gazebo=gazebo)

    if selection.reads_stdin:
        from ..errors import UsageError

        raise UsageError("mcar ci builds files into --build-dir: give files, not - (stdin)")
    items += [item(inp, None) for inp in selection.inputs]
    if selection.kind in ("package", "folder"):
        top_level = [inp for inp in selection.inputs if len(inp.relative.parts) == 1
                     and inp.is_xacro]
        for variant in variant_files(selection.root):
            items += [item(inp, variant) for inp in top_level]
    _refuse_destroying(items, [inp.path for inp in selection.inputs])
    return items


def _refuse_destroying(items: list[CiItem], inputs: list[Path]) -> None:
    """No two items written to one file, no output over an input (see load.outputs)."""
    from ..load.outputs import refuse_clashes, refuse_overwriting_each

    outputs = [(item.urdf, item) for item in items] + \
        [(item.png, item) for item in items if item.png is not None]
    refuse_clashes((path, item.source) for path, item in outputs)
    refuse_overwriting_each([path for path, _item in outputs], inputs)


def fail(item: CiItem, name: str, message: str, diagnostics=(), exit_code: int = 1,
          error: McarError | None = None) -> None:
    item.steps.append(Step(name, "failed", message, list(diagnostics), exit_code=exit_code,
                           error=error))
    # The steps after this one are skipped; one before it that did not run (sim, left out
    # with --no-sim, before a failed render) is not reported at all.
    done = {step.name for step in item.steps}
    item.steps += [Step(rest, "skipped", f"skipped: {name} failed")
                   for rest in STEPS[STEPS.index(name) + 1:]
                   if rest not in done and (rest != "gazebo" or item.gazebo)
                   and (rest != "export" or item.exports)]


@contextlib.contextmanager
def _item_options(item: CiItem, options: LoadOptions):
    """The load options of an item: a variant's dimensions (validated as --config is),
    with the command line's overrides on top."""
    if item.variant is None:
        yield options
        return
    from ..config.overrides import evaluate, override_mappings, read_overrides
    from ..packages.search import PackageSearch

    search = PackageSearch(package_paths=list(options.package_paths), origin=item.source)
    spec, values = read_overrides(search, [], [item.variant])
    if options.overrides is not None:
        values.update(options.overrides.values)
    with override_mappings(values) as mappings:
        evaluate(spec, mappings, search)
        yield LoadOptions({**options.mappings, **mappings}, options.package_paths)


def build_and_check(item: CiItem, options: LoadOptions, strict: bool = True) -> bool:
    """The build and check steps of one item; True if both passed."""
    import time

    from ..check.checker import check_loaded
    from ..load.outputs import refuse_overwriting
    from ..load.robot import load_robot

    started = time.perf_counter()
    try:
        with _item_options(item, options) as item_options:
            loaded = load_robot(item.input, item_options)
            written = [options.overrides.path if options.overrides else None,
                       item_options.mappings.get(CONFIG_ARG) if item.variant else None]
            item.generated = tuple(Path(p) for p in written if p is not None)
        item.deps = list(loaded.deps)
        item.loaded = loaded if item.exports else None
        item.expansion_warnings = [str(w) for w in loaded.warnings]
        refuse_overwriting(item.urdf, loaded.deps)
        atomic_write(item.urdf, _built(item, loaded, item_options))
    except McarError as error:
        fail(item, "build", str(error), exit_code=error.exit_code, error=error)
        return False
    item.steps.append(Step("build", message=f"wrote {display_path(item.urdf)}",
                           seconds=time.perf_counter() - started))
    started = time.perf_counter()
    result = item.check_result = check_loaded(loaded)
    if result.robot is not None:
        item.links, item.joints = len(result.robot.links), len(result.robot.joints)
    if result.errors or (strict and result.warnings):
        fail(item, "check", result.diagnostics[0].text(), result.diagnostics)
        return False
    item.steps.append(Step("check", diagnostics=result.diagnostics,
                           seconds=time.perf_counter() - started))
    item.checked = result
    return True


def _built(item: CiItem, loaded, options: LoadOptions) -> bytes:
    """What the build writes: a xacro's expansion, and for a plain URDF what `mcar build`
    writes of it (through xacro), so that ci and build leave the same file and neither
    finds the other's output changed. The check reads the URDF as it is."""
    if loaded.from_xacro:
        return loaded.urdf
    from ..load.robot import load_robot

    try:
        return load_robot(item.input, options.replace(through_xacro=True)).urdf
    except McarError:  # xacro cannot parse it: written as it is, and its check says why
        return loaded.urdf


def gazebo_step(item: CiItem, strict: bool = True) -> None:
    """What Gazebo changes in an item that passed its check, as ``mcar check --gazebo``
    finds it; only for a robot with a ``<gazebo>`` block (one meant for Gazebo: a part's
    test file is not), else skipped saying why. Notes never fail it; errors do, and
    warnings when ``strict``. GazeboUnavailable (a helper of another format) passes
    through: the run cannot be made."""
    import time

    from ..gazebo.check import check_in_gazebo

    checked = item.checked
    if not any(element.tag == "gazebo" for element in checked.robot.others):
        item.steps.append(Step("gazebo", "skipped", "not for Gazebo: no <gazebo> element"))
        return
    started = time.perf_counter()
    before = set(checked.diagnostics)
    check_in_gazebo(checked)
    found = [d for d in checked.diagnostics if d not in before]
    checked.diagnostics = sorted(before, key=Diagnostic.sort_key)  # check's, for render
    seconds = time.perf_counter() - started
    view = checked.gazebo
    message = f"gazebo: {view.summary()}" if view is not None else "gazebo: not loaded"
    failing = [d for d in found if d.is_error or (strict and d.is_warning)]
    if failing:
        item.steps.append(Step("gazebo", "failed", failing[0].text(), found, seconds, 1))
        return
    item.steps.append(Step("gazebo", message=message, diagnostics=found, seconds=seconds))


def render_step(item: CiItem, session, manifest, basis=None) -> None:
    """Draw the built URDF of an item that passed build and check (``basis``: the item's,
    to keep stamps of what the picture was made from)."""
    from ..render.session import RenderJob

    if item.png is None:
        return
    job = RenderJob(item.input, item.png, item.label, checked=item.checked, basis=basis,
                    generated=item.generated)
    result = session.render_one(job, manifest)
    if result.error is not None:
        fail(item, "render", str(result.error), getattr(result.error, "diagnostics", ()),
              exit_code=result.error.exit_code, error=result.error)
        return
    verb = "unchanged" if result.status == "unchanged" else "wrote"
    item.steps.append(Step("render", message=f"{verb} {display_path(item.png)}",
                           seconds=result.seconds))


def exit_code(items: list[CiItem]) -> int:
    return combine_exit_codes(step.exit_code for item in items for step in item.steps
                              if step.status == "failed")
