"""`fishbot_urdf.diagnostics`: a finding's line is one line, safe to print."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA
from test_bad_input import CASES

from fishbot_urdf import Config, check_file
from fishbot_urdf.catalog import get
from fishbot_urdf.catalog.physics import CollisionFacts
from fishbot_urdf.cli import cli
from fishbot_urdf.cli._hints import command_hint
from fishbot_urdf.diagnostics import (
    Diagnostic,
    Severity,
    diagnostic,
    escape_controls,
    from_error,
    without_consequences,
)
from fishbot_urdf.errors import FishbotUrdfError


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("plain base_link", "plain base_link"),
        ("a\nb", "a\\nb"),
        ("a\r\nb\tc", "a\\r\\nb\\tc"),
        ("\x1b[31mred\x1b[0m", "\\x1b[31mred\\x1b[0m"),
        ("\x00\x07\x7f", "\\x00\\x07\\x7f"),
        ("\x85\x9b", "\\x85\\x9b"),  # C1: NEL, CSI
        ("\u2028\u2029", "\\u2028\\u2029"),
        ("no-utf8-\udc9b-\udce9", "no-utf8-\\x9b-\udce9"),  # a C1 byte of a file name
        ("back\\nslash", "back\\nslash"),  # not a control character: left alone
        ("é ü 日本", "é ü 日本"),
    ],
)
def test_escape_controls(text: str, shown: str) -> None:
    assert escape_controls(text) == shown


def test_a_finding_is_one_line_whatever_its_path_and_message() -> None:
    finding = diagnostic(
        "io",
        Severity.ERROR,
        "no such file\n::error file=x::pwned",
        path="a\n::error file=x::pwned.urdf",
        line=3,
        column=1,
        hint="look \x1b]0;title\x07 here",
    )
    assert finding.format() == (
        "a\\n::error file=x::pwned.urdf:3:1: error: no such file\\n::error file=x::pwned "
        "(look \\x1b]0;title\\x07 here) [io]"
    )
    assert finding.format_with("a\rb") == (
        "a\\n::error file=x::pwned.urdf:3:1: error: no such file\\n::error file=x::pwned "
        "(a\\rb) [io]"
    )
    assert finding.message.count("\n") == 1  # the finding itself keeps its text


def _checked(text: str, config: Config | None = None) -> list[Diagnostic]:
    return list(check_file(text.encode(), path="r.urdf", config=config).diagnostics)


_MISMATCH = """<robot name="r">
  <link name="base"/>
  <link name="wheel">
    <inertial><mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><origin xyz="0 0 0.1" rpy="0 0 0"/>
      <geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="wheel"/>
    <axis xyz="0 1 0"/></joint>
</robot>"""


def test_every_finding_of_a_check_carries_its_catalogued_rule() -> None:
    findings = _checked(_MISMATCH.replace('link="base"/><child', 'link="bse"/><child'))
    assert {d.rule for d in findings} >= {"undefined-link", "inertia-mismatch"}
    for finding in findings:
        assert finding.definition is get(finding.rule)


def test_facts_are_typed_and_read_as_the_mapping_they_were() -> None:
    (mismatch,) = [d for d in _checked(_MISMATCH) if d.rule == "inertia-mismatch"]
    facts = mismatch.data
    assert isinstance(facts, CollisionFacts)
    # the cylinder written in the file, independent of any computation
    assert (facts.shape, facts.radius, facts.length, facts.mass) == ("cylinder", 0.05, 0.02, 2)
    assert facts.xyz == (0, 0, 0.1) and facts.size is None
    # the mapping view: the fields that are set, JSON-ready as lists
    assert facts["radius"] == 0.05 and "size" not in facts
    assert set(facts) == {"shape", "mass", "xyz", "rpy", "radius", "length"}
    as_json = json.loads(json.dumps(mismatch.to_dict()))
    assert as_json["data"]["xyz"] == [0, 0, 0.1]
    with pytest.raises(KeyError):
        facts["size"]


def test_the_cli_hint_is_chosen_by_the_findings_rule_not_its_id_text() -> None:
    (mismatch,) = [d for d in _checked(_MISMATCH) if d.rule == "inertia-mismatch"]
    hint = command_hint(mismatch)
    assert hint is not None
    assert "`fishbot inertia cylinder --mass 2 --radius 0.05 --length 0.02 --xyz 0 0 0.1`" in hint
    # the same words made elsewhere, without the rule, are not taken for it
    stranger = diagnostic(
        "inertia-mismatch", Severity.WARNING, mismatch.message, data=dict(mismatch.data)
    )
    assert command_hint(stranger) is None


def test_a_consequence_says_what_it_follows_from_and_goes_with_its_cause() -> None:
    text = _MISMATCH.replace('link="base"/><child', 'link="bse"/><child')
    assert "multiple-roots" not in {d.rule for d in _checked(text)}
    quiet = _checked(text, Config(ignore=("undefined-link",)))
    (roots,) = [d for d in quiet if d.rule == "multiple-roots"]
    assert roots.follows == ("undefined-link",)
    assert roots.to_dict()["data"]["follows"] == ["undefined-link"]
    cause = diagnostic("undefined-link", Severity.ERROR, "joint 'j': ...", path="r.urdf")
    assert without_consequences([cause, roots]) == [cause]


def _reported(source: Path | bytes, path: str | None = None) -> tuple[Diagnostic, ...]:
    """What `fishbot check` reports: the findings, or the one finding of the error that
    stopped the file from being read."""
    try:
        return check_file(source, path=path).diagnostics
    except FishbotUrdfError as exc:
        return (from_error(exc),)


def test_every_finding_and_every_error_that_stops_a_file_carries_its_documented_rule(
    tmp_path: Path,
) -> None:
    files = sorted(p for p in DATA.rglob("*") if p.suffix in (".urdf", ".xacro"))
    reported = [d for path in files for d in _reported(path)]
    reported += [d for name, (data, _) in CASES.items() for d in _reported(data, f"{name}.urdf")]
    # a file that is not there, and one whose xacro names a package that is not found
    reported += _reported(tmp_path / "gone.urdf")
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find no_such_package)/x.xacro"/></robot>',
        encoding="utf-8",
    )
    reported += _reported(tmp_path / "r.urdf.xacro")
    seen = {d.rule for d in reported}
    # errors that stop a file among them, of each kind
    assert {"io", "xml-syntax", "package-not-found", "xacro-include", "xacro-error"} <= seen
    for finding in reported:
        assert finding.definition is not None, finding
        assert finding.definition.id == finding.rule
        assert finding.definition is get(finding.rule)
    for rule in sorted(seen):
        shown = CliRunner().invoke(cli, ["rules", rule])
        assert shown.exit_code == 0, shown.output
        assert shown.stdout.startswith(rule), shown.stdout[:80]
