"""`fishbot check` against the real check_urdf, on every fixture, the fishbot robot and a corpus.

What check_urdf prints for each of them is kept in tests/golden/ (see regenerate.py there), so
parity is checked on any machine; where check_urdf is installed it also runs live and must
print exactly what is kept. Our stdout is check_urdf's byte for byte, whatever either verdict:
its tree wherever urdfdom builds the robot (our errors or not), nothing where it refuses the
file. Where the verdicts differ, the difference must be one of the rules in STRICTER, each of
which is a deliberate choice explained there.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import (
    CORPUS_PACKAGE,
    GOLDEN,
    REGENERATE,
    RUNS,
    GoldenInput,
    check_urdf,
    golden_check_urdf,
    golden_index,
    golden_inputs,
    installed_corpus_version,
)

from fishbot_urdf.cli import cli

# Rules for faults check_urdf lets through (it logs some of them and still exits 0):
STRICTER = {
    "bad-number": "urdfdom logs an unparsable mass/inertia/limit value and drops the element",
    "bad-vector": "urdfdom logs a link's malformed origin, and reads no fixed joint's axis",
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
    "limit-unset": "a bound left out (0) that leaves lower above upper: no position is left",
    "zero-axis": "a moving joint with a zero axis cannot move",
    "negative-limit": "effort and velocity limits are magnitudes",
    "negative-mass": "a negative mass is not physical",
    "inertia-not-positive": "no matter has a negative moment of inertia; simulators refuse it",
    "inertia-triangle": "no rigid body has one moment above the sum of the other two (MuJoCo)",
    "massless-link": "a moving body without mass or inertia cannot be simulated (MuJoCo)",
    "missing-inertial": "Gazebo drops a moving link without <inertial>, as one of mass 0",
    "mesh-uri": "a malformed URI (package:/, file://relative) names no file anyone finds",
    "mesh-not-found": "a mesh that is not there is drawn by nobody",
    "shape-size": "a collision shape of size 0 or less, which MuJoCo refuses",
    "unknown-reference": "Gazebo and ros2_control cannot attach to a part that does not exist",
    "gazebo-dropped-link": "Gazebo leaves out the links, and their mass, below a massless one",
    "gazebo-plugin-link": "a Gazebo plugin that names a link lumped into another finds none",
}

# Corpus robots check_urdf accepts and we reject, each for a fault in the file itself.
FAULTY = {
    "alex_psyonic_hands.urdf": "mimic joints name joints that do not exist",
    "icub.urdf": "moving links with mass and an all-zero (or 1e-20) inertia",
    "icub_reduced.urdf": "moving links with mass and an all-zero (or 1e-20) inertia",
    "romeo_laas_small.urdf": "meshes named by absolute file:// paths that are not there",
    "pr2.urdf": "<gazebo reference> blocks name links the robot does not have",
    "talos_left_arm.urdf": "a <transmission> and a <gazebo> block for a joint left out",
    "tiago_dual.urdf": "<gazebo reference> names with an unexpanded {side} in them",
}

# ... and those whose faults harm only the simulators: warnings by default (they have no
# <gazebo> block), errors with --target all.
FAULTY_FOR_SIMULATORS = {
    "romeo.urdf": "moving finger links whose mass is 0",
    "romeo_small.urdf": "arm inertias that break the triangle inequality",
    "human.urdf": "massless links between a limb's two revolute joints: Gazebo leaves the limb out",
}


def _ours(path: Path, *options: str) -> tuple[int, bytes, str]:
    result = CliRunner().invoke(cli, ["check", *options, str(path)])
    return result.exit_code, result.stdout_bytes, result.stderr


def _compare(item: GoldenInput) -> None:
    real = check_urdf(item)
    status, out, err = _ours(item.path)
    if real.status is not None:  # (check_urdf never ends on a loop: see ENDLESS below)
        assert out == real.stdout, err
    real_ok = real.status == 0
    if real_ok and status == 0:
        return
    if not real_ok:
        # check_urdf rejects it (or never answers): so must we.
        assert status == 1, err
        return
    # check_urdf accepts, we do not: only for the deliberate rules above.
    rules = {line.rsplit("[", 1)[-1].rstrip("]") for line in err.splitlines() if ": error:" in line}
    assert rules, err
    assert rules <= set(STRICTER), err


INPUTS = golden_inputs()
FIXTURES = [item for item in INPUTS if not item.in_corpus]
CORPUS_INPUTS = [item for item in INPUTS if item.in_corpus]


@pytest.mark.parametrize("item", FIXTURES, ids=[item.id for item in FIXTURES])
def test_fixture_parity(item: GoldenInput) -> None:
    _compare(item)


@pytest.mark.parametrize("item", CORPUS_INPUTS, ids=[item.id for item in CORPUS_INPUTS])
def test_corpus_parity(item: GoldenInput) -> None:
    _compare(item)


# Broken robots, one fault each: urdfdom refuses some (a fault in a joint, which it never
# drops), and check_urdf prints nothing; it builds the others (a link's fault is logged and
# the link kept, a fixed joint's axis is not read), and prints their tree.
BROKEN = [item for item in FIXTURES if item.id.startswith("data/broken/")]


@pytest.mark.parametrize("item", BROKEN, ids=[item.id for item in BROKEN])
def test_a_broken_file_prints_what_check_urdf_prints_and_nothing_more(
    item: GoldenInput,
) -> None:
    real = check_urdf(item)
    status, out, err = _ours(item.path)
    assert status == 1
    assert ": error: " in err
    assert out == real.stdout
    assert (out != b"") is (real.status == 0)


@pytest.mark.parametrize("item", BROKEN, ids=[item.id for item in BROKEN])
def test_the_tree_is_check_urdfs_whatever_the_targets(item: GoldenInput) -> None:
    # A fault urdfdom refuses a joint for is a warning for a program that does not read
    # joints so (ros2_control alone): the tree is still check_urdf's.
    real = golden_check_urdf(item)
    for target in ("ros2_control", "mujoco", "drake", "check_urdf"):
        assert _ours(item.path, "--target", target)[1] == real.stdout, target


def test_a_silenced_fault_still_tells_what_check_urdf_prints(tmp_path: Path) -> None:
    item = GoldenInput.from_id("data/broken/joint_mimic_without_joint.urdf")
    silenced = tmp_path / "silenced.urdf"
    silenced.write_text(
        item.path.read_text().replace(
            "  <joint ", "  <!-- fishbot: ignore[missing-attribute] -->\n  <joint "
        )
    )
    status, out, err = _ours(silenced)
    assert (status, err) == (0, "")
    assert out == check_urdf(item).stdout == b""


def test_the_broken_files_have_both_outcomes() -> None:
    printed = {golden_check_urdf(item).stdout != b"" for item in BROKEN}
    assert printed == {True, False}
    assert len(BROKEN) >= 10


# check_urdf never finishes on these: it prints the loop until it is stopped.
ENDLESS = ("self_loop", "loop_from_root")


@pytest.mark.parametrize("name", ENDLESS)
def test_check_urdf_never_finishes_on_a_loop_from_the_root_and_we_do(name: str) -> None:
    item = GoldenInput.from_id(f"data/invalid/{name}.urdf")
    # Stopped when the golden files were made; where check_urdf is installed, run again
    # live and stopped again.
    assert check_urdf(item).status is None
    status, out, err = _ours(item.path)
    assert status == 1
    assert "[joint-self-loop]" in err or "[cycle]" in err
    if name == "loop_from_root":
        assert out == b""  # the tree has no end: it is not printed
    else:  # the self-loop is no edge of the tree: the rest is printed
        assert out.startswith(b"robot name is: ")


def test_the_corpus_has_robots_we_accept_byte_for_byte() -> None:
    # Guard against a parity sweep that passes because everything is rejected: what we
    # reject and check_urdf accepts is exactly the known-faulty list.
    ours_reject = {i.path.name for i in CORPUS_INPUTS if _ours(i.path)[0] != 0}
    real_reject = {i.path.name for i in CORPUS_INPUTS if golden_check_urdf(i).status != 0}
    assert ours_reject - real_reject == set(FAULTY)
    assert len(CORPUS_INPUTS) - len(ours_reject) >= 55
    for_all = {i.path.name for i in CORPUS_INPUTS if _ours(i.path, "--target", "all")[0] != 0}
    assert for_all - real_reject == set(FAULTY) | set(FAULTY_FOR_SIMULATORS)


# --target check_urdf: exit 1 exactly where check_urdf fails (for a CI that swaps the two).
ANSWERED = [item for item in INPUTS if golden_check_urdf(item).status is not None]


@pytest.mark.parametrize("item", ANSWERED, ids=[item.id for item in ANSWERED])
def test_target_check_urdf_exits_as_check_urdf_does(item: GoldenInput) -> None:
    real = check_urdf(item)
    status, out, err = _ours(item.path, "--target", "check_urdf")
    assert status == (0 if real.status == 0 else 1), err
    assert out == real.stdout
    assert status == 1 or ": error: " not in err


def test_target_check_urdf_sees_both_outcomes() -> None:
    assert {golden_check_urdf(item).status == 0 for item in ANSWERED} == {True, False}
    assert len(ANSWERED) >= 100


# ------------------------------------------------------------------ the golden files


def test_every_input_has_a_golden_entry_and_no_entry_is_orphaned() -> None:
    index = golden_index()
    ids = {item.id for item in INPUTS}
    recorded = set(index["inputs"])
    missing, orphaned = sorted(ids - recorded), sorted(recorded - ids)
    assert missing == [], f"inputs without a golden entry: regenerate with {REGENERATE}"
    assert orphaned == [], f"golden entries of no input: regenerate with {REGENERATE}"
    assert sorted(index["runs"]) == sorted(RUNS), f"regenerate with {REGENERATE}"
    # Every golden output file is one an entry names, and the other way round.
    named = {
        record[key]
        for entry in index["inputs"].values()
        for tool, key in (("check_urdf", "stdout"), ("urdf_to_graphviz", "gv"))
        if (record := entry[tool]).get(key) is not None
    }
    on_disk = {
        path.relative_to(GOLDEN).as_posix()
        for folder in ("check_urdf", "urdf_to_graphviz")
        for path in (GOLDEN / folder).rglob("*")
        if path.is_file()
    }
    assert on_disk == named, f"regenerate with {REGENERATE}"


def test_the_golden_corpus_is_the_installed_one() -> None:
    recorded = golden_index()["versions"][CORPUS_PACKAGE]
    assert installed_corpus_version() == recorded, (
        f"the golden outputs are of {CORPUS_PACKAGE} {recorded}: install it "
        f"(pip install -e '.[test]' pins it) or regenerate with {REGENERATE}"
    )
    assert len(CORPUS_INPUTS) >= 60


def test_regenerating_refuses_to_run_without_the_real_tools(tmp_path: Path) -> None:
    script = GOLDEN / "regenerate.py"
    env = {**os.environ, "PATH": str(tmp_path)}  # no check_urdf, urdf_to_graphviz or dot
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, env=env, check=False
    )
    assert done.returncode == 2, done.stderr
    assert done.stdout == ""
    assert "check_urdf, dot, urdf_to_graphviz not found" in done.stderr
    assert "apt-get install graphviz liburdfdom-tools" in done.stderr
