"""What `fishbot view` sends the page, without a browser: a transparent shape as a glTF
file that other readers open as written, and a camera that frames every point."""

from __future__ import annotations

import io
import json
import math
import struct
from pathlib import Path

import numpy as np
import pytest

from fishbot_urdf.drawing._camera import FILL, framing
from fishbot_urdf.drawing._glb import glb


def _chunks(data: bytes) -> tuple[dict[str, object], bytes]:
    """A GLB file's JSON and binary chunks, read by its specification's layout."""
    magic, version, length = struct.unpack_from("<4sII", data)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    size, kind = struct.unpack_from("<I4s", data, 12)
    assert kind == b"JSON" and size % 4 == 0
    document = json.loads(data[20 : 20 + size])
    rest = 20 + size
    binary_size, binary_kind = struct.unpack_from("<I4s", data, rest)
    assert binary_kind == b"BIN\0" and binary_size % 4 == 0
    return document, data[rest + 8 : rest + 8 + binary_size]


def test_a_transparent_shape_is_a_glb_file_blended_by_its_alpha() -> None:
    triangles = np.array([[[0, 0, 0], [1, 0, 0], [0, 2, 0]], [[0, 0, 0], [0, 2, 0], [0, 0, 3]]])
    data = glb(np, triangles, (1.0, 0.5, 0.0, 0.25))
    document, binary = _chunks(data)
    [material] = document["materials"]  # type: ignore[misc]
    assert material["alphaMode"] == "BLEND" and material["doubleSided"] is True
    pbr = material["pbrMetallicRoughness"]
    # sRGB 0.5 is linear ((0.5 + 0.055) / 1.055) ** 2.4 = 0.2140
    assert pbr["baseColorFactor"] == pytest.approx([1.0, 0.21404, 0.0, 0.25], abs=1e-4)
    assert pbr["metallicFactor"] == 0.0
    [accessor] = document["accessors"]  # type: ignore[misc]
    assert (accessor["count"], accessor["min"], accessor["max"]) == (6, [0, 0, 0], [1, 2, 3])
    points = np.frombuffer(binary[: 6 * 12], dtype="<f4").reshape(-1, 3)
    np.testing.assert_array_equal(points, triangles.reshape(-1, 3))
    trimesh = pytest.importorskip("trimesh")
    read = trimesh.load(io.BytesIO(data), file_type="glb", force="mesh")
    assert len(read.faces) == 2
    np.testing.assert_allclose(read.bounds, [[0, 0, 0], [1, 2, 3]])


@pytest.mark.parametrize("aspect", [0.5, 1.0, 1.6])
def test_the_camera_sees_every_point_and_fills_the_view(aspect: float) -> None:
    points = np.random.default_rng(3).normal(size=(500, 3)) * [0.3, 0.1, 0.05] + [1, 2, 0.4]
    view = framing(np, points, aspect)
    # A pinhole camera at the position, looking at the point looked at, z up.
    eye, target = np.array(view.position), np.array(view.look_at)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    depth = (points - eye) @ forward
    assert (depth > view.near).all() and (depth < view.far).all()
    half = math.tan(view.fov / 2)
    x = (points - eye) @ right / depth / (half * aspect)  # -1 .. 1 across the view
    y = (points - eye) @ up / depth / half
    reach = max(np.abs(x).max(), np.abs(y).max())
    assert reach == pytest.approx(FILL, abs=1e-6)  # in view, as near as can be
    assert (x.max() + x.min()) / 2 == pytest.approx(0, abs=0.01)  # centred
    assert (y.max() + y.min()) / 2 == pytest.approx(0, abs=0.01)


def test_the_corners_of_the_box_around_points() -> None:
    from fishbot_urdf.drawing._camera import corners

    points = np.array([[0.0, 1.0, -2.0], [3.0, -1.0, 0.5], [1.0, 0.0, 0.0]])
    found = {tuple(c) for c in corners(np, points).tolist()}
    assert found == {(x, y, z) for x in (0.0, 3.0) for y in (-1.0, 1.0) for z in (-2.0, 0.5)}


def test_a_material_named_alone_takes_the_colour_urdfdom_gives_it(tmp_path: Path) -> None:
    import fishbot_urdf
    from fishbot_urdf.drawing.scene import build_scene

    robot = tmp_path / "robot.urdf"
    robot.write_text(
        '<robot name="r"><material name="red"><color rgba="1 0 0 1"/></material>'
        '<link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
        '<material name="red"><color rgba="0 0 1 1"/></material></visual>'
        '<visual><geometry><box size="1 1 1"/></geometry>'
        '<material name="green"><color rgba="0 1 0 0.5"/></material></visual>'
        '<visual><geometry><box size="1 1 1"/></geometry><material name="green"/></visual>'
        "</link></robot>"
    )
    # the top-level red first; green as the visual before defined it
    colours = [part.color for part in build_scene(fishbot_urdf.load(robot)).parts]
    assert colours == [(1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 0.5), (0.0, 1.0, 0.0, 0.5)]
