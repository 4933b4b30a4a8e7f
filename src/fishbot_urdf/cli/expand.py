"""`fishbot expand`: xacro -> URDF, as ROS's xacro command does, without ROS."""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

import click

from ..errors import FishbotUrdfError

if TYPE_CHECKING:
    from ..expansion import Expansion
from dataclasses import replace

from ..config import Config, find_config, load_config
from ..diagnostics import Severity
from ..expansion import declared_args
from ..expansion import expand as run
from ..expansion._findings import unknown_args, xacro_warning
from ..output import write_atomic
from ..workspace import Workspace
from ._common import (
    EXIT_INVALID,
    EXIT_OK,
    emit_findings,
    inputs_read,
    limit_options,
    output_option,
    package_option,
    packages_option,
    stop_on,
    to_stdout,
    xacro_args,
)


@click.command()
@click.argument("file", type=click.Path())
@click.argument("args", nargs=-1)
@output_option("the URDF")
@click.option("--deps", is_flag=True, help="Print the files the expansion reads instead.")
@click.option(
    "--strict",
    is_flag=True,
    help="Warnings (an argument no file declares, xacro's own) fail: exit 1, nothing written.",
)
@package_option()
@limit_options()
def expand(
    file: str,
    args: Sequence[str],
    output: str,
    deps: bool,
    strict: bool,
    package_items: Sequence[str],
) -> None:
    """Expand a xacro file to URDF, as ROS's xacro command does, without ROS.

    ARGS are name:=value values for <xacro:arg>. $(find PKG) is resolved without ROS:
    --package first, then the package.xml above the file, ROS_PACKAGE_PATH,
    AMENT_PREFIX_PATH, the colcon workspace around the file, and ament_index_python.
    Errors point at the xacro source and the macro calls that led there. An argument that
    no <xacro:arg> declares is a warning (xacro ignores it silently). Files are read only
    in the robot's tree (its git repository, else its package, else its folder), the
    packages $(find) finds, and the folders of --allow-read and of allow-read in the
    nearest [tool.fishbot] (or fishbot.toml), unless --trust-expressions. Exit status: 0 done,
    1 xacro refuses the input (or, with --strict, warns), 2 a file could not be read or
    written, a package was not found, or the command line is wrong.

    \b
    Examples:
      fishbot expand robots/fishbot/urdf/fishbot/fishbot.urdf.xacro
      fishbot expand robot.urdf.xacro use_gpu:=false -o build/robot.urdf
      fishbot expand robot.urdf.xacro --package my_description=src/my_description
      fishbot expand robot.urdf.xacro --allow-read ../shared_descriptions
      fishbot expand robot.urdf.xacro --deps
      fishbot expand --strict robot.urdf.xacro use_sim:=true
    """

    values = xacro_args(args)
    packages = packages_option(package_items)
    read = inputs_read()
    try:
        found = find_config(file)
        config = Config() if found is None else load_config(found)
        workspace = Workspace(packages, keep=0)
        with workspace.reading():
            expansion = run(
                file, args=values, packages=workspace.packages, allow_read=config.allow_read
            )
        findings = [xacro_warning(message, file) for message in expansion.messages]
        if values:
            findings += unknown_args(values, declared_args(expansion), file)
        if strict and findings:
            emit_findings(replace(d, severity=Severity.ERROR) for d in findings)
            sys.exit(EXIT_INVALID)
        if deps:  # like xacro's, but one line in the order first read
            text = " ".join(expansion.dependencies) + "\n" if expansion.dependencies else ""
        else:
            text = expansion.text
        if output == "-":
            to_stdout(text.encode("utf-8", "surrogateescape"))
        else:
            meshes = [] if deps else _mesh_files(expansion, packages)
            # Never over what was read: the file, its includes and YAML files, the meshes
            # it names, the package.xml files its packages were found by, the configuration.
            inputs = [file, *expansion.dependencies, *meshes, *read]
            if found is not None:
                inputs.append(str(found))
            write_atomic(output, text, inputs=inputs)
    except FishbotUrdfError as exc:
        stop_on(exc)
    emit_findings(findings)
    sys.exit(EXIT_OK)


def _mesh_files(expansion: Expansion, packages: dict[str, str]) -> list[str]:
    """The mesh files the expanded robot names that are there, read as far as it reads, and
    found as every command finds them (`fishbot_urdf.analysis.meshpaths`)."""
    # lxml, the model and the reader load only when -o writes a file (`expand` needs none)
    from ..analysis import analyse
    from ..parsing import read

    try:
        robot = read(expansion.text.encode("utf-8", "replace"), path=expansion.path).robot
    except FishbotUrdfError:
        return []
    if robot is None:
        return []
    found = analyse(robot, expansion.path, packages=packages).mesh_paths.found(robot)
    return [str(file) for file in found]
