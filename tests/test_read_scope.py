"""What an expansion may read: only inside the robot's tree, the packages ``$(find)``
resolves and the folders allowed, links resolved; anywhere with trusted expressions.

Each robot below lives in a git repository (``repo/``, with a ``.git``) and tries to read
``outside/``, beside it, which holds text that a YAML or XML error would show. The
property: the expansion stops with one located ``xacro-read-outside`` error that names the
file and the tree, and nothing of that text reaches the message.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest
from click.testing import CliRunner

from fishbot_urdf.cli import cli
from fishbot_urdf.config import load_config
from fishbot_urdf.expansion import (
    ReadOutsideError,
    XacroError,
    allowing_reads,
    expand,
    robot_tree,
    trusting_expressions,
)
from fishbot_urdf.inputs import reads_allowed
from fishbot_urdf.lint import check_file

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SECRET = "SECRET-CONTENT"
CLI_HINT = (
    "if the robot should read it, allow a folder that holds it with --allow-read DIR or "
    "allow-read in [tool.fishbot]"
)


def _robot(body: str) -> str:
    return f'<robot name="r" {NS}>\n{body}\n<link name="base_link"/>\n</robot>\n'


@pytest.fixture
def place(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """``repo/`` (a git repository, the robot's tree) and ``outside/`` beside it; the
    current folder is the one above both."""
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    (tmp_path / "repo" / "urdf").mkdir()
    outside = tmp_path / "outside"
    outside.mkdir()
    # Text that PyYAML's and expat's errors would quote, were it read.
    (outside / "secret.yaml").write_text(f"key: [{SECRET}\n")
    (outside / "secret.xacro").write_text(f"{SECRET} <not-closed>\n")
    (outside / "part.xacro").write_text(
        f'<robot {NS}><link name="shared_link"/><joint name="shared_joint" type="fixed">'
        '<parent link="base_link"/><child link="shared_link"/></joint></robot>\n'
    )
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _yaml(call: str, name: str) -> str:
    """A robot whose link is named by a value of the YAML file ``name``."""
    return _robot(
        f'<xacro:property name="p" value="${{{call}(\'{name}\')}}"/>\n<link name="${{p}}"/>'
    )


def _write(place: Path, text: str, name: str = "robot.urdf.xacro") -> Path:
    robot = place / "repo" / "urdf" / name
    robot.write_text(text)
    return robot


def _real(path: Path) -> str:
    return os.path.realpath(path)


def _refused(robot: Path, **kwargs: object) -> ReadOutsideError:
    with pytest.raises(ReadOutsideError) as caught:
        expand(robot, **kwargs)  # type: ignore[arg-type]
    error = caught.value
    assert isinstance(error, XacroError)
    assert error.rule == "xacro-read-outside"
    assert SECRET not in str(error) and SECRET not in (error.hint or "")
    return error


# -- the robot's tree ----------------------------------------------------------------------


def test_the_tree_is_the_git_repository_else_the_package_else_the_folder(tmp_path: Path) -> None:
    deep = tmp_path / "ws" / "pkg" / "urdf" / "parts"
    deep.mkdir(parents=True)
    robot = deep / "robot.urdf.xacro"
    assert robot_tree(robot) == str(deep)
    (tmp_path / "ws" / "pkg" / "package.xml").write_text("<package/>")
    assert robot_tree(robot) == str(tmp_path / "ws" / "pkg")
    (tmp_path / "ws" / ".git").write_text("gitdir: ../.git/worktrees/ws\n")  # a worktree's
    assert robot_tree(robot) == str(tmp_path / "ws")  # a repository wins over a package
    (deep / ".git").mkdir()
    assert robot_tree(robot) == str(deep)


def test_a_file_in_the_tree_is_read(place: Path) -> None:
    (place / "repo" / "common").mkdir()
    (place / "repo" / "common" / "part.xacro").write_text(
        f'<robot {NS}><link name="part_link"/></robot>\n'
    )
    (place / "repo" / "common" / "wheel.yaml").write_text("radius: 0.03\n")
    robot = _write(
        place,
        _robot(
            '<xacro:include filename="../common/part.xacro"/>\n'
            '<xacro:property name="w" value="${xacro.load_yaml(\'../common/wheel.yaml\')}"/>\n'
            '<link name="wheel_${w.radius}"/>'
        ),
    )
    text = expand(robot).text
    assert 'name="part_link"' in text and 'name="wheel_0.03"' in text


# -- what is refused -----------------------------------------------------------------------


@pytest.mark.parametrize("call", ["xacro.load_yaml", "load_yaml"])
def test_load_yaml_of_an_absolute_path_outside_is_refused(place: Path, call: str) -> None:
    secret = place / "outside" / "secret.yaml"
    robot = _write(place, _yaml(call, str(secret)))
    error = _refused(robot)
    assert error.message == (
        f"cannot read {_real(secret)}: it is outside the robot's tree {_real(place / 'repo')}"
    )
    assert (error.path, error.line, error.column) == ("repo/urdf/robot.urdf.xacro", 3, 1)
    assert (error.file, error.real, error.tree) == (
        str(secret),
        _real(secret),
        _real(place / "repo"),
    )
    assert error.hint == (
        "if the robot should read it, allow a folder that holds it with allow_read=[DIR] or "
        "allow-read in [tool.fishbot]"
    )


def test_the_refusal_shows_nothing_of_the_file_that_reading_it_would(place: Path) -> None:
    # Read, the file's YAML error quotes its text: the refusal comes before any reading.
    secret = place / "outside" / "secret.yaml"
    robot = _write(place, _yaml("xacro.load_yaml", str(secret)))
    _refused(robot)
    with pytest.raises(XacroError) as read:
        expand(robot, allow_read=[place / "outside"])
    assert SECRET in str(read.value)


def test_an_include_of_a_relative_path_outside_is_refused(place: Path) -> None:
    robot = _write(place, _robot('<xacro:include filename="../../outside/secret.xacro"/>'))
    error = _refused(robot)
    secret = _real(place / "outside" / "secret.xacro")
    assert str(error) == (
        f"repo/urdf/robot.urdf.xacro:2:1: cannot read {secret}: it is outside the robot's "
        f"tree {_real(place / 'repo')}"
    )


def test_a_file_outside_is_refused_whether_or_not_it_exists(place: Path) -> None:
    for name in ("../../outside/missing.xacro", "/etc/passwd", "../../../../../../etc/passwd"):
        robot = _write(place, _robot(f'<xacro:include filename="{name}" optional="true"/>'))
        assert _refused(robot).line == 2, name


def test_an_include_through_a_link_inside_the_tree_is_refused(place: Path) -> None:
    link = place / "repo" / "urdf" / "shared.xacro"
    link.symlink_to(place / "outside" / "secret.xacro")
    robot = _write(place, _robot('<xacro:include filename="shared.xacro"/>'))
    error = _refused(robot)
    assert error.message == (
        f"cannot read {link}, which is {_real(place / 'outside' / 'secret.xacro')}: it is "
        f"outside the robot's tree {_real(place / 'repo')}"
    )


def test_a_yaml_file_through_a_linked_folder_is_refused(place: Path) -> None:
    (place / "repo" / "config").symlink_to(place / "outside", target_is_directory=True)
    robot = _write(place, _yaml("xacro.load_yaml", "../config/secret.yaml"))
    assert _refused(robot).real == _real(place / "outside" / "secret.yaml")


def test_an_include_pattern_that_looks_outside_is_refused_before_it_looks(place: Path) -> None:
    # (outside/ holds no .urdf file: unrefused, the pattern would match nothing and warn)
    for pattern, folder in (
        ("../../outside/*.xacro", place / "outside"),
        ("../../outside/*.urdf", place / "outside"),
        ("../../nowhere/*.xacro", place / "nowhere"),
        ("../*/../../outside/*.xacro", place),  # back up through a folder matched
    ):
        robot = _write(place, _robot(f'<xacro:include filename="{pattern}"/>'))
        error = _refused(robot)
        assert error.pattern == f"{place}/repo/urdf/{pattern}"
        assert error.real == _real(folder), pattern
        assert error.message.startswith(f"include pattern {error.pattern} looks in "), pattern
        assert error.line == 2


def test_an_include_pattern_that_matches_a_link_out_is_refused(place: Path) -> None:
    (place / "repo" / "urdf" / "parts").mkdir()
    (place / "repo" / "urdf" / "parts" / "a.xacro").write_text(f"<robot {NS}/>\n")
    (place / "repo" / "urdf" / "parts" / "b.xacro").symlink_to(place / "outside" / "secret.xacro")
    robot = _write(place, _robot('<xacro:include filename="parts/*.xacro"/>'))
    assert _refused(robot).real == _real(place / "outside" / "secret.xacro")
    # A folder linked out is not looked in.
    (place / "repo" / "urdf" / "parts" / "b.xacro").unlink()
    (place / "repo" / "urdf" / "parts" / "more").symlink_to(place / "outside")
    robot = _write(place, _robot('<xacro:include filename="parts/*/*.xacro"/>'))
    error = _refused(robot)
    assert (error.pattern is not None, error.real) == (True, _real(place / "outside"))


def test_a_refusal_in_a_macro_names_the_calls(place: Path) -> None:
    robot = _write(
        place,
        _robot(
            '<xacro:macro name="m" params="f"><xacro:include filename="${f}"/></xacro:macro>\n'
            '<xacro:m f="../../outside/secret.xacro"/>'
        ),
    )
    error = _refused(robot)
    assert error.line == 2
    assert [name for name, _ in error.calls] == ["m"]
    assert str(error).endswith(", in macro m called from repo/urdf/robot.urdf.xacro:3")


# -- what is allowed -----------------------------------------------------------------------


def _package(root: Path, name: str) -> Path:
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text(f"<package><name>{name}</name></package>\n")
    (root / "urdf" / "part.xacro").write_text(f'<robot {NS}><link name="{name}_link"/></robot>\n')
    return root


def test_a_package_found_by_find_may_be_read(place: Path) -> None:
    other = _package(place / "ws" / "src" / "other_description", "other_description")
    robot = _write(
        place, _robot('<xacro:include filename="$(find other_description)/urdf/part.xacro"/>')
    )
    text = expand(robot, packages={"other_description": other}).text
    assert 'name="other_description_link"' in text
    # A package is readable once found, not before.
    robot = _write(
        place,
        _robot(
            f'<xacro:include filename="{other}/urdf/part.xacro"/>\n'
            '<xacro:include filename="$(find other_description)/urdf/part.xacro"/>'
        ),
    )
    assert _refused(robot, packages={"other_description": other}).line == 2


def test_a_package_found_by_find_may_be_globbed(place: Path) -> None:
    other = _package(place / "ws" / "src" / "other_description", "other_description")
    robot = _write(
        place, _robot('<xacro:include filename="$(find other_description)/urdf/*.xacro"/>')
    )
    assert (
        'name="other_description_link"' in expand(robot, packages={"other_description": other}).text
    )


def test_a_symlink_install_reads_the_sources_its_links_lead_to(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # colcon build --symlink-install: install/share/PKG holds a link to each source file.
    source = _package(tmp_path / "ws" / "src" / "bot_description", "bot_description")
    (source / "urdf" / "robot.urdf.xacro").write_text(
        _robot('<xacro:include filename="$(find bot_description)/urdf/part.xacro"/>')
    )
    installed = tmp_path / "ws" / "install" / "bot_description" / "share" / "bot_description"
    (installed / "urdf").mkdir(parents=True)
    for name in ("package.xml", "urdf/part.xacro", "urdf/robot.urdf.xacro"):
        (installed / name).symlink_to(source / name)
    (source / ".git").mkdir()  # the sources are a repository of their own
    monkeypatch.chdir(tmp_path)
    robot = installed / "urdf" / "robot.urdf.xacro"
    text = expand(robot, packages={"bot_description": installed}).text
    assert 'name="bot_description_link"' in text


def test_allow_read_lets_a_folder_be_read(place: Path) -> None:
    robot = _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    _refused(robot)
    assert 'name="shared_link"' in expand(robot, allow_read=["outside"]).text
    assert 'name="shared_link"' in expand(robot, allow_read="outside").text  # one folder
    with allowing_reads(place / "outside"):
        assert reads_allowed() == (_real(place / "outside"),)
        assert 'name="shared_link"' in expand(robot).text
        with allowing_reads([place / "elsewhere"]):  # adds to the enclosing one
            assert len(reads_allowed()) == 2
            expand(robot)
    assert reads_allowed() == ()
    _refused(robot)


def test_allowing_reads_holds_for_its_own_thread_only(place: Path) -> None:
    robot = _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    seen: list[BaseException | None] = []

    def other() -> None:
        try:
            expand(robot)
            seen.append(None)
        except XacroError as exc:
            seen.append(exc)

    with allowing_reads(["outside"]):
        thread = threading.Thread(target=other)
        thread.start()
        thread.join()
        expand(robot)
    assert isinstance(seen[0], ReadOutsideError)


def test_trusted_expressions_read_anywhere(place: Path) -> None:
    robot = _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    assert 'name="shared_link"' in expand(robot, trust_expressions=True).text
    with trusting_expressions():
        assert 'name="shared_link"' in expand(robot).text


# -- the configuration and the command line ------------------------------------------------


def test_allow_read_in_the_configuration_is_from_its_folder(place: Path) -> None:
    (place / "repo" / "pyproject.toml").write_text('[tool.fishbot]\nallow-read = ["../outside"]\n')
    config = load_config(place / "repo" / "pyproject.toml")
    assert config.allow_read == (str(place / "outside"),)
    robot = _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    assert check_file(robot, config=config).robot is not None
    (place / "repo" / "pyproject.toml").write_text('[tool.fishbot]\nallow-read = "../outside"\n')
    result = CliRunner().invoke(cli, ["check", "-q", "repo/urdf/robot.urdf.xacro"])
    assert (result.exit_code, result.stderr) == (
        2,
        "repo/pyproject.toml:2: error: allow-read must be a list of folders [config]\n",
    )


def _refusal_line(place: Path) -> str:
    secret = _real(place / "outside" / "secret.xacro")
    return (
        f"repo/urdf/robot.urdf.xacro:2:1: error: cannot read {secret}: it is outside the "
        f"robot's tree {_real(place / 'repo')} ({CLI_HINT}) [xacro-read-outside]\n"
    )


@pytest.mark.parametrize(
    "command",
    [["check"], ["expand"], ["graph", "-o", "-"], ["inertia"], ["tf", "base_link", "base_link"]],
)
def test_a_refused_read_is_one_line_and_exit_1(place: Path, command: list[str]) -> None:
    _write(place, _robot('<xacro:include filename="../../outside/secret.xacro"/>'))
    result = CliRunner().invoke(cli, [command[0], "repo/urdf/robot.urdf.xacro", *command[1:]])
    assert (result.exit_code, result.stdout, result.stderr) == (1, "", _refusal_line(place))


def test_allow_read_on_the_command_line_and_in_the_configuration(place: Path) -> None:
    _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    runner = CliRunner()
    for command in (["expand"], ["check", "-q"]):
        refused = runner.invoke(cli, [*command, "repo/urdf/robot.urdf.xacro"])
        assert refused.exit_code == 1, refused.output
        allowed = runner.invoke(
            cli, [*command, "--allow-read", "outside", "repo/urdf/robot.urdf.xacro"]
        )
        assert (allowed.exit_code, allowed.stderr) == (0, ""), allowed.output
    (place / "repo" / "fishbot.toml").write_text('allow-read = ["../outside"]\n')
    for command in (["expand"], ["check", "-q"], ["tf"]):
        tail = ["base_link", "shared_link"] if command == ["tf"] else []
        result = runner.invoke(cli, [*command, "repo/urdf/robot.urdf.xacro", *tail])
        assert (result.exit_code, result.stderr) == (0, ""), result.output
    isolated = runner.invoke(cli, ["check", "--isolated", "repo/urdf/robot.urdf.xacro"])
    assert isolated.exit_code == 1


def test_allow_read_names_a_folder_that_exists(place: Path) -> None:
    _write(place, _robot(""))
    result = CliRunner().invoke(
        cli, ["expand", "--allow-read", "nowhere", "repo/urdf/robot.urdf.xacro"]
    )
    assert result.exit_code == 2
    assert "Invalid value for '--allow-read': Directory 'nowhere' does not exist." in result.stderr


def test_trust_expressions_on_the_command_line_reads_anywhere(place: Path) -> None:
    _write(place, _robot('<xacro:include filename="../../outside/part.xacro"/>'))
    result = CliRunner().invoke(
        cli, ["expand", "--trust-expressions", "repo/urdf/robot.urdf.xacro"]
    )
    assert result.exit_code == 0 and 'name="shared_link"' in result.stdout
