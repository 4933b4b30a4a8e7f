"""Fuzzing: mutated robots and xacro files run through every command, in process.

The property is the command line's contract: an exit status of 0, 1 or 2, no exception
but the SystemExit that carries it, no traceback in the output, and JSON output that is
JSON. Hypothesis mutates real files (bytes, attribute values, numbers, the element
structure, xacro expressions) from ``tests/data`` and the fishbot package.

In the suite a bounded, derandomized number of examples runs. A long campaign:

    FISHBOT_FUZZ=long python -m pytest tests/test_fuzz.py -x

runs many more, randomized, and keeps what it found in ``.hypothesis/`` so that a failure
replays; ``FISHBOT_FUZZ_EXAMPLES=N`` sets how many (and implies the long campaign).

Beyond robots and xacro files: expressions from the interpreter's grammar and its hostile
fragments (``tests/test_interpreter.py``) in a real xacro file, random and mutated STL and
OBJ meshes (the mesh readers, then ``render`` and ``check`` of a robot naming the mesh),
random and mutated configurations beside a robot (``check``), and the values the viewer's
page may send. The property everywhere: no traceback, a documented exit status, and each
finding on one line.

A failure found becomes a fixture: save the input printed with the failure under
``tests/data/fuzz/`` (``.urdf`` or ``.urdf.xacro``); `test_fuzz_findings_stay_fixed` runs
every file there through every command with the same property.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import shutil
import struct
from collections.abc import Callable
from pathlib import Path
from types import SimpleNamespace
from typing import Any
from xml.sax.saxutils import escape

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

# The interpreter's grammar with its hostile fragments (the interpreter's own test watches
# each walk; here the expressions go through a whole expansion and the command line).
from test_interpreter import ANY as EXPRESSION_GRAMMAR

from fishbot_urdf.cli import cli
from fishbot_urdf.errors import FishbotUrdfError
from fishbot_urdf.expansion import expand

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
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
    max_examples=int(os.environ.get("FISHBOT_FUZZ_EXAMPLES", "5000")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
LONG = os.environ.get("FISHBOT_FUZZ") == "long" or "FISHBOT_FUZZ_EXAMPLES" in os.environ
PROFILE = "long" if LONG else "suite"

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
    # what the budget of a whole document stops, and the reads outside the robot's tree
    "${xacro.load_yaml('/etc/passwd')}", "${xacro.load_yaml('../../../../etc/hostname')}",
    "${python.any(python.map(python.abs, python.range(10**7)))}", "${(3**630000) // 7**178000}",
    "${[2**999999 + i for i in python.range(300)]}", "${'-' * 100000}", "${" + "-" * 5000 + "1}",
    "${python.str.format('{0:' + '>' + '{1' + '}' + '}', 'x', 10**9)}",
    "${(lambda: ().__class__)() if python.repr(lambda: 0) != '&lt;lambda&gt;' else 1}",
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
        ["sdf", name],
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


# -- expressions in a real xacro file ---------------------------------------------------------
def _one_line_per_finding(result: Any, context: str) -> None:
    """The contract, and for a failure (exit 1) each line of stderr one finding: no
    indented continuation, no blank line."""
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise AssertionError(f"{context} raised {result.exception!r}") from result.exception
    assert result.exit_code in (0, 1, 2), context
    assert "Traceback" not in result.output, context
    if result.exit_code == 1:
        for line in result.stderr.splitlines():
            assert line and not line[0].isspace(), f"{context}: {line!r}"


@settings(settings.get_profile(PROFILE))
@given(expression=EXPRESSION_GRAMMAR)
def test_expressions_in_a_xacro_file_end_in_a_documented_way(
    expression: str, tmp_path_factory: pytest.TempPathFactory
) -> None:
    folder = tmp_path_factory.mktemp("expression")
    text = escape(expression, {'"': "&quot;"})
    robot = folder / "robot.urdf.xacro"
    robot.write_text(
        f'<robot name="r" {XACRO_NS}>\n<link name="a${{{text}}}"/>\n'
        f'<xacro:if value="${{python.len(python.str({text})) > 0}}"><link name="b"/></xacro:if>\n'
        "</robot>\n"
    )
    with contextlib.suppress(FishbotUrdfError):
        expand(robot)
    _one_line_per_finding(CliRunner().invoke(cli, ["expand", str(robot)]), expression)


# -- meshes -------------------------------------------------------------------------------------
def _binary_stl(triangles: list[list[float]]) -> bytes:
    body = b"".join(struct.pack("<12fH", 0, 0, 1, *t[:9], 0) for t in triangles)
    return b"fishbot".ljust(80, b" ") + struct.pack("<I", len(triangles)) + body


def _ascii_stl(triangles: list[list[float]]) -> bytes:
    facets = "".join(
        "facet normal 0 0 1\n outer loop\n"
        + "".join(f"  vertex {t[i]!r} {t[i + 1]!r} {t[i + 2]!r}\n" for i in (0, 3, 6))
        + " endloop\nendfacet\n"
        for t in triangles
    )
    return f"solid s\n{facets}endsolid s\n".encode()


def _obj(triangles: list[list[float]]) -> bytes:
    lines = [f"v {t[i]!r} {t[i + 1]!r} {t[i + 2]!r}" for t in triangles for i in (0, 3, 6)]
    lines += [f"f {3 * k + 1} {3 * k + 2}/1 {3 * k + 3}//2" for k in range(len(triangles))]
    return ("\n".join(lines) + "\n").encode()


_COORDINATE = st.one_of(
    st.floats(-10, 10, allow_nan=False, width=32),
    st.sampled_from([0.0, 1e30, -1e30, 3.4e38, float("inf"), float("nan"), 1e-40]),
)
_TRIANGLES = st.lists(st.lists(_COORDINATE, min_size=9, max_size=9), max_size=6)
_MESH_NOISE = [b"vertex", b"vertex nan inf -inf", b"\nf 1 2 3 4 5\n", b"\nf -9 0 99\n",
               b"\nf a/b/c\n", b"\nv 1e999 1 1\n", b"facet", b"\xff\xfe", b"\0" * 50,
               b"\nf 1/2/3\n", b"\nv 1 2\n", b"solid", b"\r\n", b"\nf\n"]  # fmt: skip


@st.composite
def meshes(draw: st.DrawFn) -> tuple[str, bytes]:
    """A mesh file's extension and bytes: made from triangles, mutated, or random."""
    kind = draw(st.sampled_from(["binary", "ascii", "obj", "random"]), label="kind")
    if kind == "random":
        return draw(st.sampled_from([".stl", ".obj"])), draw(st.binary(max_size=300))
    triangles = draw(_TRIANGLES, label="triangles")
    data = {"binary": _binary_stl, "ascii": _ascii_stl, "obj": _obj}[kind](triangles)
    how = draw(st.sampled_from(["as made", "bytes", "noise", "count"]), label="how")
    if how == "bytes":
        data = draw(byte_mutations(data))
    elif how == "noise":
        at = draw(st.integers(0, len(data)))
        data = data[:at] + draw(st.sampled_from(_MESH_NOISE)) + data[at:]
    elif how == "count" and kind == "binary":  # a count that does or does not fit the size
        count = draw(st.sampled_from([0, 1, 2**31, 2**32 - 1, len(triangles) + 1]))
        data = data[:80] + struct.pack("<I", count) + data[84:]
    return (".obj" if kind == "obj" else ".stl"), data


@settings(settings.get_profile(PROFILE))
@given(mesh=meshes())
def test_mesh_readers_read_a_mesh_or_say_why_not(
    mesh: tuple[str, bytes], tmp_path_factory: pytest.TempPathFactory
) -> None:
    from fishbot_urdf.analysis.meshcontents import MeshContents
    from fishbot_urdf.errors import FishbotUrdfError as Refusal
    from fishbot_urdf.meshfile import mesh_facts

    suffix, data = mesh
    folder = tmp_path_factory.mktemp("mesh")
    path = folder / f"part{suffix}"
    path.write_bytes(data)
    facts = mesh_facts(path)
    if facts is not None:
        assert facts.faces >= 0
        assert all(lo <= hi for lo, hi in zip(facts.low, facts.high, strict=True))
    try:
        triangles = MeshContents().triangles(path)
    except (OSError, Refusal):  # what the scene's loader turns into a warning
        pass
    else:
        assert triangles.ndim == 3 and triangles.shape[1:] == (3, 3)


@settings(
    settings.get_profile(PROFILE),
    max_examples=max(20, settings.get_profile(PROFILE).max_examples // 5),
)
@given(mesh=meshes())
def test_a_robot_naming_a_mesh_renders_and_checks_in_a_documented_way(
    mesh: tuple[str, bytes], tmp_path_factory: pytest.TempPathFactory
) -> None:
    suffix, data = mesh
    folder = tmp_path_factory.mktemp("robot")
    (folder / f"part{suffix}").write_bytes(data)
    robot = folder / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry>'
        f'<mesh filename="part{suffix}"/></geometry></visual><collision><geometry>'
        f'<mesh filename="part{suffix}" scale="0.001 0.001 0.001"/></geometry></collision>'
        "</link></robot>\n"
    )
    for command in (
        ["render", str(robot), "-o", str(folder / "out.png"), "--size", "16x16"],
        ["render", str(robot), "-o", str(folder / "out.png"), "--size", "16x16", "--collision"],
        ["check", str(robot)],
    ):
        _one_line_per_finding(CliRunner().invoke(cli, command), " ".join(command[:1]))


# -- configurations -----------------------------------------------------------------------------
_CONFIG_SEED = b"""select = ["ALL"]
extend-select = ["undefined-link"]
ignore = ["inertia"]
strict = true
ground-tolerance = 2.5

[severity]
undefined-link = "warning"
"""
_TOML_VALUES = ['"ALL"', "[]", '["nope"]', "true", "1", "-1", "nan", "inf", "1e400", "{}",
                '"error"', '"loud"', "[1, 2]", '[["a"]]', "{a = 1}", '"\\u0000"', "'x'",
                "[" * 40 + "]" * 40, '"""\nx"""']  # fmt: skip
_TOML_KEYS = ["select", "extend-select", "ignore", "strict", "ground-tolerance", "severity",
              "severity.undefined-link", "severity.nope", "nope", '"select"', "tool.fishbot",
              "a.b.c"]  # fmt: skip


@st.composite
def configurations(draw: st.DrawFn) -> bytes:
    how = draw(st.sampled_from(["lines", "bytes", "random"]), label="how")
    if how == "random":
        return draw(st.binary(max_size=200))
    if how == "bytes":
        return draw(byte_mutations(_CONFIG_SEED))
    lines = draw(
        st.lists(
            st.one_of(
                st.builds(
                    lambda k, v: f"{k} = {v}",
                    st.sampled_from(_TOML_KEYS),
                    st.sampled_from(_TOML_VALUES),
                ),
                st.sampled_from(
                    [
                        "[severity]",
                        "[tool.fishbot]",
                        "[tool]",
                        "[[severity]]",
                        "[nope]",
                        "x =",
                        "= 1",
                        "[tool.fishbot.severity]",
                    ]
                ),
            ),
            max_size=6,
        )
    )
    return "\n".join(lines).encode()


@settings(settings.get_profile(PROFILE))
@given(config=configurations(), where=st.sampled_from(["fishbot.toml", "pyproject.toml"]))
def test_a_configuration_beside_a_robot_checks_in_a_documented_way(
    config: bytes, where: str, tmp_path_factory: pytest.TempPathFactory
) -> None:
    folder = tmp_path_factory.mktemp("config")
    if where == "pyproject.toml":
        config = b"[project]\nname = 'x'\n\n[tool.fishbot]\n" + config
    (folder / where).write_bytes(config)
    robot = folder / "robot.urdf"
    robot.write_bytes((DATA / "valid" / "single_link.urdf").read_bytes())
    for command in (["check", str(robot)], ["check", "--format", "json", str(robot)]):
        result = CliRunner().invoke(cli, command)
        _one_line_per_finding(result, f"{where}: {config[:60]!r}")
        if "json" in command and result.stdout.strip():
            json.loads(result.stdout)


# -- what the viewer's page may send -------------------------------------------------------------
_PAGE_VALUES = st.recursive(
    st.one_of(
        st.none(), st.booleans(), st.integers(), st.floats(), st.text(max_size=10),
        st.sampled_from([10**400, -(10**400), "nan", "1", float("nan"), float("-inf")]),
    ),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.text(max_size=5), inner, max_size=3)),
    max_leaves=5,
)  # fmt: skip
_RANGES = st.tuples(st.floats(-1e6, 1e6), st.floats(0, 1e6)).map(lambda t: (t[0], t[0] + t[1]))


@settings(settings.get_profile(PROFILE))
@given(value=_PAGE_VALUES, limits=_RANGES)
def test_a_slider_value_from_the_page_is_a_number_in_range_or_dropped(
    value: Any, limits: tuple[float, float]
) -> None:
    from fishbot_urdf.drawing.viewer import _position

    low, high = limits
    position = _position(value, low, high)
    if position is not None:
        assert type(position) is float and low <= position <= high
        assert not isinstance(value, bool) and isinstance(value, int | float)


@settings(settings.get_profile(PROFILE))
@given(
    uuid=st.one_of(st.sampled_from(["slider", "toggle"]), _PAGE_VALUES),
    updates=st.one_of(_PAGE_VALUES, st.fixed_dictionaries({"value": _PAGE_VALUES})),
    limits=_RANGES,
)
def test_a_message_from_the_page_is_accepted_only_when_its_control_can_hold_it(
    uuid: Any, updates: Any, limits: tuple[float, float]
) -> None:
    from fishbot_urdf.drawing.viewer import Viewer, _Input

    viewer = SimpleNamespace(
        _inputs={"slider": _Input("j", *limits), "toggle": _Input("t", toggle=True)}
    )
    accepted = Viewer._accepts(viewer, SimpleNamespace(uuid=uuid, updates=updates))
    assert accepted in (True, False)
    if accepted:
        value = updates["value"]
        if uuid == "toggle":
            assert type(value) is bool
        else:
            assert not isinstance(value, bool) and isinstance(value, int | float)
            assert math.isfinite(float(value))
