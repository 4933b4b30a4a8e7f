"""ROS package resolution without ROS: each place in its order, and the failures."""

from __future__ import annotations

import builtins
import os
import sys
from pathlib import Path
from typing import Any

import pytest

from fishbot_urdf import packages
from fishbot_urdf.inputs import recording_inputs
from fishbot_urdf.packages import (
    PackageFinder,
    PackageNotFoundError,
    find_package,
    package_name,
    resolve_package_uri,
)


def _package(folder: Path, name: str | None) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    inner = f"<name>{name}</name>" if name is not None else ""
    (folder / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<package format="3">\n  <!-- <name>not_this</name> -->\n'
        f"  {inner}\n  <version>0.1.0</version>\n</package>\n"
    )
    return folder


@pytest.fixture(autouse=True)
def _no_ros(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    # not importable here, whatever the machine has
    monkeypatch.setitem(sys.modules, "ament_index_python", None)
    monkeypatch.setitem(sys.modules, "ament_index_python.packages", None)


def test_package_name_skips_comments(tmp_path: Path) -> None:
    assert package_name(_package(tmp_path / "a", "real_name") / "package.xml") == "real_name"
    assert package_name(_package(tmp_path / "b", None) / "package.xml") is None
    assert package_name(tmp_path / "missing.xml") is None


def test_explicit_packages_come_first(tmp_path: Path) -> None:
    own = _package(tmp_path / "pkg", "fishbot_description")
    given = tmp_path / "given"
    given.mkdir()
    found = find_package(
        "fishbot_description",
        near=own / "urdf" / "x.xacro",
        packages={"fishbot_description": given},
    )
    assert found == given


def test_walking_up_from_the_file(tmp_path: Path) -> None:
    own = _package(tmp_path / "fishbot_description", "fishbot_description")
    near = own / "urdf" / "fishbot" / "fishbot.urdf.xacro"
    assert find_package("fishbot_description", near=near) == own.resolve()


def test_ros_package_path_in_order(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first = _package(tmp_path / "one" / "deep" / "wheel_description", "wheel_description")
    _package(tmp_path / "two" / "wheel_description", "wheel_description")
    monkeypatch.setenv(
        "ROS_PACKAGE_PATH", os.pathsep.join([str(tmp_path / "one"), str(tmp_path / "two")])
    )
    assert find_package("wheel_description", near=tmp_path / "robot.xacro") == first


def test_the_shallower_of_two_packages_wins(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    near = _package(tmp_path / "root" / "a" / "wheel_description", "wheel_description")
    _package(tmp_path / "root" / "b" / "c" / "wheel_description", "wheel_description")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "root"))
    assert find_package("wheel_description") == near


def test_packages_are_not_searched_inside(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    outer = _package(tmp_path / "root" / "outer", "outer")
    _package(outer / "inner", "inner")
    (tmp_path / "root" / "ignored").mkdir()
    (tmp_path / "root" / "ignored" / "COLCON_IGNORE").touch()
    _package(tmp_path / "root" / "ignored" / "hidden", "hidden")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "root"))
    for name in ("inner", "hidden"):
        with pytest.raises(PackageNotFoundError):
            find_package(name)


def test_ament_prefix_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = tmp_path / "install"
    share = prefix / "share" / "lidar_description"
    share.mkdir(parents=True)
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages"
    marker.mkdir(parents=True)
    (marker / "lidar_description").touch()
    monkeypatch.setenv("AMENT_PREFIX_PATH", os.pathsep.join([str(tmp_path / "none"), str(prefix)]))
    assert find_package("lidar_description") == share


def test_colcon_workspace_around_the_file(tmp_path: Path) -> None:
    workspace = tmp_path / "ws"
    own = _package(workspace / "src" / "robot_bringup", "robot_bringup")
    other = _package(workspace / "src" / "parts" / "camera_description", "camera_description")
    (workspace / "build").mkdir()
    near = own / "urdf" / "robot.urdf.xacro"
    assert find_package("camera_description", near=near) == other


def test_ament_index_python_last(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    stub = Path(__file__).resolve().parent / "ament_stub"
    monkeypatch.delitem(sys.modules, "ament_index_python")
    monkeypatch.delitem(sys.modules, "ament_index_python.packages")
    monkeypatch.syspath_prepend(str(stub))
    monkeypatch.setenv("FISHBOT_TEST_PACKAGES", f"sourced_description={tmp_path}")
    assert find_package("sourced_description") == tmp_path
    with pytest.raises(PackageNotFoundError) as info:
        find_package("not_sourced")
    assert info.value.searched[-1] == "ament_index_python"


def test_a_package_without_a_name_is_not_a_match(tmp_path: Path) -> None:
    nameless = _package(tmp_path / "fishbot_description", None)
    with pytest.raises(PackageNotFoundError) as info:
        find_package("fishbot_description", near=nameless / "urdf" / "x.xacro")
    assert info.value.searched == (
        "the packages given (none)",
        f"the folders above {(nameless / 'urdf').resolve()}",
        "ROS_PACKAGE_PATH (not set)",
        "AMENT_PREFIX_PATH (not set)",
        "ament_index_python (not installed)",
    )


def test_package_uris(tmp_path: Path) -> None:
    own = _package(tmp_path / "fishbot_description", "fishbot_description")
    near = own / "urdf" / "robot.urdf"
    assert resolve_package_uri("package://fishbot_description/meshes/a.stl", near=near) == (
        own.resolve() / "meshes" / "a.stl"
    )
    assert resolve_package_uri("file:///abs/b.stl") == Path("/abs/b.stl")
    assert resolve_package_uri("meshes/c.stl", near=near) == own / "urdf" / "meshes" / "c.stl"
    with pytest.raises(PackageNotFoundError):
        resolve_package_uri("package://elsewhere/x.stl", near=near)


def test_linked_packages_are_followed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real = _package(tmp_path / "elsewhere" / "fishbot_description", "fishbot_description")
    src = tmp_path / "ws" / "src"
    src.mkdir(parents=True)
    (src / "fishbot_description").symlink_to(real, target_is_directory=True)
    (src / "loop").symlink_to(src, target_is_directory=True)  # a cycle is walked once
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(src))
    assert find_package("fishbot_description") == src / "fishbot_description"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="this system has no FIFOs")
def test_a_package_xml_that_is_a_fifo_is_no_package_and_no_hang(tmp_path: Path) -> None:
    os.mkfifo(tmp_path / "package.xml")  # nothing writes to it: a read would wait for ever
    assert package_name(tmp_path / "package.xml") is None


def test_a_package_xml_of_unclosed_comments_has_no_name(tmp_path: Path) -> None:
    (tmp_path / "package.xml").write_text("<package>" + "<!--" * 50_000)
    assert package_name(tmp_path / "package.xml") is None
    (tmp_path / "package.xml").write_text(
        '<package format="3"><!-- <name>no</name> --><name> pkg </name></package>'
    )
    assert package_name(tmp_path / "package.xml") == "pkg"


def _lxml_name(data: bytes) -> str | None:
    """The name as lxml reads it: the text of the root <package>'s first <name> child."""
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, load_dtd=False, no_network=True)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return None
    if etree.QName(root).localname != "package":
        return None
    name = root.find("{*}name")
    return None if name is None or name.text is None else name.text.strip() or None


@pytest.mark.parametrize(
    "text",
    [
        "<package><name>a</name></package>",
        "<package><name> a b </name><name>c</name></package>",
        "<package><description><name>x</name></description><name>y</name></package>",
        "<p:package xmlns:p='u'><p:name>n</p:name></p:package>",
        "<package xmlns='u'><name>n</name></package>",
        "<robot><name>n</name></robot>",
        "<package><name>a<!--c-->b</name></package>",
        "<package><name>a<b/>c</name></package>",
        "<package><name>a<?pi x?>b</name></package>",
        "<package><name><![CDATA[q]]>r</name></package>",
        "<package><name>a&amp;b&#65;</name></package>",
        "<package><name/></package>",
        "<package><name>   </name></package>",
        "<package><nam>x</nam></package>",
        "<package><name>grün</name></package>",
        "<?xml version='1.0'?>\n<!-- c --><package format='3'>\n <name>\n pkg\n </name></package>",
        "<package><name>a</name>",  # not well-formed
        "<package><name>a</name></package><x/>",
        "",
    ],
)
def test_package_name_reads_as_lxml_reads(tmp_path: Path, text: str) -> None:
    path = tmp_path / "package.xml"
    path.write_text(text, encoding="utf-8")
    assert package_name(path) == _lxml_name(text.encode("utf-8"))


def test_package_name_refuses_a_file_that_declares_entities(tmp_path: Path) -> None:
    path = tmp_path / "package.xml"
    path.write_text("<!DOCTYPE package [<!ENTITY e 'x'>]><package><name>&e;</name></package>")
    assert package_name(path) is None


def test_a_finder_answers_as_find_package_once_per_package_and_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    own = _package(tmp_path / "robot_description", "robot_description")
    (own / "urdf").mkdir()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "linked.urdf").write_text("<robot/>")
    # A file linked into the package's folder starts its search from where it really is.
    (own / "urdf" / "linked.urdf").symlink_to(elsewhere / "linked.urdf")
    looked: list[tuple[str, str]] = []
    real = packages.find_package

    def counted(name: str, **options: object) -> Path:
        looked.append((name, os.path.basename(os.path.dirname(str(options["near"])))))
        return real(name, **options)

    monkeypatch.setattr(packages, "find_package", counted)
    finder = PackageFinder({"given": tmp_path})
    for file in ("a.urdf", "b.urdf", "a.urdf"):
        near = own / "urdf" / file
        assert finder.find("robot_description", near=near) == real("robot_description", near=near)
        with pytest.raises(PackageNotFoundError) as error:
            finder.find("nowhere", near=near)
        with pytest.raises(PackageNotFoundError) as expected:
            real("nowhere", near=near, packages={"given": tmp_path})
        assert (error.value.package, error.value.searched, error.value.given) == (
            expected.value.package,
            expected.value.searched,
            expected.value.given,
        )
        assert str(error.value) == str(expected.value)
    assert finder.find("given", near=own / "urdf" / "a.urdf") == tmp_path.resolve()
    with pytest.raises(PackageNotFoundError):
        finder.find("robot_description", near=own / "urdf" / "linked.urdf")
    assert looked == [
        ("robot_description", "urdf"),
        ("nowhere", "urdf"),
        ("given", "urdf"),
        ("robot_description", "urdf"),  # the linked file, which really is elsewhere
    ]


def test_ament_index_python_not_found_is_remembered_until_the_import_path_changes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.delitem(sys.modules, "ament_index_python")
    monkeypatch.delitem(sys.modules, "ament_index_python.packages")
    monkeypatch.setattr(sys, "path", [p for p in sys.path if not p.endswith("ament_stub")])
    monkeypatch.setattr(packages, "_ament_missing_from", [])
    tried: list[str] = []
    real_import = builtins.__import__

    def counting(name: str, *args: Any, **kwargs: Any) -> Any:
        if name.startswith("ament_index_python"):
            tried.append(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", counting)
    assert packages._ament_lookup() is None
    assert packages._ament_lookup() is None
    assert tried == ["ament_index_python.packages"]  # looked for once
    monkeypatch.syspath_prepend(str(Path(__file__).resolve().parent / "ament_stub"))
    assert packages._ament_lookup() is not None  # a new import path: looked for again
    assert len(tried) == 2


def test_links_that_cannot_be_followed_in_a_workspace_are_passed_over(tmp_path: Path) -> None:
    workspace = tmp_path / "ws"
    own = _package(workspace / "src" / "robot_bringup", "robot_bringup")
    other = _package(workspace / "src" / "zz" / "camera_description", "camera_description")
    (workspace / "build").mkdir()
    (workspace / "src" / "loop").symlink_to("loop")  # a link to itself
    (workspace / "src" / "a").symlink_to("b")  # a loop of two
    (workspace / "src" / "b").symlink_to("a")
    (workspace / "src" / "dangling").symlink_to(tmp_path / "nowhere")
    near = own / "urdf" / "robot.urdf.xacro"
    assert find_package("camera_description", near=near) == other
    with pytest.raises(PackageNotFoundError, match="the workspace"):
        find_package("missing", near=near)


def test_a_folder_that_cannot_be_listed_is_passed_over(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    workspace = tmp_path / "ws"
    own = _package(workspace / "src" / "robot_bringup", "robot_bringup")
    other = _package(workspace / "src" / "zz" / "camera_description", "camera_description")
    (workspace / "build").mkdir()
    (workspace / "src" / "locked").mkdir()
    (workspace / "src" / "locked" / "link").symlink_to("x")

    class Refused:
        """A folder entry whose link cannot be looked at (no permission, as for a user)."""

        name = "link"
        path = str(workspace / "src" / "locked" / "link")

        def is_dir(self) -> bool:
            raise PermissionError(13, "Permission denied", self.path)

    real = os.scandir

    def scandir(folder: Any) -> Any:
        if str(folder).endswith("locked"):
            return iter([Refused()])
        return real(folder)

    monkeypatch.setattr(os, "scandir", scandir)
    assert find_package("camera_description", near=own / "urdf" / "r.urdf") == other


def test_the_manifests_read_are_recorded(tmp_path: Path) -> None:
    workspace = tmp_path / "ws"
    own = _package(workspace / "src" / "robot_bringup", "robot_bringup")
    other = _package(workspace / "src" / "zz" / "camera_description", "camera_description")
    (workspace / "build").mkdir()
    near = own / "urdf" / "robot.urdf"
    with recording_inputs() as read:
        find_package("robot_bringup", near=near)
    assert read == [os.path.join(own, "package.xml")]
    finder = PackageFinder()
    with recording_inputs() as outer:
        with recording_inputs() as inner:
            assert finder.find("camera_description", near=near) == other
        assert str(other / "package.xml") in inner
        assert outer == inner  # an inner recording's manifests are the outer one's too
    with recording_inputs() as again:  # a remembered answer: the same manifests
        finder.find("camera_description", near=near)
    assert again == inner
    find_package("robot_bringup", near=near)  # outside a recording: nothing to note


def test_the_manifest_of_a_package_found_by_its_place_is_recorded(tmp_path: Path) -> None:
    # Found without reading its package.xml (by --package, or under AMENT_PREFIX_PATH),
    # the package still stands on it: an output must not replace it.
    given = _package(tmp_path / "given", "given_pkg")
    installed = _package(tmp_path / "install" / "share" / "installed_pkg", "installed_pkg")
    environ = {"AMENT_PREFIX_PATH": str(tmp_path / "install")}
    with recording_inputs() as read:
        assert find_package("given_pkg", packages={"given_pkg": given}) == given
        assert find_package("installed_pkg", environ=environ) == installed
    assert read == [str(given / "package.xml"), str(installed / "package.xml")]
