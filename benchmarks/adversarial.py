"""Adversarial input of about 1 MB for every text scan fishbot runs: each case must finish
within a time budget. Run by hand:

    python benchmarks/adversarial.py              # every case, budget 2 s
    python benchmarks/adversarial.py --budget 5 --size 4000000 comment

A case is a file built to make a backtracking or repeated scan slow (a long run of openers
with no closer, a quote that never ends, white space without end), run through the real
command in a process of its own and stopped at ten times the budget. The exit status is 1
when any case is over the budget. check_urdf's time on the same file is shown beside, where
it is installed.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from robots import ros_tool

FISHBOT = [sys.executable, "-m", "fishbot_urdf"]
ROBOT = b'<robot name="r">'
XACRO = b'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'


def _fill(prefix: bytes, unit: bytes, size: int, suffix: bytes = b"") -> bytes:
    return prefix + unit * max(1, (size - len(prefix) - len(suffix)) // len(unit)) + suffix


# name -> (file name, the bytes of a file of about `size` bytes, the command's arguments)
Case = tuple[str, Callable[[int], bytes], list[str]]
CASES: dict[str, Case] = {
    "newlines in an open quote in a comment": (
        "r.urdf",
        lambda n: _fill(ROBOT + b'<!-- x="', b"\n", n),
        ["check"],
    ),
    "newlines after a quote in a closed comment": (
        "r.urdf",
        lambda n: _fill(ROBOT + b'<!-- x="', b"\n", n, b" --></robot>"),
        ["check"],
    ),
    "tabs after quotes in a closed comment": (
        "r.urdf",
        lambda n: _fill(ROBOT + b"<!--", b'="\t', n, b" --></robot>"),
        ["check"],
    ),
    "many comments": ("r.urdf", lambda n: _fill(ROBOT, b"<!-- -->", n, b"</robot>"), ["check"]),
    "many markers in a closed comment": (
        "r.urdf",
        lambda n: _fill(
            ROBOT + b'<link name="a"/><!--', b" fishbot: ignore[", n, b"-->" + b"</robot>"
        ),
        ["check"],
    ),
    "newlines in an open quote": (
        "r.urdf",
        lambda n: _fill(ROBOT + b'<link name="', b"\n", n),
        ["check"],
    ),
    "tabs in an open quote after =": (
        "r.urdf",
        lambda n: _fill(ROBOT + b"=", b'"\t', n),
        ["check"],
    ),
    "unclosed comments": ("r.urdf", lambda n: _fill(ROBOT, b"<!--", n), ["check"]),
    "unclosed CDATA sections": ("r.urdf", lambda n: _fill(ROBOT, b"<![CDATA[", n), ["check"]),
    "unclosed doctype subsets": ("r.urdf", lambda n: _fill(b"", b"<!DOCTYPE [", n), ["check"]),
    "unclosed processing instructions": ("r.urdf", lambda n: _fill(ROBOT, b"<?a ", n), ["check"]),
    "unclosed xml declarations": ("r.urdf", lambda n: _fill(b"", b"<?xml ", n), ["check"]),
    "declaration with endless encoding": (
        "r.urdf",
        lambda n: _fill(b'<?xml version="1.0" encoding="', b"a", n, b'"?>' + ROBOT + b"</robot>"),
        ["check"],
    ),
    "many encoding words": ("r.urdf", lambda n: _fill(b"<?xml ", b"encoding ", n), ["check"]),
    "unclosed character references": ("r.urdf", lambda n: _fill(ROBOT, b"&#", n), ["check"]),
    "many default namespaces": ("r.urdf", lambda n: _fill(b"<robot ", b'xmlns = "', n), ["check"]),
    "open angle brackets": ("r.urdf", lambda n: _fill(ROBOT, b"<", n), ["check"]),
    "equals signs and spaces": ("r.urdf", lambda n: _fill(ROBOT + b"<link ", b"= ", n), ["check"]),
    "many attributes": ("r.urdf", lambda n: _fill(b"<robot ", b'a="1" ', n, b"/>"), ["check"]),
    "unclosed doctype": ("r.urdf", lambda n: _fill(b"<!DOCTYPE r [", b"<!ENTITY ", n), ["check"]),
    "deep nesting": ("r.urdf", lambda n: _fill(ROBOT, b"<a>", n), ["check"]),
    "one long line of text": ("r.urdf", lambda n: _fill(ROBOT, b"x", n, b"</robot>"), ["check"]),
    "many suppression markers": (
        "r.urdf",
        lambda n: _fill(ROBOT + b"<!--", b" fishbot: ignore[", n, b"-->" + b"</robot>"),
        ["check"],
    ),
    "many loose suppression words": (
        "r.urdf",
        lambda n: _fill(ROBOT + b"<!--", b"fishbot:ignore ", n, b"-->" + b"</robot>"),
        ["check"],
    ),
    "xacro: unclosed ${": (
        "r.xacro",
        lambda n: _fill(XACRO + b'<link name="', b"${", n, b'"/></robot>'),
        ["expand"],
    ),
    "xacro: unclosed $(": (
        "r.xacro",
        lambda n: _fill(XACRO + b'<link name="', b"$(", n, b'"/></robot>'),
        ["expand"],
    ),
    "xacro: many dollars": (
        "r.xacro",
        lambda n: _fill(XACRO + b'<link name="', b"$", n, b'"/></robot>'),
        ["expand"],
    ),
    "graph of an unclosed quote": (
        "r.urdf",
        lambda n: _fill(ROBOT + b'<link name="', b"\n", n),
        ["graph", "--format", "text", "-o", "-"],
    ),
}

PACKAGE_CASES: dict[str, Callable[[int], bytes]] = {
    "package.xml: unclosed comments": lambda n: _fill(b"<package>", b"<!--", n),
    "package.xml: unclosed name": lambda n: _fill(b"<package>", b"<name ", n),
    "package.xml: many comments": lambda n: _fill(b"<package>", b"<!-- -->", n, b"</package>"),
}


def run(command: list[str], budget: float) -> float | None:
    start = time.perf_counter()
    try:
        subprocess.run(command, capture_output=True, timeout=budget * 10, check=False)
    except subprocess.TimeoutExpired:
        return None
    return time.perf_counter() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--budget", type=float, default=2.0, help="seconds per case")
    parser.add_argument("--size", type=int, default=1_000_000, help="bytes per file")
    parser.add_argument("only", nargs="*", help="run the cases whose name contains this")
    options = parser.parse_args()
    check_urdf = ros_tool("check_urdf")
    over = 0
    print(f"| case ({options.size:,} bytes) | fishbot | check_urdf |")
    print("| --- | ---: | ---: |")
    with tempfile.TemporaryDirectory() as folder:
        rows: list[tuple[str, list[str], list[str] | None]] = []
        for name, (file_name, build, args) in CASES.items():
            path = Path(folder) / name.replace(" ", "_").replace(":", "").replace("$", "d")
            path.mkdir()
            target = path / file_name
            target.write_bytes(build(options.size))
            ours = [*FISHBOT, *args, str(target)]
            theirs = [check_urdf, str(target)] if check_urdf and args == ["check"] else None
            rows.append((name, ours, theirs))
        for name, build_package in PACKAGE_CASES.items():
            path = Path(folder) / name.replace(" ", "_").replace(":", "").replace(".", "_")
            (path / "pkg" / "urdf").mkdir(parents=True)
            (path / "pkg" / "package.xml").write_bytes(build_package(options.size))
            robot = path / "pkg" / "urdf" / "r.xacro"
            robot.write_bytes(XACRO + b'<link name="$(find nothing_here)"/></robot>')
            rows.append((name, [*FISHBOT, "expand", str(robot)], None))
        for name, ours, theirs in rows:
            if options.only and not any(word in name for word in options.only):
                continue
            mine = run(ours, options.budget)
            other = run(theirs, options.budget) if theirs else None
            shown = f"> {options.budget * 10:.0f} s" if mine is None else f"{mine:.2f} s"
            reference = "" if theirs is None else ("timeout" if other is None else f"{other:.2f} s")
            late = mine is None or mine > options.budget
            over += late
            print(
                f"| {name} | {shown}{' (over budget)' if late else ''} | {reference} |", flush=True
            )
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
