"""The mesh rules: every mesh name resolves to a file, in its exact case, through a
well-formed URI, in a format robot programs load."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import binary_stl, box_stl, fine_stl

from fishbot_urdf import Config, check_file
from fishbot_urdf.cli import cli
from fishbot_urdf.inputs import recording_inputs

ROBOT = """\
<robot name="r">
  <link name="base_link">
    <visual><geometry><mesh filename="{name}"/></geometry></visual>
  </link>
</robot>
"""


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A ROS package "demo" with meshes/base_link.stl, and a robot file in its urdf/ folder."""
    root = tmp_path / "demo"
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "meshes" / "base_link.stl").write_bytes(b"solid s\nendsolid s\n")
    (root / "package.xml").write_text(
        '<package format="3"><name>demo</name></package>', encoding="utf-8"
    )
    return root


def _found(package: Path, name: str, **packages: Path) -> list[tuple[str, str, str]]:
    path = package / "urdf" / "robot.urdf"
    path.write_text(ROBOT.format(name=name), encoding="utf-8")
    found = check_file(path, packages=packages).diagnostics
    return [(d.rule, d.severity.value, d.format().split(": ", 2)[2]) for d in found]


@pytest.mark.parametrize(
    "name",
    [
        "package://demo/meshes/base_link.stl",  # found by the package.xml above the robot
        "../meshes/base_link.stl",  # beside the robot file
        "{root}/meshes/base_link.stl",
        "file://{root}/meshes/base_link.stl",
        "https://example.com/base_link.stl",  # not ours to fetch
    ],
)
def test_meshes_that_resolve(package: Path, name: str) -> None:
    assert _found(package, name.format(root=package)) == []


def test_a_missing_mesh_says_where_it_looked_and_suggests_a_name(package: Path) -> None:
    found = _found(package, "package://demo/meshes/base_lnk.stl")
    looked = package / "meshes" / "base_lnk.stl"
    assert found == [
        (
            "mesh-not-found",
            "error",
            f"link 'base_link': mesh 'package://demo/meshes/base_lnk.stl' is not found "
            f"(looked for {looked}) (did you mean 'package://demo/meshes/base_link.stl'? "
            "package:// names a file inside the package's folder) [mesh-not-found]",
        )
    ]


def test_a_mesh_named_in_another_case(package: Path) -> None:
    [(rule, severity, message)] = _found(package, "package://demo/meshes/Base_Link.STL")
    assert (rule, severity) == ("mesh-case", "error")
    assert "is found only as 'package://demo/meshes/base_link.stl'" in message
    [(rule, _, message)] = _found(package, "package://demo/Meshes/base_link.stl")  # a folder too
    assert rule == "mesh-case"
    assert "is found only as 'package://demo/meshes/base_link.stl'" in message


@pytest.mark.parametrize(
    ("name", "suggested"),
    [
        ("../meshes/base_lnk.stl", "../meshes/base_link.stl"),
        ("file://{root}/meshes/base_lnk.stl", "file://{root}/meshes/base_link.stl"),
        ("{root}/meshes/base_lnk.stl", "{root}/meshes/base_link.stl"),  # as the robot writes
    ],
)
def test_a_name_suggested_is_written_as_the_robot_writes_its_name(
    package: Path, name: str, suggested: str
) -> None:
    [(rule, _, message)] = _found(package, name.format(root=package))
    assert rule == "mesh-not-found"
    assert f"did you mean '{suggested.format(root=package)}'?" in message


XACRO_MESHES = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link">
    <visual><geometry><mesh filename="{name}"/></geometry></visual>
  </link>
</robot>
"""


@pytest.mark.parametrize(
    ("name", "found"),
    [
        ("$(find demo)/meshes/base_lnk.stl", "did you mean '$(find demo)/meshes/base_link.stl'?"),
        ("file://$(find demo)/meshes/base_lnk.stl", "'file://$(find demo)/meshes/base_link.stl'"),
        ("$(find demo)/meshes/Base_Link.stl", "found only as '$(find demo)/meshes/base_link.stl'"),
        (
            "package://demo/meshes/base_lnk.stl",
            "did you mean 'package://demo/meshes/base_link.stl'",
        ),
    ],
)
def test_a_xacro_robot_is_offered_names_in_its_own_form_never_this_machine_s_path(
    package: Path, name: str, found: str
) -> None:
    path = package / "urdf" / "robot.urdf.xacro"
    path.write_text(XACRO_MESHES.format(name=name), encoding="utf-8")
    [finding] = [d for d in check_file(path).diagnostics if d.rule.startswith("mesh-")]
    said = f"{finding.message} ({finding.hint})"
    assert found in said
    offered = said.partition(" is ")[2]  # after the mesh's name, as expanded
    assert f"'{package}" not in offered
    assert f"'file://{package}" not in offered


@pytest.mark.parametrize(
    ("name", "what"),
    [
        ("package:///", "names no package and no file"),
        ("package://demo", "names a package but no file in it"),
        ("package:/demo/meshes/base_link.stl", "is not a package:// URI"),
        ("file://meshes/base_link.stl", "is a file:// URI with a relative path"),
        ("..\\meshes\\base_link.stl", "holds backslashes"),
    ],
)
def test_malformed_uris(package: Path, name: str, what: str) -> None:
    [(rule, severity, message)] = _found(package, name)
    assert (rule, severity) == ("mesh-uri", "error")
    assert f"mesh {name!r} {what}" in message


def test_a_package_uri_without_the_package_is_found_by_its_path(package: Path) -> None:
    # As PyBullet and yourdfpy find it: the path above the robot file's folder; as
    # pinocchio does: the package its first folder names (TALOS in example-robot-data).
    for name in ("package:///meshes/base_link.stl", "package:///demo/meshes/base_link.stl"):
        [(rule, severity, message)] = _found(package, name, demo=package)
        assert (rule, severity) == ("package-no-name", "warning")
        assert message == (
            f"link 'base_link': mesh {name!r} names no package (package:///), which ROS's "
            "resource_retriever refuses (RViz, MoveIt); PyBullet, yourdfpy and pinocchio "
            f"(given its package folders) find it by its path, as {package}/meshes/"
            "base_link.stl (write package://demo/meshes/base_link.stl) [package-no-name]"
        )


def test_a_package_uri_without_the_package_leading_nowhere_is_also_not_found(
    package: Path,
) -> None:
    for name in ("package:///base_link.stl", "package:///meshes/gone.stl"):
        found = _found(package, name)
        assert [(rule, severity) for rule, severity, _ in found] == [
            ("mesh-not-found", "error"),
            ("package-no-name", "warning"),
        ]
        # its first folder is no package to look for: 'meshes' is never one
        assert "package 'meshes'" not in found[0][2] and "--package" not in found[0][2]
        assert found[0][2].endswith(
            "(with no package named, it was looked for from the robot file's folder and each "
            "folder above it, as PyBullet and yourdfpy look) [mesh-not-found]"
        )
        assert found[1][2].endswith(
            "(write package://PACKAGE/path, with the package's name after the two slashes) "
            "[package-no-name]"
        )


def test_a_package_not_found_is_a_warning_naming_the_places_searched(
    package: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    [(rule, severity, message)] = _found(package, "package://elsewhere/meshes/a.stl")
    assert (rule, severity) == ("mesh-not-found", "warning")
    assert "is in package 'elsewhere', which is not found, so the file cannot be checked" in message
    assert "ROS_PACKAGE_PATH (not set)" in message
    assert "--package" not in message  # the library's words name no command-line option
    from click.testing import CliRunner

    from fishbot_urdf.cli import cli

    robot = str(package / "urdf" / "robot.urdf")
    said = CliRunner().invoke(cli, ["check", "-q", "--isolated", robot]).stderr
    assert said.endswith("; give its folder with --package elsewhere=PATH) [mesh-not-found]\n")
    other = package.parent / "elsewhere"
    (other / "meshes").mkdir(parents=True)
    (other / "meshes" / "a.stl").write_bytes(b"")
    assert _found(package, "package://elsewhere/meshes/a.stl", elsewhere=other) == []


LEFT_UNEXPANDED = (
    "a xacro substitution left unexpanded (run xacro or `fishbot expand` on the .xacro file "
    "it came from, or give that file instead) [mesh-not-found]"
)


@pytest.mark.parametrize(
    ("name", "left"),
    [
        ("$(find demo)/meshes/base_link.stl", "$(find demo)"),
        ("package://demo/meshes/$(arg model)/base_link.stl", "$(arg model)"),
        ("package://elsewhere/meshes/${model}.stl", "${model}"),  # a package not found too
        ("$(arg mesh)", "$(arg mesh)"),  # no extension either: no word on its format
    ],
)
def test_a_xacro_substitution_left_in_a_mesh_name_is_named_not_another_name_suggested(
    package: Path, name: str, left: str
) -> None:
    robot = package / "urdf" / "robot.urdf"
    robot.write_text(ROBOT.format(name=name), encoding="utf-8")
    said = CliRunner().invoke(cli, ["check", "-q", "--isolated", str(robot)])
    assert (said.exit_code, said.stderr) == (
        1,
        f"{robot}:3:23: error: link 'base_link': mesh {name!r} is not found: {left!r} in it is "
        f"{LEFT_UNEXPANDED}\n",
    )
    # A file of that very name is a file like any other.
    (package / "urdf" / "$(arg mesh)").write_bytes(b"solid s\nendsolid s\n")
    robot.write_text(ROBOT.format(name="$(arg mesh)"), encoding="utf-8")
    found = CliRunner().invoke(cli, ["check", "-q", "--isolated", str(robot)]).stderr
    assert "left unexpanded" not in found


@pytest.mark.parametrize(
    ("name", "what"),
    [("../meshes/base_link.step", "is a .step file"), ("../meshes/base_link", "has no file")],
)
def test_formats_few_programs_load(package: Path, name: str, what: str) -> None:
    (package / "meshes" / Path(name).name).write_bytes(b"")
    [(rule, severity, message)] = _found(package, name)
    assert (rule, severity) == ("mesh-format", "warning")
    assert what in message


def test_the_command_line_finds_packages_given_and_stdin_has_no_folder(package: Path) -> None:
    text = ROBOT.format(name="package://demo/meshes/base_link.stl")
    given = ["check", "--package", f"demo={package}", "-"]
    assert CliRunner().invoke(cli, given, input=text).exit_code == 0
    relative = ROBOT.format(name="meshes/nowhere.stl")  # nothing to be relative to: not judged
    assert CliRunner().invoke(cli, ["check", "-"], input=relative).exit_code == 0


# -- what the mesh files hold ----------------------------------------------------------------

SIZED = """\
<robot name="r">
  <link name="base_link">
    <visual><geometry><mesh filename="../meshes/part.stl"{scale}/></geometry></visual>
    {other}
  </link>
</robot>
"""


@pytest.mark.parametrize(
    ("size", "scale", "other", "said"),
    [
        # 200 units: 200 m as metres, more than any robot part
        (
            200,
            "",
            "",
            "is 200 m across, more than any robot part; in millimetres it would be 0.2 m",
        ),
        (200, ' scale="0.001 0.001 0.001"', "", None),
        (3, "", "", None),  # 3 m: large, but a part may be
        # 3 units against a 3 mm box beside it
        (
            3,
            "",
            '<visual><geometry><box size="0.003 0.003 0.003"/></geometry></visual>',
            "is 3 m across, but its box says the link is about 0.003 m",
        ),
        # 200 units beside a 150 m box: a large part in metres (a field, a building)
        (200, "", '<visual><geometry><box size="150 150 1"/></geometry></visual>', None),
        # 3 units against an inertia: a 1 kg rod of length L has I = L^2 / 12; L = 0.003
        (
            3,
            "",
            '<inertial><mass value="1"/><inertia ixx="7.5e-7" iyy="7.5e-7" '
            'izz="1e-8" ixy="0" ixz="0" iyz="0"/></inertial>',
            "is 3 m across, but its inertia says the link is about 0.003 m",
        ),
    ],
)
def test_a_mesh_in_millimetres(
    package: Path, size: float, scale: str, other: str, said: str | None
) -> None:
    (package / "meshes" / "part.stl").write_bytes(box_stl(size, size / 2, size / 4))
    path = package / "urdf" / "robot.urdf"
    path.write_text(SIZED.format(scale=scale, other=other), encoding="utf-8")
    found = [d for d in check_file(path).diagnostics if d.rule == "mesh-units"]
    if said is None:
        assert found == []
    else:
        [finding] = found
        assert said in finding.message
        assert (
            finding.hint == 'if it is in millimetres, add scale="0.001 0.001 0.001" to the <mesh>'
        )


def test_a_fine_collision_mesh_is_a_note_a_fine_visual_one_nothing(package: Path) -> None:
    (package / "meshes" / "fine.stl").write_bytes(fine_stl(25_000))
    path = package / "urdf" / "robot.urdf"
    mesh = '<geometry><mesh filename="../meshes/fine.stl"/></geometry>'
    path.write_text(f'<robot name="r"><link name="a"><visual>{mesh}</visual></link></robot>')
    assert [d.rule for d in check_file(path).diagnostics] == []
    path.write_text(
        f'<robot name="r"><link name="a"><collision>{mesh}</collision>'
        '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>'
        "</inertial></link></robot>"
    )
    [finding] = check_file(path).diagnostics
    assert (finding.rule, finding.severity.value) == ("mesh-faces", "note")
    assert "has 25000 faces, too many for a collision shape" in finding.message


def test_a_package_not_found_is_reported_once_for_all_its_meshes(
    package: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    path = package / "urdf" / "robot.urdf"
    mesh = '<geometry><mesh filename="package://elsewhere/{}.stl"/></geometry>'
    path.write_text(
        f'<robot name="r"><link name="a"><visual>{mesh.format("a")}</visual>'
        f"<visual>{mesh.format('b')}</visual><visual>{mesh.format('c')}</visual></link></robot>"
    )
    [finding] = check_file(path).diagnostics
    assert finding.message == (
        "link 'a': mesh 'package://elsewhere/a.stl' is in package 'elsewhere', which is not "
        "found, so the file cannot be checked (nor 2 other meshes of it)"
    )


@pytest.mark.parametrize(
    ("data", "said"),
    [
        (
            b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
            b"vertex 1e999 1 0\nendloop\nendfacet\nendsolid s\n",
            "a vertex is not a finite number",
        ),
        (
            b"\0" * 80 + (2).to_bytes(4, "little") + b"\0" * 50,  # says 2 triangles, holds 1
            "a binary STL of 2 triangles is 184 bytes long, not 134",
        ),
    ],
)
def test_a_malformed_mesh_is_a_warning_saying_what_is_wrong(
    package: Path, data: bytes, said: str
) -> None:
    (package / "meshes" / "bad.stl").write_bytes(data)
    [(rule, severity, message)] = _found(package, "package://demo/meshes/bad.stl")
    assert (rule, severity) == ("mesh-invalid", "warning")
    assert message.startswith("link 'base_link': mesh 'package://demo/meshes/bad.stl' ")
    assert said in message
    assert message.endswith("(export the mesh again) [mesh-invalid]")


COLLIDING = """\
<robot name="r">
  <link name="base_link">
    <collision><geometry><mesh filename="{name}"/></geometry></collision>
    <visual><geometry><mesh filename="{name}"/></geometry></visual>
  </link>
</robot>
"""


def _turned(triangles: list[tuple[float, ...]]) -> list[tuple[float, ...]]:
    """The triangles turned about x by 30 degrees and about z by 40, and moved off the origin."""
    import math

    def turn(x: float, y: float, z: float) -> tuple[float, float, float]:
        a, b = math.radians(30), math.radians(40)
        y, z = y * math.cos(a) - z * math.sin(a), y * math.sin(a) + z * math.cos(a)
        x, y = x * math.cos(b) - y * math.sin(b), x * math.sin(b) + y * math.cos(b)
        return x + 10.0, y + 20.0, z + 5.0

    return [tuple(v for k in range(3) for v in turn(*t[3 * k : 3 * k + 3])) for t in triangles]


def _flat_found(tmp_path: Path, stl: bytes) -> list[tuple[str, str, str]]:
    (tmp_path / "part.stl").write_bytes(stl)
    path = tmp_path / "r.urdf"
    path.write_text(COLLIDING.format(name="part.stl"), encoding="utf-8")
    found = check_file(path).diagnostics
    return [(d.rule, d.severity.value, d.message) for d in found if d.rule == "mesh-flat"]


def test_a_flat_collision_mesh_has_no_hull(tmp_path: Path) -> None:
    # the visual of the same mesh is no fault: nothing collides with it
    assert _flat_found(tmp_path, box_stl(0.2, 0.3, 0.0)) == [
        (
            "mesh-flat",
            "warning",
            "link 'base_link': mesh 'part.stl' has every vertex in one plane, no volume to "
            "collide with: MuJoCo refuses the robot ('coplanar vertices, cannot compute convex "
            "hull')",
        )
    ]
    [(_, _, line)] = _flat_found(tmp_path, box_stl(0.2, 0.0, 0.0))
    assert "every vertex on one line" in line and "'collinear vertices" in line
    [(_, _, few)] = _flat_found(tmp_path, binary_stl([(0, 0, 0, 1, 0, 0, 0, 1, 0)]))
    assert "has 3 distinct vertices" in few and "('at least 4 vertices required')" in few


def test_a_turned_plate_is_flat_but_for_its_rounding(tmp_path: Path) -> None:
    # float32 rounds a turned plate's vertices off its plane, by about 1e-6 here
    plate = _turned([(0, 0, 0, 0.5, 0, 0, 0.5, 0.4, 0), (0, 0, 0, 0.5, 0.4, 0, 0, 0.4, 0)])
    [(_, _, message)] = _flat_found(tmp_path, binary_stl(plate))
    assert "has every vertex in one plane but for " in message
    assert message.endswith("MuJoCo makes a convex hull of it only as thick as that")


@pytest.mark.parametrize("thickness", [0.001, 0.0001])
def test_a_thin_plate_is_no_flat_mesh(tmp_path: Path, thickness: float) -> None:
    # 0.1 mm on 0.5 m: a sheet, but one a hull can be made of
    assert _flat_found(tmp_path, binary_stl(_turned(_box(0.5, 0.4, thickness)))) == []


def _box(x: float, y: float, z: float) -> list[tuple[float, ...]]:
    c = [(i * x, j * y, k * z) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return [(*c[a], *c[b], *c[d]) for a, b, d in faces]


_MESHES = """<robot name="r">
  <link name="base_link">
    <visual><geometry><mesh filename="meshes/body.stl"/></geometry></visual>
    <collision><geometry><mesh filename="meshes/hull.stl"/></geometry></collision>
  </link>
  <link name="arm">
    <visual><geometry><mesh filename="meshes/gone.stl"/></geometry></visual>
  </link>
  <joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_a_selection_of_mesh_name_rules_reads_no_mesh_file(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    for name in ("body", "hull"):
        (tmp_path / "meshes" / f"{name}.stl").write_bytes(box_stl(200, 200, 100))  # in mm
    robot = tmp_path / "r.urdf"
    robot.write_text(_MESHES, encoding="utf-8")
    meshes = {str(tmp_path / "meshes" / f"{name}.stl") for name in ("body", "hull")}

    # (the selection first: a mesh file's facts, once read, are kept for the process)
    with recording_inputs() as read:
        chosen = check_file(robot, config=Config(select=("mesh-not-found",))).diagnostics
    assert meshes.isdisjoint(read)
    assert read == [str(robot)]

    with recording_inputs() as read:
        full = check_file(robot).diagnostics
    assert meshes <= set(read)  # the whole check reads them: mesh-units is found
    assert {"mesh-not-found", "mesh-units"} <= {d.rule for d in full}
    assert chosen == tuple(d for d in full if d.rule == "mesh-not-found")
    assert len(chosen) == 1 and "gone.stl" in chosen[0].message
