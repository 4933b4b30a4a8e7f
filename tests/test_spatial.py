"""`fishbot_urdf.spatial`: plain-Python rotations and eigen-decomposition against numpy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fishbot_urdf.model import Origin
from fishbot_urdf.spatial import Pose, axis_angle, eigenvalues, eigh, rpy_matrix

angles = st.floats(min_value=-math.pi, max_value=math.pi)
entries = st.floats(min_value=-10.0, max_value=10.0)


def _rx(a: float) -> np.ndarray:
    return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])


def _ry(a: float) -> np.ndarray:
    return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])


def _rz(a: float) -> np.ndarray:
    return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])


@given(angles, angles, angles)
def test_rpy_is_yaw_then_pitch_then_roll_about_fixed_axes(r: float, p: float, y: float) -> None:
    # URDF: roll about x, then pitch about y, then yaw about z, all about the fixed axes.
    expected = _rz(y) @ _ry(p) @ _rx(r)
    assert np.allclose(np.array(rpy_matrix((r, p, y))), expected, atol=1e-12)


@given(st.tuples(entries, entries, entries).filter(lambda v: np.linalg.norm(v) > 1e-3), angles)
def test_axis_angle_is_rodrigues(axis: tuple[float, float, float], angle: float) -> None:
    k = np.array(axis) / np.linalg.norm(axis)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    expected = np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * cross @ cross
    assert np.allclose(np.array(axis_angle(axis, angle)), expected, atol=1e-12)


@given(st.lists(entries, min_size=6, max_size=6))
def test_eigh_agrees_with_numpy(values: list[float]) -> None:
    a, b, c, d, e, f = values
    m = ((a, b, c), (b, d, e), (c, e, f))
    found, vectors = eigh(m)
    expected = np.linalg.eigvalsh(np.array(m))
    scale = max(1.0, float(np.max(np.abs(expected))))
    assert np.allclose(found, expected, atol=1e-9 * scale)
    v = np.array(vectors)
    assert np.allclose(v.T @ v, np.eye(3), atol=1e-9)  # orthonormal
    assert np.allclose(np.array(m) @ v, v * np.array(found), atol=1e-8 * scale)


@given(st.lists(entries, min_size=6, max_size=6), st.booleans())
def test_eigenvalues_are_eighs(values: list[float], diagonal: bool) -> None:
    a, b, c, d, e, f = values
    if diagonal:
        b = c = e = 0.0
    m = ((a, b, c), (b, d, e), (c, e, f))
    assert eigenvalues(m) == eigh(m)[0]
    expected = np.linalg.eigvalsh(np.array(m))
    assert np.allclose(
        eigenvalues(m), expected, atol=1e-9 * max(1.0, float(np.max(np.abs(expected))))
    )


def test_eigh_of_equal_moments() -> None:
    assert eigh(((2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.0)))[0] == (2.0, 2.0, 2.0)


@given(st.tuples(angles, angles, angles), st.tuples(entries, entries, entries))
def test_pose_then_and_apply_match_homogeneous_matrices(
    rpy: tuple[float, float, float], xyz: tuple[float, float, float]
) -> None:
    outer = Pose.of(Origin(xyz=xyz, rpy=rpy))
    inner = Pose.of(Origin(xyz=(0.1, -0.2, 0.3), rpy=(0.3, 0.2, 0.1)))
    expected = np.array(outer.matrix()) @ np.array(inner.matrix())
    assert np.allclose(np.array(outer.then(inner).matrix()), expected, atol=1e-12)
    point = np.array([0.5, -1.0, 2.0, 1.0])
    assert np.allclose(outer.apply((0.5, -1.0, 2.0)), (np.array(outer.matrix()) @ point)[:3])


def test_eigh_of_entries_whose_squares_overflow_is_the_scaled_eigh() -> None:
    # 1e200 is a float; its square is not. The eigenvalues scale with the matrix.
    small = ((1.0, 0.5, 0.0), (0.5, 2.0, 0.25), (0.0, 0.25, 3.0))
    big = tuple(tuple(x * 1e200 for x in row) for row in small)
    values, _ = eigh(big)  # type: ignore[arg-type]
    expected, _ = eigh(small)
    assert values == pytest.approx([v * 1e200 for v in expected], rel=1e-12)
