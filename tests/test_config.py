"""`fishbot_urdf.config` and the options of `fishbot check` that choose rules: selection as
ruff resolves it, [tool.fishbot] / fishbot.toml found upward from each file, --config,
--isolated, and one clear line (exit 2) for a wrong configuration or option."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import DATA

from fishbot_urdf import Config, ConfigError, find_config, load_config
from fishbot_urdf.catalog import Family, all_rules, ids
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity

# An arm with one finding in each of three families: urdf (a warning), physics and
# structure (errors: its <gazebo> block makes it a robot for Gazebo, which both harm).
ARM = """\
<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <link name="upper_arm">
    <collision>
      <geometry><box size="0.1 0.1 0.5"/></geometry>
      <material name="grey"/>
    </collision>
    <inertial>
      <mass value="0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <axis xyz="0 1 0"/>
    <limit lower="1.5" upper="-1.5" effort="10" velocity="1"/>
  </joint>
  <gazebo reference="upper_arm"/>
</robot>
"""
TREE = (
    "robot name is: arm\n"
    "---------- Successfully Parsed XML ---------------\n"
    "root Link: base_link has 1 child(ren)\n"
    "    child(1):  upper_arm\n"
)
MATERIAL = (
    "{f}:7:7: {level}: link 'upper_arm': <material> inside <collision> is ignored (colours "
    "belong in <visual>; move the <material> there) [collision-material]\n"
)
MASSLESS = (
    "{f}:9:5: {level}: link 'upper_arm' moves (joint 'shoulder' is revolute) but its mass is "
    "0 kg (a moving body needs a mass (MuJoCo: above 1e-15); give its real mass) "
    "[massless-link]\n"
)
RANGE = (
    "{f}:18:5: {level}: joint 'shoulder': lower limit 1.5 is above upper limit -1.5 (swap "
    "them, lower <= upper) [limit-range]\n"
)
USAGE = (
    "Usage: fishbot check [OPTIONS] FILE... [name:=value]...\n"
    "Try 'fishbot check --help' for help.\n\n"
)


def material(f: str = "arm.urdf", level: str = "warning") -> str:
    return MATERIAL.format(f=f, level=level)


def massless(f: str = "arm.urdf", level: str = "error") -> str:
    return MASSLESS.format(f=f, level=level)


def limit_range(f: str = "arm.urdf", level: str = "error") -> str:
    return RANGE.format(f=f, level=level)


def run(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["check", *args])
    return result.exit_code, result.stdout, result.stderr


@pytest.fixture
def arm(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """arm.urdf in a fresh folder, which is the current one."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "arm.urdf").write_text(ARM)
    return tmp_path


# --- the selection, resolved as ruff resolves it ---------------------------------------


def test_the_default_applies_every_rule() -> None:
    assert Config().enabled == ids()


def test_a_rule_id_outranks_a_family_which_outranks_all() -> None:
    config = Config(ignore=("physics",), extend_select=("massless-link",))
    physics = {r.id for r in all_rules() if r.family is Family.PHYSICS}
    assert "massless-link" in config.enabled
    assert config.enabled & physics == {"massless-link"}
    fatal = {r.id for r in all_rules() if r.fatal}
    assert Config(select=("physics",), ignore=("ALL",)).enabled == physics | fatal
    assert Config(select=("ALL",), ignore=("physics",)).enabled == ids() - physics
    # Same rank: the ignore wins.
    assert not Config(select=("physics",), ignore=("physics",)).applies("massless-link")


def test_fatal_rules_always_apply_and_cannot_be_changed() -> None:
    fatal = {r.id for r in all_rules() if r.fatal}
    assert fatal >= {"xml-syntax", "io", "config", "xacro-syntax", "package-not-found"}
    assert Config(select=()).enabled == fatal
    assert Config(ignore=("ALL",)).enabled == fatal
    assert Config(ignore=("xacro",)).enabled >= {"xacro-syntax", "xacro-undefined"}
    with pytest.raises(ConfigError, match="rule 'xml-syntax' cannot be changed"):
        Config(ignore=("xml-syntax",))
    with pytest.raises(ConfigError, match="rule 'io' cannot be changed"):
        Config(severity={"io": Severity.WARNING})


def test_the_command_line_select_replaces_the_files_selection() -> None:
    file = Config(select=("structure",), extend_select=("urdf",), ignore=("limit-range",))
    assert file.applies("collision-material") and not file.applies("limit-range")
    both = file.updated(select=["physics", "structure"])
    assert both.applies("massless-link")
    assert not both.applies("collision-material")  # the file's extend-select went with it
    assert not both.applies("limit-range")  # the file's ignore holds
    assert file.updated(select=["limit-range"]).enabled - file.enabled == set()


def test_the_command_line_extends_and_ignores_on_top_of_the_file() -> None:
    file = Config(ignore=("physics",))
    assert not file.applies("massless-link")
    assert file.updated(extend_select=["massless-link"]).applies("massless-link")
    assert file.updated(extend_select=["physics"]).applies("inertia-mismatch")
    assert (
        not Config(extend_select=("massless-link",))
        .updated(ignore=["physics"])
        .applies("massless-link")
    )
    assert file.updated(severity={"limit-range": Severity.NOTE}).severity == {
        "limit-range": Severity.NOTE
    }


def test_apply_drops_unselected_findings_and_relevels() -> None:
    from fishbot_urdf.lint import check_file

    config = Config(select=("structure", "urdf"), severity={"limit-range": Severity.WARNING})
    result = check_file(ARM.encode(), path="arm.urdf", config=config)
    assert [(d.rule, d.severity) for d in result.diagnostics] == [
        ("collision-material", Severity.WARNING),
        ("limit-range", Severity.WARNING),
    ]
    assert result.ok


# --- finding and reading configuration files --------------------------------------------


def test_find_config_takes_the_nearest_file_upward(tmp_path: Path) -> None:
    inner = tmp_path / "pkg" / "urdf"
    inner.mkdir(parents=True)
    (tmp_path / "fishbot.toml").write_text("")
    assert find_config(inner / "robot.urdf") == tmp_path / "fishbot.toml"
    (tmp_path / "pkg" / "pyproject.toml").write_text('[project]\nname = "pkg"\n')
    assert find_config(inner / "robot.urdf") == tmp_path / "fishbot.toml"  # no table
    (tmp_path / "pkg" / "pyproject.toml").write_text("[tool.fishbot]\nstrict = true\n")
    assert find_config(inner / "robot.urdf") == tmp_path / "pkg" / "pyproject.toml"
    (tmp_path / "pkg" / "fishbot.toml").write_text("")
    assert find_config(inner) == tmp_path / "pkg" / "fishbot.toml"  # before pyproject.toml


def test_a_pyproject_table_in_any_toml_form_counts(tmp_path: Path) -> None:
    pyproject = tmp_path / "pyproject.toml"
    for text in (
        'tool.fishbot.select = ["physics"]\n',
        '[tool]\nfishbot = { select = ["physics"] }\n',
        '[tool.fishbot.severity]\nlimit-range = "warning"\n',
    ):
        pyproject.write_text(text)
        assert find_config(tmp_path) == pyproject
    pyproject.write_text('[project]\ndependencies = ["fishbot-urdf"]\n')
    assert find_config(tmp_path) is None
    pyproject.write_text("[tool.fishbot]\nstrict = \n")  # broken: reading it says so
    assert find_config(tmp_path) == pyproject


def test_load_config_reads_every_key(tmp_path: Path) -> None:
    path = tmp_path / "pyproject.toml"
    path.write_text(
        '[project]\nname = "x"\n\n[tool.fishbot]\nselect = ["ALL"]\n'
        'extend-select = ["physics"]\nignore = ["inertia-mismatch", "lint"]\nstrict = true\n'
        'ground-tolerance = 5\n\n[tool.fishbot.severity]\nlimit-range = "warning"\n'
    )
    config = load_config(path)
    assert config == Config(
        select=("ALL",),
        extend_select=("physics",),
        ignore=("inertia-mismatch", "lint"),
        severity={"limit-range": Severity.WARNING},
        strict=True,
        ground_tolerance=5.0,
        path=str(path),
    )
    assert not config.applies("unused-suppression")
    path.write_text('[project]\nname = "x"\n')
    assert load_config(path) == Config(path=str(path))


# --- the command line: configuration files ----------------------------------------------


def test_pyproject_selection(arm: Path) -> None:
    (arm / "pyproject.toml").write_text('[tool.fishbot]\nselect = ["structure"]\n')
    assert run("arm.urdf") == (1, TREE, limit_range())


def test_command_line_select_replaces_and_the_others_add(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('select = ["structure"]\nextend-select = ["physics"]\n')
    assert run("-q", "arm.urdf") == (1, "", massless() + limit_range())
    assert run("-q", "--select", "urdf", "arm.urdf") == (0, "", material())
    assert run("-q", "--extend-select", "urdf", "arm.urdf") == (
        1,
        "",
        material() + massless() + limit_range(),
    )
    assert run("-q", "--ignore", "physics", "arm.urdf") == (1, "", limit_range())
    assert run("-q", "--select", "urdf", "--select", "massless-link,limit-range", "arm.urdf") == (
        1,
        "",
        material() + massless() + limit_range(),
    )


def test_severity_from_file_and_command_line(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('[severity]\nmassless-link = "warning"\n')
    expected = material() + massless(level="warning") + limit_range(level="note")
    assert run("-q", "--severity", "limit-range=note", "arm.urdf") == (0, "", expected)


def test_strict_from_the_file_and_no_strict(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('select = ["urdf"]\nstrict = true\n')
    assert run("-q", "arm.urdf") == (1, "", material())
    assert run("-q", "--no-strict", "arm.urdf") == (0, "", material())
    (arm / "fishbot.toml").write_text('select = ["urdf"]\n')
    assert run("-q", "--strict", "arm.urdf") == (1, "", material())


def test_ground_tolerance_key(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    robot = (DATA / "physics" / "wheels_under_ground.urdf").read_bytes()
    Path("robot.urdf").write_bytes(robot)
    status, _, err = run("-q", "robot.urdf")
    assert (status, err.count("[below-ground]")) == (0, 2)
    Path("fishbot.toml").write_text("ground-tolerance = 20\n")  # the wheels sink 16 mm
    assert run("-q", "robot.urdf") == (0, "", "")
    assert run("-q", "--ground-tolerance", "10", "robot.urdf")[2].count("[below-ground]") == 2


def test_each_file_gets_its_own_configuration(arm: Path) -> None:
    for folder, text in (("a", 'select = ["urdf"]\n'), ("b", 'ignore = ["urdf", "physics"]\n')):
        (arm / folder).mkdir()
        (arm / folder / "arm.urdf").write_text(ARM)
        (arm / folder / "fishbot.toml").write_text(text)
    assert run("-q", "a/arm.urdf", "b/arm.urdf") == (
        1,
        "",
        material("a/arm.urdf") + limit_range("b/arm.urdf"),
    )
    status, out, err = run("--format", "json", "a/arm.urdf", "b/arm.urdf", "arm.urdf")
    assert (status, err) == (1, "")
    files = json.loads(out)["files"]
    assert [(f["path"], f["config"], f["ok"]) for f in files] == [
        ("a/arm.urdf", "a/fishbot.toml", True),
        ("b/arm.urdf", "b/fishbot.toml", False),
        ("arm.urdf", None, False),
    ]
    assert [len(f["diagnostics"]) for f in files] == [1, 1, 3]


def test_a_pyproject_without_the_table_is_skipped(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('select = ["structure"]\n')
    (arm / "pkg").mkdir()
    (arm / "pkg" / "pyproject.toml").write_text('[project]\nname = "pkg"\n')
    (arm / "pkg" / "arm.urdf").write_text(ARM)
    assert run("-q", "pkg/arm.urdf") == (1, "", limit_range("pkg/arm.urdf"))
    _, out, _ = run("--format", "json", "pkg/arm.urdf")
    assert json.loads(out)["files"][0]["config"] == "fishbot.toml"


def test_config_option_overrides_discovery_and_isolated_reads_none(arm: Path) -> None:
    (arm / "fishbot.toml").write_text('select = ["structure"]\n')
    (arm / "ci.toml").write_text('select = ["physics"]\n')
    assert run("-q", "--config", "ci.toml", "arm.urdf") == (1, "", massless())
    _, out, _ = run("--format", "json", "--config", "ci.toml", "arm.urdf")
    assert json.loads(out)["files"][0]["config"] == "ci.toml"
    assert run("-q", "--isolated", "arm.urdf") == (1, "", material() + massless() + limit_range())
    _, out, _ = run("--format", "json", "--isolated", "arm.urdf")
    assert json.loads(out)["files"][0]["config"] is None


def test_an_empty_selection_still_prints_the_tree(arm: Path) -> None:
    assert run("--select", "xml", "arm.urdf") == (0, TREE, "")
    (arm / "fishbot.toml").write_text("select = []\n")
    assert run("arm.urdf") == (0, TREE, "")


# --- a wrong configuration: one line, exit 2, before anything is checked -------------------


@pytest.mark.parametrize(
    ("text", "line"),
    [
        (
            '[tool.fishbot]\nselect = ["structure", "massless-lnk"]\n',
            "pyproject.toml:2: error: select: no rule or family 'massless-lnk' (did you mean "
            "'massless-link'? families: xml, urdf, structure, joints, references, meshes, "
            "physics, gazebo, simulation, xacro, setup, lint; "
            "`fishbot rules` lists the rules) [config]",
        ),
        (
            '[tool.fishbot]\nextend-select = ["physic"]\n',
            "pyproject.toml:2: error: extend-select: no rule or family 'physic' (did you mean "
            "'physics'? families: xml, urdf, structure, joints, references, meshes, "
            "physics, gazebo, simulation, xacro, setup, lint; "
            "`fishbot rules` lists the rules) [config]",
        ),
        (
            '[project]\nname = "x"\n\n[tool.fishbot]\nignroe = ["physics"]\n',
            "pyproject.toml:5: error: unknown key 'ignroe' (did you mean 'ignore'? keys: "
            "select, extend-select, ignore, severity, strict, ground-tolerance, allow-read, "
            "targets) "
            "[config]",
        ),
        (
            '[tool.fishbot]\nselect = "physics"\n',
            "pyproject.toml:2: error: select must be a list of rule ids or family names [config]",
        ),
        (
            "[tool.fishbot]\nstrict = 1\n",
            "pyproject.toml:2: error: strict must be true or false [config]",
        ),
        (
            '[tool.fishbot]\nground-tolerance = "2mm"\n',
            "pyproject.toml:2: error: ground-tolerance must be a number of millimetres, >= 0 "
            "[config]",
        ),
        (
            '[tool.fishbot.severity]\nlimit-range = "fatal"\n',
            "pyproject.toml:2: error: severity of 'limit-range' is 'fatal': it must be error, "
            "warning or note [config]",
        ),
        (
            '[tool.fishbot.severity]\nphysics = "warning"\n',
            "pyproject.toml:2: error: severity: no rule 'physics' (a severity is set per rule, "
            "not for 'physics'; `fishbot rules` lists the rules) [config]",
        ),
        (
            '[tool.fishbot]\nignore = ["xml-syntax"]\n',
            "pyproject.toml:2: error: ignore: rule 'xml-syntax' cannot be changed: it stops the "
            "file from being read [config]",
        ),
        (
            "[tool.fishbot]\nselect = [physics]\n",
            "pyproject.toml:2:11: error: not valid TOML: Invalid value [config]",
        ),
        (
            '[tool]\nfishbot = "strict"\n',
            "pyproject.toml:2: error: [tool.fishbot] must be a table [config]",
        ),
    ],
)
def test_a_wrong_pyproject_is_one_line_and_exit_2(arm: Path, text: str, line: str) -> None:
    (arm / "pyproject.toml").write_text(text)
    (arm / "good.urdf").write_bytes((DATA / "valid" / "single_link.urdf").read_bytes())
    (arm / "sub").mkdir()
    (arm / "sub" / "fishbot.toml").write_text("")
    # The good file (which has its own configuration) is not checked either.
    assert run("sub/../good.urdf", "arm.urdf") == (2, "", line + "\n")


def test_a_configuration_that_cannot_be_read(arm: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert run("--config", "missing.toml", "arm.urdf") == (
        2,
        "",
        "missing.toml: error: cannot read the configuration: no such file [config]\n",
    )
    (arm / "fishbot.toml").write_bytes(b'select = ["\xff"]\n')
    assert run("arm.urdf") == (
        2,
        "",
        "fishbot.toml: error: cannot read the configuration: not UTF-8 text [config]\n",
    )
    (arm / "fishbot.toml").write_text("")
    real = os.open

    def refuse(path: str, *args: int) -> int:
        if os.path.basename(path) == "fishbot.toml":
            raise PermissionError(13, "Permission denied", path)
        return real(path, *args)

    monkeypatch.setattr(os, "open", refuse)
    assert run("arm.urdf") == (
        2,
        "",
        "fishbot.toml: error: cannot read the configuration: permission denied [config]\n",
    )


def test_a_wrong_option_is_a_usage_error(arm: Path) -> None:
    families = (
        "families: xml, urdf, structure, joints, references, meshes, physics, gazebo, "
        "simulation, xacro, setup, lint"
    )
    cases = {
        ("--select", "structure,physic"): "Invalid value for '--select': no rule or family "
        f"'physic' (did you mean 'physics'? {families}; `fishbot rules` lists the rules)",
        ("--ignore", "massless-lnk"): "Invalid value for '--ignore': no rule or family "
        f"'massless-lnk' (did you mean 'massless-link'? {families}; `fishbot rules` lists "
        "the rules)",
        ("--ignore", "xml-syntax"): "Invalid value for '--ignore': rule 'xml-syntax' cannot be "
        "changed: it stops the file from being read",
        ("--extend-select", "nope"): "Invalid value for '--extend-select': no rule or family "
        f"'nope' ({families}; `fishbot rules` lists the rules)",
        ("--severity", "limit-range"): "Invalid value for '--severity': 'limit-range' is not "
        "RULE=error|warning|note",
        ("--severity", "limit-range=fatal"): "Invalid value for '--severity': "
        "'limit-range=fatal' is not RULE=error|warning|note",
        ("--severity", "io=warning"): "Invalid value for '--severity': rule 'io' cannot be "
        "changed: it stops the file from being read",
        ("--ground-tolerance", "-1"): "Invalid value for '--ground-tolerance': '-1' must be >= 0",
    }
    for args, message in cases.items():
        assert run(*args, "arm.urdf") == (2, "", f"{USAGE}Error: {message}\n"), args
    assert run("--isolated", "--config", "a.toml", "arm.urdf") == (
        2,
        "",
        f"{USAGE}Error: --config and --isolated cannot be used together\n",
    )
    assert run("x:=1") == (
        2,
        "",
        f"{USAGE}Error: no FILE to check (name:=value arguments go with a .xacro file)\n",
    )


def test_find_config_remembers_the_folders_it_searched(tmp_path: Path) -> None:
    (tmp_path / "fishbot.toml").write_text('ignore = ["inertia-mismatch"]\n')
    deep = tmp_path / "a" / "b"
    deep.mkdir(parents=True)
    (tmp_path / "a" / "robot.urdf").write_text("<robot/>")
    known: dict[Path, Path | None] = {}
    first = find_config(deep / "robot.urdf", known)
    assert first == tmp_path / "fishbot.toml"
    assert known[deep] == known[tmp_path / "a"] == known[tmp_path] == first
    # Answered from what was found: the same as a search without it.
    assert find_config(tmp_path / "a" / "robot.urdf", known) == find_config(tmp_path / "a")


def test_a_toml_nested_too_deeply_is_one_configuration_error(arm: Path) -> None:
    deep = "[" * 3000 + "]" * 3000
    (arm / "pyproject.toml").write_text(f"[tool.fishbot]\nselect = {deep}\n")
    message = "not valid TOML: arrays or tables nested too deeply to read (nest them less)"
    assert run("arm.urdf") == (2, "", f"pyproject.toml: error: {message} [config]\n")
    (arm / "pyproject.toml").unlink()
    (arm / "fishbot.toml").write_text(f"select = {deep}\n")
    assert run("arm.urdf") == (2, "", f"fishbot.toml: error: {message} [config]\n")
    with pytest.raises(ConfigError, match="nested too deeply"):
        load_config(arm / "fishbot.toml")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs: POSIX only")
def test_a_configuration_that_is_no_regular_file_is_refused_at_once(arm: Path) -> None:
    os.mkfifo(arm / "pipe.toml")  # read as a file, it would wait for a writer forever
    assert run("--config", "pipe.toml", "arm.urdf") == (
        2,
        "",
        "pipe.toml: error: cannot read the configuration: is a FIFO (named pipe), not a "
        "regular file [config]\n",
    )
    if os.path.exists("/dev/zero"):  # read whole, it would fill the memory
        assert run("--config", "/dev/zero", "arm.urdf") == (
            2,
            "",
            "/dev/zero: error: cannot read the configuration: is a device, not a regular "
            "file [config]\n",
        )


def test_a_configuration_over_the_size_limit_is_refused(arm: Path) -> None:
    (arm / "fishbot.toml").write_text("# " + "x" * 2_000_000 + "\n")
    status, out, err = run("--max-size", "1", "arm.urdf")
    assert (status, out) == (2, "")
    assert err == (
        "fishbot.toml: error: cannot read the configuration: is 1.9 MiB, more than the limit "
        "of 1.0 MiB [config]\n"
    )
