"""Generate synthetic robots for the benchmarks: a chain (each link the child of the last)
and a balanced binary tree, each of N links."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path


def ros_tool(name: str) -> str | None:
    """The system's check_urdf or urdf_to_graphviz (liburdfdom-tools, or a ROS install): no
    Python environment's bin folder is searched, where pin's cmeel-urdfdom puts another
    build of them."""
    folders = [f for f in os.environ.get("PATH", "").split(os.pathsep) if f]
    kept = [
        f
        for f in folders
        if not (Path(f).resolve().parent / "pyvenv.cfg").exists()
        and not (Path(f).resolve().parent / "conda-meta").is_dir()
    ]
    return shutil.which(name, path=os.pathsep.join(kept))


def _value(base: float, i: int) -> str:
    # Every link gets its own numbers, as in a robot exported from CAD (a reader cannot
    # reuse the value it parsed for the link before).
    return f"{base * (1 + i * 1e-6):.9g}"


def _link(i: int) -> str:
    mass, moment = _value(0.1, i), _value(1e-4, i)
    width, height = _value(0.05, i), _value(0.1, i)
    return (
        f'  <link name="link_{i}">\n'
        f'    <inertial><mass value="{mass}"/><inertia ixx="{moment}" ixy="0" ixz="0" '
        f'iyy="{moment}" iyz="0" izz="{moment}"/></inertial>\n'
        f'    <visual><geometry><box size="{width} {width} {height}"/></geometry></visual>\n'
        f'    <collision><geometry><box size="{width} {width} {height}"/></geometry></collision>\n'
        "  </link>\n"
    )


def _joint(i: int, parent: int) -> str:
    offset, turn = _value(0.1, i), _value(0.1, i + 1)
    return (
        f'  <joint name="joint_{i}" type="revolute">\n'
        f'    <parent link="link_{parent}"/>\n    <child link="link_{i}"/>\n'
        f'    <origin xyz="0 0 {offset}" rpy="0 0 {turn}"/>\n    <axis xyz="0 0 1"/>\n'
        f'    <limit lower="-{_value(1, i)}" upper="{_value(1, i)}" effort="{_value(10, i)}" '
        f'velocity="{_value(1, i)}"/>\n'
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
