"""`fishbot_urdf.report`: SARIF 2.1.0 validated against the official schema, GitHub
workflow annotations with their escaping, and -o written whole and never over an input."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path
from typing import Any

import jsonschema
import pytest
from click.testing import CliRunner
from conftest import DATA, FISHBOT
from test_config import ARM

from fishbot_urdf import Config
from fishbot_urdf.catalog import all_rules
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity, diagnostic
from fishbot_urdf.lint import check_file
from fishbot_urdf.report import SARIF_SCHEMA, github_annotations

SCHEMA = json.loads((DATA / "schemas" / "sarif-schema-2.1.0.json").read_text())
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "note"}
# RFC 3986: the characters a URI reference may hold, and %XX escapes only.
URI = re.compile(r"^(?:[A-Za-z0-9\-._~:/?#\[\]@!$&'()*+,;=]|%[0-9A-F]{2})*$")


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["check", *args])
    return result.exit_code, result.stdout, result.stderr


def sarif(*args: str) -> dict[str, Any]:
    """The SARIF log of `fishbot check`, after checking it against the schema."""
    _, out, _ = run("--format", "sarif", *args)
    log: dict[str, Any] = json.loads(out)
    errors = sorted(jsonschema.Draft4Validator(SCHEMA).iter_errors(log), key=lambda e: list(e.path))
    assert not errors, [f"{list(e.path)}: {e.message}" for e in errors]
    for location in _artifacts(log):
        assert URI.match(location["uri"]), location
    return log


def _artifacts(log: dict[str, Any]) -> list[dict[str, Any]]:
    return [
        location["physicalLocation"]["artifactLocation"]
        for result in log["runs"][0]["results"]
        for location in result.get("locations", [])
    ]


def results(log: dict[str, Any]) -> list[tuple[str, str, str, int | None, int | None, bool]]:
    """Each result as (rule, level, uri, line, column, suppressed)."""
    found = []
    for result in log["runs"][0]["results"]:
        place = result["locations"][0]["physicalLocation"]
        region = place.get("region", {})
        found.append(
            (
                result["ruleId"],
                result["level"],
                place["artifactLocation"]["uri"],
                region.get("startLine"),
                region.get("startColumn"),
                "suppressions" in result,
            )
        )
    return found


@pytest.fixture
def arm(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm.urdf").write_text(ARM)
    return tmp_path


def test_sarif_of_a_clean_robot() -> None:
    log = sarif(str(FISHBOT / "urdf" / "first_robot.urdf"))
    assert log["$schema"] == SARIF_SCHEMA == SCHEMA["id"]
    assert log["version"] == "2.1.0"
    (run_,) = log["runs"]
    assert run_["results"] == []
    assert run_["tool"]["driver"]["name"] == "fishbot"
    assert run_["columnKind"] == "unicodeCodePoints"


def test_sarif_describes_every_rule() -> None:
    log = sarif(str(FISHBOT / "urdf" / "first_robot.urdf"))
    rules = log["runs"][0]["tool"]["driver"]["rules"]
    registry = all_rules()
    assert [r["id"] for r in rules] == [r.id for r in registry]
    for descriptor, rule in zip(rules, registry, strict=True):
        assert descriptor["defaultConfiguration"] == {"level": LEVELS[rule.severity]}
        assert descriptor["shortDescription"] == {"text": rule.summary}
        assert descriptor["properties"]["tags"] == [rule.family.value]
        assert rule.summary in descriptor["help"]["text"]
        assert f"`{rule.id}`" in descriptor["help"]["markdown"]
    by_id = {r["id"]: r for r in rules}
    assert by_id["massless-link"]["defaultConfiguration"] == {"level": "error"}
    assert by_id["inertia-mismatch"]["defaultConfiguration"] == {"level": "warning"}


def test_sarif_of_errors_and_warnings(arm: Path) -> None:
    log = sarif("arm.urdf")
    assert results(log) == [
        ("collision-material", "warning", "arm.urdf", 7, 7, False),
        ("massless-link", "error", "arm.urdf", 9, 5, False),
        ("limit-range", "error", "arm.urdf", 18, 5, False),
    ]
    # The same places as the findings, which name the line of the element.
    found = check_file(arm / "arm.urdf", path="arm.urdf").diagnostics
    assert [(d.line, d.column) for d in found] == [(7, 7), (9, 5), (18, 5)]
    assert [ARM.splitlines()[d.line - 1][d.column - 1 :][:6] for d in found if d.line] == [
        "<mater",
        "<inert",
        "<limit",
    ]
    (run_,) = log["runs"]
    rules = [r["id"] for r in run_["tool"]["driver"]["rules"]]
    for result in run_["results"]:
        assert rules[result["ruleIndex"]] == result["ruleId"]
        assert result["locations"][0]["physicalLocation"]["artifactLocation"] == {
            "uri": "arm.urdf",
            "uriBaseId": "%SRCROOT%",
        }
    assert run_["originalUriBaseIds"] == {"%SRCROOT%": {"uri": arm.resolve().as_uri() + "/"}}
    assert run_["results"][1]["message"]["text"] == (
        "link 'upper_arm' moves (joint 'shoulder' is revolute) but its mass is 0 kg (a moving "
        "body needs a mass (MuJoCo: above 1e-15); give its real mass)"
    )
    assert run_["results"][1]["properties"] == {"subject": {"kind": "link", "name": "upper_arm"}}


def test_sarif_with_configured_levels(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('ignore = ["urdf"]\n[severity]\nlimit-range = "note"\n')
    assert [r[:2] for r in results(sarif("arm.urdf"))] == [
        ("massless-link", "error"),
        ("limit-range", "note"),
    ]


def test_sarif_of_suppressed_findings(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(DATA / "suppress")
    assert results(sarif("tokens.urdf")) == [
        ("collision-material", "warning", "tokens.urdf", 39, 78, False),
        ("massless-link", "error", "tokens.urdf", 17, 5, True),
        ("limit-range", "error", "tokens.urdf", 27, 42, True),
        ("collision-material", "warning", "tokens.urdf", 29, 148, True),
    ]
    suppressed = [r for r in sarif("tokens.urdf")["runs"][0]["results"] if "suppressions" in r]
    assert {json.dumps(r["suppressions"]) for r in suppressed} == {'[{"kind": "inSource"}]'}


def test_sarif_of_a_xacro_robot(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    folder = tmp_path / "robot with spaces"
    shutil.copytree(DATA / "suppress" / "xacro", folder)
    monkeypatch.chdir(tmp_path)
    assert results(sarif("robot with spaces/robot.urdf.xacro")) == [
        ("xacro-warning", "warning", "robot%20with%20spaces/robot.urdf.xacro", None, None, True),
        ("inertia-mismatch", "warning", "robot%20with%20spaces/wheel.xacro", 15, 7, True),
        ("inertia-mismatch", "warning", "robot%20with%20spaces/wheel.xacro", 15, 7, True),
    ]


def test_sarif_of_files_that_cannot_be_read(arm: Path, tmp_path: Path) -> None:
    outside = tmp_path.parent / f"{tmp_path.name}-outside.urdf"
    outside.write_text("<robot")
    try:
        assert results(sarif("missing.urdf", "arm.urdf", str(outside))) == [
            ("io", "error", "missing.urdf", None, None, False),
            ("collision-material", "warning", "arm.urdf", 7, 7, False),
            ("massless-link", "error", "arm.urdf", 9, 5, False),
            ("limit-range", "error", "arm.urdf", 18, 5, False),
            ("xml-syntax", "error", outside.as_uri(), 1, 7, False),
        ]
        assert run("--format", "sarif", "missing.urdf")[0] == 2
    finally:
        outside.unlink()


def test_sarif_to_a_file_is_written_whole(arm: Path) -> None:
    assert run("--format", "sarif", "-o", "reports/fishbot.sarif", "arm.urdf") == (1, "", "")
    log = json.loads((arm / "reports" / "fishbot.sarif").read_text())
    assert [r["ruleId"] for r in log["runs"][0]["results"]] == [
        "collision-material",
        "massless-link",
        "limit-range",
    ]
    assert list(arm.joinpath("reports").iterdir()) == [arm / "reports" / "fishbot.sarif"]


def test_output_never_goes_over_an_input(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('select = ["ALL"]\n')
    for target in ("arm.urdf", "fishbot.toml"):
        before = (arm / target).read_bytes()
        assert run("--format", "sarif", "-o", target, "arm.urdf") == (
            2,
            "",
            f"{target}: error: refusing to write over the input {target} [io]\n",
        )
        assert (arm / target).read_bytes() == before
    robot = DATA / "suppress" / "xacro" / "robot.urdf.xacro"
    shutil.copytree(robot.parent, arm / "xacro")
    assert run("--format", "json", "-o", "xacro/wheel.xacro", "xacro/robot.urdf.xacro")[0] == 2
    assert (arm / "xacro" / "wheel.xacro").read_bytes() == (
        robot.parent / "wheel.xacro"
    ).read_bytes()


# --- GitHub Actions workflow commands -------------------------------------------------


def test_github_annotations(arm: Path) -> None:
    (arm / "pkg").mkdir()
    (arm / "pkg" / "arm.urdf").write_text(ARM)
    material = (
        "link 'upper_arm': <material> inside <collision> is ignored (colours belong in "
        "<visual>; move the <material> there) [collision-material]"
    )
    massless = (
        "link 'upper_arm' moves (joint 'shoulder' is revolute) but its mass is 0 kg (a moving "
        "body needs a mass (MuJoCo: above 1e-15); give its real mass) [massless-link]"
    )
    limit = (
        "joint 'shoulder': lower limit 1.5 is above upper limit -1.5 (swap them, lower <= "
        "upper) [limit-range]"
    )
    assert run(
        "--format", "github", "--severity", "limit-range=note", "pkg/arm.urdf", "x.urdf"
    ) == (
        2,
        "::warning file=pkg/arm.urdf,line=7,col=7,title=fishbot collision-material::"
        f"{material}\n"
        f"::error file=pkg/arm.urdf,line=9,col=5,title=fishbot massless-link::{massless}\n"
        f"::notice file=pkg/arm.urdf,line=18,col=5,title=fishbot limit-range::{limit}\n"
        "::error file=x.urdf,title=fishbot io::no such file [io]\n",
        "",
    )


def test_github_escapes_percent_and_newlines_in_data_and_comma_colon_in_properties(
    arm: Path,
) -> None:
    name = "tool,50%:grip"
    (arm / f"{name}.urdf").write_text(ARM.replace("upper_arm", name).replace("shoulder", "j%1"))
    status, out, err = run("--format", "github", "--select", "structure", f"{name}.urdf")
    assert (status, err) == (1, "")
    assert out == (
        "::error file=tool%2C50%25%3Agrip.urdf,line=18,col=5,title=fishbot limit-range::joint "
        "'j%251': lower limit 1.5 is above upper limit -1.5 (swap them, lower <= upper) "
        "[limit-range]\n"
    )
    finding = diagnostic(
        "limit-range",
        Severity.ERROR,
        "two\r\nlines, 100% : sure",
        path="a,b:c.urdf",
        line=3,
        column=1,
        hint="x%y",
    )
    assert github_annotations([finding]) == (
        "::error file=a%2Cb%3Ac.urdf,line=3,col=1,title=fishbot limit-range::"
        "two%0D%0Alines, 100%25 : sure (x%25y) [limit-range]\n"
    )


def test_github_leaves_out_what_comments_silenced(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(DATA / "suppress")
    assert run("--format", "github", "tokens.urdf") == (
        0,
        "::warning file=tokens.urdf,line=39,col=78,title=fishbot collision-material::link "
        "'tool': <material> inside <collision> is ignored (colours belong in <visual>; move "
        "the <material> there) [collision-material]\n",
        "",
    )


def test_json_counts_what_was_silenced(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(DATA / "suppress")
    status, out, err = run("--format", "json", "tokens.urdf", "whole_file.urdf")
    assert (status, err) == (0, "")
    files = json.loads(out)["files"]
    assert [(f["path"], f["suppressed"]) for f in files] == [
        (
            "tokens.urdf",
            {
                "count": 3,
                "rules": {"collision-material": 1, "limit-range": 1, "massless-link": 1},
            },
        ),
        ("whole_file.urdf", {"count": 2, "rules": {"collision-material": 2}}),
    ]
    assert Config().applies("unused-suppression")


def test_github_writes_other_control_characters_visibly() -> None:
    finding = diagnostic(
        "limit-range",
        Severity.ERROR,
        "joint '\x1b[2Jj': one\x85two\u2028three",
        path="a\n::error file=x::pwned\x1b.urdf",
        line=3,
        hint="tab\there",
    )
    assert github_annotations([finding]) == (
        "::error file=a%0A%3A%3Aerror file=x%3A%3Apwned\\x1b.urdf,line=3,"
        "title=fishbot limit-range::joint '\\x1b[2Jj': one\\x85two\\u2028three (tab\\there) "
        "[limit-range]\n"
    )
