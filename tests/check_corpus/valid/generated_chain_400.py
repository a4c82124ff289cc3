"""A chain of 400 links, made at test time: check_urdf indents each generation four more
spaces, so its output grows with the square of the depth; mcar must not recurse."""

LINKS = 400


def urdf() -> str:
    out = ['<robot name="chain_400">']
    out += [f'  <link name="segment_{i}"/>' for i in range(LINKS)]
    out += [f'  <joint name="joint_{i}" type="fixed"><parent link="segment_{i - 1}"/>'
            f'<child link="segment_{i}"/></joint>' for i in range(1, LINKS)]
    out.append("</robot>")
    return "\n".join(out) + "\n"
