"""`fishbot check` against the real check_urdf, run live, on every fixture and a corpus.

Wherever check_urdf accepts a robot, our stdout is identical to its byte for byte, whatever
our verdict. Where the verdicts differ, the difference must be one of the rules in STRICTER,
each of which is a deliberate choice explained there.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import CORPUS, INVALID, VALID, require_tool, run_check_urdf

from fishbot_urdf.cli import cli

# Rules for faults check_urdf lets through (it logs some of them and still exits 0):
STRICTER = {
    "bad-number": "urdfdom logs an unparsable mass/inertia/limit value and drops the element",
    "bad-color": "urdfdom logs a colour outside 0..1 and drops the material",
    "missing-attribute": "urdfdom logs a shape without its size and drops the visual",
    "missing-element": "urdfdom logs a visual without geometry and drops it",
    "unknown-geometry": "urdfdom logs an unknown shape and drops the visual",
    "cycle": "a joint loop that misses the root leaves links unconnected",
    "unreachable-link": "links below a joint loop are not connected to the root",
    "multiple-parents": "check_urdf prints such a link twice; it is not a tree",
    "joint-self-loop": "check_urdf hangs on a joint whose parent is its child",
    "undefined-mimic": "robot_state_publisher and simulators fail on it",
    "limit-range": "no position satisfies lower > upper",
    "zero-axis": "a moving joint with a zero axis cannot move",
    "negative-limit": "effort and velocity limits are magnitudes",
    "negative-mass": "a negative mass is not physical",
    "inertia-not-positive": "no matter has a negative moment of inertia; simulators refuse it",
    "inertia-triangle": "no rigid body has one moment above the sum of the other two (MuJoCo)",
    "massless-link": "a moving body without mass or inertia cannot be simulated (MuJoCo)",
}

# Corpus robots check_urdf accepts and we reject, each for a fault in the file itself.
FAULTY = {
    "alex_psyonic_hands.urdf": "mimic joints name joints that do not exist",
    "icub.urdf": "moving links with mass and an all-zero (or 1e-20) inertia",
    "icub_reduced.urdf": "moving links with mass and an all-zero (or 1e-20) inertia",
    "romeo.urdf": "moving finger links whose mass is 0",
    "romeo_laas_small.urdf": "hip inertias with a negative principal moment",
    "romeo_small.urdf": "arm inertias that break the triangle inequality",
}


def _ours(path: Path) -> tuple[int, bytes, str]:
    result = CliRunner().invoke(cli, ["check", str(path)])
    return result.exit_code, result.stdout_bytes, result.stderr


def _compare(path: Path) -> None:
    real = run_check_urdf(path)
    status, out, err = _ours(path)
    real_ok = real.returncode == 0
    if real_ok:
        assert out == real.stdout
    if real_ok and status == 0:
        return
    if not real_ok:
        # check_urdf rejects it: so must we.
        assert status == 1, err
        return
    # check_urdf accepts, we do not: only for the deliberate rules above.
    rules = {line.rsplit("[", 1)[-1].rstrip("]") for line in err.splitlines() if ": error:" in line}
    assert rules, err
    assert rules <= set(STRICTER), err


# check_urdf never finishes on these (it prints the loop until it crashes): own test below.
ENDLESS = ("self_loop", "loop_from_root")
PHYSICS = sorted((Path(__file__).parent / "data" / "physics").glob("*.urdf"))
FIXTURES = [p for p in VALID + INVALID + PHYSICS if p.stem not in ENDLESS]


@pytest.mark.parametrize("path", FIXTURES, ids=[p.name for p in FIXTURES])
def test_fixture_parity(path: Path) -> None:
    _compare(path)


@pytest.mark.parametrize("path", CORPUS, ids=[f"{p.parent.parent.name}/{p.name}" for p in CORPUS])
def test_corpus_parity(path: Path) -> None:
    _compare(path)


@pytest.mark.parametrize("name", ENDLESS)
def test_check_urdf_never_finishes_on_a_loop_from_the_root_and_we_do(name: str) -> None:
    path = Path(__file__).parent / "data" / "invalid" / f"{name}.urdf"
    tool = require_tool("check_urdf", "liburdfdom-tools")
    with pytest.raises(subprocess.TimeoutExpired):
        # Its output grows without end: send it nowhere.
        subprocess.run(
            [tool, str(path)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            timeout=3,
            check=False,
        )
    status, out, err = _ours(path)
    assert status == 1
    assert "[joint-self-loop]" in err or "[cycle]" in err
    if name == "loop_from_root":
        assert out == b""  # the tree has no end: it is not printed
    else:  # the self-loop is no edge of the tree: the rest is printed
        assert out.startswith(b"robot name is: ")


def test_the_corpus_has_robots_we_accept_byte_for_byte() -> None:
    # Guard against a parity sweep that passes because everything is rejected: what we
    # reject and check_urdf accepts is exactly the known-faulty list.
    ours_reject = {p.name for p in CORPUS if _ours(p)[0] != 0}
    real_reject = {p.name for p in CORPUS if run_check_urdf(p).returncode != 0}
    assert ours_reject - real_reject == set(FAULTY)
    assert len(CORPUS) - len(ours_reject) >= 60
