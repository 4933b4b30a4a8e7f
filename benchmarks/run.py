"""Benchmarks: fishbot vs check_urdf, whole process and in process. Run by hand:

    python benchmarks/run.py            # prints a Markdown table for the README

Times are the best of several runs (seconds) on generated chain and tree robots of 100,
1 000 and 10 000 links (see robots.py), the fishbot's first_robot.urdf, and the
example-robot-data corpus.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from lxml import etree

import fishbot_urdf
from robots import ros_tool, write_all

HERE = Path(__file__).resolve().parent
FIRST = HERE.parent / "robots" / "fishbot" / "urdf" / "first_robot.urdf"
FISHBOT = [sys.executable, "-m", "fishbot_urdf"]
if shutil.which("fishbot"):
    FISHBOT = [str(shutil.which("fishbot"))]


def best(run: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def process(args: Sequence[str], repeat: int) -> float:
    def run() -> None:
        subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)

    return best(run, repeat)


def corpus() -> list[Path]:
    share = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share"
    return sorted((share / "example-robot-data" / "robots").rglob("*.urdf"))


def main() -> None:
    check_urdf = ros_tool("check_urdf")
    with tempfile.TemporaryDirectory() as folder:
        print(
            "| robot | links | check_urdf (s) | fishbot check (s) | ratio | lxml parse (s) | "
            "fishbot_urdf.load (s) | load / lxml |"
        )
        print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for path in write_all(Path(folder)):
            kind, size = path.stem.split("_")
            repeat = 3 if int(size) >= 10000 else 7
            ours = process([*FISHBOT, "check", str(path)], repeat)
            theirs = process([check_urdf, str(path)], repeat) if check_urdf else float("nan")
            data = path.read_bytes()
            parser = etree.XMLParser(resolve_entities=False, no_network=True)
            bare = best(lambda d=data, x=parser: etree.fromstring(d, x), repeat)
            load = best(lambda p=path: fishbot_urdf.load(p), repeat)
            print(
                f"| {kind} | {int(size):,} | {theirs:.3f} | {ours:.3f} | {theirs / ours:.2f}x | "
                f"{bare:.3f} | {load:.3f} | {load / bare:.1f}x |"
            )
    print()
    pass_time = process([sys.executable, "-c", "pass"], 15)
    small = process([*FISHBOT, "check", str(FIRST)], 15)
    small_real = process([check_urdf, str(FIRST)], 15) if check_urdf else float("nan")
    print(
        f"- first_robot.urdf: `fishbot check` {small * 1000:.0f} ms, check_urdf "
        f"{small_real * 1000:.0f} ms, `python3 -c pass` {pass_time * 1000:.0f} ms "
        f"({small / pass_time:.1f}x)"
    )
    files = [str(p) for p in corpus()]
    if files:
        many = process([*FISHBOT, "check", *files], 3)
        each = (
            best(
                lambda: [
                    subprocess.run([check_urdf, f], capture_output=True, check=False) for f in files
                ],
                3,
            )
            if check_urdf
            else float("nan")
        )
        print(
            f"- {len(files)} corpus files: one `fishbot check` {many:.2f} s, one check_urdf "
            f"per file {each:.2f} s"
        )
    print(f"- machine: {os.cpu_count()} cores, Python {sys.version.split()[0]}")


if __name__ == "__main__":
    main()
