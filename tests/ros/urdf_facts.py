"""What a URDF says the tests/ros/ launches must show: its root, links, moving joints and
colours, and every link's pose at joint zero (by yourdfpy, as the reference)."""

from __future__ import annotations


def robot_facts(urdf: str) -> dict:
    """Root, links, movable-joint children and material colours of a URDF text."""
    from lxml import etree

    robot = etree.fromstring(urdf.encode())
    links = [link.get("name") for link in robot.findall("link")]
    children = {joint.find("child").get("link"): joint.get("type")
                for joint in robot.findall("joint")}
    colours = {material.get("name"): [float(v) for v in material.find("color").get(
        "rgba").split()] for material in robot.iter("material")
        if material.find("color") is not None}
    root = next(link for link in links if link not in children)
    return {"root": root, "links": links, "colours": colours,
            "moving": sorted(c for c, kind in children.items() if kind != "fixed")}


def expected_transforms(urdf: str, root: str) -> dict:
    """Every link's 4x4 pose in ``root``'s frame, all joints at zero, by yourdfpy."""
    import io

    import yourdfpy

    model = yourdfpy.URDF.load(io.StringIO(urdf), load_meshes=False,
                               build_collision_scene_graph=False)
    return {link: model.get_transform(frame_to=link, frame_from=root)
            for link in model.link_map}


def matrix(pose) -> object:
    """[x, y, z, qx, qy, qz, qw] as a 4x4 matrix."""
    import numpy as np
    import trimesh.transformations as tf

    x, y, z, qx, qy, qz, qw = pose
    result = tf.quaternion_matrix([qw, qx, qy, qz])
    result[:3, 3] = [x, y, z]
    return np.asarray(result)
