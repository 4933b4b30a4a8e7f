"""`fishbot_urdf.expand` and `fishbot expand`: the xacro command's document, without ROS."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA, FISHBOT, XACRO_CORPUS, run_check_urdf, xacro_command

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.expansion import XacroError, expand, parse_args
from fishbot_urdf.expansion._errors import shown_path
from fishbot_urdf.location import Location

FISHBOT_XACRO = FISHBOT / "urdf" / "fishbot" / "fishbot.urdf.xacro"
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _write(folder: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        target = folder / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text, encoding="utf-8")


def _same_as_xacro(folder: Path, top: str, *args: str, **packages: Path) -> str:
    """Expand ``top`` (in ``folder``) with both tools; assert equal output; return it."""
    reference = xacro_command(top, *args, cwd=folder, packages=packages)
    assert reference.returncode == 0, reference.stderr
    here = Path.cwd()
    os.chdir(folder)
    try:
        values = parse_args(list(args))
        ours = expand(top, args=values, packages=packages)
    finally:
        os.chdir(here)
    assert ours.text == reference.stdout
    return ours.text


# -- every xacro feature, against the real command --------------------------------------------

FEATURES: dict[str, tuple[dict[str, str], tuple[str, ...]]] = {
    "properties-lazy-and-scoped": (
        {
            "robot.xacro": f"""<robot name="p" {NS}>
  <xacro:property name="b" value="${{a * 2}}"/>
  <xacro:property name="a" value="3"/>
  <xacro:property name="words" value="hello world"/>
  <xacro:macro name="m" params="">
    <xacro:property name="a" value="10"/>
    <xacro:property name="up" value="7" scope="parent"/>
    <link name="inner_${{a}}"/>
  </xacro:macro>
  <xacro:m/>
  <link name="outer_${{a}}_${{b}}_${{up}}" note="${{words}}"/>
  <xacro:property name="block"><origin xyz="1 2 3"/></xacro:property>
  <link name="with_block"><xacro:insert_block name="block"/></link>
</robot>
"""
        },
        (),
    ),
    "math": (
        {
            "robot.xacro": f"""<robot name="m" {NS}>
  <xacro:property name="r" value="0.032"/>
  <link name="l">
    <inertial>
      <mass value="${{0.1 + 0.2}}"/>
      <inertia ixx="${{1/12 * 0.1 * (3 * r**2 + 0.04**2)}}" ixy="0" ixz="0"
               iyy="${{pi/2}}" iyz="${{radians(90)}}" izz="${{sqrt(2) * cos(0)}}"/>
    </inertial>
  </link>
  <joint name="j" type="fixed"><origin rpy="${{-pi/2}} 0 ${{int(7/2)}}"/>
    <parent link="l"/><child link="l2"/></joint>
  <link name="l2" big="${{1e20}}" small="${{1e-7}}" neg="${{-0.0}}"/>
</robot>
"""
        },
        (),
    ),
    "macros-defaults-caret-blocks": (
        {
            "robot.xacro": f"""<robot name="mb" {NS}>
  <xacro:property name="size" value="0.5"/>
  <xacro:macro name="box" params="name size:=^ mass:=^|1.5 *origin **extra">
    <link name="${{name}}">
      <visual><xacro:insert_block name="origin"/>
        <geometry><box size="${{size}} ${{size}} ${{size}}"/></geometry></visual>
      <xacro:insert_block name="extra"/>
      <inertial><mass value="${{mass}}"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    </link>
  </xacro:macro>
  <xacro:box name="a">
    <origin xyz="0 0 1"/>
    <extra><collision><geometry><sphere radius="1"/></geometry></collision></extra>
  </xacro:box>
  <xacro:box name="b" size="2" mass="3">
    <origin xyz="0 0 2"/>
    <extra/>
  </xacro:box>
</robot>
"""
        },
        (),
    ),
    "if-unless": (
        {
            "robot.xacro": f"""<robot name="c" {NS}>
  <xacro:property name="on" value="true"/>
  <xacro:if value="${{on}}"><link name="yes"/></xacro:if>
  <xacro:unless value="${{on}}"><link name="no"/></xacro:unless>
  <xacro:if value="${{1 == 2}}"><link name="never"/></xacro:if>
  <xacro:if value="1"><link name="one"/></xacro:if>
  <xacro:unless value="false"><link name="unless_false"/></xacro:unless>
</robot>
"""
        },
        (),
    ),
    "include-ns-relative": (
        {
            "robot.xacro": f"""<robot name="i" {NS}>
  <xacro:include filename="parts/wheel.xacro"/>
  <xacro:include filename="parts/wheel.xacro" ns="other"/>
  <xacro:include filename="parts/missing.xacro" optional="true"/>
  <xacro:wheel side="left"/>
  <xacro:other.wheel side="right"/>
  <link name="r_${{other.radius}}"/>
</robot>
""",
            "parts/wheel.xacro": f"""<?xml version="1.0"?>
<robot {NS}>
  <xacro:include filename="common.xacro"/>
  <xacro:property name="radius" value="${{base_radius}}"/>
  <xacro:macro name="wheel" params="side">
    <!-- a wheel -->
    <link name="${{side}}_wheel"/>
  </xacro:macro>
</robot>
""",
            "parts/common.xacro": f"""<robot {NS}>
  <xacro:property name="base_radius" value="0.032"/>
</robot>
""",
        },
        (),
    ),
    "args-env-optenv-eval": (
        {
            "robot.xacro": f"""<robot name="$(arg name)" {NS}>
  <xacro:arg name="name" default="argbot"/>
  <xacro:arg name="use_lidar" default="false"/>
  <xacro:arg name="scale" default="2"/>
  <link name="home_$(optenv FISHBOT_TEST_UNSET fallback value)"/>
  <link name="shell_$(env FISHBOT_TEST_SET)"/>
  <link name="eval_$(eval 2 * scale + 1)"/>
  <xacro:if value="$(arg use_lidar)"><link name="lidar"/></xacro:if>
  <link name="xacro_arg_${{xacro.arg('scale')}}"/>
</robot>
"""
        },
        ("name:=mybot", "use_lidar:=true"),
    ),
    "load-yaml": (
        {
            "robot.xacro": f"""<robot name="y" {NS}>
  <xacro:property name="cfg" value="${{xacro.load_yaml('config/wheels.yaml')}}"/>
  <link name="w_${{cfg['radius']}}_${{cfg['names'][1]}}_${{cfg.nested.value}}"/>
</robot>
""",
            "config/wheels.yaml": "radius: 0.032\nnames: [left, right]\nnested:\n  value: 7\n",
        },
        (),
    ),
    "comments-and-text": (
        {
            "robot.xacro": f"""<?xml version="1.0"?>
<!-- top comment -->
<robot name="t" {NS}>
  <!-- kept -->
  <xacro:property name="x" value="1"/>
  <!-- xacro:eval-comments -->
  <!-- evaluated ${{x + 1}} -->
  <link name="a"><note>text ${{x}} &amp; more</note></link>
</robot>
"""
        },
        (),
    ),
    "element-and-call": (
        {
            "robot.xacro": f"""<robot name="e" {NS}>
  <xacro:property name="tag" value="link"/>
  <xacro:macro name="named" params="n"><link name="${{n}}"/></xacro:macro>
  <xacro:element xacro:name="${{tag}}" name="made"/>
  <xacro:call macro="named" n="called"/>
</robot>
"""
        },
        (),
    ),
}


@pytest.mark.parametrize("case", sorted(FEATURES))
def test_feature_matches_the_xacro_command(
    case: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    files, args = FEATURES[case]
    _write(tmp_path, files)
    monkeypatch.setenv("FISHBOT_TEST_SET", "from_env")
    monkeypatch.delenv("FISHBOT_TEST_UNSET", raising=False)
    text = _same_as_xacro(tmp_path, "robot.xacro", *args)
    assert "<robot" in text


def test_the_fishbot_matches_the_xacro_command(monkeypatch: pytest.MonkeyPatch) -> None:
    # run from the repository, the way the README does
    root = FISHBOT.parent.parent
    monkeypatch.chdir(root)
    top = str(FISHBOT_XACRO.relative_to(root))
    reference = xacro_command(top, cwd=root, packages={"fishbot_description": FISHBOT})
    assert reference.returncode == 0, reference.stderr
    ours = expand(top)  # the package is found by walking up from the file
    assert ours.text == reference.stdout
    assert "base_footprint" in ours.text


def test_first_robot_xacro_matches(monkeypatch: pytest.MonkeyPatch) -> None:
    folder = FISHBOT / "urdf"
    monkeypatch.chdir(folder)
    reference = xacro_command("first_robot.urdf.xacro", cwd=folder)
    assert reference.returncode == 0, reference.stderr
    assert expand("first_robot.urdf.xacro").text == reference.stdout


@pytest.mark.parametrize("path", XACRO_CORPUS, ids=[p.name for p in XACRO_CORPUS])
def test_real_robot_xacro_matches(path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(path.parent)
    reference = xacro_command(path.name, cwd=path.parent)
    if reference.returncode != 0:
        # the same verdict: example-robot-data's quadrotor_base.xacro includes a
        # package:// path, which xacro does not resolve in includes
        with pytest.raises(fishbot_urdf.FishbotUrdfError):
            expand(path.name)
        return
    assert expand(path.name).text == reference.stdout


def test_the_corpus_is_there() -> None:
    assert len(XACRO_CORPUS) >= 19
    robots = [p for p in XACRO_CORPUS if p.name in ("cookie.xacro", "desk.urdf.xacro")]
    assert len(robots) == 2
    for path in robots:  # whole robots, not only macros
        assert len(fishbot_urdf.load(path).links) > 10


# -- state does not leak between expansions ----------------------------------------------------


def test_two_expansions_do_not_leak(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "a.xacro": f"""<robot name="a" {NS}>
  <xacro:include filename="part.xacro"/>
  <xacro:property name="only_in_a" value="1" scope="global"/>
  <xacro:arg name="colour" default="red"/>
  <link name="a_$(arg colour)"/>
</robot>
""",
            "part.xacro": f'<robot {NS}><xacro:property name="p" value="1"/></robot>',
            "b.xacro": f"""<robot name="b" {NS}>
  <link name="b_${{only_in_a}}"/>
</robot>
""",
            "c.xacro": f"""<robot name="c" {NS}>
  <link name="c_$(arg colour)"/>
</robot>
""",
        },
    )
    first = expand(tmp_path / "a.xacro", args={"colour": "blue"})
    assert first.dependencies == (str(tmp_path / "part.xacro"),)
    assert 'name="a_blue"' in first.text
    with pytest.raises(XacroError) as info:
        expand(tmp_path / "b.xacro")
    assert "'only_in_a' is not defined" in info.value.message
    with pytest.raises(XacroError) as info:
        expand(tmp_path / "c.xacro")  # the argument of the first run is gone
    assert "argument 'colour' is not declared" in info.value.message
    again = expand(tmp_path / "a.xacro")
    assert again.dependencies == first.dependencies
    assert 'name="a_red"' in again.text


def test_xacro_module_state_is_restored(tmp_path: Path) -> None:
    import xacro
    import xacro.color

    def state() -> tuple[object, ...]:
        exposed = xacro._global_symbols["xacro"]["message"]
        return (xacro.eval_all, xacro.parse, xacro.all_includes, xacro.color.message, exposed)

    before = (*state(), sys.stdout, sys.stderr)
    _write(tmp_path, {"r.xacro": f'<robot name="r" {NS}><link name="l"/></robot>'})
    expand(tmp_path / "r.xacro")
    with pytest.raises(XacroError):
        _write(tmp_path, {"bad.xacro": f'<robot name="r" {NS}><xacro:nope/></robot>'})
        expand(tmp_path / "bad.xacro")
    after = (*state(), sys.stdout, sys.stderr)
    assert after == before


# -- what xacro 2.1.1 gets wrong ---------------------------------------------------------------


def test_dirname_works(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "r.xacro": f"""<robot name="r" {NS}>
  <xacro:include filename="sub/part.xacro"/>
  <link name="top"><visual><geometry><mesh filename="$(dirname)/a.stl"/></geometry></visual></link>
</robot>
""",
            "sub/part.xacro": f"""<robot {NS}>
  <link name="part" where="$(dirname)"/>
</robot>
""",
        },
    )
    broken = xacro_command("r.xacro", cwd=tmp_path)
    assert broken.returncode != 0 and "dirname" in broken.stderr  # still broken upstream
    text = expand(tmp_path / "r.xacro").text
    assert f'filename="{tmp_path}/a.stl"' in text
    assert f'where="{tmp_path / "sub"}"' in text


def test_attribute_with_a_number_value(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "r.xacro": f"""<robot name="r" {NS}>
  <link name="l"><xacro:attribute name="weight" value="${{1 + 1}}"/></link>
</robot>
"""
        },
    )
    broken = xacro_command("r.xacro", cwd=tmp_path)
    assert broken.returncode != 0 and "Traceback" in broken.stderr  # still broken upstream
    assert '<link name="l" weight="2"/>' in expand(tmp_path / "r.xacro").text


# -- errors point at the xacro source ----------------------------------------------------------


def _error(tmp_path: Path, files: dict[str, str], top: str = "robot.xacro") -> XacroError:
    _write(tmp_path, files)
    with pytest.raises(XacroError) as info:
        expand(tmp_path / top)
    return info.value


def test_missing_include_suggests_the_real_name() -> None:
    folder = DATA / "xacro" / "missing_include"
    with pytest.raises(XacroError) as info:
        expand(folder / "robot.urdf.xacro")
    error = info.value
    assert error.rule == "xacro-include"
    lines = (folder / "robot.urdf.xacro").read_text().splitlines()
    assert "base_urdf.xacro" in lines[error.line - 1]  # type: ignore[operator]
    assert "base_urdf.xacro does not exist" in error.message
    assert error.hint == "did you mean 'base.urdf.xacro'?"


def test_missing_namespace_declaration() -> None:
    path = DATA / "xacro" / "no_xmlns" / "robot.urdf.xacro"
    with pytest.raises(XacroError) as info:
        expand(path)
    error = info.value
    assert error.rule == "xacro-namespace"
    assert error.message == "the xacro: prefix is used but not declared"
    assert error.hint == 'add xmlns:xacro="http://www.ros.org/wiki/xacro" to the root element'
    line = path.read_text().splitlines()[error.line - 1]  # type: ignore[operator]
    assert line[error.column - 1 :].startswith("<xacro:")  # type: ignore[operator]


def test_undefined_property_in_a_macro_names_the_call(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:property name="wheel_radius" value="0.032"/>
  <xacro:include filename="wheel.xacro"/>
  <xacro:wheel_xacro side="left"/>
</robot>
""",
            "wheel.xacro": f"""<robot {NS}>
  <xacro:macro name="wheel_xacro" params="side">
    <link name="${{side}}_wheel">
      <visual><geometry>
        <cylinder radius="${{wheel_radus}}" length="0.04"/>
      </geometry></visual>
    </link>
  </xacro:macro>
</robot>
""",
        },
    )
    assert error.rule == "xacro-undefined"
    assert (Path(error.path or "").name, error.line, error.column) == ("wheel.xacro", 5, 9)
    assert error.message.startswith("'wheel_radus' is not defined in ${wheel_radus}")
    assert error.message.endswith("in macro wheel_xacro called from " + _at(tmp_path, 4))
    assert error.hint == "did you mean 'wheel_radius'?"
    assert [name for name, _ in error.calls] == ["wheel_xacro"]


def _at(folder: Path, line: int) -> str:
    return f"{shown_path(str(folder / 'robot.xacro'))}:{line}"


def test_nested_macro_calls_are_listed_innermost_first(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:macro name="inner" params="">
    <link name="${{nope}}"/>
  </xacro:macro>
  <xacro:macro name="outer" params="">
    <xacro:inner/>
  </xacro:macro>
  <xacro:outer/>
</robot>
"""
        },
    )
    assert error.line == 3
    assert [name for name, _ in error.calls] == ["inner", "outer"]
    assert [site.line for _, site in error.calls if site] == [6, 8]
    assert error.message.endswith(
        f"in macro inner called from {_at(tmp_path, 6)}, "
        f"in macro outer called from {_at(tmp_path, 8)}"
    )


def test_unknown_macro_suggests_close_names(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:macro name="wheel" params="side"><link name="${{side}}"/></xacro:macro>
  <xacro:wheels side="a"/>
</robot>
"""
        },
    )
    assert (error.rule, error.line, error.column) == ("xacro-undefined", 3, 3)
    assert error.message == "macro 'wheels' is not defined"
    assert error.hint == "did you mean 'wheel'?"


def test_wrong_and_missing_macro_parameters(tmp_path: Path) -> None:
    macro = f"""<robot name="r" {NS}>
  <xacro:macro name="wheel" params="side radius"><link name="${{side}}"/></xacro:macro>
  CALL
</robot>
"""
    wrong = _error(
        tmp_path, {"robot.xacro": macro.replace("CALL", '<xacro:wheel side="a" radus="1"/>')}
    )
    assert (wrong.line, wrong.message) == (3, "macro wheel has no parameter 'radus'")
    assert wrong.hint == "did you mean 'radius'?"
    missing = _error(tmp_path, {"robot.xacro": macro.replace("CALL", '<xacro:wheel side="a"/>')})
    assert (missing.line, missing.message) == (
        3,
        "the call of macro wheel gives no value for radius",
    )
    assert missing.hint == "its parameters: side, radius"


def test_undeclared_argument(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:arg name="use_gpu" default="false"/>
  <link name="$(arg use_gpus)"/>
</robot>
"""
        },
    )
    assert (error.rule, error.line) == ("xacro-undefined", 3)
    assert error.message == "argument 'use_gpus' is not declared"
    assert error.hint == "did you mean 'use_gpu'?"


def test_missing_package_lists_every_place(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:include filename="$(find no_such_description)/urdf/x.xacro"/>
</robot>
"""
        },
    )
    with pytest.raises(fishbot_urdf.PackageNotFoundError) as info:
        expand(tmp_path / "robot.xacro")
    error = info.value
    assert (error.package, error.line, error.column) == ("no_such_description", 2, 3)
    assert error.message.startswith(
        "package 'no_such_description' not found (searched: the packages given (none); "
    )
    assert "ROS_PACKAGE_PATH (not set)" in error.message
    assert "AMENT_PREFIX_PATH (not set)" in error.message
    # On the command line the same error names the option that fixes it.
    result = CliRunner().invoke(cli, ["expand", str(tmp_path / "robot.xacro")])
    assert result.exit_code == 2
    assert "not found (searched: --package (none given); " in result.stderr
    assert result.stderr.rstrip().endswith(
        "(name its folder with --package no_such_description=PATH) [package-not-found]"
    )


def test_syntax_error_in_an_included_file(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": (
                f'<robot name="r" {NS}>\n  <xacro:include filename="part.xacro"/>\n</robot>\n'
            ),
            "part.xacro": f"<robot {NS}>\n  <link name='a'>\n</robot>\n",
        },
    )
    assert (Path(error.path or "").name, error.line, error.rule) == (
        "part.xacro",
        3,
        "xacro-syntax",
    )
    assert error.message == (
        "not well-formed XML: mismatched tag: </robot> ends <link> of line 2, which is still open"
    )


def test_external_entities_are_not_read(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET")
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY leak SYSTEM "file://{secret}">]>
<robot name="r" {NS}><link name="l">&leak;</link></robot>
"""
        },
    )
    try:
        text = expand(tmp_path / "robot.xacro").text
    except XacroError:
        return
    assert "TOP-SECRET" not in text


# -- the command -------------------------------------------------------------------------------


def test_expand_command_to_stdout_and_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(FISHBOT.parent.parent)
    top = str(FISHBOT_XACRO.relative_to(FISHBOT.parent.parent))
    runner = CliRunner()
    shown = runner.invoke(cli, ["expand", top])
    assert shown.exit_code == 0
    assert shown.output == expand(top).text
    out = tmp_path / "new" / "folder" / "fishbot.urdf"
    written = runner.invoke(cli, ["expand", top, "-o", str(out)])
    assert (written.exit_code, written.output) == (0, "")
    assert out.read_text(encoding="utf-8") == shown.output
    assert [p.name for p in out.parent.iterdir()] == ["fishbot.urdf"]  # no temporary left


def test_expand_command_deps(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(FISHBOT.parent.parent)
    top = str(FISHBOT_XACRO.relative_to(FISHBOT.parent.parent))
    result = CliRunner().invoke(cli, ["expand", top, "--deps"])
    assert result.exit_code == 0
    reference = xacro_command(top, "--deps", packages={"fishbot_description": FISHBOT})
    assert set(result.output.split()) == set(reference.stdout.split())
    assert len(result.output.split()) == 8


def test_expand_command_args_and_packages(tmp_path: Path) -> None:
    pkg = tmp_path / "elsewhere" / "my_parts"
    _write(pkg, {"part.xacro": f'<robot {NS}><link name="from_pkg"/></robot>'})
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="$(arg name)" {NS}>
  <xacro:arg name="name" default="x"/>
  <xacro:include filename="$(find my_parts)/part.xacro"/>
</robot>
"""
        },
    )
    runner = CliRunner()
    args = ["expand", str(tmp_path / "robot.xacro"), "name:=given"]
    result = runner.invoke(cli, [*args, "--package", f"my_parts={pkg}"])
    assert result.exit_code == 0, result.output
    assert '<robot name="given">' in result.output and 'name="from_pkg"' in result.output
    missing = runner.invoke(cli, args)
    assert missing.exit_code == 2
    assert "package 'my_parts' not found" in missing.output
    bad_arg = runner.invoke(cli, [*args, "oops"])
    assert bad_arg.exit_code == 2
    assert "'oops' is not an argument: write name:=value" in bad_arg.output


ARMS = """\
<?xml version="1.0"?>
<robot name="arms" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="arm" default="none"/>
  <xacro:arg name="hand" default="none"/>
  <link name="base_link"/>
  <xacro:include filename="$(find arms)/urdf/$(arg arm)/$(arg hand)_$(arg arm).xacro"/>
</robot>
"""


def test_an_include_made_from_arguments_names_them_and_their_values(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    Path("arms/urdf").mkdir(parents=True)
    Path("arms/package.xml").write_text('<package format="3"><name>arms</name></package>\n')
    Path("arms/urdf/robot.urdf.xacro").write_text(ARMS)
    for arm, hand in (("ur5", "gripper"), ("ur10", "vacuum")):
        Path(f"arms/urdf/{arm}").mkdir()
        Path(f"arms/urdf/{arm}/{hand}_{arm}.xacro").write_text(
            f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="{hand}"/></robot>\n'
        )
    given = ["expand", "arms/urdf/robot.urdf.xacro", "--package", "arms=arms"]

    def said(*args: str) -> tuple[int, str]:
        result = CliRunner().invoke(cli, [*given, *args])
        return result.exit_code, result.stderr

    at = "arms/urdf/robot.urdf.xacro:6:3: error: included file arms/urdf"
    # Run with no arguments: the defaults made a folder that is not there; the values that
    # name files there are offered.
    assert said() == (
        1,
        f"{at}/none/none_none.xacro does not exist: its path is made from arguments left at "
        "their defaults: arm:=none and hand:=none (there is no folder arms/urdf/none; give "
        "arm:=ur10 hand:=vacuum or arm:=ur5 hand:=gripper) [xacro-include]\n",
    )
    assert said("arm:=ur5") == (
        1,
        f"{at}/ur5/none_ur5.xacro does not exist: its path is made from argument left at its "
        "default: hand:=none, with arm:=ur5 given (give hand:=gripper) [xacro-include]\n",
    )
    assert said("hand:=claw") == (
        1,
        f"{at}/none/claw_none.xacro does not exist: its path is made from argument left at its "
        "default: arm:=none, with hand:=claw given (there is no folder arms/urdf/none; give "
        "arm:=VALUE) [xacro-include]\n",
    )
    assert said("arm:=ur6", "hand:=gripper") == (
        1,
        f"{at}/ur6/gripper_ur6.xacro does not exist: its path is made from the arguments "
        "given: arm:=ur6 and hand:=gripper (there is no folder arms/urdf/ur6; check the values "
        "given; files there are named by arm:=ur10 hand:=vacuum or arm:=ur5 hand:=gripper) "
        "[xacro-include]\n",
    )
    assert said("arm:=ur5", "hand:=gripper")[0] == 0


def test_expand_command_errors(tmp_path: Path) -> None:
    runner = CliRunner()
    folder = DATA / "xacro" / "missing_include"
    result = runner.invoke(cli, ["expand", str(folder / "robot.urdf.xacro")])
    assert result.exit_code == 1
    [line] = result.output.splitlines()
    assert line.endswith(
        "error: included file "
        f"{os.path.relpath(folder / 'base_urdf.xacro')} does not exist "
        "(did you mean 'base.urdf.xacro'?) [xacro-include]"
    )
    gone = runner.invoke(cli, ["expand", str(tmp_path / "nope.xacro")])
    assert gone.exit_code == 2
    assert (
        gone.output
        == f"{tmp_path / 'nope.xacro'}: error: {tmp_path / 'nope.xacro'} does not exist [io]\n"
    )


def test_expand_never_writes_over_an_input(tmp_path: Path) -> None:
    _write(tmp_path, {"r.xacro": f'<robot name="r" {NS}><link name="l"/></robot>'})
    before = (tmp_path / "r.xacro").read_bytes()
    result = CliRunner().invoke(
        cli, ["expand", str(tmp_path / "r.xacro"), "-o", str(tmp_path / "r.xacro")]
    )
    assert result.exit_code == 2
    assert "refusing to write over the input" in result.output
    assert (tmp_path / "r.xacro").read_bytes() == before


def test_expand_help_has_an_example() -> None:
    result = CliRunner().invoke(cli, ["expand", "--help"])
    assert result.exit_code == 0
    assert "fishbot expand robots/fishbot/urdf/fishbot/fishbot.urdf.xacro" in result.output


def test_xacro_warnings_become_findings(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="w" {NS}>
  <xacro:property name="pi" value="3"/>
  <link name="l"/>
</robot>
"""
        },
    )
    path = str(tmp_path / "robot.xacro")
    warning = f"{path}: warning: redefining global symbol: pi [xacro-warning]\n"
    assert expand(path).messages == ("warning: redefining global symbol: pi",)
    runner = CliRunner()
    expanded = runner.invoke(cli, ["expand", path, "-o", str(tmp_path / "out.urdf")])
    assert (expanded.exit_code, expanded.output) == (0, warning)
    checked = runner.invoke(cli, ["check", path])
    assert checked.exit_code == 0
    assert checked.output.startswith(warning + "robot name is: w\n")
    assert runner.invoke(cli, ["check", "--strict", path]).exit_code == 1


# The lines xacro's print_location adds after a message; findings carry the place instead.
_LOCATION_LINES = (
    "when processing file:",
    "when instantiating macro:",
    "instantiated from:",
    "in file:",
    "included from:",
)


def test_messages_are_the_xacro_command_s(monkeypatch: pytest.MonkeyPatch) -> None:
    folder = DATA / "xacro" / "warnings"
    reference = xacro_command("robot.urdf.xacro", cwd=folder)
    assert reference.returncode == 0, reference.stderr
    expected = tuple(
        line
        for line in reference.stderr.splitlines()
        if line.strip() and not line.startswith(_LOCATION_LINES)
    )
    monkeypatch.chdir(folder)
    stderr = sys.stderr
    ours = expand("robot.urdf.xacro")
    assert ours.text == reference.stdout
    assert ours.messages == expected
    assert len(expected) == 10  # every kind: warning, error, message, deprecation, include
    assert sys.stderr is stderr


def test_arguments_are_read_like_the_xacro_command(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="a" {NS}>
  <xacro:arg name="radius" default="0.1"/>
  <xacro:arg name="prefix" default="p_"/>
  <link name="$(arg prefix)base" r="$(arg radius)"/>
</robot>
"""
        },
    )
    text = _same_as_xacro(tmp_path, "robot.xacro", "radius:=", " prefix := x_ ", "_private:=1")
    assert '<link name="x_base" r="0.1"/>' in text
    with pytest.raises(ValueError):
        parse_args(["a:=b:=c"])


def test_condition_errors_point_at_the_condition(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <link name="a"/>
  <xacro:if value="${{use_imu}}">
    <link name="imu"/>
  </xacro:if>
</robot>
"""
        },
    )
    assert (error.line, error.column) == (3, 3)
    assert error.message == "'use_imu' is not defined in ${use_imu}"
    assert error.hint is None or "__builtins__" not in error.hint


def test_circular_property_points_at_its_definition(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:property name="a" value="${{b + 1}}"/>
  <xacro:property name="b" value="${{a * 2}}"/>
  <link name="l" x="${{a}}"/>
</robot>
"""
        },
    )
    assert (error.rule, error.line) == ("xacro-circular", 2)
    assert error.message == "property 'a' is defined in terms of itself: a -> b -> a"


def test_including_a_folder(tmp_path: Path) -> None:
    (tmp_path / "parts").mkdir()
    error = _error(
        tmp_path,
        {"robot.xacro": f'<robot name="r" {NS}>\n  <xacro:include filename="parts"/>\n</robot>'},
    )
    assert (error.rule, error.line) == ("xacro-include", 2)
    assert error.message.endswith("parts is a folder, not a file")


def test_relative_package_folders(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pkg = tmp_path / "pkgs" / "my_parts"
    _write(
        pkg,
        {
            "part.xacro": f'<robot {NS}><link name="from_pkg"/></robot>',
            "package.xml": "<package><name>my_parts</name></package>",
        },
    )
    _write(
        tmp_path,
        {
            "robots/robot.xacro": f"""<robot name="r" {NS}>
  <xacro:include filename="$(find my_parts)/part.xacro"/>
</robot>
"""
        },
    )
    monkeypatch.chdir(tmp_path)
    given = expand("robots/robot.xacro", packages={"my_parts": "pkgs/my_parts"})
    assert 'name="from_pkg"' in given.text
    monkeypatch.setenv("ROS_PACKAGE_PATH", "pkgs")
    assert expand("robots/robot.xacro").text == given.text


def test_output_goes_through_links_and_into_devices(tmp_path: Path) -> None:
    _write(tmp_path, {"r.xacro": f'<robot name="r" {NS}><link name="l"/></robot>'})
    real = tmp_path / "real.urdf"
    real.write_text("old")
    (tmp_path / "link.urdf").symlink_to(real)
    runner = CliRunner()
    result = runner.invoke(
        cli, ["expand", str(tmp_path / "r.xacro"), "-o", str(tmp_path / "link.urdf")]
    )
    assert result.exit_code == 0
    assert (tmp_path / "link.urdf").is_symlink()
    assert real.read_text().startswith("<?xml")
    devnull = runner.invoke(cli, ["expand", str(tmp_path / "r.xacro"), "-o", os.devnull])
    assert devnull.exit_code == 0
    assert not Path(os.devnull).is_file()  # still the device
    nothing = runner.invoke(cli, ["expand", str(tmp_path / "r.xacro"), "--deps"])
    assert (nothing.exit_code, nothing.output) == (0, "")
    for bad in ("", str(tmp_path)):
        refused = runner.invoke(cli, ["expand", str(tmp_path / "r.xacro"), "-o", bad])
        assert refused.exit_code == 2
        assert refused.output.count("\n") == 1


# -- arguments no file declares, properties used before their definition -------------------

ARGS_XACRO = """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="with_arm" default="false"/>
  <xacro:property name="camera" value="$(arg use_camera)"/>
  <link name="a"/>
</robot>
"""


def test_an_argument_no_file_declares_is_a_warning_with_the_closest_name(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    Path("robot.urdf.xacro").write_text(ARGS_XACRO, encoding="utf-8")
    given = ["expand", "robot.urdf.xacro", "use_camera:=true", "wiht_arm:=true", "_private:=1"]
    result = CliRunner().invoke(cli, given)
    assert result.exit_code == 0
    assert result.stdout.startswith("<?xml")
    assert result.stderr == (
        "robot.urdf.xacro: warning: argument 'wiht_arm' is given, but no <xacro:arg> declares "
        "it and nothing reads it (did you mean 'with_arm'?) [xacro-unknown-arg]\n"
    )
    # read by $(arg ...) without a declaration: known; declared: known
    quiet = CliRunner().invoke(cli, ["expand", "robot.urdf.xacro", "use_camera:=1", "with_arm:=1"])
    assert (quiet.exit_code, quiet.stderr) == (0, "")


def test_under_strict_an_unknown_argument_fails_and_nothing_is_written(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    Path("robot.urdf.xacro").write_text(ARGS_XACRO, encoding="utf-8")
    args = ["robot.urdf.xacro", "use_camera:=1", "wiht_arm:=true"]
    result = CliRunner().invoke(cli, ["expand", "--strict", *args, "-o", "robot.urdf"])
    assert result.exit_code == 1
    assert "error: argument 'wiht_arm' is given" in result.stderr
    assert not Path("robot.urdf").exists()
    checked = CliRunner().invoke(cli, ["check", "--strict", *args])
    assert checked.exit_code == 1
    assert "[xacro-unknown-arg]" in checked.stderr
    assert CliRunner().invoke(cli, ["check", *args]).exit_code == 0


def test_a_property_used_before_its_definition_says_where_it_is_defined(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a">
    <visual><geometry><box size="${wheel_w} 1 1"/></geometry></visual>
  </link>
  <xacro:property name="wheel_w" value="0.04"/>
</robot>
""",
        encoding="utf-8",
    )
    with pytest.raises(XacroError) as caught:
        expand(path)
    assert caught.value.rule == "xacro-undefined"
    assert (caught.value.line, caught.value.column) == (3, 23)
    assert str(caught.value).endswith("'wheel_w' is used in ${wheel_w} before it is defined")
    assert caught.value.hint == (
        f"it is defined later, at {shown_path(str(path))}:5: move the definition above its "
        "first use"
    )


def test_a_property_local_to_a_macro_is_no_later_definition(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        """\
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="m"><xacro:property name="wheel_w" value="1"/></xacro:macro>
  <link name="a">
    <visual><geometry><box size="${wheel_w} 1 1"/></geometry></visual>
  </link>
</robot>
""",
        encoding="utf-8",
    )
    with pytest.raises(XacroError) as caught:
        expand(path)
    assert "is not defined" in str(caught.value)


# -- YAML with units, as the Universal Robots descriptions load it ---------------------------

UR_STYLE = DATA / "xacro" / "ur_style"
UR_PACKAGE = {"ur_style_description": UR_STYLE / "ur_style_description"}
UR_TOP = "ur_style_description/urdf/ur.urdf.xacro"
UR_ARGS = ("ur_type:=ur5e", "name:=ur5e")


@pytest.mark.parametrize("trust", [False, True])
def test_a_ur_style_description_expands_as_the_xacro_command_with_no_message(
    trust: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Its macros read joint limits and kinematics with xacro.load_yaml, from files written
    # with !degrees, !radians, !meters, !millimeters, !foot and !inches.
    reference = xacro_command(UR_TOP, *UR_ARGS, cwd=UR_STYLE, packages=UR_PACKAGE)
    assert (reference.returncode, reference.stderr) == (0, "")
    assert 'upper="6.283185307179586"' in reference.stdout  # !degrees 360.0
    monkeypatch.chdir(UR_STYLE)
    ours = expand(UR_TOP, parse_args(UR_ARGS), UR_PACKAGE, trust_expressions=trust)
    assert (ours.text, ours.messages) == (reference.stdout, ())


def test_a_ur_style_description_passes_strict_expand_and_check(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    reference = xacro_command(UR_TOP, *UR_ARGS, cwd=UR_STYLE, packages=UR_PACKAGE)
    monkeypatch.chdir(UR_STYLE)
    given = [
        UR_TOP,
        *UR_ARGS,
        "--package",
        f"ur_style_description={UR_PACKAGE['ur_style_description']}",
    ]
    runner = CliRunner()
    expanded = runner.invoke(cli, ["expand", "--strict", *given])
    assert (expanded.exit_code, expanded.stderr) == (0, "")
    assert expanded.stdout == reference.stdout
    checked = runner.invoke(cli, ["check", "--strict", *given])
    assert (checked.exit_code, checked.stderr) == (0, "")


UNITS_YAML = """\
angles: {deg: !degrees 360.0, neg: !degrees -90, expr: !degrees 2 * 45, rad: !radians pi / 2}
lengths: {m: !meters 1.5, mm: !millimeters 162.5, ft: !foot 2, in: !inches 10}
plain: [1, 2.5, text]
"""


@pytest.mark.parametrize("trust", [False, True])
def test_yaml_units_load_as_the_xacro_command_loads_them(
    trust: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _write(
        tmp_path,
        {
            "units.yaml": UNITS_YAML,
            "robot.xacro": f"""<robot name="u" {NS}>
  <xacro:property name="u" value="${{xacro.load_yaml('units.yaml')}}"/>
  <xacro:property name="again" value="${{load_yaml('units.yaml')}}"/>
  <link name="a" x="${{u['angles']['deg']}} ${{u.angles.neg}}"
                 y="${{u.angles.expr}} ${{u.angles.rad}}"/>
  <link name="b" x="${{u.lengths.m}} ${{u.lengths.mm}}"
                 y="${{again.lengths.ft}} ${{again.lengths['in']}}"/>
  <link name="c" x="${{u.plain}} ${{[v * 2 for v in again.plain[:2]]}}"/>
</robot>
""",
        },
    )
    reference = xacro_command("robot.xacro", cwd=tmp_path)
    assert reference.returncode == 0, reference.stderr
    # xacro's own words for the deprecated load_yaml(), and nothing else
    said = tuple(line for line in reference.stderr.splitlines() if line.strip())
    assert said[0] == (
        "warning: Using load_yaml() directly is deprecated. Use xacro.load_yaml() instead."
    )
    monkeypatch.chdir(tmp_path)
    ours = expand("robot.xacro", trust_expressions=trust)
    assert ours.text == reference.stdout
    assert ours.messages == tuple(line for line in said if not line.startswith(_LOCATION_LINES))


def test_an_argument_used_before_its_declaration_says_where_it_is_declared(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # As the UR description's top file: <robot name="$(arg name)"> above <xacro:arg name="name">.
    reference = xacro_command(UR_TOP, "ur_type:=ur5e", cwd=UR_STYLE, packages=UR_PACKAGE)
    assert reference.returncode != 0  # xacro refuses it too
    assert "Undefined substitution argument name" in reference.stderr
    monkeypatch.chdir(UR_STYLE)
    with pytest.raises(XacroError) as caught:
        expand(UR_TOP, {"ur_type": "ur5e"}, UR_PACKAGE)
    error = caught.value
    lines = Path(UR_TOP).read_text(encoding="utf-8").splitlines()
    used = next(n for n, line in enumerate(lines, 1) if 'name="$(arg name)">' in line)
    declared = next(n for n, line in enumerate(lines, 1) if '<xacro:arg name="name"' in line)
    assert (error.rule, error.path, error.line) == ("xacro-undefined", UR_TOP, used)
    assert error.message == "argument 'name' is used before its <xacro:arg> declaration"
    assert error.hint == (
        f"it is declared later, at {UR_TOP}:{declared}, and xacro needs the declaration "
        "first; the root element's attributes are read before anything in it: give "
        "name:=... on the command line"
    )
    package = f"ur_style_description={UR_PACKAGE['ur_style_description']}"
    result = CliRunner().invoke(cli, ["expand", UR_TOP, "ur_type:=ur5e", "--package", package])
    assert result.exit_code == 1
    assert result.stderr.startswith(f"{UR_TOP}:{used}:1: error: argument 'name' is used before")


def test_an_argument_declared_below_its_use_in_the_robot(tmp_path: Path) -> None:
    _write(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <link name="$(arg prefix)base"/>
  <xacro:arg name="prefix" default="my_"/>
</robot>
"""
        },
    )
    assert xacro_command("robot.xacro", cwd=tmp_path).returncode != 0
    error = _error(tmp_path, {})
    assert (error.rule, error.line) == ("xacro-undefined", 2)
    assert error.message == "argument 'prefix' is used before its <xacro:arg> declaration"
    assert error.hint == (
        f"it is declared later, at {shown_path(str(tmp_path / 'robot.xacro'))}:3, and xacro "
        "needs the declaration first; move the declaration above the first use, or give "
        "prefix:=... on the command line"
    )


# -- findings about what macro calls made name the calls ---------------------------------------

TWO_WHEELS = f"""<robot name="r" {NS}>
  <link name="base_link"/>
  <xacro:macro name="wheel" params="side">
    <link name="wheel_link"/>
    <joint name="${{side}}_wheel_joint" type="continuous">
      <parent link="base_link"/>
      <child link="wheel_link"/>
      <axis xyz="0 1 0"/>
    </joint>
  </xacro:macro>
  <xacro:macro name="wheels">
    <xacro:wheel side="left"/>
    <xacro:wheel side="right"/>
  </xacro:macro>
  WHEELS
</robot>
"""


def test_a_link_two_macro_calls_make_names_both_calls(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(TWO_WHEELS.replace("WHEELS", "<xacro:wheels/>"), encoding="utf-8")
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(xacro_command(path.name, cwd=tmp_path).stdout, encoding="utf-8")
    refused = run_check_urdf(urdf)  # urdfdom refuses the robot for it
    assert b"link 'wheel_link' is not unique" in refused.stdout + refused.stderr
    [finding] = [d for d in fishbot_urdf.check_file(path).diagnostics if d.rule == "duplicate-link"]
    shown = shown_path(str(path))
    assert (finding.path, finding.line) == (shown, 4)  # the macro's <link>
    assert finding.message == (
        "link 'wheel_link' is defined twice (first by macro wheel called at "
        f"{shown}:12, in macro wheels called at {shown}:15; again by macro wheel called at "
        f"{shown}:13, in macro wheels called at {shown}:15)"
    )
    assert finding.hint == (
        "every link needs a unique name: make it from a parameter of macro wheel that "
        "each call gives its own value"
    )


# -- an element never closed names its start tag and line -----------------------------------

UNCLOSED = f"""<?xml version="1.0"?>
<robot name="r" {NS}>
  <link name="a">
    <visual>
      <geometry><box size="1 1 1"/></geometry>
  </link>
</robot>
"""


def test_a_mismatched_end_tag_names_the_element_left_open(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(UNCLOSED, encoding="utf-8")
    reference = xacro_command(path.name, cwd=tmp_path)
    assert reference.returncode != 0
    assert "mismatched tag: line 6, column 4" in reference.stderr  # 0-based column
    with pytest.raises(XacroError) as caught:
        expand(path)
    error = caught.value
    assert (error.rule, error.line, error.column) == ("xacro-syntax", 6, 5)
    assert error.message == (
        "not well-formed XML: mismatched tag: </link> ends <visual> of line 4, which is still open"
    )
    assert error.hint == "close it with </visual> before </link>"


def test_a_file_that_ends_inside_an_element_names_it(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(UNCLOSED.split("  </link>")[0], encoding="utf-8")
    assert xacro_command(path.name, cwd=tmp_path).returncode != 0
    with pytest.raises(XacroError) as caught:
        expand(path)
    error = caught.value
    assert (error.rule, error.line) == ("xacro-syntax", 6)
    assert error.message == (
        "not well-formed XML: the file ends with <visual> of line 4 still open"
    )
    assert error.hint == (
        "close it with </visual>; <link> of line 3 and <robot> of line 2 are still open too"
    )


# -- an expression Python cannot compute quotes it and says why in plain words --------------

KG = f"""<robot name="r" {NS}>
  <xacro:property name="m" value="1kg"/>
  <link name="a">
    <inertial>
      <mass value="${{EXPRESSION}}"/>
    </inertial>
  </link>
</robot>
"""


@pytest.mark.parametrize(
    ("expression", "said"),
    [
        ("m + 2", 'can only concatenate str (not "int") to str'),
        ("m * 2.0", "can't multiply sequence by non-int of type 'float'"),
        ("2 / m", "unsupported operand type(s) for /: 'int' and 'str'"),
        ("float(m)", "could not convert string to float: '1kg'"),
    ],
)
def test_a_value_with_a_unit_in_arithmetic_is_named(
    expression: str, said: str, tmp_path: Path
) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(KG.replace("EXPRESSION", expression), encoding="utf-8")
    reference = xacro_command(path.name, cwd=tmp_path)
    assert reference.returncode != 0
    assert f"error: {said}" in reference.stderr  # Python's words, and no expression
    with pytest.raises(XacroError) as caught:
        expand(path)
    error = caught.value
    assert (error.rule, error.line) == ("xacro-error", 5)
    assert error.message == (
        f"${{{expression}}} cannot be computed: property 'm' is the text '1kg', not a number "
        f"({said})"
    )
    assert error.hint == (
        f"property 'm' is defined at {shown_path(str(path))}:2; write the number alone, "
        'value="1": xacro values have no units'
    )


def test_an_expression_python_cannot_compute_is_quoted(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        {
            "robot.xacro": f"""<robot name="r" {NS}>
  <xacro:property name="n" value="0"/>
  <link name="a" x="${{1 / n}}"/>
</robot>
"""
        },
    )
    assert (error.rule, error.line) == ("xacro-error", 3)
    assert error.message == "${1 / n} cannot be computed: it divides by zero (division by zero)"


def test_probe_macros_calls_the_top_levels_macros_with_its_properties(tmp_path: Path) -> None:
    from fishbot_urdf.expansion import probe_macros

    _write(
        tmp_path,
        {
            "parts.xacro": f"""<robot {NS}>
  <xacro:macro name="plate" params="w *body side:=1">
    <plate w="${{w * scale}}" side="${{side}}"/>
  </xacro:macro>
</robot>
""",
            "r.urdf.xacro": f"""<robot name="r" {NS}>
  <xacro:property name="scale" value="10"/>
  <xacro:include filename="parts.xacro"/>
  <xacro:include filename="parts.xacro" ns="inner"/>
  <link name="a"/>
</robot>
""",
        },
    )
    seen = probe_macros(
        tmp_path / "r.urdf.xacro",
        lambda table: (
            table.definitions,
            table.call("plate", {"w": "2"}),
            table.call("plate", {}),  # w is missing: xacro refuses it
            table.call("nothing", {}),
            table.written(Location(shown_path(str(tmp_path / "parts.xacro")), 3, 5)),
        ),
    )
    (plate,), made, missing, unknown, written = seen
    # The macro of the include without a namespace only; the block parameter is no value.
    assert (plate.name, plate.params, plate.required) == ("plate", ("w", "*body", "side"), ("w",))
    assert plate.optional == frozenset({"side"})
    assert (plate.source.path, plate.source.line) == (shown_path(str(tmp_path / "parts.xacro")), 2)
    assert made is None  # a block parameter was not given
    assert (missing, unknown) == (None, None)
    assert written == {"w": "${w * scale}", "side": "${side}"}


def test_probe_macros_gives_what_a_call_makes(tmp_path: Path) -> None:
    from fishbot_urdf.expansion import probe_macros

    _write(
        tmp_path,
        {
            "r.urdf.xacro": f"""<robot name="r" {NS}>
  <xacro:property name="scale" value="10"/>
  <xacro:macro name="plate" params="w side:=1">
    <plate w="${{w * scale}}" side="${{side}}"/>
  </xacro:macro>
  <link name="a"/>
</robot>
"""
        },
    )
    made = probe_macros(tmp_path / "r.urdf.xacro", lambda t: t.call("plate", {"w": "2"}))
    assert made is not None
    assert made.split() == ["<plate", 'side="1"', 'w="20"/>']
