"""Start-up: small `fishbot` commands against the floors they stand on, side by side in one
run (medians of whole processes, interleaved, so that the machine's drift hits both sides).
Run by hand, in the venv fishbot-urdf is installed in:

    python benchmarks/startup.py [--runs N]

Rows: `fishbot check first_robot.urdf` against `python -c "import click, lxml.etree"`,
`fishbot --help` against `python -c "import click"`, and `fishbot expand` on the fishbot
xacro against ROS's `xacro` command (the PyPI package's script) on the same file.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import time
from collections.abc import Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIRST = ROOT / "robots" / "fishbot" / "urdf" / "first_robot.urdf"
XACRO = ROOT / "robots" / "fishbot" / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def _tool(name: str) -> list[str]:
    found = shutil.which(name, path=str(Path(sys.executable).parent))
    if found is None:
        sys.exit(f"{name} is not installed in this environment: pip install -e '.[test]'")
    return [found]


def _pair(ours: Sequence[str], floor: Sequence[str], runs: int) -> tuple[float, float]:
    """Median seconds of each command, run alternately."""
    times: tuple[list[float], list[float]] = ([], [])
    for _ in range(runs):
        for side, command in enumerate((ours, floor)):
            start = time.perf_counter()
            subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times[side].append(time.perf_counter() - start)
    return statistics.median(times[0]), statistics.median(times[1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=21)
    runs = parser.parse_args(argv).runs
    fishbot, xacro, python = _tool("fishbot"), _tool("xacro"), [sys.executable]
    rows = [
        (
            '`fishbot check first_robot.urdf` / `python -c "import click, lxml.etree"`',
            [*fishbot, "check", str(FIRST)],
            [*python, "-c", "import click, lxml.etree"],
            1.3,
        ),
        (
            '`fishbot --help` / `python -c "import click"`',
            [*fishbot, "--help"],
            [*python, "-c", "import click"],
            1.2,
        ),
        (
            "`fishbot expand` / `xacro` on the fishbot xacro",
            [*fishbot, "expand", str(XACRO)],
            [*xacro, str(XACRO)],
            1.25,
        ),
    ]
    print("| measure | fishbot (ms) | floor (ms) | ratio | goal |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for label, ours, floor, goal in rows:
        mine, theirs = _pair(ours, floor, runs)
        print(
            f"| {label} | {mine * 1000:.0f} | {theirs * 1000:.0f} | {mine / theirs:.2f}x | "
            f"<= {goal}x |"
        )


if __name__ == "__main__":
    main()
