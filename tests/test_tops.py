"""The robots a file belongs to: itself when it holds links or joints or nothing of its
package reads it, else the outermost xacro files of its package that read it."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import FISHBOT

from fishbot_urdf.tops import find_tops, holds_robot, package_folder
from fishbot_urdf.workspace import Workspace


@pytest.fixture
def package(tmp_path: Path) -> Path:
    copy = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, copy)
    return copy


def test_an_included_file_belongs_to_the_robot_that_reads_it(package: Path) -> None:
    urdf = package / "urdf" / "fishbot"
    top = str(urdf / "fishbot.urdf.xacro")
    workspace = Workspace()
    for part in ("base.urdf.xacro", "common_inertia.xacro", "actuator/wheel.urdf.xacro"):
        assert find_tops(urdf / part, workspace) == (top,)
    assert find_tops(top, workspace) == (top,)
    # a robot file of its own
    first = str(package / "urdf" / "first_robot.urdf")
    assert find_tops(first, workspace) == (first,)


def test_what_a_file_belongs_to_follows_the_editors_text(package: Path) -> None:
    urdf = package / "urdf" / "fishbot"
    top = urdf / "fishbot.urdf.xacro"
    base = str(urdf / "base.urdf.xacro")
    workspace = Workspace()
    assert find_tops(base, workspace) == (str(top),)
    text = top.read_text(encoding="utf-8")
    include = '<xacro:include filename="$(find fishbot_description)/urdf/fishbot/base.urdf.xacro"/>'
    assert include in text
    workspace.open(top, text.replace(include, ""))
    assert find_tops(base, workspace) == (base,)  # nothing reads it now
    workspace.close(top)
    assert find_tops(base, workspace) == (str(top),)
    # a robot that includes the top file is the one robot of both
    outer = urdf / "outer.urdf.xacro"
    outer.write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="outer">\n'
        '  <xacro:include filename="fishbot.urdf.xacro"/>\n</robot>\n',
        encoding="utf-8",
    )
    assert find_tops(base, workspace) == (str(outer),)
    assert find_tops(top, workspace) == (str(outer),)


def test_an_included_file_that_breaks_its_robot_still_belongs_to_it(package: Path) -> None:
    urdf = package / "urdf" / "fishbot"
    base = urdf / "base.urdf.xacro"
    workspace = Workspace()
    workspace.open(base, base.read_text(encoding="utf-8")[:200])  # not XML any more
    assert find_tops(base, workspace) == (str(urdf / "fishbot.urdf.xacro"),)


def test_holds_robot() -> None:
    assert holds_robot(b'<robot name="r"><link name="a"/></robot>')
    assert holds_robot(b'<robot name="r"><joint name="j" type="fixed"/></robot>')
    macros = b'<robot xmlns:xacro="x"><xacro:macro name="m"><link name="a"/></xacro:macro></robot>'
    assert not holds_robot(macros)
    assert not holds_robot(b"<robot><xacro:property name='p' value='1'/></robot>")
    # as far as the text can be read (the rest may be being typed)
    assert holds_robot(b"<robot><link")
    assert not holds_robot(b"<robot><xacro:macro><link")
    assert not holds_robot(b"\x00\xff")


def test_package_folder(package: Path, tmp_path: Path) -> None:
    assert package_folder(package / "urdf" / "fishbot" / "base.urdf.xacro") == str(package)
    loose = tmp_path / "loose" / "robot.urdf"
    assert package_folder(loose) == str(tmp_path / "loose")
