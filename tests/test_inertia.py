"""`fishbot_urdf.inertia`: the closed forms against the fishbot's own xacro macros and
against numerical integration over the solid."""

from __future__ import annotations

import math
import random
import sys
from collections.abc import Callable
from fractions import Fraction
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
    from fishbot_urdf.inputs import allowing_reads

    with allowing_reads(COMMON.parent):  # the fishbot's macros, outside this robot's folder
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
    # A mesh is read from its file (tests/test_mesh.py); here its package is nowhere.
    with pytest.raises(fishbot_urdf.PackageNotFoundError):
        geometry_inertia(fishbot_urdf.Mesh("package://no_such_package_here/m.stl"), 1.0)
    assert math.isclose(sphere_inertia(1.0, 1.0).inertia.ixx, 0.4)


# -- whole robots ---------------------------------------------------------------------------

# The fishbot's parts as its xacro files place them: (mass kg, centre in base_footprint m,
# the inertia macro's diagonal about that centre, turned by rpy about x). base_link is
# 0.091 above the footprint; everything else hangs off base_link.
_Z = 0.091
FISHBOT_PARTS = [
    (1.0, (0, 0, _Z), (1.0 / 12 * (3 * 0.1**2 + 0.12**2),) * 2 + (0.5 * 0.1**2,), 0.0),
    (0.01, (0, 0, _Z + 0.02), (0.01 / 12 * 2 * 0.02**2,) * 3, 0.0),
    (
        0.01,
        (0.10, 0, _Z + 0.075),
        (0.01 / 12 * (0.1**2 + 0.02**2), 0.01 / 12 * 2 * 0.02**2, 0.01 / 12 * (0.1**2 + 0.02**2)),
        0.0,
    ),
    (0.05, (0, 0, _Z + 0.10), (0.05 / 12 * (3e-4 + 0.01),) * 2 + (0.025 * 1e-4,), 0.0),
    (0.1, (0, 0, _Z + 0.15), (0.1 / 12 * (3 * 4e-4 + 4e-4),) * 2 + (0.05 * 4e-4,), 0.0),
    *[
        (
            0.1,
            (0, y, _Z - 0.06),
            (0.1 / 12 * (3 * 0.032**2 + 0.04**2),) * 2 + (0.05 * 0.032**2,),
            1.57079,
        )
        for y in (0.1, -0.1)
    ],
    *[(0.02, (x, 0, _Z - 0.076), (0.4 * 0.02 * 0.016**2,) * 3, 0.0) for x in (0.08, -0.08)],
]


def test_the_fishbot_totals_against_a_hand_computation() -> None:
    robot = fishbot_urdf.load(FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro")
    found = fishbot_urdf.mass_properties(robot)
    total = sum(m for m, _, _, _ in FISHBOT_PARTS)
    assert total == pytest.approx(1.41)
    assert found.mass == pytest.approx(total, rel=1e-12)
    com = sum(m * np.array(c) for m, c, _, _ in FISHBOT_PARTS) / total
    # By hand: x = (0.01 * 0.10 + 0.02 * 0.08 - 0.02 * 0.08) / 1.41, z = 0.13422 / 1.41.
    assert com == pytest.approx([0.001 / 1.41, 0, 0.13422 / 1.41])
    assert found.com == pytest.approx(tuple(com), abs=1e-12)
    tensor = np.zeros((3, 3))
    for m, c, diagonal, roll in FISHBOT_PARTS:
        turn = np.array(
            [[1, 0, 0], [0, math.cos(roll), -math.sin(roll)], [0, math.sin(roll), math.cos(roll)]]
        )
        d = np.array(c) - com
        tensor += turn @ np.diag(diagonal) @ turn.T + m * (d @ d * np.eye(3) - np.outer(d, d))
    assert np.allclose(np.array(found.inertia.matrix()), tensor, rtol=1e-9, atol=1e-15)
    assert found.principal_moments == pytest.approx(tuple(np.linalg.eigvalsh(tensor)))


def test_mass_properties_at_a_configuration() -> None:
    # Two 1 kg points, one on a 1 m arm that turns about z: at 90 degrees it is at (0, 1, 0).
    point = fishbot_urdf.Inertial(mass=1.0)
    robot = fishbot_urdf.Robot(
        "r",
        links=(fishbot_urdf.Link("a", inertial=point), fishbot_urdf.Link("b", inertial=point)),
        joints=(
            fishbot_urdf.Joint(
                "j",
                fishbot_urdf.JointType.CONTINUOUS,
                "a",
                "b",
                fishbot_urdf.Origin(rpy=(0, 0, 0)),
                axis=(0, 0, 1),
            ),
        ),
    )
    moved = fishbot_urdf.Robot(
        "r",
        robot.links,
        (fishbot_urdf.Joint("j", fishbot_urdf.JointType.CONTINUOUS, "a", "b", axis=(0, 0, 1)),),
    )
    assert fishbot_urdf.mass_properties(moved).com == (0.0, 0.0, 0.0)
    arm = fishbot_urdf.Robot(
        "r",
        robot.links,
        (
            fishbot_urdf.Joint(
                "j",
                fishbot_urdf.JointType.CONTINUOUS,
                "a",
                "b",
                fishbot_urdf.Origin(),
                axis=(0, 0, 1),
            ),
        ),
    )
    assert fishbot_urdf.mass_properties(arm, {"j": 1.0}).mass == 2.0
    offset = fishbot_urdf.Robot(
        "r",
        (
            fishbot_urdf.Link("a", inertial=point),
            fishbot_urdf.Link(
                "b", inertial=fishbot_urdf.Inertial(mass=1.0, origin=fishbot_urdf.Origin((1, 0, 0)))
            ),
        ),
        (fishbot_urdf.Joint("j", fishbot_urdf.JointType.CONTINUOUS, "a", "b", axis=(0, 0, 1)),),
    )
    turned = fishbot_urdf.mass_properties(offset, {"j": math.pi / 2})
    assert turned.com == pytest.approx((0.0, 0.5, 0.0), abs=1e-12)
    # Two 1 kg points 1 m apart about their middle: 2 * 0.5^2 = 0.5 about x and z, 0 about y.
    assert turned.inertia.ixx == pytest.approx(0.5)
    assert turned.inertia.iyy == pytest.approx(0.0, abs=1e-12)
    assert turned.inertia.izz == pytest.approx(0.5)


def test_mass_properties_need_one_root() -> None:
    two = fishbot_urdf.Robot("r", (fishbot_urdf.Link("a"), fishbot_urdf.Link("b")))
    with pytest.raises(fishbot_urdf.StructureError, match="needs one root link, and has 2"):
        fishbot_urdf.mass_properties(two)


def test_volumes() -> None:
    assert fishbot_urdf.volume(fishbot_urdf.Box((0.3, 0.2, 0.1))) == pytest.approx(0.006)
    assert fishbot_urdf.volume(fishbot_urdf.Cylinder(0.1, 0.12)) == pytest.approx(
        math.pi * 0.01 * 0.12
    )
    assert fishbot_urdf.volume(fishbot_urdf.Sphere(0.5)) == pytest.approx(math.pi / 6)


def test_link_inertial_from_one_shape_is_the_closed_form_at_the_shape() -> None:
    origin = fishbot_urdf.Origin(rpy=(1.57079, 0, 0))
    wheel = fishbot_urdf.Link(
        "wheel", collisions=(fishbot_urdf.Collision(fishbot_urdf.Cylinder(0.032, 0.04), origin),)
    )
    assert fishbot_urdf.link_inertial(wheel, mass=0.1) == cylinder_inertia(0.1, 0.032, 0.04, origin)
    # 1000 kg/m^3 * pi 0.032^2 0.04 m^3
    by_density = fishbot_urdf.link_inertial(wheel, density=1000.0)
    assert by_density.mass == pytest.approx(1000 * math.pi * 0.032**2 * 0.04)
    with pytest.raises(ValueError, match="not both"):
        fishbot_urdf.link_inertial(wheel, mass=1.0, density=1.0)
    with pytest.raises(ValueError, match="no collision shape"):
        fishbot_urdf.link_inertial(fishbot_urdf.Link("bare"), mass=1.0)


def test_two_half_boxes_make_one_box() -> None:
    half = fishbot_urdf.Box((0.1, 0.1, 0.1))
    link = fishbot_urdf.Link(
        "two",
        collisions=tuple(
            fishbot_urdf.Collision(half, fishbot_urdf.Origin((x, 0.0, 0.3))) for x in (-0.05, 0.05)
        ),
    )
    made = fishbot_urdf.link_inertial(link, mass=2.0)
    whole = box_inertia(2.0, 0.2, 0.1, 0.1)
    assert made.mass == 2.0
    assert made.origin.xyz == pytest.approx((0.0, 0.0, 0.3))
    assert np.allclose(_matrix(made), _matrix(whole), rtol=1e-12)


def test_link_inertial_says_what_is_missing_or_wrong() -> None:
    box = fishbot_urdf.Link("b", collisions=(fishbot_urdf.Collision(fishbot_urdf.Box((1, 1, 1))),))
    with pytest.raises(ValueError, match=r"give the density or the mass$"):
        fishbot_urdf.link_inertial(box)
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="finite number > 0"):
            fishbot_urdf.link_inertial(box, mass=bad)


def test_the_mass_asked_for_is_the_mass_written() -> None:
    shapes = tuple(
        fishbot_urdf.Collision(fishbot_urdf.Box((0.1, 0.1, 0.1)), fishbot_urdf.Origin((x, 0, 0)))
        for x in (0.0, 0.3, 0.7)
    )
    assert (
        fishbot_urdf.link_inertial(fishbot_urdf.Link("l", collisions=shapes), mass=2.0).mass == 2.0
    )


# -- a shape too small for its inertia to be a float --------------------------------------

_NORMAL = Fraction(sys.float_info.min)  # the smallest normal float, 2.2e-308


def _exact_moments(kind: str, m: float, sizes: tuple[float, ...]) -> tuple[Fraction, ...]:
    """The moments in exact arithmetic, from the textbook formulas."""
    mass, s = Fraction(m), [Fraction(x) for x in sizes]
    if kind == "sphere":
        return (Fraction(2, 5) * mass * s[0] ** 2,) * 3
    if kind == "cylinder":
        r, h = s
        across = mass / 12 * (3 * r**2 + h**2)
        return (across, across, mass / 2 * r**2)
    w, h, d = s
    return (mass / 12 * (h**2 + d**2), mass / 12 * (w**2 + d**2), mass / 12 * (w**2 + h**2))


_MADE: dict[str, Callable[..., fishbot_urdf.Inertial]] = {
    "box": box_inertia,
    "cylinder": cylinder_inertia,
    "sphere": sphere_inertia,
}


@pytest.mark.parametrize("kind", ["box", "cylinder", "sphere"])
def test_an_inertia_that_underflows_is_refused_and_one_that_does_not_is_exact(kind: str) -> None:
    rng = random.Random(kind)
    count = {"box": 3, "cylinder": 2, "sphere": 1}[kind]
    refused = kept = 0
    for _ in range(400):
        # (Up to 1 kg, each step of the formula is at least as large as the moment it makes.)
        m = 10 ** rng.uniform(-12, 0)
        sizes = tuple(
            10 ** rng.choice((rng.uniform(-200, -140), rng.uniform(-6, 1))) for _ in range(count)
        )
        exact = _exact_moments(kind, m, sizes)
        if min(exact) < _NORMAL / 2:
            with pytest.raises(fishbot_urdf.InertiaUnderflowError) as caught:
                _MADE[kind](m, *sizes)
            assert (caught.value.shape, caught.value.mass) == (kind, m)
            assert [v for _, v in caught.value.sizes] == list(sizes)
            assert caught.value.rule == "shape"
            refused += 1
        elif min(exact) > _NORMAL * 2:
            i = _MADE[kind](m, *sizes).inertia
            for got, want in zip((i.ixx, i.iyy, i.izz), exact, strict=True):
                assert got == pytest.approx(float(want), rel=1e-12)
            kept += 1
    assert refused > 40 and kept > 40  # both sides of the edge are tried


def test_the_sphere_of_radius_1e_200_and_its_message() -> None:
    # 2/5 m r^2 = 4e-401: below the smallest float, 4.9e-324, so it comes out 0.
    with pytest.raises(fishbot_urdf.InertiaUnderflowError) as caught:
        sphere_inertia(1.0, 1e-200)
    error = caught.value
    assert isinstance(error, fishbot_urdf.ShapeError)
    assert (error.shape, error.sizes, error.mass, error.moments) == (
        "sphere",
        (("radius", 1e-200),),
        1.0,
        (0.0, 0.0, 0.0),
    )
    assert error.message == (
        "the sphere's inertia underflows to 0 kg*m^2 (radius 1e-200 m, mass 1 kg): too small "
        "for a float; give a larger size or mass"
    )
    # A subnormal moment (precision lost) is refused too, and a flat box is not a small one:
    # its moments about the axes in its plane are mathematically positive, the third not.
    with pytest.raises(fishbot_urdf.InertiaUnderflowError, match="underflows to 4e-309"):
        sphere_inertia(1.0, 1e-154)
    assert box_inertia(1.0, 1.0, 1.0, 0.0).inertia.izz == pytest.approx(1 / 6)
    assert sphere_inertia(0.0, 1e-200).inertia.ixx == 0.0  # no mass: 0 is the answer


def test_fill_leaves_out_a_link_whose_inertia_underflows() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="dust"><collision><geometry><sphere radius="1e-100"/>'
        "</geometry></collision></link></robot>"
    )
    filling = fishbot_urdf.fill_inertials(robot, density=1000.0)
    assert dict(filling.inertials) == {}
    (skipped,) = filling.skipped
    assert skipped.rule == "fill-skipped"
    assert "the sphere's inertia underflows to 0 kg*m^2 (radius 1e-100 m" in skipped.message


def test_a_mesh_whose_inertia_underflows(tmp_path: Path) -> None:
    pytest.importorskip("trimesh")
    from conftest import box_stl

    from fishbot_urdf.inertia import mesh_inertia

    mesh = tmp_path / "box.stl"
    mesh.write_bytes(box_stl(1.0, 1.0, 1.0))
    assert mesh_inertia(mesh, 12.0).inertia.ixx == pytest.approx(2.0)
    with pytest.raises(fishbot_urdf.InertiaUnderflowError) as caught:
        mesh_inertia(mesh, 12.0, scale=(1e-160, 1e-160, 1e-160))
    assert (caught.value.shape, caught.value.path) == ("mesh", str(mesh))


# -- the mass sphere and inertia box RViz draws (rviz_default_plugins' robot link) ---------


def test_the_mass_sphere_is_a_ball_of_lead() -> None:
    from fishbot_urdf.inertia import mass_sphere_diameter

    # 1 kg of lead (11340 kg/m^3) is 8.818e-5 m^3: a ball of radius 0.027612 m.
    volume = 1.0 / 11340.0
    assert mass_sphere_diameter(1.0) == pytest.approx(2 * (3 * volume / (4 * math.pi)) ** (1 / 3))
    assert mass_sphere_diameter(1.0) == pytest.approx(0.0552242, rel=1e-6)
    assert mass_sphere_diameter(0.0) == 0.0


def test_the_inertia_box_of_a_box_is_the_box() -> None:
    from fishbot_urdf.inertia import equivalent_box

    box = equivalent_box(box_inertia(2.0, 0.3, 0.2, 0.1))
    assert box is not None
    assert box.size == pytest.approx((0.3, 0.2, 0.1))
    assert box.axes == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def test_the_inertia_box_of_the_fishbot_body() -> None:
    from fishbot_urdf.inertia import equivalent_box

    # A cylinder of 1 kg, radius 0.1, length 0.12: ixx = iyy = (3 r^2 + h^2) / 12 = 0.0037,
    # izz = r^2 / 2 = 0.005; the box's sides sqrt(6 (iyy + izz - ixx) / m) = sqrt(0.03)
    # across and sqrt(6 (2 * 0.0037 - 0.005)) = 0.12 along its axis.
    box = equivalent_box(cylinder_inertia(1.0, 0.1, 0.12))
    assert box is not None
    assert box.size == pytest.approx((math.sqrt(0.03), math.sqrt(0.03), 0.12))


def test_the_inertia_box_lies_on_the_principal_axes() -> None:
    from fishbot_urdf.inertia import equivalent_box

    # A 0.4 x 0.2 x 0.1 box of 3 kg turned 30 degrees about z: its inertia written in the
    # link's axes has ixy; the box found is the box, turned back.
    moments = np.diag([3 / 12 * (0.04 + 0.01), 3 / 12 * (0.16 + 0.01), 3 / 12 * (0.16 + 0.04)])
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    tensor = turn @ moments @ turn.T
    inertial = fishbot_urdf.Inertial(
        mass=3.0,
        inertia=fishbot_urdf.Inertia(
            ixx=tensor[0, 0], ixy=tensor[0, 1], ixz=0.0, iyy=tensor[1, 1], iyz=0.0, izz=tensor[2, 2]
        ),
    )
    box = equivalent_box(inertial)
    assert box is not None
    axes = np.array(box.axes)
    for side, axis in zip(box.size, axes.T, strict=True):
        along = np.abs(turn.T @ axis)  # the axis in the box's own frame: one of x, y, z
        k = int(np.argmax(along))
        assert along[k] == pytest.approx(1.0)
        assert side == pytest.approx((0.4, 0.2, 0.1)[k])


@pytest.mark.parametrize(
    ("mass", "moments", "why"),
    [
        (1.0, (-1e-3, 1e-3, 1e-3), "NOT_DEFINITE"),  # a negative moment
        (0.0, (1e-3, 1e-3, 1e-3), "MASS"),  # no mass
        (-1.0, (1e-3, 1e-3, 1e-3), "MASS"),
        (1.0, (1e-3, 1e-3, 3e-3), "TRIANGLE"),  # one moment larger than the other two together
        (1.0, (0.0, 0.0, 0.0), "NOT_DEFINITE"),
        (1.0, (1e300, 1e300, 1e300), "NOT_FINITE"),  # ixx iyy overflows
        (math.nan, (1e-3, 1e-3, 1e-3), "NOT_FINITE"),
    ],
)
def test_an_inertia_no_solid_has_has_no_box(
    mass: float, moments: tuple[float, ...], why: str
) -> None:
    from fishbot_urdf.inertia import NoBox, equivalent_box, why_no_box

    ixx, iyy, izz = moments
    inertial = fishbot_urdf.Inertial(
        mass=mass, inertia=fishbot_urdf.Inertia(ixx=ixx, iyy=iyy, izz=izz)
    )
    assert equivalent_box(inertial) is None
    assert why_no_box(inertial) is NoBox[why]


def test_an_inertia_with_a_box_has_no_fault() -> None:
    from fishbot_urdf.inertia import why_no_box

    assert why_no_box(cylinder_inertia(1.0, 0.1, 0.12)) is None
