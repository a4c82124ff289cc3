"""What the attack tests of tests/untrusted/ share: the package.xml of the hostile package
``atk`` they build, as a pull request would commit it."""

PACKAGE_XML = """<package format="2"><name>atk</name><version>0.0.0</version>
<description>x</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
</package>
"""


def files_holding(folder, marker: bytes) -> list[str]:
    """The files under ``folder`` (relative, sorted) whose bytes hold ``marker``: where a
    planted secret ended up. Links are not counted: a test plants them itself."""
    return sorted(str(path.relative_to(folder)) for path in folder.rglob("*")
                  if path.is_file() and not path.is_symlink() and marker in path.read_bytes())
