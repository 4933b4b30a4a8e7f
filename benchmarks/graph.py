"""Benchmark: `fishbot graph` vs urdf_to_graphviz, whole processes. Run by hand:

    python benchmarks/graph.py            # prints a Markdown table for docs/performance.md
    python benchmarks/graph.py --quick    # 100 and 1 000 links only

On the generated chain and tree robots (see robots.py), best of several runs, seconds:

- urdf_to_graphviz as users run it, `urdf_to_graphviz ROBOT OUT`: writes OUT.gv, then runs
  `dot -Tpdf` on it;
- the same with no `dot` on PATH, which leaves only its own work (reading the URDF and
  writing the .gv; it then fails to start dot);
- `fishbot graph ROBOT -o x.gv` (reads and checks the robot, writes the same .gv);
- `fishbot graph ROBOT` (the .gv and the PDF, like urdf_to_graphviz).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path

from robots import ros_tool, write_all

FISHBOT = [sys.executable, "-m", "fishbot_urdf"]
if shutil.which("fishbot"):
    FISHBOT = [str(shutil.which("fishbot"))]


def timed(args: Sequence[str], cwd: Path, repeat: int, env: dict[str, str] | None = None) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(
            args,
            cwd=cwd,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            check=False,
        )
        times.append(time.perf_counter() - start)
    return min(times)


def main(quick: bool) -> None:
    tool = ros_tool("urdf_to_graphviz")
    if tool is None:
        sys.exit(
            "urdf_to_graphviz is not installed (Debian/Ubuntu: apt-get install liburdfdom-tools)"
        )
    sizes = (100, 1000) if quick else (100, 1000, 10000)
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        no_dot = folder / "no-dot"
        no_dot.mkdir()
        without_dot = dict(os.environ, PATH=str(no_dot))
        print(
            "| robot | links | urdf_to_graphviz (gv + pdf) | urdf_to_graphviz, no dot (gv) | "
            "fishbot graph -o x.gv | ratio | fishbot graph (gv + pdf) |"
        )
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
        for path in write_all(folder / "robots", sizes):
            kind, size = path.stem.split("_")
            repeat = 1 if int(size) >= 10000 else 3
            real = timed([tool, str(path), "out"], folder, repeat)
            real_gv = timed([tool, str(path), "out"], folder, repeat, without_dot)
            ours_gv = timed([*FISHBOT, "graph", str(path), "-o", "x.gv"], folder, repeat)
            ours = timed([*FISHBOT, "graph", str(path)], folder, repeat)
            print(
                f"| {kind} | {int(size):,} | {real:.3f} | {real_gv:.3f} | {ours_gv:.3f} | "
                f"{real / ours_gv:.1f}x | {ours:.3f} |",
                flush=True,
            )


if __name__ == "__main__":
    main("--quick" in sys.argv[1:])
