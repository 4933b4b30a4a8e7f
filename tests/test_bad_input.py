"""Bad input of every kind: one clear finding, the documented exit status, no traceback,
and nothing read from outside the file."""

from __future__ import annotations

import errno
import os
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from fishbot_urdf import XmlSyntaxError, check_file
from fishbot_urdf.cli import cli

SECRET = "fishbot-secret-marker"

CASES: dict[str, tuple[bytes, str]] = {
    "empty": (b"", "the file is empty"),
    "blank": (b"  \n\t\n", "the file is empty"),
    "binary": (bytes(range(256)) * 40, "this is not an XML file: it does not start with '<'"),
    "truncated": (
        b'<?xml version="1.0"?>\n<robot name="r">\n  <link name="a">',
        "XML syntax error: Premature end of data in tag link line 3",
    ),
    "deep": (
        b'<robot name="r">' + b"<a>" * 5000 + b"</a>" * 5000 + b"</robot>",
        "XML syntax error: elements are nested more than 256 deep (no URDF needs that)",
    ),
    "entity_bomb": (
        b'<?xml version="1.0"?>\n<!DOCTYPE lolz [\n <!ENTITY lol "lol">\n'
        + b"".join(
            b' <!ENTITY lol%d "%s">\n' % (i, (b"&lol%d;" % (i - 1) if i > 1 else b"&lol;") * 10)
            for i in range(1, 10)
        )
        + b']>\n<robot name="&lol9;"><link name="a"/></robot>',
        "XML entity declarations are not allowed",
    ),
    "utf16": (
        '<?xml version="1.0" encoding="UTF-16"?><robot name="r"><link name="a"/></robot>'.encode(
            "utf-16"
        ),
        "the file is UTF-16 or UTF-32: urdfdom reads it only up to its first NUL byte",
    ),
    "internal_subset": (
        b'<!DOCTYPE robot [<!ELEMENT robot ANY>]>\n<robot name="r"><link name="a"/></robot>',
        "urdfdom cannot read this file: its DOCTYPE ends at the first '>', inside the [...] part",
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_is_one_clear_line(name: str, tmp_path: Path) -> None:
    data, message = CASES[name]
    path = tmp_path / f"{name}.urdf"
    path.write_bytes(data)
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 1
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"{path}:")
    assert f"error: {message}" in lines[0]
    assert lines[0].endswith("[xml-syntax]")
    assert "Traceback" not in result.stderr


def test_external_entity_is_not_read(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text(SECRET)
    for target in (secret.as_uri(), "file:///etc/passwd"):
        data = (
            '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY xxe SYSTEM "' + target + '">]>\n'
            '<robot name="r"><link name="&xxe;"/></robot>'
        ).encode()
        with pytest.raises(XmlSyntaxError) as info:
            check_file(data, path="xxe.urdf")
        line = data.decode().splitlines()[1]
        assert (info.value.line, info.value.column) == (2, line.index("<!ENTITY") + 1)
        assert SECRET not in str(info.value)
        assert "root:" not in str(info.value)


def test_parameter_entity_is_refused() -> None:
    data = b'<!DOCTYPE r [<!ENTITY % p SYSTEM "http://example.invalid/x.dtd"> %p;]><robot/>'
    with pytest.raises(XmlSyntaxError, match="entity declarations are not allowed"):
        check_file(data)


def test_a_plain_doctype_is_harmless() -> None:
    assert check_file(b'<!DOCTYPE robot>\n<robot name="r"><link name="a"/></robot>').ok


def test_undefined_entity_reads_as_urdfdom_reads_it() -> None:
    # No DTD, nothing to expand: urdfdom drops the '&' (check_urdf prints "foo;").
    result = check_file(b'<robot name="&foo;"><link name="a"/></robot>')
    assert result.ok and result.robot is not None
    assert result.robot.name == "foo;"
    assert [d.rule for d in result.diagnostics] == ["xml-escape"]


def test_ten_megabyte_robot(tmp_path: Path) -> None:
    parts = ['<?xml version="1.0"?>\n<robot name="big">\n<link name="l0"/>\n']
    size, i = 0, 0
    while size < 10_000_000:
        i += 1
        chunk = (
            f'<link name="l{i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry>'
            f"</visual><!-- {'padding ' * 20} --></link>\n"
            f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/>'
            '<origin xyz="0 0 0.1"/></joint>\n'
        )
        parts.append(chunk)
        size += len(chunk)
    parts.append("</robot>\n")
    path = tmp_path / "big.urdf"
    path.write_text("".join(parts))
    assert path.stat().st_size > 10_000_000
    result = check_file(path)
    assert result.ok
    assert result.robot is not None and len(result.robot.links) == i + 1


def test_unreadable_file_is_exit_2(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tmp_path / "locked.urdf"
    path.write_text('<robot name="r"><link name="a"/></robot>')

    real_open = os.open

    def refuse(name: str, flags: int, *rest: int) -> int:
        if name == str(path):
            raise PermissionError(13, "Permission denied", name)
        return real_open(name, flags, *rest)

    # Simulated: file permissions do not stop root, which CI runs as.
    monkeypatch.setattr(os, "open", refuse)
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 2
    assert result.stderr == f"{path}: error: permission denied [io]\n"


@pytest.mark.parametrize("suffix", [".urdf", ".urdf.xacro"])
@pytest.mark.parametrize("command", [["check"], ["expand"], ["graph"], ["inertia"]])
def test_a_file_name_too_long_to_look_at_is_exit_2(
    tmp_path: Path, command: list[str], suffix: str
) -> None:
    # The folder and configuration lookups that come before the read must not stop on it.
    path = tmp_path / ("x" * 300 + suffix)
    result = CliRunner().invoke(cli, [*command, str(path)])
    assert result.exit_code == 2
    assert result.exception is None or isinstance(result.exception, SystemExit)
    why = os.strerror(errno.ENAMETOOLONG)
    assert result.stderr == f"{path}: error: cannot read: {why} [io]\n"


def _utf16_with_an_entity(xacro: bool) -> bytes:
    namespace = ' xmlns:xacro="http://www.ros.org/wiki/xacro"' if xacro else ""
    text = (
        '<?xml version="1.0" encoding="UTF-16"?>\n<!DOCTYPE robot [<!ENTITY x "boom">]>\n'
        f'<robot name="r"{namespace}><link name="a&x;"/></robot>\n'
    )
    return text.encode("utf-16")


@pytest.mark.parametrize("name", ["r.urdf", "r.urdf.xacro"])
def test_a_utf16_file_declaring_an_entity_is_refused_and_nothing_expands(
    tmp_path: Path, name: str
) -> None:
    path = tmp_path / name
    path.write_bytes(_utf16_with_an_entity(name.endswith(".xacro")))
    for command in (["check"], ["expand"], ["graph", "-o", "-"], ["inertia"]):
        result = CliRunner().invoke(cli, [*command, str(path)])
        assert result.exit_code == 1, command
        assert "boom" not in result.output, command
        assert "UTF-16 or UTF-32" in result.stderr, command
        assert result.stderr.count("\n") == 1, command


# Numbers a float holds, whose arithmetic does not: each command gives findings, no traceback.
HUGE_PRODUCT = (
    '<robot name="r"><link name="a"><inertial><mass value="1"/>'
    '<inertia ixx="1" ixy="1e200" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>'
)


@pytest.mark.parametrize("command", [["check"], ["graph", "-o", "-"], ["inertia"]])
def test_a_product_of_inertia_of_1e200_is_a_finding(tmp_path: Path, command: list[str]) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(HUGE_PRODUCT)
    (tmp_path / "fishbot.toml").write_text('targets = ["all"]\n')  # errors for the simulators
    result = CliRunner().invoke(cli, [*command, str(path)])
    assert result.exit_code == 1, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "[inertia-not-positive]" in result.stderr


def test_a_joint_without_parent_holding_a_collision_is_a_finding(tmp_path: Path) -> None:
    # c hangs from a joint with an empty parent and from base_link: the ground rule held c
    # through one joint while the tree placed it through none (KeyError).
    path = tmp_path / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="base_footprint"/>'
        '<link name="base_link"><collision><geometry><box size="1 1 1"/></geometry></collision>'
        "</link>"
        '<link name="c"><collision><geometry><box size="1 1 1"/></geometry></collision></link>'
        '<joint name="j" type="fixed"><parent link="base_footprint"/><child link="base_link"/>'
        "</joint>"
        '<joint name="k" type="fixed"><parent link=""/><child link="c"/></joint>'
        '<joint name="m" type="fixed"><parent link="base_link"/><child link="c"/></joint>'
        "</robot>"
    )
    for command in (["check"], ["graph", "-o", "-"], ["inertia"]):
        result = CliRunner().invoke(cli, [*command, str(path)])
        assert result.exception is None or isinstance(result.exception, SystemExit), command
        assert result.exit_code == 1, command
        assert "joint 'k': <parent> has no 'link' attribute" in result.stderr, command


def _one_link(collision: str) -> str:
    return (
        f'<robot name="r"><link name="a"><collision><geometry>{collision}</geometry>'
        "</collision></link></robot>"
    )


@pytest.mark.parametrize(
    ("shape", "why"),
    [
        ('<sphere radius="1e120"/>', "its collision shapes have no finite volume"),
        ('<box size="1e200 1e200 1e200"/>', "its collision shapes have no finite volume"),
        (
            '<box size="1e102 1e102 1e102"/>',
            "its collision shapes are too large for a finite mass and inertia (mass inf kg)",
        ),
    ],
)
def test_fill_never_writes_a_number_past_the_floats(tmp_path: Path, shape: str, why: str) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(_one_link(shape))
    out = tmp_path / "out.urdf"
    result = CliRunner().invoke(
        cli, ["inertia", str(path), "--fill", "--density", "1000", "-o", str(out)]
    )
    assert result.exit_code == 1
    assert f"link 'a': no <inertial> added (link 'a': {why}) [fill-skipped]" in result.stderr
    assert not out.exists()


def test_a_total_past_the_floats_is_said_not_printed_as_nan(tmp_path: Path) -> None:
    path = tmp_path / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="a"><inertial><origin xyz="1e308 0 0"/>'
        '<mass value="1e308"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial></link><link name="b"><inertial><origin xyz="-1e308 0 0"/>'
        '<mass value="1e308"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial></link><joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        "</joint></robot>"
    )
    text = CliRunner().invoke(cli, ["inertia", str(path)])
    assert text.stdout.splitlines()[-1] == (
        "total: no total: the links' masses and inertias add up beyond the largest number a "
        "float holds (about 1.8e308)"
    )
    assert "nan" not in text.stdout and "inf" not in text.stdout
    report = CliRunner().invoke(cli, ["inertia", str(path), "--format", "json"])
    import json

    assert json.loads(report.stdout)["total"] is None  # and it is JSON: no NaN in it


@pytest.mark.parametrize(
    ("name", "data", "why"),
    [
        ("box.foo", b"solid x\nendsolid x\n", "is not a file fishbot reads"),
        ("box", b"solid x\nendsolid x\n", "is not a file fishbot reads"),
        # trimesh 4 refuses these bytes; trimesh 5 reads them as an empty ASCII STL
        ("noise.stl", bytes(range(256)) * 12, "cannot read the mesh|holds no triangles"),
    ],
)
def test_fill_on_a_mesh_that_is_no_mesh_is_one_finding(
    tmp_path: Path, name: str, data: bytes, why: str
) -> None:
    pytest.importorskip("trimesh", reason="meshes are read by the optional trimesh package")
    (tmp_path / name).write_bytes(data)
    path = tmp_path / "r.urdf"
    path.write_text(_one_link(f'<mesh filename="{name}"/>'))
    result = CliRunner().invoke(
        cli, ["inertia", str(path), "--fill", "--density", "1000", "-o", str(tmp_path / "o.urdf")]
    )
    assert result.exit_code == 1
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert re.search(why, result.stderr) and "[fill-skipped]" in result.stderr


def test_joints_that_mimic_each_other_round_a_loop_are_each_reported(tmp_path: Path) -> None:
    joint = (
        '<joint name="{0}" type="revolute"><parent link="base"/><child link="{1}"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        '<mimic joint="{2}"/></joint>'
    )
    path = tmp_path / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/>'
        + joint.format("a", "l1", "b")
        + joint.format("b", "l2", "a")
        + joint.format("c", "l3", "a")  # follows the loop, is not in it
        + "</robot>"
    )
    result = CliRunner().invoke(cli, ["check", str(path)])
    assert result.exit_code == 1
    loops = [line for line in result.stderr.splitlines() if "mimics in a loop" in line]
    assert [line.split("joint '")[1][0] for line in loops] == ["a", "b"]
    assert all("(a -> b -> a)" in line and line.endswith("[undefined-mimic]") for line in loops)


def test_fill_on_a_closed_mesh_of_coordinates_near_the_floats_limit_writes_nothing(
    tmp_path: Path,
) -> None:
    trimesh = pytest.importorskip("trimesh", reason="meshes are read by the optional trimesh")
    import numpy as np

    with np.errstate(all="ignore"):  # trimesh's own normals overflow
        trimesh.creation.box(extents=(1.5e308, 1.5e308, 1.5e308)).export(tmp_path / "huge.obj")
    path = tmp_path / "r.urdf"
    path.write_text(_one_link('<mesh filename="huge.obj"/>'))
    out = tmp_path / "out.urdf"
    for given in (["--density", "1000"], ["--mass", "a=1"]):
        result = CliRunner().invoke(cli, ["inertia", str(path), "--fill", *given, "-o", str(out)])
        assert result.exit_code == 1, given
        assert result.stderr.count("\n") == 2, result.stderr  # the finding, "nothing written"
        assert "[fill-skipped]" in result.stderr, given
        assert not out.exists(), given


def test_a_turned_wheel_inertia_with_a_zero_moment_is_findings_not_a_math_error(
    tmp_path: Path,
) -> None:
    # Turned by rpy 1.57079 (not quite pi/2), izz = 0 leaves a moment of -1e-17 in the
    # collision's frame, whose square root was a math domain error.
    path = tmp_path / "r.urdf"
    path.write_text(
        '<robot name="r"><link name="base_link"/><joint name="j" type="continuous">'
        '<parent link="base_link"/><child link="wheel"/><axis xyz="0 1 0"/></joint>'
        '<link name="wheel"><inertial><origin rpy="1.57079 0 0"/><mass value="0.1"/>'
        '<inertia ixx="1e-05" ixy="0" ixz="0" iyy="1e-05" iyz="0" izz="0"/></inertial>'
        '<collision><origin rpy="1.57079 0 0"/>'
        '<geometry><cylinder radius="0.032" length="0.04"/></geometry></collision></link></robot>'
    )
    (tmp_path / "fishbot.toml").write_text('targets = ["all"]\n')  # errors for the simulators
    for command in (["check"], ["graph", "-o", "-"], ["inertia"]):
        result = CliRunner().invoke(cli, [*command, str(path)])
        assert result.exception is None or isinstance(result.exception, SystemExit), command
        assert result.exit_code == 1, command
        assert "[massless-link]" in result.stderr, command


def test_the_shapes_that_made_scans_quadratic_read_as_before(tmp_path: Path) -> None:
    # A quote followed by a run of newlines in a comment (the raw-white-space scan), and a
    # comment full of suppression markers: the same outcome, at any size (benchmarks/
    # adversarial.py times them at 1 MB).
    quote = tmp_path / "quote.urdf"
    quote.write_text('<robot name="r"><!-- x="' + "\n" * 2000 + ' --><link name="a"/></robot>')
    result = CliRunner().invoke(cli, ["check", str(quote)])
    assert (result.exit_code, result.stderr) == (0, "")
    raw = tmp_path / "raw.urdf"
    raw.write_text('<robot name="r"><link name="a"><visual><origin xyz="0 0\t1"/>'
                   '<geometry><box size="1 1 1"/></geometry></visual></link></robot>')  # fmt: skip
    assert check_file(raw).diagnostics  # a raw tab in a vector is still found
    markers = tmp_path / "markers.urdf"
    markers.write_text(
        '<robot name="r"><link name="a"/><!--' + " fishbot: ignore[" * 2000 + "--></robot>"
    )
    result = CliRunner().invoke(cli, ["check", str(markers)])
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert result.exit_code in (0, 1)
