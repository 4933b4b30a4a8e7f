"""`fishbot_urdf.export.mjcf.write_mjcf`: the meshes MuJoCo cannot read, converted into a
folder beside the model where MuJoCo reads them, at the place the source file gives them
(held to a COLLADA reading of our own, not trimesh's); and the visuals' colours in MuJoCo."""

from __future__ import annotations

import os
from importlib.util import find_spec
from pathlib import Path

import mujoco
import numpy as np
import pytest
from conftest import FISHBOT, box_stl, corpus, fine_stl
from lxml import etree

import fishbot_urdf
from fishbot_urdf.analysis import Analysis, of
from fishbot_urdf.errors import InputError, ToolNotFoundError
from fishbot_urdf.export.meshfolder import MOST_STL_TRIANGLES
from fishbot_urdf.export.mjcf import export_mjcf, mesh_folder, write_mjcf
from fishbot_urdf.meshfile import mesh_facts
from fishbot_urdf.model import Visual

PANDA = next(path for path in corpus() if path.name == "panda.urdf")
DATA = next(p for p in PANDA.parents if p.name == "example-robot-data")
VISUALS = PANDA.parent.parent / "meshes" / "visual"
XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
C = "{http://www.collada.org/2005/11/COLLADASchema}"
INSTALL = "pip install 'fishbot-urdf[mesh]'"

# COLLADA is read by pycollada, of the mesh extra (installed with the test extra)
collada = pytest.mark.skipif(find_spec("collada") is None, reason="pycollada is not installed")


def _analysis(path: Path) -> Analysis:
    packages = {"example-robot-data": DATA}
    return of(fishbot_urdf.load(path, packages=packages), packages=packages)


def _listing(folder: Path) -> list[tuple[str, int, int]]:
    return sorted(
        (str(p.relative_to(folder)), p.stat().st_size, p.stat().st_mtime_ns)
        for p in folder.rglob("*")
    )


def _collada_box(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The box around a COLLADA file's positions, each moved by its nodes' matrices and
    scaled by the file's <unit meter>: read here with lxml, as the format says."""
    root = etree.parse(str(path)).getroot()
    unit = root.find(f"{C}asset/{C}unit")
    metres = float(unit.get("meter")) if unit is not None else 1.0
    geometries = {g.get("id"): g for g in root.iter(f"{C}geometry")}
    points = []

    def visit(node: etree._Element, above: np.ndarray) -> None:
        here = above
        for matrix in node.findall(f"{C}matrix"):
            here = here @ np.array(matrix.text.split(), dtype=float).reshape(4, 4)
        for instance in node.findall(f"{C}instance_geometry"):
            geometry = geometries[instance.get("url").lstrip("#")]
            vertices = geometry.find(f"{C}mesh/{C}vertices")
            source = vertices.find(f"{C}input[@semantic='POSITION']").get("source").lstrip("#")
            array = geometry.find(f"{C}mesh/{C}source[@id='{source}']/{C}float_array")
            xyz = np.array(array.text.split(), dtype=float).reshape(-1, 3)
            points.append(xyz @ here[:3, :3].T + here[:3, 3])
        for child in node.findall(f"{C}node"):
            visit(child, here)

    for scene in root.iter(f"{C}visual_scene"):
        for node in scene.findall(f"{C}node"):
            visit(node, np.eye(4))
    every = np.concatenate(points) * metres
    return every.min(axis=0), every.max(axis=0)


def _mesh_box(model: mujoco.MjModel, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The box around a mesh's vertices in its file's frame: MuJoCo moves a mesh to its
    centre and principal axes (mesh_pos, mesh_quat), which this undoes."""
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MESH, name)
    start, count = model.mesh_vertadr[index], model.mesh_vertnum[index]
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.mesh_quat[index])
    vertices = model.mesh_vert[start : start + count] @ rotation.reshape(3, 3).T
    vertices += model.mesh_pos[index]
    return vertices.min(axis=0), vertices.max(axis=0)


@collada
def test_the_pandas_collada_visuals_are_converted_where_rviz_places_them(
    tmp_path: Path,
) -> None:
    before = _listing(PANDA.parent.parent)
    out = tmp_path / "out" / "panda.xml"
    made = write_mjcf(_analysis(PANDA), out)
    assert mesh_folder(out) == tmp_path / "out" / "panda_meshes"
    converted = sorted(p.name for p in (tmp_path / "out" / "panda_meshes").iterdir())
    assert converted == sorted(f"{p.stem}.stl" for p in VISUALS.glob("*.dae"))
    assert made.text == out.read_text()
    assert '<compiler angle="radian" autolimits="true" inertiafromgeom="false" ' in made.text
    assert 'meshdir="panda_meshes"' in made.text
    rules = [d.rule for d in made.findings]
    assert rules.count("mjcf-mesh-converted") == 11  # ten links, both fingers
    assert "mjcf-left-out" not in rules
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.nmesh == 19  # 10 visual files converted, 9 collision STL as they are
    for dae in sorted(VISUALS.glob("*.dae")):
        low, high = _mesh_box(model, dae.stem)
        want_low, want_high = _collada_box(dae)
        # float32 in the STL and in MuJoCo
        np.testing.assert_allclose(low, want_low, atol=2e-7, err_msg=dae.name)
        np.testing.assert_allclose(high, want_high, atol=2e-7, err_msg=dae.name)
    # one node of link1 moves its triangles 0.192 m down: the collision STL agrees
    assert _mesh_box(model, "link1")[0][2] == pytest.approx(-0.192, abs=1e-6)
    assert _listing(PANDA.parent.parent) == before  # no input touched, nothing added


@collada
def test_converting_twice_writes_the_same_files_and_leaves_them(tmp_path: Path) -> None:
    out = tmp_path / "panda.xml"
    write_mjcf(_analysis(PANDA), out)
    folder = mesh_folder(out)
    first = {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in folder.iterdir()}
    text = out.read_text()
    write_mjcf(_analysis(PANDA), out)
    assert {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in folder.iterdir()} == first
    assert out.read_text() == text


@collada
def test_a_collada_unit_is_applied(tmp_path: Path) -> None:
    source = (VISUALS / "finger.dae").read_text()
    assert '<unit name="meter" meter="1"/>' in source
    (tmp_path / "parts").mkdir()
    part = tmp_path / "parts" / "finger_mm.dae"
    part.write_text(source.replace('meter="1"', 'meter="0.001"'))
    robot = tmp_path / "parts" / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="finger_mm.dae" '
        'scale="2 2 2"/></geometry></visual></link></robot>'
    )
    out = tmp_path / "robot.xml"
    write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    model = mujoco.MjModel.from_xml_path(str(out))
    low, high = _collada_box(part)  # in metres: 1000 times smaller than finger.dae
    np.testing.assert_allclose(_collada_box(VISUALS / "finger.dae")[1] / 1000, high, rtol=1e-12)
    # the <mesh scale> stays the asset's: MuJoCo applies it
    found_low, found_high = _mesh_box(model, "finger_mm")
    np.testing.assert_allclose(found_low, 2 * low, atol=1e-9)
    np.testing.assert_allclose(found_high, 2 * high, atol=1e-9)
    assert 'scale="2 2 2"' in out.read_text()


def _ascii_stl(triangles: np.ndarray) -> str:
    lines = ["solid part"]
    for triangle in triangles.tolist():
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += [f"vertex {x!r} {y!r} {z!r}" for x, y, z in triangle]
        lines += ["endloop", "endfacet"]
    return "\n".join([*lines, "endsolid part"]) + "\n"


def _box_triangles(x: float, y: float, z: float) -> np.ndarray:
    record = np.dtype([("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")])
    return np.frombuffer(box_stl(x, y, z), record, offset=84)["c"].astype(float)


def test_an_ascii_stl_is_converted_and_a_mesh_of_nothing_left_out(tmp_path: Path) -> None:
    (tmp_path / "part.stl").write_text(_ascii_stl(_box_triangles(0.25, 0.5, 2.0)))
    (tmp_path / "empty.STL").write_bytes(b"")
    (tmp_path / "binary.STL").write_bytes(box_stl(1.0, 1.0, 1.0))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a">\n'
        '<visual><geometry><mesh filename="part.stl"/></geometry></visual>\n'
        '<collision><geometry><mesh filename="empty.STL"/></geometry></collision>\n'
        '<collision><geometry><mesh filename="binary.STL"/></geometry></collision>\n'
        "</link></robot>\n"
    )
    out = tmp_path / "build" / "robot.xml"
    text, findings = write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    assert [d.format() for d in findings] == [
        f"{robot}:2:19: note: link 'a': visual mesh 'part.stl' is an ASCII STL, which MuJoCo "
        "cannot read: converted to part.stl in the mesh folder (export it as binary STL or OBJ "
        "to have MuJoCo read it where it is) [mjcf-mesh-converted]",
        f"{robot}:3:22: warning: link 'a': collision mesh 'empty.STL' holds no triangles MuJoCo "
        "reads, and cannot be converted: the file is empty: left out of the MJCF "
        "[mjcf-left-out]",
    ]
    assert '<compiler angle="radian" autolimits="true" inertiafromgeom="false" ' in text
    assert 'meshdir="robot_meshes"' in text
    assert f'file="{(tmp_path / "binary.STL").resolve()}"' in text  # read as it is
    model = mujoco.MjModel.from_xml_path(str(out))
    low, high = _mesh_box(model, "part")
    np.testing.assert_allclose(low, [0, 0, 0], atol=1e-7)
    np.testing.assert_allclose(high, [0.25, 0.5, 2.0], atol=1e-7)
    assert sorted(os.listdir(tmp_path / "build" / "robot_meshes")) == ["part.stl"]


def test_no_mesh_is_written_into_a_folder_of_inputs(tmp_path: Path) -> None:
    (tmp_path / "part.stl").write_text(_ascii_stl(_box_triangles(1.0, 1.0, 1.0)))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="part.stl"/>'
        "</geometry></visual></link></robot>"
    )
    before = _listing(tmp_path)
    with pytest.raises(
        InputError, match="refusing to write converted meshes into the folder of the input"
    ):
        write_mjcf(of(fishbot_urdf.load(robot)), tmp_path / "out" / "r.xml", meshes=tmp_path)
    assert _listing(tmp_path) == before


def _visual_colours(analysis: Analysis) -> dict[str, list[tuple[float, ...]]]:
    """Each link's visual colours as the URDF gives them, in order."""
    found: dict[str, list[tuple[float, ...]]] = {}
    for link in analysis.robot.links:
        for visual in link.visuals:
            assert isinstance(visual, Visual)
            material = analysis.material(visual)
            assert material is not None and material.color is not None
            found.setdefault(link.name, []).append(material.color)
    return found


def _geom_colours(model: mujoco.MjModel, group: int) -> dict[str, list[tuple[float, ...]]]:
    found: dict[str, list[tuple[float, ...]]] = {}
    for geom in range(model.ngeom):
        if model.geom_group[geom] == group:
            body = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[geom])
            found.setdefault(body, []).append(tuple(model.geom_rgba[geom].tolist()))
    return found


def test_visuals_are_in_the_urdfs_colours_and_collisions_in_mujocos(tmp_path: Path) -> None:
    analysis = of(fishbot_urdf.load(XACRO))
    model = mujoco.MjModel.from_xml_string(export_mjcf(analysis).text)
    want = {
        link: [tuple(np.float32(v).item() for v in rgba) for rgba in colours]
        for link, colours in _visual_colours(analysis).items()
    }
    assert want["base_link"] == [tuple(np.float32(v).item() for v in (0.1, 0.1, 1.0, 0.5))]
    assert _geom_colours(model, 2) == want
    grey = (0.5, 0.5, 0.5, 1.0)  # MuJoCo's default
    assert {c for colours in _geom_colours(model, 3).values() for c in colours} == {grey}


def test_a_material_named_at_the_top_gives_its_colour(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><material name="red"><color rgba="1 0 0 1"/></material>'
        '<link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
        '<material name="red"/></visual>'
        '<visual><geometry><sphere radius="1"/></geometry>'
        '<material name="green"><color rgba="0 1 0 0.25"/></material></visual>'
        '<visual><geometry><sphere radius="1"/></geometry><material name="green"/></visual>'
        '<visual><geometry><sphere radius="1"/></geometry></visual>'
        "</link></robot>"
    )
    model = mujoco.MjModel.from_xml_string(export_mjcf(fishbot_urdf.load(robot), base="fixed").text)
    assert model.geom_rgba.tolist() == [
        [1, 0, 0, 1],
        [0, 1, 0, 0.25],
        [0, 1, 0, 0.25],
        [0.5, 0.5, 0.5, 1],  # none: MuJoCo's default
    ]


def test_without_trimesh_a_collada_mesh_is_left_out_saying_how_to_install_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf.analysis import meshcontents

    def missing(what: str) -> None:
        raise ToolNotFoundError(f"{what} needs the trimesh package", tool="trimesh", hint=INSTALL)

    monkeypatch.setattr(meshcontents, "_trimesh", missing)
    (tmp_path / "part.dae").write_bytes((VISUALS / "finger.dae").read_bytes())
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="part.dae"/>'
        "</geometry></visual></link></robot>"
    )
    out = tmp_path / "out" / "robot.xml"
    text, findings = write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    assert [d.format() for d in findings] == [
        f"{robot}:1:50: warning: link 'a': visual mesh 'part.dae' is a .dae file, which MuJoCo "
        "cannot read, and reading a .dae mesh needs the trimesh package: left out of the MJCF "
        f"({INSTALL}) [mjcf-left-out]"
    ]
    assert "<geom" not in text and "meshdir" not in text
    assert not mesh_folder(out).exists()


def test_a_mesh_of_fewer_than_4_vertices_is_left_out(tmp_path: Path) -> None:
    # MuJoCo 4.0 refuses it: "at least 4 vertices required"
    triangle = _box_triangles(1.0, 1.0, 1.0)[:1]
    (tmp_path / "one.stl").write_text(_ascii_stl(triangle))
    record = np.zeros(1, dtype=[("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")])
    record["c"] = triangle
    (tmp_path / "one_binary.stl").write_bytes(
        bytes(80) + (1).to_bytes(4, "little") + record.tobytes()
    )
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a">\n'
        '<visual><geometry><mesh filename="one.stl"/></geometry></visual>\n'
        '<visual><geometry><mesh filename="one_binary.stl"/></geometry></visual>\n'
        '<visual><geometry><box size="1 1 1"/></geometry></visual>\n'
        "</link></robot>\n"
    )
    out = tmp_path / "out" / "robot.xml"
    _, findings = write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    hint = "give it its thickness, or draw it as a thin box"
    assert [d.format() for d in findings] == [
        f"{robot}:2:19: warning: link 'a': visual mesh 'one.stl' is an ASCII STL, which MuJoCo "
        "cannot read, and has 3 distinct vertices, fewer than the 4 MuJoCo needs: left out of "
        f"the MJCF ({hint}) [mjcf-left-out]",
        f"{robot}:3:19: warning: link 'a': visual mesh 'one_binary.stl' has 3 distinct "
        f"vertices, fewer than the 4 MuJoCo needs: left out of the MJCF ({hint}) "
        "[mjcf-left-out]",
    ]
    assert mujoco.MjModel.from_xml_path(str(out)).ngeom == 1
    assert not mesh_folder(out).exists()


def test_a_device_has_no_folder_beside_it(tmp_path: Path) -> None:
    (tmp_path / "part.stl").write_text(_ascii_stl(_box_triangles(1.0, 1.0, 1.0)))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="part.stl"/>'
        "</geometry></visual></link></robot>"
    )
    text, findings = write_mjcf(of(fishbot_urdf.load(robot)), os.devnull, base="fixed")
    assert [(d.rule, d.data["convertible"]) for d in findings] == [("mjcf-left-out", True)]
    assert "meshdir" not in text and "<geom" not in text
    assert not Path(os.devnull + "_meshes").exists()


def test_an_stl_of_more_triangles_than_mujoco_reads_becomes_an_obj(tmp_path: Path) -> None:
    (tmp_path / "fine.stl").write_bytes(fine_stl(MOST_STL_TRIANGLES + 1))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="fine.stl"/>'
        "</geometry></visual></link></robot>"
    )
    out = tmp_path / "out" / "robot.xml"
    _, findings = write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    assert [d.message for d in findings] == [
        "link 'a': visual mesh 'fine.stl' is an STL of 200,001 triangles, more than MuJoCo "
        "reads: converted to fine.obj in the mesh folder"
    ]
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.mesh_facenum.tolist() == [MOST_STL_TRIANGLES + 1]
    facts = mesh_facts(tmp_path / "fine.stl")
    assert facts is not None
    low, high = _mesh_box(model, "fine")
    np.testing.assert_allclose(low, facts.low, atol=1e-7)
    np.testing.assert_allclose(high, facts.high, atol=1e-7)


def test_a_flat_collision_mesh_is_left_out_and_kept_as_a_visual(tmp_path: Path) -> None:
    # MuJoCo 4.0 refuses to collide with it: "has coplanar vertices, cannot compute convex
    # hull"; a visual, which collides with nothing, it draws
    (tmp_path / "plate.stl").write_bytes(box_stl(0.2, 0.2, 0.0))
    (tmp_path / "plate_ascii.stl").write_text(_ascii_stl(_box_triangles(0.2, 0.2, 0.0)))
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><link name="a">\n'
        '<visual><geometry><mesh filename="plate.stl"/></geometry></visual>\n'
        '<collision><geometry><mesh filename="plate.stl"/></geometry></collision>\n'
        '<collision><geometry><mesh filename="plate_ascii.stl"/></geometry></collision>\n'
        "</link></robot>\n"
    )
    out = tmp_path / "out" / "robot.xml"
    _, findings = write_mjcf(of(fishbot_urdf.load(robot)), out, base="fixed")
    why = (
        "has every vertex in one plane, no volume for a convex hull: left out of the MJCF "
        "(collide with a thin box, or give the mesh its thickness) [mjcf-left-out]"
    )
    assert [d.format() for d in findings] == [
        f"{robot}:3:22: warning: link 'a': collision mesh 'plate.stl' {why}",
        f"{robot}:4:22: warning: link 'a': collision mesh 'plate_ascii.stl' {why}",
    ]
    model = mujoco.MjModel.from_xml_path(str(out))
    assert model.geom_group.tolist() == [2]  # the visual alone
