"""The faces a scene format declares (COLLADA, glTF), each geometry counted once per
instance through the node graph (nodes may instance nodes: counted with memory, never
expanded), and the images and buffers it reads. Part of :mod:`.mesh_limits`' scan.
"""

from __future__ import annotations

import urllib.parse
from pathlib import Path

from .mesh_scan import MeshBroken, MeshScan, declared_count, find_beside


def _instanced(own: dict, children: dict, roots, shown: str) -> int:
    """Faces drawn: each node's own faces once per path from a root to it. Counted over
    the graph with memory (a node instanced twice by each of 30 nested nodes is 2**30
    instances, computed in 30 steps); a cycle adds nothing."""
    memo: dict = {}
    visiting: set = set()

    def faces(node) -> int:
        if node in memo:
            return memo[node]
        if node in visiting:
            return 0
        visiting.add(node)
        total = own.get(node, 0) + sum(faces(child) for child in children.get(node, ()))
        visiting.discard(node)
        memo[node] = total
        return total

    try:
        return sum(faces(root) for root in roots)
    except RecursionError:
        raise MeshBroken("its nodes are nested too deep to count", file=shown) from None


_DAE_PRIMITIVES = {"triangles", "polylist", "polygons", "trifans", "tristrips", "lines",
                   "linestrips"}


def dae(handle, size: int, shown: str, folder) -> MeshScan:
    """Counted in one pass of lxml's iterparse, no entities, no network; element text
    (the numbers) dropped as it goes. A file that is not well-formed XML is counted again
    as libxml2 recovers it: that is what the reader hands pycollada (:mod:`.collada`)."""
    from lxml import etree

    start = handle.tell()
    try:
        return _dae_counted(handle, shown, folder, recover=False)
    except etree.XMLSyntaxError:
        handle.seek(start)
    try:
        return _dae_counted(handle, shown, folder, recover=True)
    except etree.LxmlError as error:
        raise MeshBroken(f"not well-formed COLLADA: {error}", file=shown) from None


def _dae_counted(handle, shown: str, folder, recover: bool) -> MeshScan:
    from lxml import etree

    geometry_faces: dict[str, int] = {}
    children: dict[str, list] = {}  # "n:ID" or "#anon" node -> geometries / nodes it holds
    own: dict[str, int] = {}
    scenes: list[str] = []
    vertices = 0
    images: list[str] = []
    stack: list[str] = []  # the node (or scene) elements around the current element
    geometry = None
    anonymous = 0
    try:
        for event, element in etree.iterparse(handle, events=("start", "end"),
                                              resolve_entities=False, no_network=True,
                                              load_dtd=False, huge_tree=False,
                                              remove_comments=True, remove_pis=True,
                                              recover=recover):
            tag = etree.QName(element).localname if isinstance(element.tag, str) else ""
            if event == "start":
                if tag == "geometry":
                    geometry = "g:" + (element.get("id") or "")
                elif tag in _DAE_PRIMITIVES and geometry is not None:
                    geometry_faces[geometry] = geometry_faces.get(geometry, 0) + \
                        declared_count(element.get("count") or "0", shown)
                elif tag == "float_array":
                    vertices += declared_count(element.get("count") or "0", shown) // 3
                elif tag in ("node", "visual_scene"):
                    anonymous += 1
                    name = "n:" + (element.get("id") or f"#{anonymous}")
                    if tag == "visual_scene":
                        scenes.append(name)
                    elif stack:
                        children.setdefault(stack[-1], []).append(name)
                    stack.append(name)
                elif tag in ("instance_geometry", "instance_node") and stack:
                    url = (element.get("url") or "").lstrip("#")
                    prefix = "g:" if tag == "instance_geometry" else "n:"
                    children.setdefault(stack[-1], []).append(prefix + url)
                continue
            if tag == "geometry":
                geometry = None
            elif tag in ("node", "visual_scene") and stack:
                stack.pop()
            elif tag in ("init_from", "ref") and element.text:
                images.append(element.text)
            element.clear(keep_tail=False)
            while element.getprevious() is not None:  # done with: let it go
                del element.getparent()[0]
    except etree.XMLSyntaxError:
        raise
    except etree.LxmlError as error:
        raise MeshBroken(f"not well-formed COLLADA: {error}", file=shown) from None
    own.update(geometry_faces)
    faces = _instanced(own, children, scenes, shown) if scenes else sum(geometry_faces.values())
    return MeshScan(faces, vertices, _images(images, folder))


def _images(names, folder) -> tuple[Path, ...]:
    if folder is None:
        return ()
    found = []
    for name in dict.fromkeys(names):
        name = name.strip()
        if name.startswith("data:") or "://" in name and not name.startswith("file://"):
            continue
        for candidate in (name, urllib.parse.unquote(name.removeprefix("file://"))):
            path = find_beside(folder, candidate)
            if path is not None:
                found.append(path)
    return tuple(dict.fromkeys(found))


def _gltf_document(handle, size: int, shown: str, binary: bool) -> dict:
    if binary:
        head = handle.read(20)
        length = int.from_bytes(head[12:16], "little") if len(head) == 20 else -1
        if head[16:20] != b"JSON" or not 0 <= length <= size:
            raise MeshBroken("not a GLB file (no JSON chunk first)", file=shown)
        text = handle.read(length)
    else:
        text = handle.read()
    import json  # only for a glTF: every check imports this module

    try:
        document = json.loads(text)
    except (ValueError, RecursionError) as error:
        raise MeshBroken(f"its glTF JSON does not parse: {error}", file=shown) from None
    if not isinstance(document, dict):
        raise MeshBroken("its glTF JSON is not an object", file=shown)
    return document


def gltf(handle, size: int, shown: str, folder, binary: bool = False) -> MeshScan:
    document = _gltf_document(handle, size, shown, binary)

    def listed(key):
        value = document.get(key)
        return value if isinstance(value, list) else []

    def entry(key, index) -> dict:
        items = listed(key)
        ok = isinstance(index, int) and 0 <= index < len(items) and isinstance(items[index], dict)
        return items[index] if ok else {}

    def count(index) -> int:
        value = entry("accessors", index).get("count")
        return value if isinstance(value, int) and value >= 0 else 0

    own: dict = {}
    vertices = 0
    for number, mesh in enumerate(listed("meshes")):
        faces = 0
        primitives = mesh.get("primitives") if isinstance(mesh, dict) else None
        for primitive in primitives if isinstance(primitives, list) else []:
            if not isinstance(primitive, dict):
                continue
            attributes = primitive.get("attributes")
            position = attributes.get("POSITION") if isinstance(attributes, dict) else None
            vertices += count(position)
            corners = count(primitive["indices"]) if "indices" in primitive else count(position)
            faces += corners // 3
        own[f"m{number}"] = faces
    children: dict = {}
    for number, node in enumerate(listed("nodes")):
        if isinstance(node, dict):
            kids = [f"n{c}" for c in node.get("children") or [] if isinstance(c, int)] \
                if isinstance(node.get("children"), list) else []
            if isinstance(node.get("mesh"), int):
                kids.append(f"m{node['mesh']}")
            children[f"n{number}"] = kids
    roots = [f"n{n}" for scene in listed("scenes") if isinstance(scene, dict)
             for n in (scene.get("nodes") if isinstance(scene.get("nodes"), list) else [])
             if isinstance(n, int)]
    faces = _instanced(own, children, roots, shown) if roots else sum(own.values())
    uris = [item.get("uri") for key in ("buffers", "images") for item in listed(key)
            if isinstance(item, dict) and isinstance(item.get("uri"), str)]
    return MeshScan(faces, vertices, _images(uris, folder))


def glb(handle, size: int, shown: str, folder) -> MeshScan:
    return gltf(handle, size, shown, folder, binary=True)
