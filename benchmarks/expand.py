"""Benchmark: `fishbot expand` vs the xacro command, whole processes. Run by hand:

    python benchmarks/expand.py         # prints Markdown lines for docs/performance.md

On the fishbot (robots/fishbot/urdf/fishbot/fishbot.urdf.xacro) and on a generated xacro
file with 1 000 macro calls. The xacro command resolves $(find) through a stand-in
ament_index_python (tests/ament_stub); both tools run in this Python.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FISHBOT = ROOT / "robots" / "fishbot"
TOP = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
XACRO = [sys.executable, "-c", "import sys, xacro; sys.exit(xacro.main())"]
OURS = [sys.executable, "-m", "fishbot_urdf", "expand"]


def generated(calls: int) -> str:
    """A robot of ``calls`` links, each made by a macro call with its own numbers."""
    lines = [
        '<robot name="many" xmlns:xacro="http://www.ros.org/wiki/xacro">',
        '  <xacro:property name="size" value="0.1"/>',
        '  <xacro:macro name="part" params="i parent x:=0 *origin">',
        '    <link name="link_${i}"><visual><xacro:insert_block name="origin"/>',
        '      <geometry><box size="${size} ${size * 2} ${x}"/></geometry></visual>',
        '      <inertial><mass value="${1 + i / 1000}"/>',
        '        <inertia ixx="${x * x / 12}" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>',
        "      </inertial></link>",
        '    <joint name="joint_${i}" type="revolute"><parent link="${parent}"/>',
        '      <child link="link_${i}"/><xacro:insert_block name="origin"/>',
        '      <limit effort="1" velocity="1" lower="${-pi}" upper="${pi}"/></joint>',
        "  </xacro:macro>",
        '  <link name="link_0"/>',
    ]
    for i in range(1, calls + 1):
        lines.append(
            f'  <xacro:part i="{i}" parent="link_{(i - 1) // 2}" x="{i / 100}">'
            f'<origin xyz="0 0 {i / 1000}"/></xacro:part>'
        )
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def best(args: list[str], repeat: int, env: dict[str, str]) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(args, stdout=subprocess.DEVNULL, check=True, env=env, cwd=ROOT)
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "tests" / "ament_stub")
    env["FISHBOT_TEST_PACKAGES"] = f"fishbot_description={FISHBOT}"
    with tempfile.TemporaryDirectory() as folder:
        big = Path(folder) / "many.urdf.xacro"
        big.write_text(generated(1000), encoding="utf-8")
        for label, path, repeat in (("the fishbot", TOP, 10), ("1 000 macro calls", big, 3)):
            theirs = best([*XACRO, str(path)], repeat, env)
            ours = best([*OURS, str(path)], repeat, env)
            print(
                f"- {label}: xacro {theirs:.3f} s, `fishbot expand` {ours:.3f} s "
                f"({(ours / theirs - 1) * 100:+.0f}%)"
            )
    print(f"- machine: {os.cpu_count()} cores, Python {sys.version.split()[0]}")


if __name__ == "__main__":
    main()
