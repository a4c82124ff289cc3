"""What the attack tests of tests/untrusted/ share: the package.xml of the hostile package
``atk`` they build, as a pull request would commit it."""

PACKAGE_XML = """<package format="2"><name>atk</name><version>0.0.0</version>
<description>x</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
</package>
"""
