"""xmlsource's Locator: every element's and attribute's line and column, against counting them
directly in the bytes."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

import fishbot_urdf
from fishbot_urdf.xml import locator
from fishbot_urdf.xml import source as xmlsource
from fishbot_urdf.xml import stream as xmlstream
from fishbot_urdf.xml.locator import Locator


def _place(data: bytes, offset: int) -> tuple[int, int]:
    """1-based line and column (characters) of byte ``offset``, counted from the start."""
    line_start = data.rfind(b"\n", 0, offset) + 1
    return data.count(b"\n", 0, offset) + 1, len(data[line_start:offset].decode("utf-8")) + 1


_GAP = st.text(alphabet=" \n\tÄé中", max_size=6)  # text between elements
_SPACE = st.text(alphabet=" \n\t", min_size=1, max_size=4)  # inside a start tag
_NAME = st.sampled_from(["link", "joint", "origin", "été", "axis"])


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(_GAP, _NAME, _SPACE, st.booleans()), min_size=1, max_size=12))
def test_every_element_and_attribute_is_where_the_bytes_say(
    parts: list[tuple[str, str, str, bool]],
) -> None:
    # A flat document: <robot> holding elements, some with their attribute on a later line.
    text = "<robot>"
    for before, name, inside, later in parts:
        text += f'{before}<{name}{inside if later else " "}a="v"/>'
    text += "</robot>"
    data = text.encode("utf-8")
    root = etree.fromstring(data)
    locator = Locator(data, "r.urdf")
    assert locator.locate(root)[1:] == _place(data, 0)
    offset = 0
    for element in root:
        offset = data.index(b"<" + element.tag.encode("utf-8"), offset + 1)
        location = locator.locate(element)
        assert (location.path, *location[1:]) == ("r.urdf", *_place(data, offset))
        attribute = data.index(b"a=", offset)
        assert locator.attribute(location, "a")[1:] == _place(data, attribute)


# -- reading a big file as a stream ---------------------------------------------------------

_DATA = Path(__file__).parent / "data"
_FILES = sorted(p for p in _DATA.rglob("*") if p.suffix in (".urdf", ".xml"))


def _outcome(path: Path) -> object:
    """All that reading ``path`` gives: the robot with every place, the findings, or the
    error."""
    try:
        parsed = fishbot_urdf.read(path)
    except fishbot_urdf.FishbotUrdfError as error:
        return type(error).__name__, str(error)
    robot = parsed.robot
    places = [] if robot is None else [part.source for part in (*robot.links, *robot.joints)]
    return robot, places, parsed.diagnostics, parsed.references


def _streamed(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every file read by lxml's stream an element at a time, however small."""
    monkeypatch.setattr(xmlsource, "STREAM_FROM", 0)


@pytest.mark.parametrize("path", _FILES, ids=lambda p: str(p.relative_to(_DATA)))
def test_a_streamed_file_reads_as_the_whole_file(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    whole = _outcome(path)
    places = _every_place(whole[0])
    _streamed(monkeypatch)
    streamed = _outcome(path)
    assert streamed == whole
    assert _every_place(streamed[0]) == places


def test_a_stream_drops_what_it_handed_out_and_never_holds_the_whole_tree() -> None:
    count = 10_000  # about 0.4 MB of XML
    links = "".join(f'<link name="l{i}"><visual/></link><!-- {i} -->' for i in range(count))
    document = xmlsource.read_xml(f'<robot name="r">{links}</robot>'.encode(), stream=True)
    seen, held = [], 0
    for child in document.children():
        if isinstance(child.tag, str):
            assert child[0].tag == "visual"  # whole
            seen.append(child.get("name"))
        held = max(held, sum(isinstance(node.tag, str) for node in child.getparent()))
    document.finish()
    assert seen == [f"l{i}" for i in range(count)]
    assert held < count / 4  # what lxml read ahead: not the whole tree


def test_a_stream_by_element_drops_each_element_once_the_next_is_asked_for() -> None:
    links = "".join(f'<link name="l{i}"/><!-- {i} -->' for i in range(100))
    document = xmlsource.read_xml(f'<robot name="r">{links}</robot>'.encode(), stream=True)
    for child in document.children():
        assert document.root[0] is child  # the comments before it gone too


_BROKEN_LATER = [
    "<link name='b'></joint></robot>",  # a mismatched end tag after the first element
    "<link name='b'><x:y/></link></robot>",  # an undeclared prefix: a whole read refuses it
    "<link name='b'/></robot><link/>",  # an element after the root
    # an undeclared prefix after more elements than are handed out between two looks
    "<link name='b'/>" * 3000 + "<x:y/></robot>",
]


@pytest.mark.parametrize("tail", _BROKEN_LATER)
def test_a_stream_by_element_that_breaks_later_is_unstreamable(tail: str) -> None:
    data = f"<robot name='r'><link name='a'/>{tail}".encode()
    document = xmlsource.read_xml(data, stream=True)
    with pytest.raises(xmlstream.Unstreamable):
        list(document.children())
        document.finish()


@pytest.mark.parametrize("tail", [*_BROKEN_LATER, "<link name='b'/></robot><!-- end -->"])
def test_a_stream_that_breaks_later_reads_as_the_whole_file(
    tail: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(f"<robot name='r'><link name='a'/><joint name='j'/>{tail}")
    whole = _outcome(path)
    _streamed(monkeypatch)
    assert _outcome(path) == whole


class _Comparing(Locator):
    """A Locator that compares every element's name with its start tag, as it does where the
    scan may be wrong."""

    __slots__ = ()

    def __init__(self, data: bytes, path: str, *rest: Any, **named: Any) -> None:
        if named.get("starts") is None:  # the scan's, given: as for a rewritten document
            named["starts"] = [m.start() for m in locator.MARKUP.finditer(data) if m.lastindex]
        super().__init__(data, path, *rest, **named)


_XACRO = sorted(_DATA.rglob("*.xacro"))


def _every_place(value: object) -> list[object]:
    """Every location in a model object and all it holds (they take no part in ==)."""
    if isinstance(value, tuple | list):
        return [place for item in value for place in _every_place(item)]
    if not dataclasses.is_dataclass(value):
        return []
    found: list[object] = []
    for spec in dataclasses.fields(value):
        item = getattr(value, spec.name)
        found.extend([item] if spec.name.endswith("source") else _every_place(item))
    return found


@pytest.mark.parametrize("path", _FILES + _XACRO, ids=lambda p: str(p.relative_to(_DATA)))
def test_the_scan_trusted_places_every_element_where_comparing_names_does(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    trusted = _outcome(path)
    trusted_places = _every_place(trusted[0])
    monkeypatch.setattr(locator, "Locator", _Comparing)
    compared = _outcome(path)
    assert compared == trusted
    assert _every_place(compared[0]) == trusted_places


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet="=\"' <>\t\n\rax/", max_size=40))
def test_the_quick_look_for_raw_white_space_agrees_with_the_pattern(text: str) -> None:
    data = text.encode()
    assert locator._has_raw_whitespace(data) == (locator._RAW_WHITESPACE.search(data) is not None)


@pytest.mark.parametrize(
    ("value", "raw"),
    [("0 0 1", False), ("0 0\t1", True), ("0\n0 1", True), ("0 0 1\r", True)],
)
def test_raw_white_space_in_a_value_is_found_and_none_elsewhere(value: str, raw: bool) -> None:
    data = f'<robot name="r">\n\t<link name="a">\n<origin xyz="{value}"/>\n'
    assert locator._has_raw_whitespace(data.encode()) is raw


@pytest.mark.parametrize("opening", [b"<!--", b"<![CDATA[", b"<?", b"<!DOCTYPE [", b"<!DOCTYPE r"])
def test_markup_never_closed_runs_to_the_end_of_the_file(opening: bytes) -> None:
    # Matched to the end, not left for the search to try again from each next one (which
    # made a file of many unclosed comments take time growing with its size squared).
    data = b"<robot>" + opening * 5 + b"<link/>"
    found = list(locator.MARKUP.finditer(data))
    assert [(m.start(), m.end(), m.lastindex) for m in found] == [
        (0, 2, 1),  # <robot>
        (7, len(data), None),  # the first unclosed one, and all after it
    ]


_PIECES_OF_XML = st.sampled_from(
    ['<?xml version="1.0"?>', "<a>", "</a>", "<b x='1'/>", "<!-- <c> -->", "<?pi <d>?>", "?", "!"]
)


@settings(max_examples=300, deadline=None)
@given(st.lists(_PIECES_OF_XML, max_size=12), st.sampled_from(["", "\n", " "]))
def test_start_tags_are_found_as_the_markup_scan_finds_them(pieces: list[str], gap: str) -> None:
    data = gap.join(pieces).encode()
    assert locator._start_tags(data) == [
        m.start() for m in locator.MARKUP.finditer(data) if m.lastindex
    ]
