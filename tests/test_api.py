"""Drift: the public API resolves, the README's Quickstart is CI's, its pictures are the tools',
and the examples run as written (tests/test_docs.py runs every other command of the README and
the documentation)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

import fishbot_urdf

README = (ROOT / "README.md").read_text(encoding="utf-8")
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


def _quickstart() -> list[str]:
    section = README.split("## Quickstart", 1)[1]
    block = re.search(r"```bash\n(.*?)```", section, re.DOTALL)
    assert block is not None
    return [line for line in block.group(1).splitlines() if line.strip()]


def test_every_name_in_all_resolves() -> None:
    for name in fishbot_urdf.__all__:
        assert getattr(fishbot_urdf, name) is not None, name
    assert sorted(fishbot_urdf.__all__) == fishbot_urdf.__all__


def _attribute_doc(name: str) -> str:
    """The string written below ``name = ...`` in the module that defines it (a type alias's
    docstring, as documentation tools read it)."""
    import ast
    import importlib

    module = importlib.import_module(f"fishbot_urdf.{fishbot_urdf._WHERE[name]}")
    tree = ast.parse(Path(str(module.__file__)).read_text(encoding="utf-8"))
    for node, after in zip(tree.body, tree.body[1:], strict=False):
        targets = node.targets if isinstance(node, ast.Assign) else []
        named = any(isinstance(t, ast.Name) and t.id == name for t in targets)
        if named and isinstance(after, ast.Expr) and isinstance(after.value, ast.Constant):
            return str(after.value.value)
    return ""


def test_every_public_name_has_a_one_line_summary() -> None:
    # The API reference takes each name's first line as its summary: a sentence of its own.
    import inspect

    for name in fishbot_urdf.__all__:
        if name == "__version__":
            continue
        value = getattr(fishbot_urdf, name)
        if inspect.isclass(value) or inspect.isroutine(value):
            doc = inspect.getdoc(value) or ""
        else:  # a type alias
            doc = inspect.cleandoc(_attribute_doc(name))
        lines = doc.splitlines()
        assert lines and lines[0].endswith("."), (name, lines[:1])
        assert len(lines) == 1 or not lines[1].strip(), (name, lines[:2])
        assert len(lines[0]) <= 100, (name, lines[0])


def test_the_3d_picture_and_the_graph_have_names_that_say_so() -> None:
    assert "picture" in fishbot_urdf.__all__ and "render_graph" in fishbot_urdf.__all__
    assert fishbot_urdf.picture.__module__ == "fishbot_urdf.drawing.picture"
    assert fishbot_urdf.render_graph.__module__ == "fishbot_urdf.drawing.dot"


def test_version_comes_from_the_package_metadata() -> None:
    from importlib.metadata import version

    assert fishbot_urdf.__version__ == version("fishbot-urdf")


def test_type_hints_are_shipped() -> None:
    assert (Path(fishbot_urdf.__file__).parent / "py.typed").exists()


def test_quickstart_is_two_commands_and_ci_runs_the_second() -> None:
    commands = _quickstart()
    assert len(commands) == 2
    install_and_check, run_tests = commands
    assert "fishbot check robots/fishbot/" in install_and_check
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert run_tests in ci.splitlines()


def test_quickstart_check_command_runs() -> None:
    # The part after the install: the installed package is the one under test.
    command = _quickstart()[0].split("&&", 1)[1].strip()
    args = command.split()
    assert args[0] == "fishbot"
    proc = subprocess.run(
        [sys.executable, "-m", "fishbot_urdf", *args[1:]],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("robot name is: ")


def test_the_architecture_page_names_every_module() -> None:
    package = Path(fishbot_urdf.__file__).parent
    modules = {p.stem for p in package.iterdir() if p.suffix == ".py" and p.name[0] != "_"}
    modules |= {p.name + "/" for p in package.iterdir() if (p / "__init__.py").exists()}
    page = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    assert sorted(m for m in modules if f"`{m}`" not in page) == []


@pytest.mark.parametrize("example", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_runs(example: Path) -> None:
    proc = subprocess.run(
        [sys.executable, str(example)], capture_output=True, text=True, check=False, cwd=ROOT
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip()
    assert proc.stderr == ""


def _run_example(name: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(ROOT / "examples" / name)], capture_output=True, text=True, check=True
    )


def test_first_robot_example_output() -> None:
    proc = _run_example("inspect_first_robot.py")
    assert proc.stdout.splitlines() == [
        "robot first_robot: 2 links, 1 joints",
        "  link  base_link  cylinder",
        "  link  imu_link   box",
        "  joint imu_joint  fixed      base_link -> imu_link at (0, 0, 0.03) m",
        "check: ok",
    ]


def test_expand_example_output() -> None:
    proc = _run_example("expand_fishbot.py")
    lines = proc.stdout.splitlines()
    # eleven links (the fishbot's parts and its camera's image frame), read from the eight
    # files fishbot.urdf.xacro includes
    assert lines[0] == "robot fishbot: 11 links from 8 files"
    links = [line.split()[1] for line in lines if line.startswith("  link ")]
    assert links[:2] == ["base_footprint", "base_link"]
    assert {"left_wheel_link", "right_wheel_link", "laser_link", "imu_link"} <= set(links)
    assert "  joint left_wheel_joint     continuous base_link -> left_wheel_link" in lines


def test_chain_example_output() -> None:
    proc = _run_example("fishbot_chain.py")
    lines = proc.stdout.splitlines()
    assert lines[:3] == [
        "fishbot: 11 links, 10 joints",
        "tree: yes",
        "chain base_footprint -> laser_link:",
    ]
    hops = [line.split()[0] for line in lines[3:-1]]
    assert hops == ["base_footprint", "base_link", "laser_cylinder_link"]
    assert lines[-2].endswith("--> laser_link")
    # fishbot.urdf.xacro: the body (base_length 0.12) sits on wheels of radius 0.032 sunk
    # 0.001 into the ground; the post is placed 0.10 above the body's centre and the laser
    # half a post (post_length 0.10) above the post's centre.
    height = (0.12 / 2 + 0.032 - 0.001) + 0.10 + 0.10 / 2
    assert lines[-1] == f"laser_link sits at (0, 0, {height:g}) m in base_footprint"


def test_readme_shows_the_fishbot_graph_made_by_the_tool() -> None:
    readme = (ROOT / "README.md").read_text()
    command = (
        "fishbot graph robots/fishbot/urdf/fishbot/fishbot.urdf.xacro -o docs/fishbot-graph.png"
    )
    assert command in readme.replace("\n", " ")
    assert "](docs/fishbot-graph.png)" in readme
    from PIL import Image

    with Image.open(ROOT / "docs" / "fishbot-graph.png") as image:
        image.load()
        assert image.format == "PNG"
        assert image.width > image.height > 300  # a wide tree: ten joints under one base


def test_readme_shows_the_fishbot_rendered_by_the_tool(tmp_path: Path) -> None:
    readme = (ROOT / "README.md").read_text()
    command = "fishbot render robots/fishbot/urdf/fishbot/fishbot.urdf.xacro -o docs/fishbot.png"
    assert command in readme.replace("\n", " ")
    assert "](docs/fishbot.png)" in readme
    import numpy as np
    from PIL import Image

    fresh = tmp_path / "fishbot.png"
    args = command.split()[1:]
    args[args.index("docs/fishbot.png")] = str(fresh)
    subprocess.run([sys.executable, "-m", "fishbot_urdf", *args], cwd=ROOT, check=True)
    with Image.open(ROOT / "docs" / "fishbot.png") as kept, Image.open(fresh) as made:
        assert kept.size == made.size == (800, 600)
        difference = np.abs(np.asarray(kept, dtype=int) - np.asarray(made, dtype=int))
    assert difference.mean() < 0.5  # the picture in the README is the tool's, as it is now


def test_mass_example_output() -> None:
    lines = _run_example("fishbot_mass.py").stdout.splitlines()
    parts = {line.split()[0]: line.split()[1:] for line in lines[1:10]}
    assert len(parts) == 9  # every link but the footprint has a mass
    # left wheel: 0.1 kg, 0.1 m to the left, 0.091 - 0.06 = 0.031 m up
    assert parts["left_wheel_link"] == ["0.1", "0.000", "0.100", "0.031"]
    # By hand: 1.41 kg; x = 0.001 / 1.41, z = 0.13422 / 1.41 (see test_inertia.py).
    assert (
        lines[10]
        == f"total 1.41 kg, centre of mass ({0.001 / 1.41:.4f}, 0.0000, {0.13422 / 1.41:.4f}) m"
    )
    assert lines[12] == "left wheel turned 60 degrees: centre of mass moves 0.0e+00 m"


def test_every_exception_the_library_raises_is_a_fishbot_urdf_error() -> None:
    # Every `raise SomeError(...)` in the library names a FishbotUrdfError subclass (an
    # assertion of an invariant aside), so that `except FishbotUrdfError` catches them all.
    import ast
    import importlib
    import typing

    package = Path(fishbot_urdf.__file__).parent
    raised: set[tuple[str, str]] = set()
    for source in package.rglob("*.py"):
        if "cli" in source.relative_to(package).parts:
            continue  # the command line turns errors into exit statuses
        tree = ast.parse(source.read_text(encoding="utf-8"))
        module = ".".join(("fishbot_urdf", *source.relative_to(package).with_suffix("").parts))
        module = module.removesuffix(".__init__")
        for node in ast.walk(tree):
            if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call):
                func = node.exc.func
                name = func.id if isinstance(func, ast.Name) else getattr(func, "attr", "")
                raised.add((module, name))
    assert raised
    for module, name in sorted(raised):
        # An invariant; the module __getattr__ protocol; signals that never leave the
        # library (the quick pass giving up, the XML model refusing a file: each caught and
        # turned into an error); and xacro's exception, raised inside xacro's run to be
        # turned into a XacroError.
        internal = ("AssertionError", "AttributeError", "_GiveUp", "Refused", "TooDeep")
        if name in (*internal, "XacroException"):
            continue
        # The expression interpreter raises what Python's eval would for the same text,
        # inside xacro's run, which turns it into a XacroError as it does eval's.
        python = ("NameError", "TypeError", "ValueError", "AttributeError")
        if module == "fishbot_urdf.expansion._interpreter" and name in python:
            continue
        # A finding's facts are a Mapping, whose protocol is a KeyError for a missing key.
        if module == "fishbot_urdf.facts" and name == "KeyError":
            continue
        # The language server answers a request it refuses with the protocol's error.
        if module.startswith("fishbot_urdf.lsp.") and name == "JsonRpcException":
            continue
        namespace = vars(importlib.import_module(module))
        cls = namespace.get(name) or getattr(fishbot_urdf.errors, name, None)
        if cls is None:  # a method of a class of the module: self._located(...)
            owners = [c for c in namespace.values() if isinstance(c, type) and hasattr(c, name)]
            cls = getattr(owners[0], name) if owners else None
        if callable(cls) and not isinstance(cls, type):  # a function that builds the error
            cls = typing.get_type_hints(cls)["return"]
        assert isinstance(cls, type), (module, name)
        assert issubclass(cls, fishbot_urdf.FishbotUrdfError), (module, name)
