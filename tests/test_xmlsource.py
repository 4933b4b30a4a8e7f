"""xmlsource's Locator: every element's and attribute's line and column, against counting them
directly in the bytes."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from fishbot_urdf.xmlsource import Locator


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
