"""`fishbot_urdf.suppress`: ``<!-- fishbot: ignore[...] -->`` comments in URDF and xacro
files, the findings they silence, and the ones that silence nothing."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA, run_check_urdf

from fishbot_urdf import Config
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Kind, Severity, Subject, diagnostic
from fishbot_urdf.lint import check_file
from fishbot_urdf.model import Location
from fishbot_urdf.suppress import Suppression, apply_suppressions, suppressions

HERE = DATA / "suppress"
REMOVE = "(remove it, or move it right before the element the finding is about)"
MOVE = "(move it right before the element the finding is about)"


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["check", *args])
    return result.exit_code, result.stdout, result.stderr


def silenced(*args: str) -> dict[str, object]:
    """The JSON report's count of silenced findings, for one file."""
    _, out, _ = run("--format", "json", *args)
    suppressed: dict[str, object] = json.loads(out)["files"][0]["suppressed"]
    return suppressed


def without_comments(source: Path, target: Path) -> Path:
    """A copy of ``source`` whose suppressions are plain comments of the same length
    (every finding keeps its line and column)."""
    text = source.read_text(encoding="utf-8").replace("fishbot: ignore[", "fishbot: ignora[")
    target.write_text(text, encoding="utf-8")
    return target


@pytest.fixture
def here(monkeypatch: pytest.MonkeyPatch) -> Path:
    """Run from the fixtures' folder: findings name the files as a user there would."""
    monkeypatch.chdir(HERE)
    return HERE


def test_a_massless_dummy_link_is_silenced(here: Path, tmp_path: Path) -> None:
    robot = here / "fishbot_laser_head.urdf"
    # The tree is check_urdf's, and nothing else is said.
    assert run(robot.name) == (0, run_check_urdf(robot).stdout.decode(), "")
    assert silenced(robot.name) == {"count": 1, "rules": {"massless-link": 1}}
    bare = without_comments(robot, tmp_path / robot.name)
    # For Gazebo, which a massless moving link harms (for the ROS tools, a warning).
    assert run("-q", "--target", "gazebo", str(bare)) == (
        1,
        "",
        f"{bare}:144:5: error: link 'laser_head_link' moves (joint 'laser_head_joint' is "
        "continuous) but its mass is 0 kg (a moving body needs a mass (MuJoCo: above 1e-15); "
        "give its real mass) [massless-link]\n",
    )
    assert silenced(str(bare)) == {"count": 0, "rules": {}}


def test_a_comment_in_a_macro_body_silences_every_call(here: Path, tmp_path: Path) -> None:
    assert run("-q", "xacro/robot.urdf.xacro") == (0, "", "")
    assert silenced("xacro/robot.urdf.xacro") == {
        "count": 3,
        "rules": {"inertia-mismatch": 2, "xacro-warning": 1},
    }
    for name in ("robot.urdf.xacro", "wheel.xacro"):
        without_comments(here / "xacro" / name, tmp_path / name)
    mismatch = (
        "{f}:15:7: warning: link '{side}_wheel_link': inertial matches a cylinder r=0.032 h=0, "
        "but the collision cylinder has h=0.04 (fix the one that is wrong; `fishbot inertia "
        "cylinder --mass 0.1 --radius 0.032 --length 0.04 --rpy 1.5708 0 0` prints the "
        "inertial of the collision) [inertia-mismatch]\n"
    )
    wheel = tmp_path / "wheel.xacro"
    assert run("-q", str(tmp_path / "robot.urdf.xacro")) == (
        0,
        "",
        f"{tmp_path}/robot.urdf.xacro: warning: redefining global symbol: pi [xacro-warning]\n"
        + mismatch.format(f=wheel, side="left")
        + mismatch.format(f=wheel, side="right"),
    )


def test_a_comment_before_a_macro_call_does_not_reach_into_the_macro(
    here: Path, tmp_path: Path
) -> None:
    shutil.copy(here / "xacro" / "wheel.xacro", tmp_path)
    without_comments(here / "xacro" / "wheel.xacro", tmp_path / "wheel.xacro")
    text = (here / "xacro" / "robot.urdf.xacro").read_text()
    call = '  <xacro:wheel side="left"'
    (tmp_path / "robot.urdf.xacro").write_text(
        text.replace(call, "  <!-- fishbot: ignore[inertia-mismatch] -->\n" + call)
    )
    status, _, err = run("-q", str(tmp_path / "robot.urdf.xacro"))
    assert status == 0
    assert err.count("[inertia-mismatch]\n") == 2
    assert (
        f"{tmp_path}/robot.urdf.xacro:27:3: warning: fishbot: ignore[inertia-mismatch] "
        f"silences nothing for the element after it {REMOVE} [unused-suppression]\n"
    ) in err


def test_a_comment_before_the_root_silences_the_whole_file(here: Path, tmp_path: Path) -> None:
    assert run("-q", "whole_file.urdf") == (0, "", "")
    assert silenced("whole_file.urdf") == {"count": 2, "rules": {"collision-material": 2}}
    bare = without_comments(here / "whole_file.urdf", tmp_path / "whole_file.urdf")
    material = (
        "warning: link '{}': <material> inside <collision> is ignored (colours belong in "
        "<visual>; move the <material> there) [collision-material]\n"
    )
    assert run("-q", str(bare)) == (
        0,
        "",
        f"{bare}:9:7: " + material.format("palm") + f"{bare}:19:7: " + material.format("finger"),
    )


def test_suppressions_that_silence_nothing_are_reported(here: Path) -> None:
    lines = [
        "unused.urdf:2:1: warning: fishbot: ignore[below-ground] silences nothing in this file "
        f"{REMOVE} [unused-suppression]",
        "unused.urdf:5:3: warning: fishbot: ignore[masless-link] names no rule (did you mean "
        "'massless-link'? `fishbot rules` lists them) [unused-suppression]",
        "unused.urdf:12:3: warning: fishbot: ignore[limit-range] silences nothing for the "
        f"element after it {REMOVE} [unused-suppression]",
        "unused.urdf:19:3: warning: fishbot: ignore[] names no rule (name the rules to "
        "silence: fishbot: ignore[rule-id, ...]) [unused-suppression]",
        "unused.urdf:25:5: warning: fishbot: ignore[limit-range] stands before no element "
        f"{MOVE} [unused-suppression]",
        "unused.urdf:27:3: warning: fishbot: ignore[physics] names no rule ('physics' is a "
        "family: name its rules (`fishbot rules physics` lists them)) [unused-suppression]",
        "unused.urdf:32:5: warning: fishbot: ignore[xml-syntax] cannot silence xml-syntax (the "
        "file cannot be read past it: fix the fault) [unused-suppression]",
        "unused.urdf:35:3: warning: this comment is not a suppression fishbot understands "
        "(write <!-- fishbot: ignore[rule-id, ...] -->) [unused-suppression]",
        "unused.urdf:42:1: warning: fishbot: ignore[multiple-roots] stands before no element "
        f"{MOVE} [unused-suppression]",
    ]
    assert run("-q", "unused.urdf") == (0, "", "".join(line + "\n" for line in lines))
    # The tilt link's massless-link is silenced by the comment that names limit-range too.
    assert silenced("unused.urdf") == {"count": 1, "rules": {"massless-link": 1}}
    assert run("-q", "--strict", "unused.urdf")[0] == 1
    assert run("-q", "--ignore", "unused-suppression", "unused.urdf") == (0, "", "")
    # A comment naming a rule that is not selected is not said to silence nothing.
    only = run("-q", "--select", "structure,unused-suppression", "unused.urdf")[2]
    assert "below-ground] silences nothing" not in only
    assert "[limit-range] silences nothing" in only


def test_the_tokens_around_a_suppression(here: Path) -> None:
    # A DOCTYPE, a processing instruction and a comment holding "<link>", a start tag over
    # three lines with ">" and "/>" in its quoted values, a comment on the line of a
    # self-closing element, non-ASCII text before a comment on one line, and a
    # suppression inside CDATA (which is text, not a comment).
    assert run("-q", "tokens.urdf") == (
        0,
        "",
        "tokens.urdf:39:78: warning: link 'tool': <material> inside <collision> is ignored "
        "(colours belong in <visual>; move the <material> there) [collision-material]\n",
    )
    assert silenced("tokens.urdf") == {
        "count": 3,
        "rules": {"collision-material": 1, "limit-range": 1, "massless-link": 1},
    }
    lines = (here / "tokens.urdf").read_text(encoding="utf-8").splitlines()

    def column(line: int, text: str, end: bool = False) -> int:
        found = lines[line - 1].index(text)
        return found + 1 + (len(text) if end else 0)

    limit = '<limit lower="1" upper="-1" effort="1" velocity="1"/>'
    assert [
        (m.rules, tuple(m.at)[1:], m.start, m.end) for m in suppressions({"tokens.urdf": None})
    ] == [
        (("massless-link",), (12, 3), (13, 3), (21, 10)),
        (("limit-range",), (27, 5), (27, column(27, limit)), (27, column(27, limit, True))),
        (
            ("collision-material",),
            (29, column(29, "<!-- fishbot")),
            (29, column(29, "<collision>")),
            (29, column(29, "</collision>", True)),
        ),
    ]


def test_columns_count_characters_like_the_findings() -> None:
    text = (
        "<robot name='r'>\n"
        "  <link name='é☃'/><!-- fishbot: ignore[x] --><link name='ü'/>\n"
        "</robot>\n"
    )
    (mark,) = suppressions({"f.urdf": text.encode("utf-8")})
    line = text.splitlines()[1]
    start = line.index("<link name='ü'") + 1
    assert (mark.at.column, mark.start, mark.end) == (
        line.index("<!--") + 1,
        (2, start),
        (2, start + len("<link name='ü'/>")),
    )


def test_a_finding_without_a_column_is_covered_by_the_elements_lines() -> None:
    mark = Suppression(("limit-range",), Location("f.urdf", 3, 3), (4, 3), (6, 11))
    file = str(Path("f.urdf").resolve())

    def at(line: int | None, column: int | None = None) -> bool:
        found = diagnostic(
            "limit-range", Severity.ERROR, "x", path="f.urdf", line=line, column=column
        )
        return mark.covers(found, file)

    assert [at(3), at(4), at(6), at(7), at(None)] == [False, True, True, False, False]
    assert [at(4, 2), at(4, 3), at(6, 10), at(6, 11)] == [False, True, True, False]


def test_a_finding_without_a_line_only_by_a_whole_file_comment(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        "  <!-- fishbot: ignore[xacro-warning] -->\n"
        '  <xacro:property name="pi" value="3.14"/>\n'
        '  <link name="base_link"/>\n'
        "</robot>\n"
    )
    assert run("-q", str(robot)) == (
        0,
        "",
        f"{robot}: warning: redefining global symbol: pi [xacro-warning]\n"
        f"{robot}:2:3: warning: fishbot: ignore[xacro-warning] silences nothing for the "
        f"element after it {REMOVE} [unused-suppression]\n",
    )


def test_fatal_findings_are_never_silenced(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text('<!-- fishbot: ignore[xml-syntax] -->\n<robot name="r">\n<link>\n</robot>\n')
    status, _, err = run(str(robot))
    assert status == 1
    assert err.startswith(f"{robot}:4:") and err.endswith("[xml-syntax]\n")
    # A fatal finding among the others (as a reader might list one) is kept too.
    fatal = diagnostic("xml-syntax", Severity.ERROR, "x", path=str(robot), line=3, column=1)
    mark = Suppression(("xml-syntax",), Location(str(robot), 1, 1), None, None)
    assert apply_suppressions([fatal], [mark], Config()) == (
        [
            fatal,
            diagnostic(
                "unused-suppression",
                Severity.WARNING,
                "fishbot: ignore[xml-syntax] cannot silence xml-syntax",
                path=str(robot),
                line=1,
                column=1,
                hint="the file cannot be read past it: fix the fault",
                subject=Subject(Kind.COMMENT, "fishbot: ignore[xml-syntax]"),
            ),
        ],
        [],
    )


def test_the_narrowest_comment_is_the_one_used(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    robot.write_text(
        (HERE / "whole_file.urdf")
        .read_text()
        .replace(
            '  <link name="finger">',
            '  <!-- fishbot: ignore[collision-material] -->\n  <link name="finger">',
        )
    )
    # The whole-file comment still silences the palm's material: both are used.
    assert run("-q", str(robot)) == (0, "", "")
    robot.write_text(
        robot.read_text().replace(
            '<material name="aluminium"><color rgba="0.8 0.8 0.8 1"/></material>', ""
        )
    )
    assert run("-q", str(robot)) == (
        0,
        "",
        f"{robot}:4:1: warning: fishbot: ignore[collision-material] silences nothing in this "
        f"file {REMOVE} [unused-suppression]\n",
    )


def test_unused_suppression_findings_can_be_silenced_too(tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf"
    unused = (HERE / "unused.urdf").read_text()
    robot.write_text(
        unused.replace(
            '<?xml version="1.0"?>\n',
            '<?xml version="1.0"?>\n<!-- fishbot: ignore[unused-suppression] -->\n',
        )
    )
    assert run("-q", str(robot)) == (0, "", "")
    robot.write_text(
        '<!-- fishbot: ignore[unused-suppression] -->\n<robot name="r"><link name="a"/></robot>\n'
    )
    assert run("-q", str(robot)) == (
        0,
        "",
        f"{robot}:1:1: warning: fishbot: ignore[unused-suppression] silences nothing in this "
        f"file {REMOVE} [unused-suppression]\n",
    )


def test_a_yaml_file_a_xacro_file_loads_is_not_read_for_comments(tmp_path: Path) -> None:
    (tmp_path / "base.yaml").write_text(
        'name: base_link\nnote: "<!-- fishbot: ignore[limit-range] -->"\n'
    )
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="base" value="${xacro.load_yaml(\'base.yaml\')}"/>\n'
        '  <link name="${base.name}"/>\n'
        "</robot>\n"
    )
    result = check_file(robot)
    assert str(tmp_path / "base.yaml") in result.files
    assert (result.diagnostics, result.suppressed) == ((), ())


def test_comments_in_memory_and_on_standard_input() -> None:
    text = (HERE / "whole_file.urdf").read_bytes()
    from_bytes = check_file(text, path="<stdin>")
    assert (from_bytes.diagnostics, len(from_bytes.suppressed)) == ((), 2)
    assert {d.path for d in from_bytes.suppressed} == {"<stdin>"}
    result = CliRunner().invoke(cli, ["check", "-q", "-"], input=text)
    assert (result.exit_code, result.stdout, result.stderr) == (0, "", "")


def test_twenty_thousand_comments_each_silence_their_own_element() -> None:
    # Matched by (file, rule) and position: linear in comments plus findings (it took
    # comments x findings once: minutes for this file).
    count = 20_000
    links = "".join(
        f'  <!-- fishbot: ignore[massless-link] -->\n  <link name="l{i}"/>\n' for i in range(count)
    )
    data = f'<robot name="r">\n{links}</robot>\n'.encode()
    marks = suppressions({"big.urdf": data})
    assert len(marks) == count
    findings = [
        diagnostic("massless-link", Severity.WARNING, "x", path="big.urdf", line=line, column=3)
        for line in range(3, 2 * count + 2, 2)  # on each link's line
    ]
    outside = diagnostic("massless-link", Severity.WARNING, "x", path="big.urdf", line=1, column=1)
    other = diagnostic("inertia-mismatch", Severity.WARNING, "x", path="big.urdf", line=3, column=3)
    config = Config(ignore=("unused-suppression",))
    kept, silenced = apply_suppressions([*findings, outside, other], marks, config)
    assert (kept, silenced) == ([outside, other], findings)
    # Every comment is used once: with its lint on, none is reported.
    kept, silenced = apply_suppressions(findings, marks, Config())
    assert (kept, len(silenced)) == ([], count)
    # With one finding only, every other comment silences nothing.
    kept, silenced = apply_suppressions(findings[:1], marks, Config())
    assert (len(kept), silenced) == (count - 1, findings[:1])
    assert {d.rule for d in kept} == {"unused-suppression"}
    assert kept[0].line == 4  # the second comment


def test_a_finding_is_credited_to_the_narrowest_of_nested_comments() -> None:
    data = (
        b'<!-- fishbot: ignore[limit-range] -->\n<robot name="r">\n'
        b'<!-- fishbot: ignore[limit-range] -->\n<joint name="a">\n'
        b'<!-- fishbot: ignore[limit-range] -->\n<limit lower="1"/>\n'
        b"<axis/></joint>\n</robot>\n"
    )
    marks = suppressions({"f.urdf": data})
    assert [(m.at.line, m.start, m.end) for m in marks] == [
        (1, None, None),
        (3, (4, 1), (7, 16)),
        (5, (6, 1), (6, 19)),
    ]

    def credited(line: int, column: int | None) -> int | None:
        found = diagnostic("limit-range", Severity.ERROR, "x", path="f.urdf", line=line)
        if column is not None:
            found = diagnostic(
                "limit-range", Severity.ERROR, "x", path="f.urdf", line=line, column=column
            )
        kept, _ = apply_suppressions([found], marks, Config())
        unused = {d.line for d in kept if d.rule == "unused-suppression"}
        (used,) = {1, 3, 5} - unused
        return used

    assert [credited(6, 1), credited(7, 15), credited(7, 16), credited(2, 1)] == [5, 3, 1, 1]
    # A finding with no column: the narrowest element whose lines hold its line.
    assert [credited(6, None), credited(4, None), credited(8, None)] == [5, 3, 1]


def test_a_comment_naming_thousands_of_rules_costs_memory_linear_in_it() -> None:
    names = [f"rule-{i}" for i in range(16_000)]
    comment = ", ".join([*names, *names])  # each one twice: reported once
    data = f'<robot name="r"><!-- fishbot: ignore[{comment}] --><link name="a"/></robot>'
    (mark,) = suppressions({"many.urdf": data.encode()})
    assert mark.rules == tuple(names)
    result = check_file(data.encode(), path="many.urdf")
    unknown = [d for d in result.diagnostics if d.message.endswith("names no rule")]
    assert len(unknown) == len(names)
    # The comment is named by its first rules, not by all of them in every finding.
    shown = "fishbot: ignore[rule-0, rule-1, rule-2, rule-3, rule-4, rule-5, rule-6, rule-7, "
    assert {d.subject for d in unknown} == {Subject(Kind.COMMENT, f"{shown}... (16000 rules)]")}
    assert unknown[0].hint == "`fishbot rules` lists them"
