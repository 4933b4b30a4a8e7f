"""The mass, inertia and ground rules of `fishbot check`, on the learner's mistakes.

Every expected number here is worked out by hand from the fixture's own values, in the
comment beside it.
"""

from __future__ import annotations

import re
from operator import mul
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from conftest import CORPUS, DATA, FISHBOT
from hypothesis import given, settings
from hypothesis import strategies as st

import fishbot_urdf
from fishbot_urdf import Config, check_file
from fishbot_urdf.cli import cli
from fishbot_urdf.inertia import cylinder_inertia, solid_moments
from fishbot_urdf.model import (
    Box,
    Collision,
    Cylinder,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Link,
    Robot,
    Sphere,
)
from fishbot_urdf.rules.physics import _shape
from fishbot_urdf.spatial import eigenvalues

PHYSICS = DATA / "physics"
XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"


# The fixtures are the fishbot, a two-wheeled robot to simulate: checked for Gazebo, which
# their physics faults harm (by default they would be warnings: no <gazebo> block says so).
GAZEBO = Config(targets=("gazebo",))
EVERY_PROGRAM = Config(targets=("all",))


def _findings(path: Path, *args: str) -> tuple[int, list[str]]:
    result = CliRunner().invoke(cli, ["check", "--target", "gazebo", str(path), *args])
    return result.exit_code, result.stderr.splitlines()


# (fixture, exit status, the one finding it must give: severity, rule, message)
CASES = [
    # base_joint z 0.076, wheel 0.06 below base_link, radius 0.032: 0.076 - 0.06 - 0.032
    # = -0.016 m, for each wheel.
    (
        "wheels_under_ground",
        0,
        "warning",
        "below-ground",
        "link 'left_wheel_link' reaches 16.0 mm below the ground (z = 0 of 'base_footprint') "
        "at the zero configuration",
    ),
    # 0.101 - 0.06 - 0.032 = 0.009 m above.
    (
        "floating",
        0,
        "warning",
        "above-ground",
        "link 'left_wheel_link', the robot's lowest point, is 9.0 mm above the ground "
        "(z = 0 of 'base_footprint') at the zero configuration",
    ),
    # cylinder_inertia(0.1, 0.032, 0.04) unrotated: the odd moment (m r^2 / 2) is about z,
    # while the collision cylinder, turned 1.57079 about x, lies along y.
    (
        "wheel_inertia_unrotated",
        0,
        "warning",
        "inertia-mismatch",
        "link 'left_wheel_link': inertial matches a cylinder r=0.032 h=0.04 along the link's "
        "z axis, but the collision cylinder lies along its y axis",
    ),
    # ixx = m/12 (h^2 + d^2) with w = 0.02 and h = 0.1 swapped: 6.67e-07 is what
    # 0.01/12 (0.02^2 + 0.02^2) gives, i.e. a box 0.1 long in x.
    (
        "box_sides_swapped",
        0,
        "warning",
        "inertia-mismatch",
        "link 'camera_link': inertial matches a box 0.10 x 0.02 x 0.02, but the collision box "
        "is 0.02 x 0.10 x 0.02",
    ),
    (
        "negative_iyy",
        1,
        "error",
        "inertia-not-positive",
        "link 'camera_link': the inertia is not positive definite: principal moments "
        "-6.67e-07, 8.67e-06, 8.67e-06 kg*m^2",
    ),
    (
        "missing_inertial",
        1,
        "error",
        "missing-inertial",
        "link 'left_wheel_link' has collision geometry and moves (joint 'left_wheel_joint' is "
        "continuous) but no <inertial>",
    ),
    (
        "massless_wheel",
        1,
        "error",
        "massless-link",
        "link 'left_wheel_link' moves (joint 'left_wheel_joint' is continuous) but its mass "
        "is 0 kg",
    ),
    # 0.0001 + 0.0001 < 0.001
    (
        "triangle",
        1,
        "error",
        "inertia-triangle",
        "link 'left_wheel_link': principal moments 0.0001, 0.0001, 0.001 kg*m^2 break the "
        "triangle inequality (0.0001 + 0.0001 < 0.001)",
    ),
]


@pytest.mark.parametrize(("name", "status", "severity", "rule", "message"), CASES)
def test_seed_mistake(name: str, status: int, severity: str, rule: str, message: str) -> None:
    code, lines = _findings(PHYSICS / f"{name}.urdf")
    assert code == status, lines
    mine = [line for line in lines if line.endswith(f"[{rule}]")]
    assert mine, lines
    assert f": {severity}: {message} (" in mine[0]
    # ... and nothing else but more of the same rule (both wheels sink).
    assert {line.rsplit("[", 1)[1] for line in lines} == {f"{rule}]"}


def test_every_physics_fixture_has_a_case() -> None:
    assert {p.stem for p in PHYSICS.glob("*.urdf")} == {case[0] for case in CASES}


def test_radius_is_length_says_what_the_inertia_matches() -> None:
    # The notes' base.urdf.xacro: collision radius = length = 0.12, inertia for r = 0.10.
    code, lines = _findings(DATA / "xacro" / "radius_is_length" / "robot.urdf.xacro")
    assert code == 0
    (line,) = [x for x in lines if x.endswith("[inertia-mismatch]")]
    assert (
        # At the link, not at common_inertia.xacro's macro: the call is in the link.
        "base.urdf.xacro:10:5: warning: link 'base_link': inertial matches a cylinder "
        "r=0.10 h=0.12, but the collision cylinder has r=0.12 (fix the one that is wrong; "
        "`fishbot inertia cylinder --mass 1 --radius 0.12 --length 0.12` prints the "
        "inertial of the collision)"
    ) in line


def test_the_fishbot_is_clean_and_its_1_mm_sink_is_within_the_tolerance() -> None:
    code, lines = _findings(XACRO)
    assert (code, lines) == (0, [])
    # 0.091 - 0.06 - 0.032 = -0.001 m: the wheels sink 1.0 mm, the casters
    # (0.091 - 0.076 - 0.016) too.
    code, lines = _findings(XACRO, "--ground-tolerance", "0.5")
    assert code == 0
    sinking = sorted(line.split("link '")[1].split("'")[0] for line in lines)
    assert sinking == [
        "back_caster_link",
        "front_caster_link",
        "left_wheel_link",
        "right_wheel_link",
    ]
    assert all(" reaches 1.0 mm below the ground" in line for line in lines)


def test_strict_makes_the_warnings_fail() -> None:
    assert _findings(PHYSICS / "wheels_under_ground.urdf", "--strict")[0] == 1


def test_a_negative_ground_tolerance_is_a_usage_error() -> None:
    code, lines = _findings(XACRO, "--ground-tolerance", "-1")
    assert code == 2
    assert "--ground-tolerance" in "\n".join(lines)


def _wheel(inertial: Inertial | None, joint: JointType = JointType.CONTINUOUS) -> Robot:
    wheel = Link(
        "wheel",
        inertial=inertial,
        collisions=(Collision(Cylinder(0.032, 0.04)),),
    )
    return Robot(
        "r",
        links=(Link("base", inertial=cylinder_inertia(1.0, 0.1, 0.1)), wheel),
        # about its cylinder's axis (z), as a wheel turns
        joints=(Joint("j", joint, "base", "wheel", axis=(0.0, 0.0, 1.0)),),
    )


def _rules(robot: Robot) -> dict[str, str]:
    return {d.rule: d.severity.value for d in fishbot_urdf.check(robot, config=EVERY_PROGRAM)}


def test_a_massless_link_on_a_fixed_joint_is_a_frame_not_a_fault() -> None:
    tool = Inertial(mass=0.0)
    assert "massless-link" in _rules(_wheel(tool))
    assert _rules(_wheel(tool, JointType.FIXED)) == {}


def test_products_that_break_a_fixed_link_are_a_warning_when_the_merged_body_is_fine() -> None:
    # Off-diagonal terms too large for the moments (tiago's antennas): the matrix
    # [[1, 2, 0], [2, 1, 0], [0, 0, 1]] * 1e-6 has eigenvalues -1e-6, 1e-6, 3e-6.
    odd = Inertial(mass=0.01, inertia=Inertia(ixx=1e-6, ixy=2e-6, iyy=1e-6, izz=1e-6))
    # (fishbot mjcf adds it to the base's body, as MuJoCo refuses it on a body of its own)
    assert _rules(_wheel(odd, JointType.FIXED)) == {
        "inertia-not-positive": "warning",
        "mjcf-joined-inertial": "warning",
    }
    # (on a wheel, which moves, nothing can take it: MuJoCo refuses the model)
    assert _rules(_wheel(odd)) == {"inertia-not-positive": "error", "mjcf-refused": "error"}


def test_a_non_finite_mass_built_in_code_is_reported() -> None:
    rules = _rules(_wheel(Inertial(mass=float("nan"))))
    assert rules == {"bad-number": "error"}


def test_every_physics_error_in_the_corpus_is_confirmed_by_numpy() -> None:
    # Independent of our eigen solver: numpy's eigvalsh on the link's own matrix.
    seen = 0
    for path in CORPUS:
        result = check_file(path, config=EVERY_PROGRAM)
        assert result.robot is not None
        by_name = {link.name: link for link in result.robot.links}
        for d in result.diagnostics:
            if d.rule not in ("inertia-not-positive", "inertia-triangle") or not d.is_error:
                continue
            link = by_name[d.message.split("'")[1]]
            assert link.inertial is not None
            moments = np.linalg.eigvalsh(np.array(link.inertial.inertia.matrix()))
            if d.rule == "inertia-not-positive":
                assert moments[0] < 0
            else:
                assert moments[0] + moments[1] < moments[2]
            seen += 1
    if CORPUS:
        assert seen > 0


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


_BOX = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
_MASS = (
    '<inertial><mass value="1"/>'
    '<inertia ixx="0.0017" ixy="0" ixz="0" iyy="0.0017" iyz="0" izz="0.0017"/></inertial>'
)


def test_a_robot_bolted_to_the_world_has_no_ground(tmp_path: Path) -> None:
    # A table-top arm: world -> base 0.75 m up, an arm link on a revolute joint.
    path = _write(
        tmp_path,
        "arm.urdf",
        f'<robot name="arm"><link name="world"/><link name="base">{_BOX}{_MASS}</link>'
        f'<link name="arm">{_BOX}{_MASS}</link>'
        '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
        '<origin xyz="0 0 0.75"/></joint>'
        '<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>',
    )
    assert _findings(path, "--strict") == (0, [])


def test_a_robot_on_legs_is_not_said_to_float(tmp_path: Path) -> None:
    # The body 0.35 m up on a footprint, a leg on a revolute joint reaching the ground.
    path = _write(
        tmp_path,
        "legs.urdf",
        f'<robot name="legs"><link name="base_footprint"/><link name="body">{_BOX}{_MASS}</link>'
        f'<link name="leg"><collision><origin xyz="0 0 -0.15"/><geometry>'
        f'<box size="0.02 0.02 0.3"/></geometry></collision>{_MASS}</link>'
        '<joint name="fix" type="fixed"><parent link="base_footprint"/><child link="body"/>'
        '<origin xyz="0 0 0.35"/></joint>'
        '<joint name="hip" type="revolute"><parent link="body"/><child link="leg"/>'
        '<origin xyz="0 0 -0.05"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        "</joint></robot>",
    )
    _, lines = _findings(path)
    assert not [line for line in lines if "ground" in line]


def test_the_tolerance_is_met_to_the_micrometre() -> None:
    # The casters sink 0.091 - 0.076 - 0.016 = 0.001 m (a float a hair above 1 mm), the
    # wheels 1 mm and 0.0001 mm more (rpy 1.57079 is not quite pi/2): 1 mm passes both.
    assert _findings(XACRO, "--ground-tolerance", "1") == (0, [])


@pytest.mark.parametrize("value", ["nan", "inf", "abc", "-1"])
def test_a_ground_tolerance_must_be_a_finite_number(value: str) -> None:
    assert _findings(XACRO, "--ground-tolerance", value)[0] == 2


def test_a_base_without_inertial_weighs_nothing(tmp_path: Path) -> None:
    text = (PHYSICS / "floating.urdf").read_text()
    start = text.index("<inertial>")
    text = text[:start] + text[text.index("</inertial>") + len("</inertial>") :]
    path = _write(tmp_path, "nobase.urdf", text.replace('xyz="0 0 0.101"', 'xyz="0 0 0.091"'))
    code, lines = _findings(path)
    assert code == 1
    (line,) = lines
    assert "error: link 'base_link' has collision geometry but no <inertial>" in line
    assert line.endswith("[missing-inertial]")


def test_a_moving_link_without_inertial_is_graded_as_one_of_mass_0() -> None:
    # The two fixtures differ only in the left wheel's inertial: none, or one of mass 0.
    # sdformat (Gazebo) drops both links alike, with everything below them ("has no
    # <inertial> block defined" / "a mass value of less than or equal to zero", then
    # "is not modeled in sdf"), so both are errors; pinocchio reads both wheels as massless.
    pin = pytest.importorskip("pinocchio")
    graded = {}
    for name in ("missing_inertial", "massless_wheel"):
        path = PHYSICS / f"{name}.urdf"
        found = check_file(path, config=GAZEBO).diagnostics
        (finding,) = [d for d in found if d.subject is not None]
        graded[name] = (finding.rule, finding.severity.value, finding.subject.name)
        model = pin.buildModelFromUrdf(str(path))
        assert model.inertias[model.getJointId("left_wheel_joint")].mass == 0.0
    assert graded == {
        "missing_inertial": ("missing-inertial", "error", "left_wheel_link"),
        "massless_wheel": ("massless-link", "error", "left_wheel_link"),
    }


def test_a_point_mass_is_no_mismatch() -> None:
    robot = _wheel(Inertial(mass=0.1), JointType.FIXED)
    assert _rules(robot) == {}


def test_a_bad_mass_is_reported_once(tmp_path: Path) -> None:
    wheel = (PHYSICS / "missing_inertial.urdf").read_text()
    for value, rule in (("1kg", "bad-number"), ("-1", "negative-mass")):
        inertial = (
            f'<inertial><mass value="{value}"/>'
            '<inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>'
        )
        text = wheel.replace("</collision>\n  </link>", "</collision>" + inertial + "</link>", 1)
        code, lines = _findings(_write(tmp_path, "bad.urdf", text))
        assert code == 1
        assert [line.rsplit("[", 1)[1] for line in lines] == [f"{rule}]"], lines


def test_an_isotropic_inertia_on_a_cylinder_is_a_size_not_an_axis(tmp_path: Path) -> None:
    # I = 1 everywhere, m = 0.2: r = sqrt(2 I / m) = sqrt(10) = 3.16, and
    # h = sqrt(12 I / m - 3 r^2) = sqrt(60 - 30) = 5.48, whichever axis is taken.
    path = tmp_path / "robot.urdf"
    path.write_text(
        """\
<robot name="r">
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="wheel">
    <collision><origin rpy="1.5708 0 0"/>
      <geometry><cylinder radius="0.032" length="0.04"/></geometry></collision>
    <inertial><mass value="0.2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="j" type="continuous">
    <parent link="base_link"/><child link="wheel"/><axis xyz="0 1 0"/></joint>
</robot>
""",
        encoding="utf-8",
    )
    [finding] = fishbot_urdf.check_file(path).diagnostics
    assert finding.rule == "inertia-mismatch"
    assert finding.message == (
        "link 'wheel': inertial matches a cylinder r=3.16 h=5.48 (its three moments are equal, "
        "so along any axis), but the collision cylinder has r=0.032 h=0.04"
    )


_factor = st.floats(0.9, 1.1)  # about the shape's own moments: at the rule's 10%
_product = st.floats(-0.05, 0.05)
_size = st.floats(1e-3, 2.0)
_solid = st.one_of(
    st.builds(Box, st.tuples(_size, _size, _size)),
    st.builds(Cylinder, _size, _size),
    st.builds(Sphere, _size),
)


@settings(max_examples=200)
@given(
    _solid,
    st.floats(1e-3, 100.0),
    st.tuples(_factor, _factor, _factor),
    st.tuples(_product, _product, _product),
)
def test_an_unturned_inertia_is_compared_as_a_turned_one_would_be(
    shape: Box | Cylinder | Sphere,
    mass: float,
    factors: tuple[float, float, float],
    products: tuple[float, float, float],
) -> None:
    # With no rpy the rule compares six numbers; through the general path (rotations by an
    # identity that is not the shared one) it compares the whole turned matrices.
    ixx, iyy, izz = map(mul, solid_moments(shape, mass), factors)
    ixy, ixz, iyz = (p * min(ixx, iyy, izz) for p in products)
    inertia = Inertia(ixx=ixx, ixy=ixy, ixz=ixz, iyy=iyy, iyz=iyz, izz=izz)
    link = Link("l", Inertial(mass, inertia), collisions=(Collision(shape),))
    principal = eigenvalues(inertia.matrix())
    quick = _shape.mismatch(link, "p", principal)
    real = _shape.rpy_matrix
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(_shape, "rpy_matrix", lambda rpy: tuple(map(tuple, real(rpy))))
        general = _shape.mismatch(link, "p", principal)
    assert quick == general
    assert (quick and quick.data) == (general and general.data)


# -- robot-units: a robot of primitives written in millimetres ------------------------------

_MILLIMETRES = """\
<robot name="arm">
  <link name="base_link">
    <collision><geometry><box size="200 200 100"/></geometry></collision>
    <inertial><mass value="2"/>
      <inertia ixx="{i}" iyy="{i}" izz="{iz}" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <link name="arm_link">
    <collision><geometry><cylinder radius="30" length="300"/></geometry></collision>
    <inertial><mass value="0.5"/>
      <inertia ixx="3863" iyy="3863" izz="225" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="arm_joint" type="revolute">
    <origin xyz="0 0 250"/><parent link="base_link"/><child link="arm_link"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
</robot>
"""


def test_a_robot_written_in_millimetres_is_said_to_be_with_the_factor(tmp_path: Path) -> None:
    path = _write(tmp_path, "arm.urdf", _MILLIMETRES.format(i="8333", iz="13333"))
    status, lines = _findings(path)
    assert status == 1
    assert lines == [
        f"{path}:1:1: error: robot 'arm' reads as written in millimetres: its boxes, "
        "cylinders and spheres are 200 to 300 m across (median 250 m), its joints 250 m from "
        "their parents, and its links weigh 5.2e-07 kg/m^3, far lighter than air (multiply every "
        "length by 0.001 (sizes and origins; inertias by 1e-6): 250 m is 0.25 m) [robot-units]"
    ]


def test_no_inertia_is_proposed_for_a_200_m_box_of_a_robot_in_millimetres(tmp_path: Path) -> None:
    # the base's inertia is that of a box 0.2 m across: the metres the lengths should be in
    path = _write(tmp_path, "arm.urdf", _MILLIMETRES.format(i="0.0083", iz="0.013"))
    _, lines = _findings(path)
    assert [line.rsplit("[", 1)[1] for line in lines] == ["robot-units]"]  # the cause only
    _, lines = _findings(path, "--ignore", "robot-units")
    [mismatch] = lines
    assert mismatch.endswith(
        "(the robot reads as written in millimetres: multiply its lengths by 0.001 first, "
        "then compare) [inertia-mismatch]"
    )
    assert "fishbot inertia box" not in mismatch


def _world(floor: str, part: str, count: int, *, spacing: float, inertial: str) -> str:
    """A floor and ``count`` parts on fixed joints, ``spacing`` metres apart along x and y."""
    links = [f'<link name="floor"><collision><geometry>{floor}</geometry></collision></link>']
    joints = []
    for n in range(count):
        links.append(
            f'<link name="part{n}"><collision><geometry>{part}</geometry></collision>'
            f"{inertial}</link>"
        )
        joints.append(
            f'<joint name="j{n}" type="fixed"><parent link="floor"/><child link="part{n}"/>'
            f'<origin xyz="{spacing * (n + 1)} {spacing * (n + 1)} 3"/></joint>'
        )
    return f'<robot name="world">{"".join(links)}{"".join(joints)}</robot>'


@pytest.mark.parametrize(
    "name",
    [
        # pybullet_data's plane.urdf: one box of 200 m, no joint
        "plane",
        # bullet_safety_gym's rooms: walls of 40 m and 4 kg, in one link
        "room",
        # big shapes with joints apart, but as heavy as things are (400 kg/m^3): a building
        # in metres
        "building",
        # a warehouse: a 60 x 40 m floor, 20 m shelves 17 m apart on fixed joints, unweighed
        "warehouse",
        # a house of 10 m rooms 8 m apart, each weighing a placeholder kilogram
        "house",
        # the arm in millimetres, but with nothing to weigh it: not judged
        "unweighed",
    ],
)
def test_big_worlds_in_metres_are_not_millimetres(tmp_path: Path, name: str) -> None:
    wall = '<collision><geometry><box size="40 0.1 2"/></geometry></collision>'
    texts = {
        "plane": '<robot name="plane"><link name="planeLink"><collision><geometry>'
        '<box size="200 200 10"/></geometry></collision></link></robot>',
        "room": f'<robot name="room"><link name="walls">{wall * 4}</link></robot>',
        "building": _MILLIMETRES.format(i="8333", iz="13333").replace(
            'mass value="2"', 'mass value="2e9"'
        ),
        "warehouse": _world(
            '<box size="60 40 0.2"/>', '<box size="20 1 6"/>', 6, spacing=6, inertial=""
        ),
        "house": _world(
            '<box size="10 8 3"/>',
            '<box size="10 8 3"/>',
            4,
            spacing=8,
            inertial='<inertial><mass value="1"/>'
            '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>',
        ),
        "unweighed": re.sub(
            r"<inertial>.*?</inertial>", "", _MILLIMETRES.format(i="1", iz="1"), flags=re.S
        ),
    }
    path = _write(tmp_path, f"{name}.urdf", texts[name])
    assert "robot-units" not in "".join(_findings(path)[1])


def test_an_inertial_to_compute_for_a_robot_in_millimetres_waits_for_metres(
    tmp_path: Path,
) -> None:
    text = _MILLIMETRES.format(i="8333", iz="13333")
    start = text.index('    <inertial><mass value="0.5"/>')
    text = text[:start] + text[text.index("</inertial>\n", start) + len("</inertial>\n") :]
    _, lines = _findings(_write(tmp_path, "arm.urdf", text))
    [missing] = [line for line in lines if line.endswith("[missing-inertial]")]
    assert "give it one computed from its collision shapes once they are in metres" in missing
