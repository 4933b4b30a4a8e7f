"""Generate synthetic robots for the benchmarks: a chain (each link the child of the last)
and a balanced binary tree, each of N links."""

from __future__ import annotations

import sys
from pathlib import Path


def _link(i: int) -> str:
    return (
        f'  <link name="link_{i}">\n'
        '    <inertial><mass value="0.1"/>'
        '<inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>\n'
        '    <visual><geometry><box size="0.05 0.05 0.1"/></geometry></visual>\n'
        '    <collision><geometry><box size="0.05 0.05 0.1"/></geometry></collision>\n'
        "  </link>\n"
    )


def _joint(i: int, parent: int) -> str:
    return (
        f'  <joint name="joint_{i}" type="revolute">\n'
        f'    <parent link="link_{parent}"/>\n    <child link="link_{i}"/>\n'
        '    <origin xyz="0 0 0.1" rpy="0 0 0.1"/>\n    <axis xyz="0 0 1"/>\n'
        '    <limit lower="-1" upper="1" effort="10" velocity="1"/>\n'
        "  </joint>\n"
    )


def robot(kind: str, size: int) -> str:
    """URDF text of a ``kind`` ('chain' or 'tree') robot with ``size`` links."""
    parts = [f'<?xml version="1.0"?>\n<robot name="{kind}_{size}">\n']
    parts.extend(_link(i) for i in range(size))
    for i in range(1, size):
        parts.append(_joint(i, i - 1 if kind == "chain" else (i - 1) // 2))
    parts.append("</robot>\n")
    return "".join(parts)


def write_all(folder: Path, sizes: tuple[int, ...] = (100, 1000, 10000)) -> list[Path]:
    """Write chain and tree robots of every size into ``folder``; return their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for kind in ("chain", "tree"):
        for size in sizes:
            path = folder / f"{kind}_{size}.urdf"
            path.write_text(robot(kind, size))
            paths.append(path)
    return paths


if __name__ == "__main__":
    for written in write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "benchmarks/out")):
        print(written)
