"""The inertia of closed meshes (the optional trimesh extra), against the closed forms."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh
from click.testing import CliRunner

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.inertia import box_inertia, cylinder_inertia, mesh_inertia


def _box(tmp_path: Path, name: str = "box.stl") -> Path:
    path = tmp_path / name
    trimesh.creation.box(extents=(0.3, 0.2, 0.1)).export(path)
    return path


def _close(a: fishbot_urdf.Inertial, b: fishbot_urdf.Inertial, rel: float) -> None:
    assert a.mass == pytest.approx(b.mass)
    assert np.allclose(a.inertia.matrix(), b.inertia.matrix(), rtol=rel, atol=1e-12)
    assert a.origin.xyz == pytest.approx(b.origin.xyz, abs=1e-6)


def test_a_box_mesh_has_the_box_formula(tmp_path: Path) -> None:
    # STL stores float32 vertices: agreement to about 1e-7.
    _close(mesh_inertia(_box(tmp_path), 2.0), box_inertia(2.0, 0.3, 0.2, 0.1), 1e-6)


def test_a_scaled_turned_and_moved_mesh(tmp_path: Path) -> None:
    origin = fishbot_urdf.Origin(xyz=(0.0, 0.0, 1.0), rpy=(0.0, 0.0, 1.5707963267948966))
    made = mesh_inertia(_box(tmp_path), 2.0, origin, scale=(2.0, 2.0, 2.0))
    # Twice as big: sides 0.6 0.4 0.2; turned 90 degrees about z, x and y swap.
    expected = box_inertia(2.0, 0.4, 0.6, 0.2, fishbot_urdf.Origin(xyz=(0.0, 0.0, 1.0)))
    _close(made, expected, 1e-6)


def test_a_cylinder_mesh_approaches_the_cylinder_formula(tmp_path: Path) -> None:
    path = tmp_path / "wheel.stl"
    trimesh.creation.cylinder(radius=0.032, height=0.04, sections=256).export(path)
    made = mesh_inertia(path, 0.1)
    # A 256-sided prism is within 0.1% of the round cylinder.
    _close(made, cylinder_inertia(0.1, 0.032, 0.04), 1e-3)


def test_an_open_mesh_has_no_volume(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(1, 1, 1))
    box.update_faces(np.arange(len(box.faces)) != 0)  # drop one triangle
    path = tmp_path / "open.stl"
    box.export(path)
    with pytest.raises(ValueError, match="is not closed"):
        mesh_inertia(path, 1.0)


def test_without_trimesh_the_error_says_how_to_install_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(fishbot_urdf.ToolNotFoundError) as caught:
        mesh_inertia(_box(tmp_path), 1.0)
    assert caught.value.rule == "tool-missing"
    assert caught.value.hint == "pip install 'fishbot-urdf[mesh]'"


def test_fill_computes_a_mesh_link_through_its_package(tmp_path: Path) -> None:
    package = tmp_path / "demo"
    (package / "meshes").mkdir(parents=True)
    _box(package / "meshes")
    source = tmp_path / "robot.urdf"
    source.write_text(
        '<robot name="m"><link name="a"/><link name="b"><collision>'
        '<origin xyz="0 0 0.5"/><geometry><mesh filename="package://demo/meshes/box.stl"/>'
        "</geometry></collision></link>"
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>'
    )
    out = tmp_path / "out.urdf"
    result = CliRunner().invoke(
        cli,
        [
            "inertia",
            str(source),
            "--fill",
            "--mass",
            "b=2",
            "--package",
            f"demo={package}",
            "-o",
            str(out),
        ],
    )
    assert result.exit_code == 0, result.output
    made = fishbot_urdf.load(out).link("b").inertial
    assert made is not None
    _close(made, box_inertia(2.0, 0.3, 0.2, 0.1, fishbot_urdf.Origin(xyz=(0, 0, 0.5))), 1e-6)


def test_fill_says_which_package_is_missing(tmp_path: Path) -> None:
    source = tmp_path / "robot.urdf"
    source.write_text(
        '<robot name="m"><link name="a"/><link name="b"><collision><geometry>'
        '<mesh filename="package://nowhere_pkg/b.stl"/></geometry></collision></link>'
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>'
    )
    result = CliRunner().invoke(
        cli, ["inertia", str(source), "--fill", "--density", "1000", "-o", str(tmp_path / "o.urdf")]
    )
    assert result.exit_code == 1
    assert "link 'b': no <inertial> added (" in result.stderr
    assert "nowhere_pkg" in result.stderr


def test_geometry_inertia_and_volume_read_a_mesh_from_its_filename(tmp_path: Path) -> None:
    path = _box(tmp_path)
    mesh = fishbot_urdf.Mesh(str(path), scale=(0.5, 0.5, 0.5))
    # Half the size: sides 0.15 0.1 0.05.
    _close(fishbot_urdf.geometry_inertia(mesh, 1.0), box_inertia(1.0, 0.15, 0.1, 0.05), 1e-6)
    assert fishbot_urdf.volume(fishbot_urdf.Mesh(f"file://{path}")) == pytest.approx(0.006)


def test_fill_refuses_a_mesh_in_millimetres(tmp_path: Path) -> None:
    # A 300 x 200 x 100 mm box exported without a unit: 300 m across when read as metres.
    trimesh.creation.box(extents=(300, 200, 100)).export(tmp_path / "part.stl")
    source = tmp_path / "robot.urdf"
    mesh = '<mesh filename="part.stl"{scale}/>'
    robot = (
        '<robot name="m"><link name="a"/><link name="b"><collision><geometry>{mesh}'
        "</geometry></collision></link>"
        '<joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint></robot>'
    )
    source.write_text(robot.format(mesh=mesh.format(scale="")), encoding="utf-8")
    out = tmp_path / "out.urdf"
    given = ["inertia", str(source), "--fill", "--density", "1000", "-o", str(out)]
    result = CliRunner().invoke(cli, given)
    assert result.exit_code == 1
    assert "is 300 m across, too large for a robot part" in result.stderr
    assert 'add scale="0.001 0.001 0.001"' in result.stderr
    assert not out.exists()
    scaled = mesh.format(scale=' scale="0.001 0.001 0.001"')
    source.write_text(robot.format(mesh=scaled), encoding="utf-8")
    assert CliRunner().invoke(cli, given).exit_code == 0
    made = fishbot_urdf.load(out).link("b").inertial
    assert made is not None
    # 1000 kg/m^3 * 0.3 * 0.2 * 0.1 m^3 = 6 kg
    assert made.mass == pytest.approx(6.0)
