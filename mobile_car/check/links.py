"""Link rules: geometry and materials (inertia: :mod:`mobile_car.check.inertia`).

urdfdom logs most of these problems and then drops the visual or collision (``check_urdf``
still exits 0): a robot silently missing a wheel in rviz. Here they are errors.

A material's colour is the exception: urdfdom, rviz and Gazebo load a robot whose material
is undefined, has no colour, or a colour they cannot read, and draw the part in a default
colour. Nothing but the look changes, so those are warnings (W216, W217; errors under
``--strict``), and mcar's pictures and exports draw such a part in the default grey too.
"""

from __future__ import annotations

from .context import MAX_LENGTH, MAX_SCALE, Reporter, has_xacro_expression
from .urdf_model import tag_name
from .urdf_reader import Body, Link, Robot

SHAPES = {"box": ("size",), "cylinder": ("radius", "length"), "sphere": ("radius",),
          "mesh": ("filename",)}


def material_colours(robot: Robot, report: Reporter) -> set[str]:
    """Names of top-level materials that define a colour or texture; reports the others."""
    defined = set()
    for element, parts in robot.materials:
        name = element.get("name")
        if name is None:
            continue  # E107, reported with the other names
        usable = _material_body(parts, f"material '{name}'", report)
        if usable is not False:  # (None: its colour is wrong, reported as such)
            defined.add(name)
        else:
            report.add("W216", element, f"material '{name}' has neither <color rgba=...> "
                       "nor <texture filename=...>: drawn in the default grey")
    return defined


def _material_body(parts: dict | None, owner: str, report: Reporter) -> bool | None:
    """True if a material's parts (None: it has none) define a usable colour or texture;
    None if they define one that is wrong (reported here, W217: the material is defined, so
    saying it is not, W216, beside the real problem would send the user the wrong way);
    False if they define neither."""
    if not parts:
        return False  # a reference by name: <material name="grey"/>
    color = parts.get("color")
    texture = parts.get("texture")
    ok = texture is not None and texture.get("filename") is not None
    rgba_text = None if color is None else color.get("rgba")
    if rgba_text is not None:
        rgba = report.numbers(color, "rgba", 4, owner, rule="W217")
        if rgba is not None and not all(0.0 <= c <= 1.0 for c in rgba):
            report.add("W217", color, f"{owner}: rgba=\"{rgba_text}\" has a component "
                       "outside 0..1; urdfdom drops the colour")
            return ok or None
        if rgba is not None or has_xacro_expression(rgba_text):
            ok = True
        elif not ok:
            return None  # unreadable numbers: W217 from report.numbers
    return ok


def check_links(links: list[Link], report: Reporter, materials: set[str],
                top_level: set) -> None:
    """Every visual and collision of ``links``; ``materials``: names defined with a colour
    so far (grows as visuals define more); ``top_level``: names of top-level materials."""
    for link in links:
        owner = f"link '{link.name}'" if link.name else "link"
        for body in link.visuals:
            report.origin(body.parts.get("origin"), owner)
            _check_geometry(body, owner, report)
            if "material" in body.parts:
                _check_visual_material(body, owner, materials, top_level, report)
        for body in link.collisions:
            report.origin(body.parts.get("origin"), owner)
            _check_geometry(body, owner, report)


def _check_geometry(body: Body, owner: str, report: Reporter) -> None:
    element, geometry, shapes = body.element, body.parts.get("geometry"), body.shapes
    where = f"{owner} <{element.tag}>"
    if geometry is None:
        report.add("E110", element, f"{where} has no <geometry>")
        return
    if not shapes:
        report.add("E110", geometry, f"{where}: <geometry> is empty; put a box, "
                   "cylinder, sphere or mesh in it")
        return
    shape = shapes[0]
    for extra in shapes[1:]:
        report.add("W209", extra, f"{where}: <geometry> holds more than one shape; urdfdom "
                                  f"reads only the first, <{tag_name(shape)}>")
    # The verdict depends on the shape's name and attributes only: check each once.
    report.once_clean((shape.tag, *shape.items()), _check_shape, shape, where,
                      owner, report)


def _check_shape(shape, where: str, owner: str, report: Reporter) -> None:
    kind = tag_name(shape)
    if kind not in SHAPES:
        if not kind.startswith("xacro:"):
            report.add("E111", shape, f"{where}: unknown geometry <{kind}>; urdfdom 3.0 "
                       "reads box, cylinder, sphere and mesh")
        return
    missing = [attr for attr in SHAPES[kind] if shape.get(attr) is None]
    if missing:
        report.add("E112", shape, f"{where}: <{kind}> has no "
                   f"{' and no '.join(missing)}")
    if kind == "box":
        size = report.numbers(shape, "size", 3, owner)
        _positive(size, shape, "size", where, report)
        report.bounded(shape, "size", size, MAX_LENGTH, " m", where)
    elif kind == "mesh":
        scale = report.numbers(shape, "scale", 3, owner)
        if scale is not None and 0 in scale:
            report.add("E113", shape, f"{where}: mesh scale=\"{shape.get('scale')}\" "
                       "has a 0, which flattens the mesh")
        report.bounded(shape, "scale", scale, MAX_SCALE, "", where)
    else:
        for attr in ("radius", "length") if kind == "cylinder" else ("radius",):
            value = report.number(shape, attr, owner)
            values = None if value is None else (value,)
            _positive(values, shape, attr, where, report)
            report.bounded(shape, attr, values, MAX_LENGTH, " m", where)


def _positive(values, shape, attr: str, where: str, report: Reporter) -> None:
    if values is not None and min(values) <= 0:
        report.add("E113", shape, f"{where}: <{tag_name(shape)} {attr}="
                   f"\"{shape.get(attr)}\"> must be > 0")


def _check_visual_material(body: Body, owner: str, materials: set[str], top_level: set,
                           report: Reporter) -> None:
    material = body.parts["material"]
    name = material.get("name")
    if name is None:
        report.add("E107", material, f"{owner} <visual>: <material> has no name; "
                   "urdfdom drops the visual")
        return
    if has_xacro_expression(name):
        return
    if _material_body(body.material, f"{owner} material '{name}'", report) is not False:
        # urdfdom registers a material defined in a visual for the links after it (one
        # with a wrong colour is reported where it is defined, not where it is used).
        materials.add(name)
    elif name not in materials and name not in top_level:  # (colourless top-level: W216 there)
        report.add("W216", material, f"{owner} uses material '{name}', which is not "
                   "defined with a colour before it (a top-level <material> or an earlier "
                   "visual): drawn in the default grey, as urdfdom and rviz do")
