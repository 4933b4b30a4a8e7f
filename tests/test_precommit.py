"""The hooks of .pre-commit-hooks.yaml, run by the real pre-commit on a scratch repository:
it installs this project into its own environment (pip, from a committed copy) as it
does for a user, then fails on a bad robot with our one-line finding, and passes once the
robot is fixed.

The first run installs the hooks' environment (6 s here, 8 s with pip's cache off; pip
downloads the dependencies on a machine without it); the later runs reuse it.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from click.testing import CliRunner
from conftest import DATA, FISHBOT, REQUIRE_TOOLS, ROOT, require_tool

from fishbot_urdf.cli import cli

BAD = DATA / "invalid" / "zero_axis.urdf"


def _pre_commit() -> list[str]:
    """The pre-commit command (a test dependency); missing, a skip, or with
    FISHBOT_REQUIRE_TOOLS=1 a failure."""
    try:
        import pre_commit  # noqa: F401
    except ImportError:
        message = "pre-commit is not installed (pip install -e '.[test]')"
        if REQUIRE_TOOLS:
            pytest.fail(message + "; FISHBOT_REQUIRE_TOOLS=1 forbids skipping")
        pytest.skip(message)
    return [sys.executable, "-m", "pre_commit"]


def _environment(home: Path) -> dict[str, str]:
    """The test's environment without anything a surrounding git hook set, with
    pre-commit's cache in ``home`` and pip quiet."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("GIT_", "PRE_COMMIT"))}
    env.update(
        PRE_COMMIT_HOME=str(home),
        PRE_COMMIT_COLOR="never",
        PIP_DISABLE_PIP_VERSION_CHECK="1",
        PIP_NO_INPUT="1",
        GIT_AUTHOR_NAME="fishbot tests",
        GIT_AUTHOR_EMAIL="tests@fishbot.invalid",
        GIT_COMMITTER_NAME="fishbot tests",
        GIT_COMMITTER_EMAIL="tests@fishbot.invalid",
    )
    return env


def _git(env: dict[str, str], folder: Path, *args: str) -> None:
    subprocess.run(
        ["git", "-c", "init.defaultBranch=main", *args],
        cwd=folder,
        env=env,
        check=True,
        capture_output=True,
        timeout=60,
    )


def _hook_repository(target: Path, env: dict[str, str]) -> str:
    """A committed copy of what installing this project needs, with the hooks file; its
    commit id."""
    target.mkdir()
    for name in ("pyproject.toml", "README.md", ".pre-commit-hooks.yaml"):
        shutil.copy(ROOT / name, target / name)
    shutil.copytree(
        ROOT / "src", target / "src", ignore=shutil.ignore_patterns("__pycache__", "*.pyc")
    )
    _git(env, target, "init", "-q")
    _git(env, target, "add", "-A")
    _git(env, target, "commit", "-q", "-m", "fishbot-urdf")
    return subprocess.run(
        ["git", "rev-parse", "HEAD"], cwd=target, env=env, capture_output=True, text=True
    ).stdout.strip()


@pytest.fixture(scope="module")
def setup(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, str]]:
    """(a scratch project whose configuration names a committed copy of this repository
    as the hooks' repository, the environment to run pre-commit in)."""
    require_tool("git", "git")
    base = tmp_path_factory.mktemp("precommit")
    env = _environment(base / "cache")
    hooks = base / "fishbot-urdf"
    commit = _hook_repository(hooks, env)
    project = base / "project"
    project.mkdir()
    shutil.copy(FISHBOT / "urdf" / "first_robot.urdf", project / "good.urdf")
    shutil.copy(BAD, project / "bad.urdf")
    # A top-level xacro robot and the file of macros it includes (no robot of its own).
    shutil.copytree(DATA / "suppress" / "xacro", project / "xacro")
    # The project's configuration, as docs/ci.md shows it (the whole-robot hook names the
    # top-level xacro robot).
    config = {
        "repos": [
            {
                "repo": str(hooks),
                "rev": commit,
                "hooks": [
                    {"id": "fishbot-check"},
                    {"id": "fishbot-check-robots", "args": ["xacro/robot.urdf.xacro"]},
                ],
            }
        ]
    }
    (project / ".pre-commit-config.yaml").write_text(yaml.safe_dump(config))
    _git(env, project, "init", "-q")
    _git(env, project, "add", "-A")
    return project, env


def _run(setup: tuple[Path, dict[str, str]], *args: str) -> subprocess.CompletedProcess[str]:
    project, env = setup
    return subprocess.run(
        [*_pre_commit(), *args],
        cwd=project,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


def _hook_output(stdout: str) -> list[str]:
    """What the failed hook printed itself (after pre-commit's lines about it)."""
    return stdout.split("- exit code: 1\n", 1)[1].strip().splitlines()


def test_the_hooks_file_is_what_pre_commit_expects() -> None:
    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())
    assert [h["id"] for h in hooks] == ["fishbot-check", "fishbot-check-robots"]
    for hook in hooks:
        assert hook["language"] == "python"
        assert hook["entry"].startswith("fishbot check ")
    files = re.compile(hooks[0]["files"])
    assert [bool(files.search(n)) for n in ("a.urdf", "b.urdf.xacro", "c.xacro", "d.sdf")] == [
        True,
        True,
        True,
        False,
    ]


def test_the_hook_fails_on_a_bad_robot_and_passes_once_it_is_fixed(
    setup: tuple[Path, dict[str, str]], monkeypatch: pytest.MonkeyPatch
) -> None:
    project = setup[0]
    monkeypatch.chdir(project)
    finding = CliRunner().invoke(cli, ["check", "-q", "bad.urdf"]).stderr
    assert finding.endswith("[zero-axis]\n") and finding.count("\n") == 1
    first = _run(setup, "run", "fishbot-check", "--all-files")
    assert first.returncode == 1, first.stdout + first.stderr
    assert "fishbot check" in first.stdout and "Failed" in first.stdout
    # Our one line, and nothing about the good robot, the xacro robot (whose comments
    # silence its findings) or the file of macros it includes.
    assert _hook_output(first.stdout) == [finding.rstrip("\n")]
    fixed = BAD.read_text().replace('<axis xyz="0 0 0"/>', '<axis xyz="0 0 1"/>')
    (project / "bad.urdf").write_text(fixed)
    second = _run(setup, "run", "fishbot-check", "--all-files")
    assert second.returncode == 0, second.stdout + second.stderr
    assert "fishbot check" in second.stdout and "Passed" in second.stdout


def test_the_whole_robot_hook_checks_the_robots_an_include_changes(
    setup: tuple[Path, dict[str, str]],
) -> None:
    project = setup[0]
    wheel = project / "xacro" / "wheel.xacro"
    original = wheel.read_text()
    try:
        wheel.write_text(original.replace('<parent link="base_link"/>', '<parent link="base"/>'))
        failed = _run(setup, "run", "fishbot-check-robots", "--all-files")
        assert failed.returncode == 1, failed.stdout + failed.stderr
        lines = _hook_output(failed.stdout)
        assert len(lines) == 2
        assert all("parent link 'base' is not defined" in line for line in lines), lines
        with pytest.MonkeyPatch.context() as patch:
            patch.chdir(project)
            alone = CliRunner().invoke(cli, ["check", "-q", "xacro/robot.urdf.xacro"])
        assert lines == alone.stderr.splitlines()
        # The file-by-file hook passes over the file of macros, as it has no robot.
        assert _run(setup, "run", "fishbot-check", "--files", str(wheel)).returncode == 0
    finally:
        wheel.write_text(original)
    passed = _run(setup, "run", "fishbot-check-robots", "--all-files")
    assert passed.returncode == 0, passed.stdout + passed.stderr


# --- the options the hooks run with -------------------------------------------------------


def _check(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(cli, ["check", *args])
    return result.exit_code, result.stdout, result.stderr


def test_skip_includes_passes_over_files_that_define_no_robot(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    shutil.copytree(DATA / "suppress" / "xacro", "xacro")
    shutil.copytree(FISHBOT, "fishbot")
    includes = [
        "xacro/wheel.xacro",
        "fishbot/urdf/fishbot/common_inertia.xacro",
        "fishbot/urdf/fishbot/base.urdf.xacro",
        "fishbot/urdf/fishbot/sensor/imu.urdf.xacro",
    ]
    # Alone, a file of macros is a robot without a name or links.
    status, _, err = _check("-q", includes[0])
    assert (status, err.count("[robot-name]"), err.count("[no-links]")) == (1, 1, 1)
    assert _check("-q", "--skip-includes", *includes) == (0, "", "")
    status, out, _ = _check("--format", "json", "--skip-includes", *includes[:2])
    assert status == 0
    assert [(f["path"], f["ok"], f["skipped"]) for f in json.loads(out)["files"]] == [
        (name, True, "defines no robot (macros for other files to include)")
        for name in includes[:2]
    ]
    # A robot is still checked: the fishbot, and one that only lacks its name.
    robot = Path("xacro/robot.urdf.xacro")
    fishbot = "fishbot/urdf/fishbot/fishbot.urdf.xacro"
    assert _check("-q", "--skip-includes", str(robot), fishbot) == (0, "", "")
    status, out, _ = _check("--skip-includes", fishbot)
    assert (status, out.splitlines()[0]) == (0, "robot name is: fishbot")
    robot.write_text(robot.read_text().replace('name="two_wheels" ', ""))
    status, _, err = _check("-q", "--skip-includes", str(robot))
    assert (status, err.count("\n"), err.endswith("[robot-name]\n")) == (1, 1, True)
    # An include that xacro cannot expand is reported.
    Path("xacro/broken.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:macro name="m">\n</robot>\n'
    )
    status, _, err = _check("-q", "--skip-includes", "xacro/broken.xacro")
    assert (status, err.startswith("xacro/broken.xacro:")) == (1, True)


def test_quiet_prints_the_findings_only() -> None:
    assert _check("-q", str(FISHBOT / "urdf" / "first_robot.urdf")) == (0, "", "")
    status, out, err = _check("--quiet", str(BAD))
    assert (status, out, err) == (1, "", _check(str(BAD))[2])


# --- the snippets of the CI recipes page (docs/ci.md) ---------------------------------------


def _ci_page_blocks(heading: str) -> list[Any]:
    """The YAML blocks of the CI recipes page's section ``heading``, parsed."""
    text = (ROOT / "docs" / "ci.md").read_text(encoding="utf-8")
    section = re.split(r"\n##+ ", text.split(f"## {heading}\n", 1)[1])[0]
    return [yaml.safe_load(b) for b in re.findall(r"```yaml\n(.*?)```", section, re.DOTALL)]


def test_the_ci_page_pre_commit_snippets_name_the_real_hooks() -> None:
    hooks = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}
    remote, local = _ci_page_blocks("pre-commit")
    assert [h["id"] for h in remote["repos"][0]["hooks"]] == list(hooks)
    (hook,) = local["repos"][0]["hooks"]
    assert hook["additional_dependencies"] == ["fishbot-urdf"]
    for key in ("id", "entry", "language", "files"):
        assert hook[key] == hooks["fishbot-check"][key], key


def test_the_ci_page_workflow_runs_as_written(tmp_path: Path) -> None:
    (workflow,) = _ci_page_blocks("GitHub Actions")
    steps = workflow["jobs"]["fishbot"]["steps"]
    uses = [s["uses"].split("@")[0] for s in steps if "uses" in s]
    assert uses == ["actions/checkout", "actions/setup-python", "github/codeql-action/upload-sarif"]
    assert workflow["permissions"]["security-events"] == "write"
    commands = [s["run"] for s in steps if s.get("run", "").startswith("fishbot check")]
    assert len(commands) == 2
    # In a copy of the fishbot package, with the fishbot command this test runs.
    package = tmp_path / "fishbot_description"
    shutil.copytree(FISHBOT, package)
    fishbot = f"{sys.executable} -m fishbot_urdf"
    for command in commands:
        proc = subprocess.run(
            ["bash", "-c", command.replace("fishbot ", fishbot + " ", 1)],
            cwd=package,
            capture_output=True,
            text=True,
            timeout=120,
            check=False,
        )
        assert (proc.returncode, proc.stdout, proc.stderr) == (0, "", "")
    upload = next(s for s in steps if s.get("uses", "").startswith("github/codeql-action"))
    log = json.loads((package / upload["with"]["sarif_file"]).read_text())
    assert log["runs"][0]["results"] == []
    assert log["version"] == "2.1.0"
