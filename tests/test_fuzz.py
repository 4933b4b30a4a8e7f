"""Fuzzing: mutated robots and xacro files run through every command, in process.

The property is the command line's contract: an exit status of 0, 1 or 2, no exception
but the SystemExit that carries it, no traceback in the output, and JSON output that is
JSON. Hypothesis mutates real files (bytes, attribute values, numbers, the element
structure, xacro expressions) from ``tests/data`` and the fishbot package.

In the suite a bounded, derandomized number of examples runs. A long campaign:

    FISHBOT_FUZZ=long python -m pytest tests/test_fuzz.py -x

runs many more, randomized, and keeps what it found in ``.hypothesis/`` so that a failure
replays. A failure found becomes a fixture: save the input printed with the failure under
``tests/data/fuzz/`` (``.urdf`` or ``.urdf.xacro``); `test_fuzz_findings_stay_fixed` runs
every file there through every command with the same property.
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from fishbot_urdf.cli import cli

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data"
FISHBOT = ROOT / "robots" / "fishbot" / "urdf"
FINDINGS = DATA / "fuzz"

settings.register_profile(
    "suite",
    max_examples=150,
    derandomize=True,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.register_profile(
    "long",
    max_examples=5000,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
PROFILE = "long" if os.environ.get("FISHBOT_FUZZ") == "long" else "suite"

URDF_SEEDS = [
    FISHBOT / "first_robot.urdf",
    DATA / "valid" / "all_elements.urdf",
    DATA / "valid" / "numbers.urdf",
    DATA / "valid" / "rotations.urdf",
    DATA / "physics" / "wheels_under_ground.urdf",
    DATA / "physics" / "massless_wheel.urdf",
    DATA / "physics" / "box_sides_swapped.urdf",
]
XACRO_SEEDS = [FISHBOT / "first_robot.urdf.xacro", FISHBOT / "fishbot" / "fishbot.urdf.xacro"]

NUMBERS = [
    "nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "0", "-0", "1e200", "-1", "",
    "1 2", "1 2 3 4", "0 0 0", "abc", "0x10", "1e", " 1 ", "\t1\n", "${1/0}", "$(arg nope)",
    "\U0001f916", "\u202e", "a&amp;b", "1.7976931348623157e308",
]  # fmt: skip
EXPRESSIONS = [
    "${1/0}", "${nope}", "${'a' * 3}", "${python.len('ab')}", "${math.sqrt(-1)}",
    "${[1, 2][5]}", "${10**400}", "${1e308 * 10}", "${xacro.arg('x')}", "$(arg nope)",
    "$(find nothing_here)", "$(eval 1 +)", "${(lambda: 1)()}", "${{}}", "${",
]  # fmt: skip


def _commands(path: Path, out: Path) -> list[list[str]]:
    name = str(path)
    commands = [
        ["check", name],
        ["check", "--format", "json", name],
        ["check", "--format", "sarif", name],
        ["graph", name, "-o", "-"],
        ["graph", name, "--format", "mmd", "-o", "-"],
        ["inertia", name, "--format", "json"],
        ["inertia", name, "--fill", "--density", "1000", "-o", str(out)],
    ]
    if name.endswith(".xacro"):
        commands.append(["expand", name])
    return commands


def _holds_the_contract(path: Path) -> None:
    """Every command on ``path`` ends in a documented way."""
    out = path.parent / "filled.urdf"
    for command in _commands(path, out):
        result = CliRunner().invoke(cli, command)
        context = f"fishbot {' '.join(command)}"
        if result.exception is not None and not isinstance(result.exception, SystemExit):
            raise AssertionError(f"{context} raised {result.exception!r}") from result.exception
        assert result.exit_code in (0, 1, 2), context
        assert "Traceback" not in result.output, context
        if ("json" in command or "sarif" in command) and result.stdout.strip():
            json.loads(result.stdout)


# -- mutations --------------------------------------------------------------------------
Mutation = Callable[[bytes], bytes]


@st.composite
def byte_mutations(draw: st.DrawFn, data: bytes) -> bytes:
    """Flip, insert, delete, duplicate or cut bytes."""
    for _ in range(draw(st.integers(1, 4))):
        if not data:
            break
        at = draw(st.integers(0, len(data) - 1))
        kind = draw(st.sampled_from(["flip", "insert", "delete", "duplicate", "cut"]))
        if kind == "flip":
            data = data[:at] + bytes([data[at] ^ draw(st.integers(1, 255))]) + data[at + 1 :]
        elif kind == "insert":
            extra = draw(st.sampled_from([b"<", b">", b'"', b"&", b"\0", b"<!--", b"]]>",
                                          b"\xff", b"\xc3", b"<link/>", b"/>"]))  # fmt: skip
            data = data[:at] + extra + data[at:]
        elif kind == "delete":
            data = data[:at] + data[at + draw(st.integers(1, 40)) :]
        elif kind == "duplicate":
            end = min(len(data), at + draw(st.integers(1, 200)))
            data = data[:end] + data[at:end] + data[end:]
        else:
            data = data[:at]
    return data


@st.composite
def tree_mutations(draw: st.DrawFn, data: bytes, values: list[str]) -> bytes:
    """Replace attribute values, drop, copy or move elements."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=False)
    root = etree.fromstring(data, parser)
    elements = [e for e in root.iter() if isinstance(e.tag, str)]
    for _ in range(draw(st.integers(1, 5))):
        element = draw(st.sampled_from(elements))
        kind = draw(st.sampled_from(["value", "value", "value", "drop", "copy", "move"]))
        if kind == "value" and element.attrib:
            key = draw(st.sampled_from(sorted(element.attrib)))
            element.set(key, draw(st.sampled_from(values)))
        elif kind == "drop" and element is not root and element.getparent() is not None:
            element.getparent().remove(element)
            elements = [e for e in root.iter() if isinstance(e.tag, str)]
        elif kind == "copy" and element is not root and element.getparent() is not None:
            element.getparent().append(_copy(element))
            elements = [e for e in root.iter() if isinstance(e.tag, str)]
        elif kind == "move" and element is not root and element.getparent() is not None:
            target = draw(st.sampled_from(elements))
            if element not in target.iterancestors() and target is not element:
                target.append(element)
                elements = [e for e in root.iter() if isinstance(e.tag, str)]
    return bytes(etree.tostring(root))


def _copy(element: etree._Element) -> etree._Element:
    return etree.fromstring(etree.tostring(element))


# -- the tests --------------------------------------------------------------------------
@settings(settings.get_profile(PROFILE))
@given(data=st.data())
def test_mutated_urdf_files_end_in_a_documented_way(
    data: st.DataObject, tmp_path_factory: pytest.TempPathFactory
) -> None:
    seed = data.draw(st.sampled_from(URDF_SEEDS), label="seed")
    text = seed.read_bytes()
    if data.draw(st.booleans(), label="as bytes"):
        mutated = data.draw(byte_mutations(text), label="bytes")
    else:
        mutated = data.draw(tree_mutations(text, NUMBERS), label="tree")
    folder = tmp_path_factory.mktemp("urdf")
    path = folder / "robot.urdf"
    path.write_bytes(mutated)
    _holds_the_contract(path)


@settings(settings.get_profile(PROFILE))
@given(data=st.data())
def test_mutated_xacro_files_end_in_a_documented_way(
    data: st.DataObject, tmp_path_factory: pytest.TempPathFactory
) -> None:
    seed = data.draw(st.sampled_from(XACRO_SEEDS), label="seed")
    folder = tmp_path_factory.mktemp("xacro")
    # The seed's folder with everything it includes, the top file mutated in it.
    copy = folder / "urdf"
    shutil.copytree(seed.parent, copy)
    top = copy / seed.name
    text = top.read_bytes()
    how = data.draw(st.sampled_from(["bytes", "tree", "expressions"]), label="how")
    if how == "bytes":
        mutated = data.draw(byte_mutations(text), label="bytes")
    elif how == "tree":
        mutated = data.draw(tree_mutations(text, NUMBERS), label="tree")
    else:
        mutated = data.draw(tree_mutations(text, EXPRESSIONS), label="expressions")
    top.write_bytes(mutated)
    _holds_the_contract(top)


@pytest.mark.parametrize(
    "path",
    sorted(FINDINGS.glob("*")) if FINDINGS.is_dir() else [],
    ids=lambda p: p.name,
)
def test_fuzz_findings_stay_fixed(path: Path, tmp_path: Path) -> None:
    copy = tmp_path / path.name
    copy.write_bytes(path.read_bytes())
    _holds_the_contract(copy)


def test_the_fuzz_findings_are_there() -> None:
    assert len(list(FINDINGS.glob("*"))) >= 1
