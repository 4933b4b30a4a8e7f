"""The quick pass for fault-free files gives exactly the full reader's robot, or gives up."""

from __future__ import annotations

import copy
import dataclasses
from pathlib import Path

import pytest
from conftest import CORPUS, FISHBOT, INVALID, VALID
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st
from lxml import etree

from fishbot_urdf.errors import XmlSyntaxError
from fishbot_urdf.parse import read
from fishbot_urdf.parse._fast import fast_robot
from fishbot_urdf.parse._reader import Reader
from fishbot_urdf.xmlsource import Locator, parse_xml

FIRST_ROBOT = FISHBOT / "urdf" / "first_robot.urdf"


def _everything(value: object) -> object:
    """``value`` as nested tuples of every field, locations included (equality skips them)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        parts = [(f.name, _everything(getattr(value, f.name))) for f in dataclasses.fields(value)]
        return (type(value).__name__, *parts)
    if isinstance(value, tuple):
        return tuple(_everything(item) for item in value)
    if isinstance(value, float):
        return repr(value)  # tells 0.0 from -0.0
    return value


def _both(data: bytes) -> tuple[object, object, int]:
    """(quick pass result, full reader result, full reader's finding count)."""
    root = parse_xml(data, "robot.urdf")
    fast = fast_robot(root, Locator(data, "robot.urdf"), data)
    reader = Reader(Locator(data, "robot.urdf"))
    full = reader.robot(root)
    return fast, full, len(reader.diagnostics)


def _agrees(data: bytes) -> bool:
    """Assert the quick pass agrees with the full reader; True if it did not give up."""
    fast, full, findings = _both(data)
    if fast is None:
        return False
    assert findings == 0, "the quick pass accepted a file the full reader has findings for"
    assert _everything(fast) == _everything(full)
    return True


@pytest.mark.parametrize("path", [*VALID, FIRST_ROBOT], ids=lambda p: p.name)
def test_valid_files(path: Path) -> None:
    taken = _agrees(path.read_bytes())
    # numbers.urdf holds every odd number form urdfdom accepts; the quick pass leaves the
    # rarest (leading spaces, runs of spaces) to the full reader.
    assert taken or path.name == "numbers.urdf"


@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.name)
def test_invalid_files(path: Path) -> None:
    data = path.read_bytes()
    if path.name == "xml_syntax.urdf":
        return  # lxml refuses it before either reader starts (see test_bad_input)
    _agrees(data)
    fast, _, findings = _both(data)
    if findings:
        assert fast is None


def test_real_robots_take_the_quick_pass_unless_they_have_findings() -> None:
    assert len(CORPUS) > 50
    for path in CORPUS:
        data = path.read_bytes()
        taken = _agrees(data)
        assert taken == (_both(data)[2] == 0), path.name


def test_read_uses_it_with_the_same_result() -> None:
    parsed = read(FIRST_ROBOT)
    assert parsed.diagnostics == ()
    assert parsed.robot is not None
    assert parsed.robot.links[0].source is not None
    assert parsed.robot.links[0].source.line > 1


# -- mutations: whatever is done to a good file, the two readers never disagree --------------

_ODD_VALUES = [
    "",
    " ",
    "1",
    "-1",
    "0",
    "-0",
    "1 2",
    "1 2 3",
    "1  2 3",
    " 1 2 3",
    "1 2 3 ",
    "1\t2 3",
    "1 2 3 4",
    "0.5 0.5 0.5 1",
    "2 0 0 1",
    "nan",
    "inf",
    "1e400",
    "1_0",
    "0x10",
    "\u0663",  # an Arabic-Indic digit: Python's float takes it, urdfdom does not
    "1.0",
    "2.0",
    "revolute",
    "fixed",
    "continuous",
    "base_link",
    "x",
]
_ODD_TAGS = [
    "origin",
    "geometry",
    "inertial",
    "visual",
    "collision",
    "material",
    "color",
    "texture",
    "limit",
    "axis",
    "parent",
    "child",
    "mass",
    "inertia",
    "box",
    "mimic",
    "foo",
]
_GOOD = [path.read_bytes() for path in [*VALID, FIRST_ROBOT]]


@st.composite
def _mutated(draw: st.DrawFn) -> bytes:
    root = etree.fromstring(draw(st.sampled_from(_GOOD)))
    for _ in range(draw(st.integers(1, 3))):
        elements = list(root.iter(etree.Element))
        el = draw(st.sampled_from(elements))
        kind = draw(st.sampled_from(["value", "drop-value", "tag", "drop", "insert", "copy"]))
        if kind in ("value", "drop-value") and el.attrib:
            name = draw(st.sampled_from(sorted(el.attrib)))
            if kind == "value":
                el.set(name, draw(st.sampled_from(_ODD_VALUES)))
            else:
                del el.attrib[name]
        elif kind == "tag":
            el.tag = draw(st.sampled_from(_ODD_TAGS))
        elif kind == "drop" and el.getparent() is not None:
            el.getparent().remove(el)
        elif kind == "insert":
            new = etree.SubElement(el, draw(st.sampled_from(_ODD_TAGS)))
            if draw(st.booleans()):
                etree.SubElement(new, draw(st.sampled_from(_ODD_TAGS)))
        elif kind == "copy" and el.getparent() is not None:
            el.addnext(copy.deepcopy(el))
    data = etree.tostring(root)
    if draw(st.booleans()):
        # the text-level faults the tree cannot hold: raw white space, character references
        data = data.replace(b'" ', draw(st.sampled_from([b'" ', b'"\n  ', b'"\t'])), 1)
        data = data.replace(
            b" 0 ", draw(st.sampled_from([b" 0 ", b"\t0 ", b"&#32;0 ", b"\n0 "])), 1
        )
    return data


@settings(max_examples=500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_mutated())
def test_mutated_files_never_disagree(data: bytes) -> None:
    try:
        parse_xml(data, "robot.urdf")
    except XmlSyntaxError:
        event("broken XML")
        return  # the mutation broke the XML: neither reader starts
    event("quick pass taken" if _agrees(data) else "quick pass gave up")
