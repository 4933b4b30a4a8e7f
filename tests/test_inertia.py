"""`fishbot_urdf.inertia`: the closed forms against the fishbot's own xacro macros and
against numerical integration over the solid."""

from __future__ import annotations

import math
import random
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from conftest import FISHBOT
from hypothesis import given
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf.inertia import box_inertia, cylinder_inertia, geometry_inertia, sphere_inertia

COMMON = FISHBOT / "urdf" / "fishbot" / "common_inertia.xacro"


def test_the_same_floats_as_the_xacro_macros(tmp_path: Path) -> None:
    rng = random.Random(5)
    calls = []
    expected = []
    for i in range(30):
        m, a, b, c = (round(rng.uniform(0.01, 3.0), rng.randint(1, 6)) for _ in range(4))
        kind = ("box", "cylinder", "sphere")[i % 3]
        if kind == "box":
            calls.append(f'<xacro:box_inertia m="{m}" w="{a}" h="{b}" d="{c}"/>')
            expected.append(box_inertia(m, a, b, c))
        elif kind == "cylinder":
            calls.append(f'<xacro:cylinder_inertia m="{m}" r="{a}" h="{b}"/>')
            expected.append(cylinder_inertia(m, a, b))
        else:
            calls.append(f'<xacro:sphere_inertia m="{m}" r="{a}"/>')
            expected.append(sphere_inertia(m, a))
    links = "".join(f'<link name="l{i}">{call}</link>' for i, call in enumerate(calls))
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/></joint>'
        for i in range(1, len(calls))
    )
    source = tmp_path / "robot.urdf.xacro"
    source.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        f'<xacro:include filename="{COMMON}"/>{links}{joints}</robot>'
    )
    robot = fishbot_urdf.load(source)
    assert [link.inertial for link in robot.links] == expected


Inside = Callable[[np.ndarray], np.ndarray]
Scaled = Callable[[float, float], fishbot_urdf.Inertial]


def _sampled(inside: Inside, half: tuple[float, ...], mass: float) -> np.ndarray:
    """The inertia matrix about the centre by Monte Carlo over the solid (seeded)."""
    rng = np.random.default_rng(7)
    points = rng.uniform(-1.0, 1.0, size=(400_000, 3)) * np.array(half)
    points = points[inside(points)]
    squared = (points**2).sum(axis=1)
    tensor = squared.mean() * np.eye(3) - points.T @ points / len(points)
    return mass * tensor


def _matrix(inertial: fishbot_urdf.Inertial) -> np.ndarray:
    return np.array(inertial.inertia.matrix())


@pytest.mark.parametrize(
    ("made", "inside", "half"),
    [
        (box_inertia(2.0, 0.3, 0.2, 0.1), lambda p: np.ones(len(p), bool), (0.15, 0.1, 0.05)),
        (
            cylinder_inertia(1.5, 0.1, 0.12),
            lambda p: p[:, 0] ** 2 + p[:, 1] ** 2 <= 0.1**2,
            (0.1, 0.1, 0.06),
        ),
        (sphere_inertia(0.7, 0.05), lambda p: (p**2).sum(axis=1) <= 0.05**2, (0.05,) * 3),
    ],
    ids=["box", "cylinder", "sphere"],
)
def test_closed_forms_match_integration(
    made: fishbot_urdf.Inertial, inside: Inside, half: tuple[float, ...]
) -> None:
    sampled = _sampled(inside, half, made.mass)
    closed = _matrix(made)
    assert np.allclose(np.diag(sampled), np.diag(closed), rtol=0.01)
    # The products of inertia vanish for these symmetric solids.
    assert np.abs(sampled - np.diag(np.diag(sampled))).max() < 0.01 * closed.max()


sizes = st.floats(min_value=1e-3, max_value=10.0)
masses = st.floats(min_value=1e-3, max_value=100.0)


@given(masses, sizes, sizes, sizes)
def test_box_invariants(m: float, w: float, h: float, d: float) -> None:
    _invariants(box_inertia(m, w, h, d), lambda k, s: box_inertia(k * m, s * w, s * h, s * d))


@given(masses, sizes, sizes)
def test_cylinder_invariants(m: float, r: float, h: float) -> None:
    _invariants(cylinder_inertia(m, r, h), lambda k, s: cylinder_inertia(k * m, s * r, s * h))


@given(masses, sizes)
def test_sphere_invariants(m: float, r: float) -> None:
    _invariants(sphere_inertia(m, r), lambda k, s: sphere_inertia(k * m, s * r))


def _invariants(inertial: fishbot_urdf.Inertial, scaled: Scaled) -> None:
    matrix = _matrix(inertial)
    assert np.array_equal(matrix, matrix.T)
    moments = np.linalg.eigvalsh(matrix)
    assert (moments > 0).all()
    a, b, c = sorted(moments)
    assert a + b >= c * (1 - 1e-12)  # the triangle inequality of a real body
    # Twice the mass, twice the inertia; twice the size, four times the inertia.
    assert np.allclose(_matrix(scaled(2.0, 1.0)), 2 * matrix, rtol=1e-12)
    assert np.allclose(_matrix(scaled(1.0, 2.0)), 4 * matrix, rtol=1e-12)


def test_geometry_inertia_follows_urdf_axes() -> None:
    box = fishbot_urdf.Box((0.3, 0.2, 0.1))
    assert geometry_inertia(box, 2.0) == box_inertia(2.0, 0.3, 0.2, 0.1)
    wheel = fishbot_urdf.Cylinder(radius=0.032, length=0.04)
    assert geometry_inertia(wheel, 0.1) == cylinder_inertia(0.1, 0.032, 0.04)
    assert geometry_inertia(fishbot_urdf.Sphere(0.016), 0.02) == sphere_inertia(0.02, 0.016)
    # A box's x side is w: its inertia about x is the smallest when x is the longest side.
    assert box_inertia(1.0, 3.0, 1.0, 1.0).inertia.ixx < box_inertia(1.0, 3.0, 1.0, 1.0).inertia.iyy
    with pytest.raises(TypeError, match="no closed form for Mesh"):
        geometry_inertia(fishbot_urdf.Mesh("package://x/m.stl"), 1.0)
    assert math.isclose(sphere_inertia(1.0, 1.0).inertia.ixx, 0.4)
