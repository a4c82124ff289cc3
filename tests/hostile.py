"""What the attack tests of tests/untrusted/ share: the package.xml of the hostile package
``atk`` they build, as a pull request would commit it, and the meshes they plant."""

import struct

PACKAGE_XML = """<package format="2"><name>atk</name><version>0.0.0</version>
<description>x</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
</package>
"""


def files_holding(folder, marker: bytes) -> list[str]:
    """The files under ``folder`` (relative, sorted) whose bytes hold ``marker``: where a
    planted secret ended up. Links are not counted: a test plants them itself."""
    return sorted(str(path.relative_to(folder)) for path in folder.rglob("*")
                  if path.is_file() and not path.is_symlink() and marker in path.read_bytes())


def cube_stl(side: float, header: bytes = b"cube") -> bytes:
    """A binary STL cube of side ``side`` (12 triangles) centred on its origin, whose
    80-byte header starts with ``header`` (a marker an attack must never get out)."""
    s = side / 2
    corners = [(x, y, z) for x in (-s, s) for y in (-s, s) for z in (-s, s)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
             (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    data = header.ljust(80, b" ") + struct.pack("<I", len(faces))
    for face in faces:
        data += struct.pack("<3f", 0, 0, 0)
        for index in face:
            data += struct.pack("<3f", *corners[index])
        data += b"\0\0"
    return data
