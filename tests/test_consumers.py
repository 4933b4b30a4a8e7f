"""What the programs that read a robot do with the faults the newer rules find, run live:
MuJoCo (its own URDF importer) and pinocchio (urdfdom's reading, and its package folders).

Each test gives the same file to `fishbot check` and to the program, and holds the finding's
words to what the program does: the error MuJoCo's message quotes is the error MuJoCo gives,
a bound urdfdom reads as 0 is 0 in pinocchio's model, a joint MuJoCo leaves free is free.
"""

from __future__ import annotations

import importlib
import os
import re
import struct
from pathlib import Path
from types import ModuleType

import pytest
from conftest import REQUIRE_TOOLS

import fishbot_urdf
from fishbot_urdf.config import Config

INERTIAL = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
)

ROBOT = f"""\
<robot name="r">
  <link name="base_link">{INERTIAL}{{geometry}}</link>
  <link name="wheel">{INERTIAL}</link>
  <joint name="wheel_joint" type="revolute">
    <parent link="base_link"/><child link="wheel"/><axis xyz="0 1 0"/>
    <limit effort="1" velocity="10"{{bounds}}/>
  </joint>
</robot>
"""


def _module(name: str) -> ModuleType:
    """A program's Python module: skipped when it is missing, or a failure in CI."""
    try:
        return importlib.import_module(name)
    except ImportError:
        message = f"{name} is not installed (pip install -e '.[test]')"
        if REQUIRE_TOOLS:
            pytest.fail(message + "; FISHBOT_REQUIRE_TOOLS=1 forbids skipping")
        pytest.skip(message)


def _robot(tmp_path: Path, geometry: str = "", bounds: str = ' lower="-1" upper="1"') -> Path:
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT.format(geometry=geometry, bounds=bounds), encoding="utf-8")
    return path


def _findings(path: Path, rule: str) -> list[str]:
    result = fishbot_urdf.check_file(path, config=Config(select=(rule,)))
    return [d.message for d in result.diagnostics if d.rule == rule]


def _mujoco_refusal(path: Path) -> str:
    """MuJoCo's error on loading ``path``, from the robot file's folder (its mesh names are
    relative to it)."""
    mujoco = _module("mujoco")
    here = os.getcwd()
    os.chdir(path.parent)
    try:
        mujoco.MjModel.from_xml_path(path.name)
    except ValueError as exc:
        return str(exc)
    finally:
        os.chdir(here)
    raise AssertionError(f"MuJoCo loaded {path}")


def _quoted(message: str) -> str:
    """The program's error a finding quotes: ('...')."""
    found = re.search(r"\('([^']+)'\)", message)
    assert found, message
    return found.group(1)


def _stl(path: Path, corners: list[tuple[float, float, float]], faces: list[tuple[int, ...]]):
    data = bytearray(80) + struct.pack("<I", len(faces))
    for face in faces:
        data += struct.pack("<3f", 0, 0, 1)
        for index in face:
            data += struct.pack("<3f", *corners[index])
        data += b"\0\0"
    path.write_bytes(bytes(data))


TETRAHEDRON = (
    [(0.0, 0.0, 0.0), (0.1, 0.0, 0.0), (0.0, 0.1, 0.0), (0.0, 0.0, 0.1)],
    [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)],
)
SQUARE = (
    [(0.0, 0.0, 0.0), (0.1, 0.0, 0.0), (0.1, 0.1, 0.0), (0.0, 0.1, 0.0)],
    [(0, 1, 2), (0, 2, 3)],
)


# ------------------------------------------------------------------ limit-unset


def test_a_limit_without_bounds_is_held_at_0_by_urdfdom_and_left_free_by_mujoco(
    tmp_path: Path,
) -> None:
    path = _robot(tmp_path, bounds="")
    [message] = _findings(path, "limit-unset")
    assert "wheel_joint" in message
    pinocchio = _module("pinocchio")
    model = pinocchio.buildModelFromUrdf(str(path))
    assert list(model.lowerPositionLimit) == list(model.upperPositionLimit) == [0.0]
    mujoco = _module("mujoco")
    free = mujoco.MjModel.from_xml_path(str(path))
    assert not free.jnt_limited[0]
    # and with both bounds, as the fix writes them, every program holds the same range
    fixed = _robot(tmp_path)
    assert _findings(fixed, "limit-unset") == []
    held = mujoco.MjModel.from_xml_path(str(fixed))
    assert held.jnt_limited[0] and list(held.jnt_range[0]) == [-1.0, 1.0]
    assert list(pinocchio.buildModelFromUrdf(str(fixed)).upperPositionLimit) == [1.0]


# ------------------------------------------------------------------ shape-size, mesh-flat


@pytest.mark.parametrize(
    "shape",
    [
        '<box size="0 0 0"/>',
        '<box size="0.2 0.2 0"/>',
        '<cylinder radius="-0.1" length="0.2"/>',
        '<cylinder radius="0.1" length="0"/>',
        '<sphere radius="0"/>',
    ],
)
def test_a_collision_shape_of_no_size_is_refused_by_mujoco_as_the_finding_says(
    tmp_path: Path, shape: str
) -> None:
    path = _robot(tmp_path, f"<collision><geometry>{shape}</geometry></collision>")
    [message] = _findings(path, "shape-size")
    assert _quoted(message) in _mujoco_refusal(path)


def test_a_mesh_scaled_by_0_is_refused_by_mujoco_as_the_finding_says(tmp_path: Path) -> None:
    _stl(tmp_path / "m.stl", *TETRAHEDRON)
    geometry = '<collision><geometry><mesh filename="m.stl" scale="0 1 1"/></geometry></collision>'
    path = _robot(tmp_path, geometry)
    [message] = _findings(path, "shape-size")
    assert _quoted(message) in _mujoco_refusal(path)


def test_a_flat_collision_mesh_is_refused_by_mujoco_as_the_finding_says(tmp_path: Path) -> None:
    _stl(tmp_path / "flat.stl", *SQUARE)
    path = _robot(
        tmp_path, '<collision><geometry><mesh filename="flat.stl"/></geometry></collision>'
    )
    [message] = _findings(path, "mesh-flat")
    assert _quoted(message) in _mujoco_refusal(path)
    # a solid one, as the fix makes it, loads
    _stl(tmp_path / "flat.stl", *TETRAHEDRON)
    assert _findings(path, "mesh-flat") == []
    mujoco = _module("mujoco")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert mujoco.MjModel.from_xml_path(path.name).nmesh == 1
    finally:
        os.chdir(here)


# ------------------------------------------------------------------ package-no-name


def test_package_with_no_name_is_found_by_pinocchio_in_its_package_folders(
    tmp_path: Path,
) -> None:
    (tmp_path / "meshes").mkdir()
    _stl(tmp_path / "meshes" / "t.stl", *TETRAHEDRON)
    geometry = (
        '<collision><geometry><mesh filename="package:///meshes/t.stl"/></geometry></collision>'
    )
    path = _robot(tmp_path, geometry)
    [message] = _findings(path, "package-no-name")
    assert "names no package" in message and "resource_retriever" in message
    assert _findings(path, "mesh-not-found") == []  # found by its path, as pinocchio finds it
    pinocchio = _module("pinocchio")
    model = pinocchio.buildModelFromUrdf(str(path))
    collision = pinocchio.GeometryType.COLLISION
    found = pinocchio.buildGeomFromUrdf(model, str(path), collision, package_dirs=[str(tmp_path)])
    [mesh] = [Path(o.meshPath) for o in found.geometryObjects]
    assert mesh.resolve() == (tmp_path / "meshes" / "t.stl").resolve()
