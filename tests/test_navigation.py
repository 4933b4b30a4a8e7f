"""Navigation: where each name of the fishbot is written and used, asked as an editor asks."""

from __future__ import annotations

import contextlib
import re
import shutil
from pathlib import Path

import pytest

from fishbot_urdf.catalog import ids
from fishbot_urdf.errors import ArgumentError, FishbotUrdfError
from fishbot_urdf.lint import CheckResult, check_file
from fishbot_urdf.model import JointType
from fishbot_urdf.navigation import Index, Span, symbols
from fishbot_urdf.workspace import Workspace

ROBOTS = Path(__file__).parent.parent / "robots" / "fishbot"


@pytest.fixture
def package(tmp_path: Path) -> Path:
    """A copy of the fishbot_description package."""
    copy = tmp_path / "fishbot_description"
    shutil.copytree(ROBOTS, copy)
    return copy


def urdf(package: Path, name: str) -> str:
    return str(package / "urdf" / "fishbot" / name)


def checked(package: Path, workspace: Workspace | None = None) -> tuple[Workspace, CheckResult]:
    workspace = workspace or Workspace({"fishbot_description": package})
    result = check_file(urdf(package, "fishbot.urdf.xacro"), workspace=workspace)
    assert result.robot is not None
    return workspace, result


def place(text: str, needle: str, into: int = 0, nth: int = 0) -> tuple[int, int]:
    """1-based line and column (in characters) of ``into`` characters into the ``nth``
    occurrence of ``needle`` in ``text``."""
    offset = -1
    for _ in range(nth + 1):
        offset = text.index(needle, offset + 1)
    offset += into
    line_start = text.rfind("\n", 0, offset) + 1
    return text.count("\n", 0, offset) + 1, offset - line_start + 1


def span_of(path: str, text: str, needle: str, name: str, nth: int = 0) -> Span:
    """The span of ``name`` inside the ``nth`` occurrence of ``needle`` in the file."""
    line, column = place(text, needle, needle.index(name), nth)
    return Span(path, line, column, line, column + len(name))


def at(path: str, needle: str, into: int = 0, nth: int = 0) -> tuple[str, int, int]:
    return (path, *place(Path(path).read_text(), needle, into, nth))


def written(span: Span) -> str:
    lines = Path(span.path).read_text().splitlines()
    assert span.line == span.end_line
    return lines[span.line - 1][span.column - 1 : span.end_column - 1]


def test_a_link_used_in_an_included_file_is_defined_where_its_link_is(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    caster, base = urdf(package, "actuator/caster.urdf.xacro"), urdf(package, "base.urdf.xacro")
    found = index.definition(*at(caster, '<parent link="base_link"/>', len('<parent link="') + 2))
    assert found == [span_of(base, Path(base).read_text(), '<link name="base_link">', "base_link")]


def test_the_references_of_a_link_are_every_place_its_name_is_written(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    base = urdf(package, "base.urdf.xacro")
    found = index.references(*at(base, '<link name="base_link">', 13))
    text = Path(base).read_text()
    assert span_of(base, text, '<gazebo reference="base_link">', "base_link") in found
    # every joint of the robot whose parent or child is base_link, wherever it is written
    ends = sum(Path(file).read_text().count(' link="base_link"/>') for file in result.files)
    assert len(found) == ends + 2  # and the link and the <gazebo reference>
    assert all(written(s) == "base_link" for s in found)
    without = index.references(*at(base, '<link name="base_link">', 13), declaration=False)
    assert len(without) == len(found) - 1
    # a frame a Gazebo plugin names
    plugin = urdf(package, "plugins/gazebo_control_plugin.xacro")
    footprint = index.references(*at(base, '<link name="base_footprint"/>', 13))
    frame = "<robot_base_frame>base_footprint</robot_base_frame>"
    assert span_of(plugin, Path(plugin).read_text(), frame, "base_footprint") in footprint


def test_a_joint_handed_to_a_macro_is_found_at_the_call_and_in_the_plugin(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top, wheel = urdf(package, "fishbot.urdf.xacro"), urdf(package, "actuator/wheel.urdf.xacro")
    plugin = urdf(package, "plugins/gazebo_control_plugin.xacro")
    call = at(top, 'left_joint="left_wheel_joint"', len('left_joint="') + 1)
    defined = index.definition(*call)
    assert defined == [
        span_of(wheel, Path(wheel).read_text(), 'name="${name}_wheel_joint"', "${name}_wheel_joint")
    ]
    found = index.references(*call)
    text = Path(plugin).read_text()
    assert span_of(plugin, text, "<left_joint>${left_joint}<", "${left_joint}") in found
    assert span_of(plugin, text, "<joint_name>${left_joint}<", "${left_joint}") in found
    given = 'left_joint="left_wheel_joint"'
    assert span_of(top, Path(top).read_text(), given, "left_wheel_joint") in found
    inside = at(plugin, "<left_joint>${left_joint}<", len("<left_joint>"))
    assert index.prepare_rename(*inside) is None
    with pytest.raises(ArgumentError, match="handed to this macro by its call"):
        index.rename(*inside, "left_drive_joint")
    # the joint is built by ${name}_wheel_joint: no text edit renames it
    with pytest.raises(ArgumentError, match=r"expression '\$\{name\}_wheel_joint'"):
        index.rename(*call, "left_drive_joint")


def test_a_macro_call_goes_to_the_macro_in_another_file(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top, wheel = urdf(package, "fishbot.urdf.xacro"), urdf(package, "actuator/wheel.urdf.xacro")
    found = index.definition(*at(top, "<xacro:wheel_xacro", len("<xacro:") + 3))
    macro = '<xacro:macro name="wheel_xacro"'
    assert found == [span_of(wheel, Path(wheel).read_text(), macro, "wheel_xacro")]
    calls = index.references(*at(wheel, macro, len('<xacro:macro name="')))
    assert len(calls) == 1 + Path(top).read_text().count("<xacro:wheel_xacro ")
    # a call's parameter goes to the macro's params
    param = index.definition(*at(top, 'y_offset="${wheel_y}"', 2))
    assert [written(s) for s in param] == ["y_offset"] and param[0].path == wheel


def test_a_property_in_an_expression_goes_to_its_definition(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top = urdf(package, "fishbot.urdf.xacro")
    text = Path(top).read_text()
    found = index.definition(*at(top, 'mass="${wheel_mass}"', len('mass="${') + 2))
    assert found == [span_of(top, text, '<xacro:property name="wheel_mass"', "wheel_mass")]
    uses = index.references(*at(top, '<xacro:property name="wheel_mass"', 25))
    assert len(uses) == 1 + text.count("${wheel_mass}")
    # in a macro's body, ${radius} is the macro's parameter
    base = urdf(package, "base.urdf.xacro")
    param = index.definition(*at(base, 'radius="${radius}"', len('radius="${') + 1))
    assert param == [span_of(base, Path(base).read_text(), "length radius mass", "radius")]


def test_an_argument_goes_to_its_declaration(package: Path) -> None:
    top = urdf(package, "fishbot.urdf.xacro")
    text = Path(top).read_text()
    declaration = '\n  <xacro:arg name="camera_mass" default="0.01"/>'
    edited = text.replace('name="fishbot">', 'name="fishbot">' + declaration, 1).replace(
        '<xacro:property name="camera_mass" value="0.01"/>',
        '<xacro:property name="camera_mass" value="$(arg camera_mass)"/>',
    )
    workspace = Workspace({"fishbot_description": package})
    workspace.open(top, edited)
    workspace, result = checked(package, workspace)
    assert result.ok
    index = Index.of(workspace, result)
    use = place(edited, "$(arg camera_mass)", len("$(arg "))
    assert index.definition(top, *use) == [
        span_of(top, edited, '<xacro:arg name="camera_mass"', "camera_mass")
    ]
    assert "`0.01`" in (index.hover(top, *use) or "")
    completions = index.completion(top, *place(edited, "$(arg camera_mass)", len("$(arg ")))
    assert [c.label for c in completions] == ["camera_mass"]


def test_an_include_goes_to_the_file_found_through_its_package(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top = urdf(package, "fishbot.urdf.xacro")
    found = index.definition(*at(top, "$(find fishbot_description)/urdf/fishbot/common_inertia"))
    assert found == [Span(urdf(package, "common_inertia.xacro"), 1, 1, 1, 1)]


def test_renaming_a_link_rewrites_every_file_and_the_robot_stays_clean(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    caster = urdf(package, "actuator/caster.urdf.xacro")
    assert index.prepare_rename(*at(caster, '"base_link"', 1)) == span_of(
        caster, Path(caster).read_text(), '"base_link"', "base_link"
    )
    edits = index.rename(*at(caster, '"base_link"', 1), "chassis_link")
    assert len(edits) > 1  # across files
    for path, changes in edits.items():
        text = Path(path).read_text()
        lines = text.splitlines(keepends=True)
        for span, new in sorted(changes, key=lambda c: (c[0].line, c[0].column), reverse=True):
            line = lines[span.line - 1]
            assert line[span.column - 1 : span.end_column - 1] == "base_link"
            lines[span.line - 1] = line[: span.column - 1] + new + line[span.end_column - 1 :]
        workspace.open(path, "".join(lines))
    again = check_file(urdf(package, "fishbot.urdf.xacro"), workspace=workspace)
    assert again.robot is not None and again.ok
    assert [d.rule for d in again.diagnostics] == [d.rule for d in result.diagnostics]
    names = {link.name for link in again.robot.links}
    assert "chassis_link" in names and "base_link" not in names
    for path in again.files:
        text = workspace.read(path).decode()
        assert not re.search(r"[\">]base_link[\"<]", text)


def test_a_name_built_by_an_expression_cannot_be_renamed(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    caster = urdf(package, "actuator/caster.urdf.xacro")
    where = at(caster, '<link name="${name}_caster_link">', len('<link name="${name}_c'))
    assert {written(s) for s in index.definition(*where)} == {"${name}_caster_link"}
    assert index.prepare_rename(*where) is None
    with pytest.raises(ArgumentError, match="builds several names") as raised:
        index.rename(*where, "x")
    assert index.rename_refusal(*where) == str(raised.value)
    assert index.rename_refusal(*at(caster, '"base_link"', 1)) is None  # it can be
    assert index.rename_refusal(caster, 1, 1) is None  # nothing is named there
    with pytest.raises(ArgumentError, match="cannot name a link"):
        index.rename(*at(caster, '"base_link"', 1), "two words")


def test_renaming_a_macro_and_a_property(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top, caster = urdf(package, "fishbot.urdf.xacro"), urdf(package, "actuator/caster.urdf.xacro")
    edits = index.rename(*at(top, "<xacro:caster_xacro", 8), "ball_xacro")
    assert set(edits) == {top, caster}
    assert len(edits[top]) == Path(top).read_text().count("<xacro:caster_xacro")
    edits = index.rename(*at(top, "${caster_radius}", 3), "ball_radius")
    assert len(edits[top]) == 1 + Path(top).read_text().count("${caster_radius}")
    with pytest.raises(ArgumentError, match="already defined"):
        index.rename(*at(top, "${caster_radius}", 3), "caster_mass")


def test_completion(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    assert result.robot is not None
    caster, top = urdf(package, "actuator/caster.urdf.xacro"), urdf(package, "fishbot.urdf.xacro")
    links = index.completion(*at(caster, '<parent link="base_link"/>', len('<parent link="')))
    assert {c.label for c in links} == {link.name for link in result.robot.links}
    macros = index.completion(*at(top, "<xacro:wheel_xacro", len("<xacro:")))
    defined = set(
        re.findall(r'<xacro:macro name="(\w+)"', "".join(Path(f).read_text() for f in result.files))
    )
    assert defined <= {c.label for c in macros}
    properties = index.completion(*at(top, "${wheel_radius}", 2))
    assert set(re.findall(r'<xacro:property name="(\w+)"', Path(top).read_text())) <= {
        c.label for c in properties
    }
    # a call's parameters, those not given yet
    text = Path(top).read_text()
    line, column = place(text, '<xacro:imu_xacro xyz="0.0 0.0 0.02" ', 36)
    workspace.open(top, text)
    params = index.completion(top, line, column)
    imu = Path(urdf(package, "sensor/imu.urdf.xacro")).read_text()
    declared = re.search(r'<xacro:macro name="imu_xacro" params="([^"]*)"', imu)
    assert declared is not None
    names = {p.partition(":=")[0] for p in declared[1].split()}
    call = re.search(r"<xacro:imu_xacro [^>]*>", text)
    assert call is not None
    assert {c.label for c in params} == names - set(re.findall(r"(\w+)=", call[0]))
    # URDF's elements by context, and rule ids in a suppression comment
    base = urdf(package, "base.urdf.xacro")
    edited = (
        Path(base)
        .read_text()
        .replace("<visual>", "<visual><!-- fishbot: ignore[ -->\n<", 1)
        .replace(' length="${length}"/>', "/>", 1)
    )
    workspace.open(base, edited)
    with pytest.raises(FishbotUrdfError):  # no longer XML: the robot cannot be read
        check_file(top, workspace=workspace)
    index = Index.of_file(workspace, base)
    rules = index.completion(base, *place(edited, "ignore[", len("ignore[")))
    assert {c.label for c in rules} == set(ids())
    elements = index.completion(base, *place(edited, "ignore[ -->\n<", 13))
    assert {c.label for c in elements} == {"origin", "geometry", "material"}
    attributes = index.completion(base, *place(edited, "<cylinder radius", len("<cylinder ")))
    assert {c.label for c in attributes} == {"length"}  # radius is written already
    kinds = index.completion(base, *place(edited, 'type="fixed"', len('type="')))
    assert {c.label for c in kinds} == {t.value for t in JointType}


def test_hover(package: Path) -> None:
    workspace, result = checked(package)
    index = Index.of(workspace, result)
    top, base = urdf(package, "fishbot.urdf.xacro"), urdf(package, "base.urdf.xacro")
    text = Path(top).read_text()
    values = dict(re.findall(r'<xacro:property name="(\w+)" value="([^"]*)"/>', text))
    shown = index.hover(*at(top, "${wheel_radius}", 3)) or ""
    assert f"\n{values['wheel_radius']}\n" in shown and "fishbot.urdf.xacro:" in shown
    macro = index.hover(*at(top, "<xacro:base_xacro", 8)) or ""
    assert "`sink` = `0.001`" in macro and "`length`" in macro
    link = index.hover(*at(base, '<link name="base_link">', 13)) or ""
    assert f"mass: {float(values['base_mass']):.6g} kg" in link
    # base_link stands base_length / 2 + wheel_radius - ground_sink over base_footprint
    z = (
        float(values["base_length"]) / 2
        + float(values["wheel_radius"])
        - float(values["ground_sink"])
    )
    assert f"pose in `base_footprint` at zero: xyz 0 0 {z:.6g}" in link
    material = index.hover(*at(base, '<material name="blue">', 17)) or ""
    colour = re.search(r'<material name="blue">\s*<color rgba="([^"]*)"', Path(base).read_text())
    assert colour is not None and f"color `{colour[1]}`" in material
    joint = index.hover(*at(base, '<joint name="base_joint"', 13)) or ""
    assert "(fixed)" in joint and "parent `base_footprint` → child `base_link`" in joint


def test_symbols_of_a_file(package: Path) -> None:
    base = urdf(package, "base.urdf.xacro")
    found = symbols(Workspace(), base)
    text = Path(base).read_text()
    assert [(s.name, s.kind) for s in found] == [("base_xacro", "macro")]
    macro = found[0]
    assert macro.selection == span_of(base, text, '<xacro:macro name="base_xacro"', "base_xacro")
    inside = [(s.name, s.kind) for s in macro.children]
    expected = [(m[2], m[1]) for m in re.finditer(r'<(link|joint) name="(\w+)"', text)]
    assert inside == expected
    link = next(s for s in macro.children if s.name == "base_link")
    assert [(s.name, s.kind) for s in link.children] == [("blue", "material")]
    top = symbols(Workspace({"fishbot_description": package}), urdf(package, "fishbot.urdf.xacro"))
    robot = top[0]
    assert robot.kind == "robot" and robot.name == "fishbot"
    kinds = [s.kind for s in robot.children]
    text = Path(urdf(package, "fishbot.urdf.xacro")).read_text()
    assert kinds.count("include") == text.count("<xacro:include ")
    assert kinds.count("property") == text.count("<xacro:property ")


def test_an_unsaved_link_is_found(package: Path) -> None:
    top = urdf(package, "fishbot.urdf.xacro")
    added = (
        '  <link name="tray_link"/>\n'
        '  <joint name="tray_joint" type="fixed">\n'
        '    <parent link="base_link"/>\n    <child link="tray_link"/>\n  </joint>\n'
    )
    edited = Path(top).read_text().replace("</robot>", added + "</robot>")
    workspace = Workspace({"fishbot_description": package})
    workspace.open(top, edited)
    workspace, result = checked(package, workspace)
    index = Index.of(workspace, result)
    found = index.definition(top, *place(edited, '<child link="tray_link"', 15))
    assert found == [span_of(top, edited, '<link name="tray_link"/>', "tray_link")]
    offered = index.completion(top, *place(edited, '<child link="', 13))
    assert "tray_link" in {c.label for c in offered}


def test_an_index_is_kept_until_a_file_changes(package: Path) -> None:
    workspace, result = checked(package)
    assert Index.of(workspace, result) is Index.of(workspace, result)
    base = urdf(package, "base.urdf.xacro")
    workspace.open(base, Path(base).read_text() + "\n")
    again = check_file(urdf(package, "fishbot.urdf.xacro"), workspace=workspace)
    assert Index.of(workspace, again) is not Index.of(workspace, result)


def test_a_file_in_the_middle_of_an_edit_answers_what_it_can(package: Path) -> None:
    base = urdf(package, "base.urdf.xacro")
    text = Path(base).read_text()
    workspace = Workspace({"fishbot_description": package})
    cuts = range(0, len(text), 7)
    for cut in cuts:
        broken = text[:cut]
        workspace.open(base, broken)
        lone = Index.of_file(workspace, base)
        symbols(workspace, base)
        for needle in ("base_link", "${radius}", "<xacro:cylinder_inertia", "sink:="):
            if needle in broken:
                where = (base, *place(broken, needle, 2))
                lone.definition(*where)
                lone.references(*where)
                lone.completion(*where)
                lone.hover(*where)
                lone.prepare_rename(*where)
                with contextlib.suppress(ArgumentError):
                    lone.rename(*where, "renamed")
        lone.completion(base, *place(broken + "\n", "\n", 0, broken.count("\n")))
    # the whole robot, its body file cut in the middle of a tag
    workspace.open(base, text[: text.index('<child link="base_link"/>') + 10])
    try:
        result = check_file(urdf(package, "fishbot.urdf.xacro"), workspace=workspace)
    except FishbotUrdfError:
        return
    index = Index.of(workspace, result)
    index.completion(base, *place(text, '<child link="base_link"/>', 10))
    index.definition(base, 1, 1)


def test_a_lone_file_defines_what_it_writes(package: Path) -> None:
    caster = urdf(package, "actuator/caster.urdf.xacro")
    index = Index.of_file(Workspace(), caster)
    text = Path(caster).read_text()
    found = index.definition(*at(caster, 'radius="${radius}"', len('radius="${')))
    assert found == [span_of(caster, text, "name xyz radius mass", "radius")]
    assert index.definition(*at(caster, '"base_link"', 1)) == []  # defined in another file


def test_a_urdf_file_names_its_joints_in_transmissions_and_ros2_control(tmp_path: Path) -> None:
    source = Path(__file__).parent / "data" / "valid" / "all_elements.urdf"
    path = str(tmp_path / "all_elements.urdf")
    shutil.copy(source, path)
    workspace = Workspace()
    result = check_file(path, workspace=workspace)
    index = Index.of(workspace, result)
    text = Path(path).read_text()
    joint = '<joint name="shoulder" type='
    found = index.references(*at(path, joint, len('<joint name="')))
    assert span_of(path, text, '<joint name="shoulder">', "shoulder", 0) in found
    assert span_of(path, text, '<joint name="shoulder">', "shoulder", 1) in found
    assert len(found) == text.count('"shoulder"')
    edits = index.rename(*at(path, joint, len('<joint name="')), "elbow")
    lines = text.splitlines(keepends=True)
    for span, new in sorted(edits[path], key=lambda c: (c[0].line, c[0].column), reverse=True):
        line = lines[span.line - 1]
        lines[span.line - 1] = line[: span.column - 1] + new + line[span.end_column - 1 :]
    workspace.open(path, "".join(lines))
    again = check_file(path, workspace=workspace)
    assert [d.rule for d in again.diagnostics] == [d.rule for d in result.diagnostics]
    assert '"shoulder"' not in workspace.read(path).decode()


def test_columns_count_characters(tmp_path: Path) -> None:
    path = str(tmp_path / "wide.urdf")
    text = (
        '<robot name="r"><!-- größe --><link name="bäse"/><link name="arm"/>\n'
        '<joint name="j" type="fixed"><!-- ü --><parent link="bäse"/><child link="arm"/></joint>\n'
        "</robot>\n"
    )
    Path(path).write_text(text, encoding="utf-8")
    workspace = Workspace()
    index = Index.of(workspace, check_file(path, workspace=workspace))
    first, second = text.splitlines()[:2]
    use = second.index('"bäse"') + 2  # a string index, plus one
    assert index.definition(path, 2, use + 1) == [
        Span(path, 1, first.index('"bäse"') + 2, 1, first.index('"bäse"') + 6)
    ]


def test_a_link_handed_to_a_macro_is_renamed_at_the_call(tmp_path: Path) -> None:
    path = str(tmp_path / "arm.urdf.xacro")
    text = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:macro name="arm" params="parent">\n'
        '    <link name="arm_link"/>\n'
        '    <joint name="arm_joint" type="fixed">\n'
        '      <parent link="${parent}"/><child link="arm_link"/>\n'
        "    </joint>\n"
        "  </xacro:macro>\n"
        '  <link name="base"/>\n'
        '  <xacro:arm parent="base"/>\n'
        "</robot>\n"
    )
    Path(path).write_text(text)
    workspace = Workspace()
    result = check_file(path, workspace=workspace)
    index = Index.of(workspace, result)
    definition = at(path, '<link name="base"/>', len('<link name="'))
    found = index.references(*definition)
    assert span_of(path, text, '<xacro:arm parent="base"', "base") in found
    assert span_of(path, text, '<parent link="${parent}"', "${parent}") in found
    edits = index.rename(*definition, "torso")
    assert sorted(written(span) for span, _ in edits[path]) == ["base", "base"]
    lines = text.splitlines(keepends=True)
    for span, new in sorted(edits[path], key=lambda c: (c[0].line, c[0].column), reverse=True):
        line = lines[span.line - 1]
        lines[span.line - 1] = line[: span.column - 1] + new + line[span.end_column - 1 :]
    workspace.open(path, "".join(lines))
    again = check_file(path, workspace=workspace)
    assert again.robot is not None and again.ok
    assert {joint.parent for joint in again.robot.joints} == {"torso"}


def test_a_property_made_of_arithmetic_shows_its_value_and_nothing_runs(tmp_path: Path) -> None:
    path = str(tmp_path / "values.urdf.xacro")
    text = (
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="a" value="0.5"/>\n'
        '  <xacro:property name="b" value="${a * 2 + 1}"/>\n'
        '  <xacro:property name="c" value="${-b / 4} ${b ** 2}"/>\n'
        '  <xacro:property name="d" value="${__import__(\'os\').getcwd()}"/>\n'
        '  <xacro:property name="e" value="${e + 1}"/>\n'
        '  <link name="l"/>\n'
        "</robot>\n"
    )
    Path(path).write_text(text)
    index = Index.of_file(Workspace(), path)
    b = index.hover(*at(path, 'name="b"', len('name="'))) or ""
    assert f"= `{0.5 * 2 + 1}`" in b
    c = index.hover(*at(path, 'name="c"', len('name="'))) or ""
    assert f"= `{-(0.5 * 2 + 1) / 4} {(0.5 * 2 + 1) ** 2}`" in c
    for name in "de":  # a call, a property defined by itself: shown as written only
        shown = index.hover(*at(path, f'name="{name}"', len('name="'))) or ""
        assert "${" in shown and "= `" not in shown
