"""Forward kinematics per configuration: fishbot_urdf.Kinematics (numpy, batched) against
pinocchio (one forwardKinematics + updateFramePlacements call per configuration), side by
side in one run. Run by hand, with the test extra installed (it brings pin):

    python benchmarks/fk.py

Robots: example-robot-data's UR5 (6 joints), a 100-link chain, and a 10,000-link chain
(ours only: the evaluation's peak allocation, traced in a child process, against the
result's B x links x 16 floats).
Each time is the best of 5 runs of the whole batch, divided by the batch size.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pinocchio as pin
from run import best

import fishbot_urdf
from robots import write_all


def _ur5() -> Path:
    share = Path(sys.prefix) / "lib"
    found = sorted(share.rglob("example-robot-data/robots/ur_description/urdf/ur5_robot.urdf"))
    if not found:
        sys.exit("example-robot-data is not installed: pip install -e '.[test]'")
    return found[0]


def _pair(path: Path, batch: int) -> tuple[float, float]:
    """Seconds per configuration: ours, pinocchio's."""
    kin = fishbot_urdf.Kinematics(fishbot_urdf.load(path))
    model = pin.buildModelFromUrdf(str(path))
    data = model.createData()
    rng = np.random.default_rng(0)
    qs = rng.uniform(-1, 1, (batch, len(kin.variables)))
    pin_qs = [pin.randomConfiguration(model) for _ in range(batch)]

    def theirs() -> None:
        for q in pin_qs:
            pin.forwardKinematics(model, data, q)
            pin.updateFramePlacements(model, data)

    return best(lambda: kin.forward(qs), 5) / batch, best(theirs, 5) / batch


_MEMORY = """
import sys, tracemalloc, numpy as np, fishbot_urdf
kin = fishbot_urdf.Kinematics(fishbot_urdf.load(sys.argv[1]))
q = np.zeros((int(sys.argv[2]), len(kin.variables)))
tracemalloc.start()
poses = kin.forward(q)
print(len(kin.links), tracemalloc.get_traced_memory()[1])
"""


def main() -> None:
    rows = []
    arm = _ur5()
    for batch in (1, 1024, 8192):
        ours, theirs = _pair(arm, batch)
        rows.append(("UR5 (6 joints)", batch, ours, theirs))
    with tempfile.TemporaryDirectory() as folder:
        written = {p.stem: p for p in write_all(Path(folder), sizes=(100, 10_000))}
        chain100 = written["chain_100"]
        for batch in (1, 1024):
            ours, theirs = _pair(chain100, batch)
            rows.append(("chain, 100 links", batch, ours, theirs))
        print("| robot | B | fishbot_urdf (us/config) | pinocchio (us/config) | pinocchio / ours |")
        print("| --- | ---: | ---: | ---: | ---: |")
        for name, batch, ours, theirs in rows:
            print(
                f"| {name} | {batch} | {ours * 1e6:.3f} | {theirs * 1e6:.3f} | "
                f"{theirs / ours:.1f}x |"
            )
        chain = written["chain_10000"]
        for batch in (1, 16, 64):
            done = subprocess.run(
                [sys.executable, "-c", _MEMORY, str(chain), str(batch)],
                capture_output=True,
                text=True,
                check=True,
            )
            links, peak = map(int, done.stdout.split())
            start = time.perf_counter()
            kin = fishbot_urdf.Kinematics(fishbot_urdf.load(chain))
            kin.forward(np.zeros((batch, len(kin.variables))))
            seconds = time.perf_counter() - start
            array = batch * links * 16 * 8 / 2**20
            print(
                f"\n10,000-link chain, B={batch}: {seconds:.2f} s (load, build, evaluate); "
                f"the evaluation's peak allocation {peak / 2**20:.1f} MiB for a result of "
                f"{array:.1f} MiB"
            )


if __name__ == "__main__":
    main()
