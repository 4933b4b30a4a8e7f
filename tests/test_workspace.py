"""The workspace: unsaved texts over the disk, and answers kept until what they read changes."""

from __future__ import annotations

import os
import shutil
import threading
from pathlib import Path

import pytest

from fishbot_urdf.errors import InputError
from fishbot_urdf.inputs import (
    Cancellation,
    Cancelled,
    allowing_reads,
    cancellable,
    deadline,
    read_input,
    trusting_expressions,
)
from fishbot_urdf.lint import check_file
from fishbot_urdf.workspace import Workspace

ROBOTS = Path(__file__).parent.parent / "robots" / "fishbot"
TOP = "urdf/fishbot/fishbot.urdf.xacro"


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A copy of the fishbot_description package, to edit."""
    copy = tmp_path / "fishbot_description"
    shutil.copytree(ROBOTS, copy)
    return copy


def test_a_held_text_is_read_in_the_place_of_the_disk(tmp_path: Path) -> None:
    file = tmp_path / "robot.urdf"
    file.write_text("<robot name='disk'/>")
    workspace = Workspace()
    workspace.open(file, "<robot name='buffer'/>")
    assert workspace.read(file) == b"<robot name='buffer'/>"
    assert read_input(file) == b"<robot name='disk'/>"  # outside the workspace: the disk
    with workspace.reading():
        assert read_input(os.path.relpath(file)) == b"<robot name='buffer'/>"
    workspace.close(file)
    assert workspace.read(file) == b"<robot name='disk'/>"


def test_a_file_only_an_editor_holds_is_read_and_checked(tmp_path: Path) -> None:
    workspace = Workspace()
    unsaved = tmp_path / "new.urdf"
    workspace.open(
        unsaved,
        "<robot name='r'><link name='a'/><joint name='j' type='fixed'>"
        "<parent link='a'/><child link='b'/></joint></robot>",
    )
    result = check_file(unsaved, workspace=workspace)
    assert [d.rule for d in result.diagnostics if d.is_error] == ["undefined-link"]
    workspace.close(unsaved)
    with pytest.raises(InputError):
        check_file(unsaved, workspace=workspace)


def test_an_unchanged_robot_is_given_again_and_an_edit_of_an_include_remakes_it(
    package: Path,
) -> None:
    workspace = Workspace()
    top = package / TOP
    first = check_file(top, workspace=workspace)
    assert first.ok and workspace.made == 2  # the expansion and the check
    assert check_file(top, workspace=workspace) is first
    assert workspace.made == 2

    base = package / "urdf/fishbot/base.urdf.xacro"
    assert workspace.readers([base])  # the check and its expansion read it
    workspace.open(base, base.read_text().replace('name="base_link"', 'name="base_lnk"', 1))
    broken = check_file(top, workspace=workspace)
    assert broken is not first
    assert "undefined-link" in {d.rule for d in broken.diagnostics}
    # Found in the unsaved text of the included file, at the line the editor shows.
    assert any(d.path.endswith("base.urdf.xacro") for d in broken.diagnostics)

    workspace.close(base)  # the edit given up: the disk's text again
    again = check_file(top, workspace=workspace)
    assert again.ok


def test_a_file_saved_on_disk_remakes_the_answers_that_read_it(package: Path) -> None:
    workspace = Workspace()
    top = package / TOP
    first = check_file(top, workspace=workspace)
    caster = package / "urdf/fishbot/actuator/caster.urdf.xacro"
    text = caster.read_text()
    caster.write_text(text.replace("<xacro:macro", "<!-- edited -->\n<xacro:macro", 1))
    os.utime(caster, ns=(1, 1))  # a time the first read did not see, whatever the clock
    assert check_file(top, workspace=workspace) is not first


def test_a_mesh_found_missing_remakes_the_check_once_it_is_there(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        "<robot name='r'><link name='a'><visual><geometry><mesh filename='part.stl'/>"
        "</geometry></visual></link></robot>"
    )
    workspace = Workspace()
    missing = check_file(robot, workspace=workspace)
    assert "mesh-not-found" in {d.rule for d in missing.diagnostics}
    # A binary STL of one triangle.
    triangle = b"\0" * 80 + (1).to_bytes(4, "little") + b"\0" * 12 * 4 + b"\0\0"
    (tmp_path / "part.stl").write_bytes(triangle)
    found = check_file(robot, workspace=workspace)
    assert "mesh-not-found" not in {d.rule for d in found.diagnostics}


def test_a_workspace_that_keeps_nothing_makes_each_answer_again(package: Path) -> None:
    workspace = Workspace(keep=0)
    top = package / TOP
    first = check_file(top, workspace=workspace)
    assert check_file(top, workspace=workspace) is not first
    assert workspace.made == 4


def test_threads_share_a_workspace(package: Path) -> None:
    workspace = Workspace()
    top = package / TOP
    results: list[bool] = []

    def work() -> None:
        results.append(check_file(top, workspace=workspace).ok)

    threads = [threading.Thread(target=work) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert results == [True] * 4


def test_cancelled_work_stops_at_its_next_look_at_the_deadline(package: Path) -> None:
    cancellation = Cancellation()
    cancellation.cancel()
    with cancellable(cancellation), pytest.raises(Cancelled):
        deadline().check("work")
    with cancellable(cancellation), pytest.raises(Cancelled):
        check_file(package / TOP, workspace=Workspace())


def test_an_answer_made_from_a_kept_answer_depends_on_its_files(tmp_path: Path) -> None:
    inner_file, outer_file = tmp_path / "inner.txt", tmp_path / "outer.txt"
    inner_file.write_text("1")
    outer_file.write_text("2")
    workspace = Workspace()

    def inner() -> bytes:
        return workspace.memo("inner", lambda: read_input(inner_file))

    assert inner() == b"1"  # kept: the outer answer below is made from it unread

    def outer() -> bytes:
        return inner() + read_input(outer_file)

    assert workspace.memo("outer", outer) == b"12"
    assert set(workspace.readers([inner_file])) == {"inner", "outer"}
    workspace.open(inner_file, "3")
    assert workspace.memo("outer", outer) == b"32"


def test_a_file_changed_while_the_answer_is_made_makes_it_stale(tmp_path: Path) -> None:
    """The fingerprint kept is the file's before it was read: one saved by another program
    while the answer was made is not taken as what the answer read."""
    file = tmp_path / "robot.urdf"
    file.write_text("<robot name='a'/>")
    workspace = Workspace()

    def make() -> bytes:
        data = read_input(file)
        file.write_text("<robot name='bb'/>")  # saved meanwhile, after the read
        os.utime(file, ns=(2, 2))
        return data

    assert workspace.memo("robot", make) == b"<robot name='a'/>"
    assert workspace.memo("robot", lambda: read_input(file)) == b"<robot name='bb'/>"


def test_an_answer_is_kept_for_the_trust_and_the_folders_it_was_made_with(
    package: Path, tmp_path: Path
) -> None:
    workspace = Workspace()
    top = package / TOP
    check_file(top, workspace=workspace)
    with trusting_expressions():
        check_file(top, workspace=workspace)
    with allowing_reads(tmp_path):
        check_file(top, workspace=workspace)
    assert workspace.made == 6  # three checks, three expansions: none given for another
