"""`inertial_xml` and `add_inertials`: an <inertial> as text, and added to a URDF in place."""

from __future__ import annotations

import pytest

import fishbot_urdf
from fishbot_urdf.inertia import sphere_inertia

URDF = """<?xml version="1.0"?>
<!-- a robot -->
<!-- two comments -->
<robot name="r">
  <link name="a">
    <!-- the body -->
    <collision>
      <geometry><sphere radius="0.1"/></geometry>
    </collision>
  </link>
  <link name="b"/>
</robot>
"""


def test_inertial_xml() -> None:
    made = sphere_inertia(2.0, 0.5, fishbot_urdf.Origin(xyz=(0.0, 0.0, 0.25)))
    # 2/5 * 2 * 0.25 = 0.2
    assert fishbot_urdf.inertial_xml(made) == (
        "<inertial>\n"
        '  <origin xyz="0 0 0.25" rpy="0 0 0"/>\n'
        '  <mass value="2"/>\n'
        '  <inertia ixx="0.2" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.2"/>\n'
        "</inertial>\n"
    )


def test_add_inertials_keeps_everything_else() -> None:
    made = sphere_inertia(1.0, 0.1)
    text = fishbot_urdf.add_inertials(URDF, {"a": made})
    assert text == URDF.replace(
        '  <link name="a">\n',
        '  <link name="a">\n'
        "    <inertial>\n"
        '      <mass value="1"/>\n'
        f'      <inertia ixx="{made.inertia.ixx!r}" ixy="0" ixz="0" iyy="{made.inertia.iyy!r}" '
        f'iyz="0" izz="{made.inertia.izz!r}"/>\n'
        "    </inertial>\n",
    )
    assert fishbot_urdf.parse(text).link("a").inertial == made


def test_add_inertials_refuses_a_second_inertial_and_unknown_links() -> None:
    once = fishbot_urdf.add_inertials(URDF.encode(), {"a": sphere_inertia(1.0, 0.1)})
    with pytest.raises(ValueError, match="link 'a' has an <inertial> already"):
        fishbot_urdf.add_inertials(once, {"a": sphere_inertia(1.0, 0.1)})
    with pytest.raises(KeyError):
        fishbot_urdf.add_inertials(URDF, {"nope": sphere_inertia(1.0, 0.1)})
