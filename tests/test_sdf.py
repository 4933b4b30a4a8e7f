"""`to_sdf` writes what sdformat 12's URDF converter writes: the golden files `ign sdf -p`
printed (tests/golden/sdf, made by tests/golden/regenerate_sdf.py), compared element for
element with numbers to 1e-9, and the real converter run live where it is installed."""

from __future__ import annotations

import hashlib
import json
import math
import random
import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import GOLDEN, ROOT, GoldenInput, golden_inputs, live_tool

import fishbot_urdf
from fishbot_urdf.cli import cli
from fishbot_urdf.errors import ConversionError, StructureError

SDF_GOLDEN = GOLDEN / "sdf"


def _golden_inputs() -> list[tuple[str, Path]]:
    """Each golden file's input, as tests/golden/regenerate_sdf.py names them."""
    import sys

    sys.path.insert(0, str(SDF_GOLDEN.parent))
    from regenerate_sdf import INPUTS

    return [(name, ROOT / path) for name, path in INPUTS.items()]


INPUTS = _golden_inputs()


def _urdf(path: Path) -> str:
    if path.suffix == ".xacro":
        return fishbot_urdf.expand(path).text
    return path.read_text(encoding="utf-8")


def _same_numbers(a: str, b: str) -> bool:
    """Texts equal, or numbers that are within 1e-9 of each other (relative; 1e-12 absolute,
    for a sum that comes out as 1e-17 in one program and 0 in the other)."""
    if a == b:
        return True
    left, right = a.split(), b.split()
    if len(left) != len(right):
        return False
    try:
        pairs = [(float(x), float(y)) for x, y in zip(left, right, strict=True)]
    except ValueError:
        return False
    return all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12) for x, y in pairs)


def differences(ours: ET.Element, theirs: ET.Element, where: str = "") -> list[str]:
    """Where two SDF trees differ: tags, attributes, texts (numbers to 1e-9), children in
    order."""
    here = f"{where}/{theirs.tag}" + (f"[{theirs.get('name')}]" if theirs.get("name") else "")
    found = []
    if ours.tag != theirs.tag or ours.attrib != theirs.attrib:
        return [f"{here}: <{ours.tag} {ours.attrib}> is not <{theirs.tag} {theirs.attrib}>"]
    if not _same_numbers((ours.text or "").strip(), (theirs.text or "").strip()):
        found.append(f"{here}: {ours.text!r} is not {theirs.text!r}")
    if len(ours) != len(theirs):
        mine, other = [c.tag for c in ours], [c.tag for c in theirs]
        return [*found, f"{here}: children {mine} are not {other}"]
    for a, b in zip(ours, theirs, strict=True):
        found += differences(a, b, here)
    return found


def _compared(ours: str, theirs: str) -> list[str]:
    """``differences`` of two SDF texts; where one is no XML (sdformat prints names such as
    ``ignition::corrected_offsets`` that XML namespaces do not allow), the bytes must agree."""
    try:
        return differences(ET.fromstring(ours), ET.fromstring(theirs))
    except ET.ParseError:
        return [] if ours == theirs else ["the texts differ, and one is no XML"]


def test_the_comparer_tells_numbers_apart() -> None:
    a = ET.fromstring("<pose>0 0 0.1 0 1.570796326794897 0</pose>")
    assert (
        differences(a, ET.fromstring("<pose>0 0 0.1000000000001 0 1.5707963267948966 0</pose>"))
        == []
    )
    assert differences(a, ET.fromstring("<pose>0 0 0.1001 0 1.570796326794897 0</pose>")) != []
    assert differences(ET.fromstring("<a><b/></a>"), ET.fromstring("<a><c/></a>")) != []


@pytest.mark.parametrize(("name", "path"), INPUTS, ids=[name for name, _ in INPUTS])
def test_to_sdf_is_the_golden_sdf(name: str, path: Path) -> None:
    ours = fishbot_urdf.to_sdf(fishbot_urdf.parse(_urdf(path), path=str(path)))
    golden = (SDF_GOLDEN / f"{name}.sdf").read_text(encoding="utf-8")
    assert _compared(ours, golden) == []
    assert ours == golden  # and, so far, byte for byte


@pytest.mark.parametrize(("name", "path"), INPUTS, ids=[name for name, _ in INPUTS])
def test_to_sdf_is_what_ign_sdf_prints(name: str, path: Path, tmp_path: Path) -> None:
    ign = live_tool("ign", "ignition-tools libsdformat-dev")
    if ign is None:
        pytest.skip("ign is not installed: the golden file stands alone")
    urdf = tmp_path / f"{name}.urdf"
    urdf.write_text(_urdf(path), encoding="utf-8")
    run = subprocess.run(
        [ign, "sdf", "-p", str(urdf)], capture_output=True, timeout=120, check=False
    )
    assert run.returncode == 0, run.stderr
    ours = fishbot_urdf.to_sdf(fishbot_urdf.load(urdf))
    assert _compared(ours, run.stdout.decode("utf-8")) == []


def test_the_golden_files_are_of_these_inputs() -> None:
    # a changed input needs `python tests/golden/regenerate_sdf.py`
    import json

    from regenerate_sdf import digest

    index = json.loads((SDF_GOLDEN / "index.json").read_text(encoding="utf-8"))
    for name, path in INPUTS:
        assert index["inputs"][name]["sha256"] == digest(_urdf(path)), name


def test_a_robot_without_mass_is_an_empty_model() -> None:
    robot = fishbot_urdf.load(ROOT / "robots/fishbot/urdf/first_robot.urdf")
    assert (
        fishbot_urdf.to_sdf(robot) == "<sdf version='1.9'>\n  <model name='first_robot'/>\n</sdf>\n"
    )


def test_a_gazebo_material_becomes_a_material_script() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
        'ixz="0" iyy="1" iyz="0" izz="1"/></inertial><visual><geometry><sphere radius="1"/>'
        '</geometry></visual></link><gazebo reference="a"><material>Gazebo/Red</material>'
        "</gazebo></robot>"
    )
    visual = ET.fromstring(fishbot_urdf.to_sdf(robot)).find("model/link/visual")
    assert visual is not None
    assert visual.findtext("material/script/name") == "Gazebo/Red"
    assert visual.findtext("material/script/uri") == (
        "file://media/materials/scripts/gazebo.material"
    )


def test_a_lumped_links_sensor_and_plugin_follow_it() -> None:
    robot = fishbot_urdf.load(ROOT / "tests/data/sdf/gazebo_sensor.urdf")
    sdf = fishbot_urdf.to_sdf(robot)
    # the imu 0.05 m along imu_link's x, which is the base's y (the joint turns it 90 degrees)
    assert "<pose>0.1 0.05 0.2 0 -0 1.5708</pose>" in sdf
    with_plugin = fishbot_urdf.parse(
        _urdf(ROOT / "tests/data/sdf/gazebo_sensor.urdf").replace(
            "</robot>",
            '<gazebo><plugin name="p" filename="libp.so"><bodyName>imu_link</bodyName>'
            "</plugin></gazebo></robot>",
        )
    )
    assert (
        "<bodyName>base</bodyName>\n      <xyzOffset>0.1 0 0.2</xyzOffset>\n"
        "      <rpyOffset>0 -0 1.5708</rpyOffset>"
    ) in fishbot_urdf.to_sdf(with_plugin)


def test_preserve_fixed_joint_keeps_a_fixed_joint() -> None:
    sdf = ET.fromstring(
        fishbot_urdf.to_sdf(fishbot_urdf.load(ROOT / "tests/data/sdf/gazebo_joint_lumping.urdf"))
    )
    types = {j.get("name"): j.get("type") for j in sdf.iter("joint")}
    assert types == {
        "kept_joint": "fixed",
        "held_joint": "revolute",
        "both_joint": "fixed",
        "arm_joint": "revolute",
    }
    held = sdf.find("model/joint[@name='held_joint']/axis/limit")
    assert held is not None and (held.findtext("lower"), held.findtext("upper")) == ("0", "0")


def test_an_empty_required_element_is_refused() -> None:
    # sdformat's reader: "Empty string used when setting a required parameter"
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
        'ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link><gazebo reference="a">'
        '<sensor name="s" type="ray"><ray><range><min/></range></ray></sensor></gazebo></robot>'
    )
    with pytest.raises(ConversionError, match="<min> is empty"):
        fishbot_urdf.to_sdf(robot)


@pytest.mark.parametrize(
    ("blob", "why"),
    [
        ("<kinematic>yes</kinematic>", "<kinematic> 'yes' is no bool"),
        ("<sensor name='s' type='imu'><pose>1 2 3</pose></sensor>", "'1 2 3' is not 6 numbers"),
        (
            "<collision><surface><friction><ode><mu>-1</mu></ode></friction></surface></collision>",
            "<mu> '-1' is less than 0.0, its least",
        ),
        (
            "<sensor name='c' type='camera'><camera><image><width>nan</width></image></camera>"
            "</sensor>",
            "<width> 'nan' is no number",
        ),
        (
            "<visual><material><diffuse>1 0 0 2</diffuse></material></visual>",
            "<diffuse> '1 0 0 2' is not a colour",
        ),
    ],
)
def test_a_value_sdformats_reader_refuses_is_refused(blob: str, why: str) -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1" ixy="0" '
        'ixz="0" iyy="1" iyz="0" izz="1"/></inertial><collision><geometry><sphere radius="1"/>'
        f'</geometry></collision><visual><geometry><sphere radius="1"/></geometry></visual>'
        f'</link><gazebo reference="a">{blob}</gazebo></robot>'
    )
    with pytest.raises(ConversionError, match=re.escape(why)):
        fishbot_urdf.to_sdf(robot)


def test_a_setting_that_is_no_number_is_refused() -> None:
    robot = fishbot_urdf.parse(
        '<robot name="r"><link name="a"/><gazebo reference="a"><mu1>${mu}</mu1></gazebo></robot>'
    )
    with pytest.raises(ConversionError, match="<mu1> is '\\$\\{mu\\}', not a number") as caught:
        fishbot_urdf.to_sdf(robot)
    assert (caught.value.target, caught.value.subject) == ("sdf", "a")


def test_a_robot_without_one_root_is_refused() -> None:
    robot = fishbot_urdf.parse('<robot name="r"><link name="a"/><link name="b"/></robot>')
    with pytest.raises(StructureError, match="one root link"):
        fishbot_urdf.to_sdf(robot)


@pytest.mark.parametrize(
    ("body", "why"),
    [
        ('<link name="a"/><link name="a"/>', "a link or joint name used twice"),
        (
            '<link name="a"/><link name="b"/><link name="c"/>'
            '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
            '<joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>'
            '<joint name="j3" type="fixed"><parent link="b"/><child link="c"/></joint>',
            "a link that is the child of several joints",
        ),
    ],
)
def test_a_tree_urdfdom_would_not_build_is_refused(body: str, why: str) -> None:
    robot = fishbot_urdf.parse(f'<robot name="r">{body}</robot>')
    with pytest.raises(StructureError, match=why):
        fishbot_urdf.to_sdf(robot)


def test_a_chain_deeper_than_python_recurses_converts() -> None:
    mass = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
    links = "".join(f'<link name="l{i}">{mass}</inertial></link>' for i in range(1200))
    joints = "".join(
        f'<joint name="j{i}" type="{"fixed" if i % 2 else "revolute"}"><parent link="l{i}"/>'
        f'<child link="l{i + 1}"/><limit effort="1" velocity="1"/></joint>'
        for i in range(1199)
    )
    sdf = fishbot_urdf.to_sdf(fishbot_urdf.parse(f'<robot name="r">{links}{joints}</robot>'))
    root = ET.fromstring(sdf)
    assert len(root.findall("model/link")) == 601  # l2, l4, ... l1198 lumped into their parents
    assert root.findall("model/joint")[-1].findtext("parent") == "l1197"  # j1198, moved up


def test_what_sdformat_refuses_is_refused() -> None:
    # a revolute joint without limits (urdfdom refuses it), and links lumped into one that
    # weigh 0 kg together (ODE divides by 0, and the SDF reader refuses the pose it gives)
    limitless = fishbot_urdf.parse(
        '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
        '<parent link="a"/><child link="b"/></joint></robot>'
    )
    with pytest.raises(ConversionError, match="joint 'j' is revolute and has no <limit>"):
        fishbot_urdf.to_sdf(limitless)
    inertial = (
        '<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
        "</inertial>"
    )
    massless = fishbot_urdf.parse(
        f'<robot name="r"><link name="a"/><link name="b">{inertial}</link>'
        '<link name="c"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" '
        'iyz="0" izz="1"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint></robot>'
    )
    with pytest.raises(ConversionError, match="link 'a': the links lumped into it") as caught:
        fishbot_urdf.to_sdf(massless)
    assert (caught.value.rule, caught.value.subject) == ("conversion", "a")


def _welded(rng: random.Random, count: int) -> fishbot_urdf.Robot:
    """A random tree of ``count`` links welded by turned fixed joints, inertials turned too
    (but the root's, whose frame the lumped inertia is written in)."""

    def numbers(low: float, high: float) -> str:
        return " ".join(str(rng.uniform(low, high)) for _ in range(3))

    links, joints = [], []
    for i in range(count):
        rpy = numbers(-1, 1) if i else "0 0 0"
        ix, iy, iz = (rng.uniform(0.1, 1) for _ in range(3))
        links.append(
            f'<link name="l{i}"><inertial><origin xyz="{numbers(-1, 1)}" rpy="{rpy}"/>'
            f'<mass value="{rng.uniform(0.1, 2)}"/><inertia ixx="{ix + iy}" ixy="0" ixz="0" '
            f'iyy="{iy + iz}" iyz="0" izz="{ix + iz}"/></inertial></link>'
        )
        if i:
            joints.append(
                f'<joint name="j{i}" type="fixed"><parent link="l{rng.randrange(i)}"/>'
                f'<child link="l{i}"/><origin xyz="{numbers(-1, 1)}" rpy="{numbers(-1, 1)}"/>'
                "</joint>"
            )
    return fishbot_urdf.parse(f'<robot name="r">{"".join(links)}{"".join(joints)}</robot>')


def test_lumping_gives_the_mass_properties_of_the_whole() -> None:
    # ODE's sums as the converter makes them equal the inertia module's whole-robot mass,
    # centre of mass and inertia about it, for trees welded at any angle
    rng = random.Random(20261127)
    for _ in range(20):
        robot = _welded(rng, rng.randrange(2, 7))
        whole = fishbot_urdf.mass_properties(robot)
        sdf = ET.fromstring(fishbot_urdf.to_sdf(robot))
        assert len(sdf.findall("model/link")) == 1
        inertial = sdf.find("model/link/inertial")
        assert inertial is not None
        pose = [float(v) for v in inertial.findtext("pose", "").split()]
        assert math.isclose(float(inertial.findtext("mass", "")), whole.mass, rel_tol=1e-12)
        for got, want in zip(pose[:3], whole.com, strict=True):
            assert math.isclose(got, want, rel_tol=1e-9, abs_tol=1e-12)
        for tag in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
            got = float(inertial.findtext(f"inertia/{tag}", ""))
            assert math.isclose(got, getattr(whole.inertia, tag), rel_tol=1e-9, abs_tol=1e-12)


@pytest.mark.parametrize(("name", "path"), INPUTS, ids=[name for name, _ in INPUTS])
def test_the_analysis_lumping_keeps_the_links_ign_sdf_keeps(name: str, path: Path) -> None:
    robot = fishbot_urdf.parse(_urdf(path), path=str(path))
    lumping = fishbot_urdf.analyse(robot).gazebo_lumping
    kept = {
        link
        for link, landing in lumping.landings.items()
        if landing.link == link and link not in lumping.lost() and link != "world"
    }
    golden = (SDF_GOLDEN / f"{name}.sdf").read_text(encoding="utf-8")
    # the model's links, by their place (a golden file may be no XML, see _compared)
    assert kept == set(re.findall(r"^    <link name='([^']*)'", golden, re.MULTILINE))


def test_the_subtree_below_a_massless_lumped_link_is_lost() -> None:
    # sdformat stops at mount (lumped, no mass) and never reaches arm, though arm has mass
    robot = fishbot_urdf.parse(
        """<robot name="r">
          <link name="base"><inertial><mass value="1"/>
            <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
          <link name="mount"/>
          <link name="arm"><inertial><mass value="1"/>
            <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
          <link name="tip"/>
          <joint name="m" type="fixed"><parent link="base"/><child link="mount"/></joint>
          <joint name="a" type="continuous"><parent link="mount"/><child link="arm"/></joint>
          <joint name="t" type="fixed"><parent link="arm"/><child link="tip"/></joint>
        </robot>"""
    )
    lumping = fishbot_urdf.analyse(robot).gazebo_lumping
    assert lumping.dropped == {"mount": ("arm", "tip")}
    assert lumping.landings["mount"].link == "base"
    assert "<link name='arm'>" not in fishbot_urdf.to_sdf(robot)


def _corpus() -> list[tuple[str, dict[str, object]]]:
    index = json.loads((SDF_GOLDEN / "index.json").read_text(encoding="utf-8"))
    return sorted(index["corpus"].items())


CORPUS = _corpus()


# Where `fishbot sdf` and `ign sdf -p` part on the check_urdf golden robots, by design:
# fishbot sdf stops on a robot whose tree or numbers are in doubt (the errors `check` prints
# and urdfdom passes over), which the converter converts as urdfdom reads it;
_STOPPED_HERE = {
    "data/broken/fixed_joint_axis_of_two.urdf",
    "data/broken/floating_joint_axis_not_numbers.urdf",
    "data/broken/visual_origin_of_two.urdf",
    "data/invalid/bad_color.urdf",
    "data/invalid/cycle.urdf",
    "data/invalid/cylinder_no_length.urdf",
    "data/invalid/missing_geometry.urdf",
    "data/invalid/multiple_parents.urdf",
    "data/invalid/undefined_mimic.urdf",
    "data/invalid/unknown_geometry.urdf",
    "data/invalid/zero_axis.urdf",
    "example-robot-data/alex_description/urdf/alex_psyonic_hands.urdf",
}
# sdformat reads the file with its own XML parser (tinyxml2) before urdfdom, and refuses
# these, which urdfdom, check_urdf and fishbot read (each with an xml-* finding);
_REFUSED_THERE = {
    "data/suppress/tokens.urdf",
    "data/xml/attribute_unquoted.urdf",
    "data/xml/declaration_after_comment.urdf",
    "data/xml/locations.urdf",
    "data/xml/markup.urdf",
}
# and in a name with an entity the file does not define, urdfdom (and so check_urdf and
# fishbot) drops the '&', where the converter's reader keeps it.
_NAMED_APART = {"data/xml/escape_ampersand.urdf", "data/xml/escape_doctype_entity.urdf"}


@pytest.mark.parametrize(("id", "entry"), CORPUS, ids=[id for id, _ in CORPUS])
def test_fishbot_sdf_is_what_ign_sdf_printed_for_every_golden_robot(
    id: str, entry: dict[str, object]
) -> None:
    # every robot of the check_urdf golden files: what ign sdf -p printed, or that it refused
    path = GoldenInput.from_id(id).path
    assert hashlib.sha256(path.read_bytes()).hexdigest() == entry["sha256"], (
        f"{id} changed: regenerate with python tests/golden/regenerate_sdf.py"
    )
    run = CliRunner().invoke(cli, ["sdf", str(path)])
    if "refused" in entry:
        assert (run.exit_code != 0) == (id not in _REFUSED_THERE), run.stdout
        return
    if id in _STOPPED_HERE:
        assert run.exit_code == 1 and ": error: " in run.stderr
        return
    golden = (SDF_GOLDEN / "corpus" / f"{id}.sdf").read_text(encoding="utf-8")
    assert run.exit_code == 0, run.stderr
    assert (run.stdout == golden) == (id not in _NAMED_APART)


def test_the_differences_are_of_golden_robots() -> None:
    ids = {id for id, _ in CORPUS}
    assert ids >= _STOPPED_HERE | _REFUSED_THERE | _NAMED_APART


def test_every_golden_robot_has_its_sdf_entry() -> None:
    assert {item.id for item in golden_inputs() if not item.is_xacro} == {id for id, _ in CORPUS}
