"""The shape rules: boxes, cylinders and spheres of no size, and meshes scaled to nothing."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.config import Config

ROBOT = """\
<robot name="r">
  <link name="base_link">
    <{kind}><geometry>{shape}</geometry></{kind}>
  </link>
</robot>
"""


def _found(tmp_path: Path, kind: str, shape: str) -> list[tuple[str, str, str]]:
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT.format(kind=kind, shape=shape), encoding="utf-8")
    # For MuJoCo, which refuses what the rule finds in a collision shape.
    config = Config(select=("shape-size",), targets=("mujoco",))
    found = fishbot_urdf.check_file(path, config=config).diagnostics
    return [(d.rule, d.severity.value, d.message) for d in found]


@pytest.mark.parametrize(
    ("shape", "said", "index"),
    [
        ('<box size="0.2 0.2 0"/>', 'box of size "0.2 0.2 0"', 2),
        ('<cylinder radius="-0.1" length="0.2"/>', "cylinder of radius -0.1", 0),
        ('<cylinder radius="0.1" length="0"/>', "cylinder of length 0", 1),
        ('<sphere radius="0"/>', "sphere of radius 0", 0),
    ],
)
def test_a_collision_shape_of_no_size_is_an_error_mujoco_refuses(
    tmp_path: Path, shape: str, said: str, index: int
) -> None:
    assert _found(tmp_path, "collision", shape) == [
        (
            "shape-size",
            "error",
            f"link 'base_link': <collision> {said}: MuJoCo refuses the robot "
            f"('size {index} must be positive in geom')",
        )
    ]


def test_a_visual_of_negative_size_is_a_warning_and_of_size_0_a_placeholder(
    tmp_path: Path,
) -> None:
    assert _found(tmp_path, "visual", '<sphere radius="-1"/>') == [
        ("shape-size", "warning", "link 'base_link': <visual> sphere of radius -1: it is no shape")
    ]
    assert _found(tmp_path, "visual", '<box size="0 -0.1 0.1"/>')[0][1] == "warning"
    # upkie's frames: <box size="0 0 0"/>, drawn as nothing, on purpose
    assert _found(tmp_path, "visual", '<box size="0 0 0"/>') == []
    assert _found(tmp_path, "visual", '<sphere radius="0"/>') == []


def test_a_mesh_scaled_by_0_is_flat_and_a_negative_scale_mirrors(tmp_path: Path) -> None:
    (tmp_path / "m.stl").write_bytes(b"solid s\nendsolid s\n")
    [(_, severity, message)] = _found(
        tmp_path, "collision", '<mesh filename="m.stl" scale="0 1 1"/>'
    )
    assert (severity, message) == (
        "error",
        "link 'base_link': <collision> mesh 'm.stl' is scaled by \"0 1 1\", which flattens it: "
        "MuJoCo refuses the robot ('mesh volume is too small')",
    )
    assert _found(tmp_path, "collision", '<mesh filename="m.stl" scale="-1 1 1"/>') == []


def test_a_value_that_cannot_be_read_hides_no_other_shape_of_its_link(tmp_path: Path) -> None:
    # scale="0" is one number where three are needed: that mesh is dropped (bad-vector), and
    # the sphere of radius 0 beside it is still said, all findings at once
    path = tmp_path / "r.urdf"
    path.write_text(
        ROBOT.format(kind="collision", shape='<sphere radius="0"/>').replace(
            "</link>",
            '<collision><geometry><mesh filename="m.stl" scale="0"/></geometry></collision></link>',
        ),
        encoding="utf-8",
    )
    result = CliRunner().invoke(cli, ["check", "-q", str(path)])
    assert result.exit_code == 1
    rules = [line.rsplit("[", 1)[1] for line in result.stderr.splitlines()]
    assert rules == ["shape-size]", "bad-vector]"]


@pytest.mark.parametrize(
    "shape",
    [
        '<capsule radius="0.1" length="0.2"/>',  # no URDF shape: none is read
        '<box size="{x} {y} {z}"/>',  # a template's placeholders: no number is read
        '<sphere radius="r"/>',
    ],
)
def test_a_shape_whose_size_cannot_be_read_is_not_said_to_be_of_size_0(
    tmp_path: Path, shape: str
) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT.format(kind="collision", shape=shape), encoding="utf-8")
    result = CliRunner().invoke(cli, ["check", "-q", str(path)])
    assert result.exit_code == 1
    assert "[shape-size]" not in result.stderr, result.stderr
