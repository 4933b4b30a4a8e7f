"""The documentation says what the tools do: every code block of README.md and docs/ runs
here, and the site builds with ``mkdocs build --strict``.

A page is read as one terminal session, in a scratch folder holding copies of ``robots/``
and ``tests/data/`` (so that paths read as in a clone of the repository), block after
block:

- a block whose lines start with ``$ `` (``console``, or no language) is commands and what
  they print: each command runs in bash, ``fishbot`` and ``python`` being the ones under
  test, and prints exactly the lines shown (standard error and output together, in the
  order a terminal shows them); a line ``...`` stands for any number of lines, and the
  scratch folder's path reads ``~/fishbot-urdf``. ``cd`` and ``$?`` carry over to the
  page's next command;
- ``python`` runs (warnings are errors) and must print nothing on standard error;
  ``pycon`` is a doctest;
- ``yaml`` and ``toml`` must parse, and a TOML block is a configuration ``fishbot`` reads;
  ``xml`` must be well-formed once put inside a ``<robot>``;
- anything else, or a block that cannot run here (an install, a server that runs until
  stopped), carries the marker ``<!-- docs-test: skip REASON -->`` on the line before
  it. ``SKIPPED`` below lists them all, so that a new one is a decision.
"""

from __future__ import annotations

import importlib.util
import inspect
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml
from conftest import DATA, REQUIRE_TOOLS, ROOT, require_tool
from lxml import etree

import fishbot_urdf
from fishbot_urdf.catalog import Consumer, all_rules

if sys.version_info >= (3, 11):
    import tomllib
else:  # the tomli the project depends on there
    import tomli as tomllib

DOCS = ROOT / "docs"
PAGES = [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]
SKIP = re.compile(r"^\s*<!-- docs-test: skip (?P<reason>\S.*?) -->\s*$")
FENCE = re.compile(r"^(?P<indent> *)(?P<fence>`{3,}|~{3,})\s*(?P<info>[\w+-]*)[^`]*$")
HOME = "~/fishbot-urdf"  # what the scratch folder's path is shown as

# Every block that does not run, by page: (a few words of its reason).
SKIPPED = {
    "README.md": ["installs fishbot-urdf", "makes a virtual environment", "runs until stopped"],
    "docs/commands/view.md": ["runs until stopped", "needs a Python without viser"],
    "docs/development.md": [
        "installs the ROS tools",
        "installs sdformat's converter",
        "a long fuzzing campaign",
    ],
    "docs/editors.md": [
        "installs fishbot-urdf",
        "an editor's settings",
        "an editor's settings",
        "an editor's settings, not fishbot's",
        "an editor's settings",
    ],
    "docs/commands/sim.md": ["it installs from PyPI", "one run's numbers", "runs until stopped"],
    "docs/gazebo.md": ["needs ROS 2 and Gazebo Classic"],
    "docs/trust.md": ["runs a file's code"],
}


@dataclass(frozen=True)
class Block:
    """One fenced code block of a page."""

    page: Path
    line: int  # of the opening fence, from 1
    lang: str
    text: str
    skip: str | None

    @property
    def where(self) -> str:
        return f"{_name(self.page)}:{self.line}"

    @property
    def kind(self) -> str:
        if self.lang in ("", "console") and self.text.startswith("$ "):
            return "console"
        return "console block without a $ command" if self.lang == "console" else self.lang


def blocks(page: Path) -> list[Block]:
    """The fenced code blocks of ``page``, in order."""
    lines = page.read_text(encoding="utf-8").splitlines()
    found: list[Block] = []
    index = 0
    while index < len(lines):
        opening = FENCE.match(lines[index])
        if opening is None:
            index += 1
            continue
        indent, fence = len(opening["indent"]), opening["fence"]
        above = next((x for x in reversed(lines[:index]) if x.strip()), "")
        marker = SKIP.match(above)
        body: list[str] = []
        index += 1
        while index < len(lines) and not (
            lines[index].strip().startswith(fence) and lines[index].strip().strip(fence[0]) == ""
        ):
            body.append(lines[index][indent:])
            index += 1
        text = "\n".join(body) + "\n"
        start = index - len(body)
        found.append(
            Block(page, start, opening["info"], text, marker["reason"] if marker else None)
        )
        index += 1
    return found


# ------------------------------------------------------------------ running a page


@dataclass
class Session:
    """A page's terminal: its scratch folder, current folder and environment."""

    home: Path
    cwd: Path
    env: dict[str, str]
    status: int = 0  # of the last command


def _session(tmp_path: Path) -> Session:
    home = tmp_path / "fishbot-urdf"
    shutil.copytree(ROOT / "robots", home / "robots")
    shutil.copytree(DATA, home / "tests" / "data")
    bin = tmp_path / "bin"
    bin.mkdir()
    # The fishbot command and the Python under test, whatever is on PATH (scripts, not
    # links: a link to a virtual environment's python is outside the environment).
    for name, run in (("fishbot", "-m fishbot_urdf "), ("python", "")):
        (bin / name).write_text(f'#!/bin/sh\nexec "{sys.executable}" {run}"$@"\n')
        (bin / name).chmod(0o755)
    src = str(Path(fishbot_urdf.__file__).parent.parent)
    env = {
        **os.environ,
        "PATH": f"{bin}{os.pathsep}{os.environ.get('PATH', '')}",
        "PYTHONPATH": os.pathsep.join(p for p in (src, os.environ.get("PYTHONPATH")) if p),
        # the order a terminal shows: standard output is not held back behind stderr
        "PYTHONUNBUFFERED": "1",
        "COLUMNS": "80",
    }
    return Session(home, home, env)


def commands(text: str) -> list[tuple[str, list[str]]]:
    """A console block's commands, each with the lines shown after it."""
    found: list[tuple[str, list[str]]] = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index]
        assert line.startswith("$ "), line
        command = line[2:]
        while command.endswith("\\") and index + 1 < len(lines):
            index += 1
            command = command[:-1] + lines[index].removeprefix("> ")
        index += 1
        shown: list[str] = []
        while index < len(lines) and not lines[index].startswith("$ "):
            shown.append(lines[index].rstrip())
            index += 1
        found.append((command, shown))
    return found


def matches(shown: list[str], real: list[str]) -> bool:
    """Whether ``real`` is ``shown``, each ``...`` line standing for any number of lines."""
    if not shown:
        return not real
    if shown[0] == "...":
        return any(matches(shown[1:], real[start:]) for start in range(len(real) + 1))
    return bool(real) and real[0] == shown[0] and matches(shown[1:], real[1:])


def _run_console(block: Block, session: Session) -> list[str]:
    problems = []
    for command, shown in commands(block.text):
        marker = session.home.parent / ".cwd"
        # `$?` is the status of the page's command before
        script = f'cd "$1" || exit 2\n(exit $3)\n{command}\nstatus=$?\npwd > "$2"\nexit $status\n'
        argv = [str(session.cwd), str(marker), str(session.status)]
        proc = subprocess.run(
            ["bash", "-c", script, "bash", *argv],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=session.env,
            timeout=300,
            check=False,
        )
        session.status = proc.returncode
        if marker.exists():
            session.cwd = Path(marker.read_text().strip())
        # the scratch folder reads as a clone in the reader's home folder
        printed = proc.stdout.replace(str(session.home), HOME)
        real = [line.rstrip() for line in printed.splitlines()]
        while shown and shown[-1] == "":
            shown = shown[:-1]
        if not matches(shown, real):
            problems.append(
                f"{block.where}: `$ {command}` printed:\n"
                + "\n".join(real)
                + "\n--- the page shows:\n"
                + "\n".join(shown)
            )
    return problems


def _run_python(block: Block, session: Session) -> list[str]:
    script = session.home.parent / ("block.txt" if block.kind == "pycon" else "block.py")
    script.write_text(block.text, encoding="utf-8")
    run = [str(script)]
    if block.kind == "pycon":
        run = ["-m", "doctest", "-o", "ELLIPSIS", "-o", "NORMALIZE_WHITESPACE", str(script)]
    proc = subprocess.run(
        [sys.executable, "-W", "error", *run],
        cwd=session.cwd,
        env=session.env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    if proc.returncode != 0 or proc.stderr:
        return [f"{block.where}: the {block.kind} block fails:\n{proc.stdout}{proc.stderr}"]
    return []


def _check_data(block: Block, session: Session) -> list[str]:
    try:
        if block.kind == "yaml":
            assert isinstance(yaml.safe_load(block.text), dict | list)
        elif block.kind == "xml":
            xacro = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
            etree.fromstring(f'<robot name="docs" {xacro}>\n{block.text}</robot>'.encode())
        else:
            data = tomllib.loads(block.text)
            folder = session.home.parent / "config"
            folder.mkdir(exist_ok=True)
            name = "pyproject.toml" if "tool" in data else "fishbot.toml"
            (folder / name).write_text(block.text, encoding="utf-8")
            fishbot_urdf.load_config(folder / name)
    except (AssertionError, yaml.YAMLError, etree.XMLSyntaxError, ValueError) as exc:
        return [f"{block.where}: the {block.kind} block does not read: {exc}"]
    except fishbot_urdf.FishbotUrdfError as exc:
        return [f"{block.where}: fishbot refuses the configuration: {exc}"]
    return []


def run_page(page: Path, tmp_path: Path) -> list[str]:
    """Run every block of ``page``; the problems found, one text each."""
    session = _session(tmp_path)
    problems: list[str] = []
    for block in blocks(page):
        if block.skip is not None:
            continue
        if block.kind == "console":
            problems += _run_console(block, session)
        elif block.kind in ("python", "pycon"):
            problems += _run_python(block, session)
        elif block.kind in ("yaml", "toml", "xml"):
            problems += _check_data(block, session)
        else:
            problems.append(
                f"{block.where}: a {block.kind or 'plain'} block that neither runs nor "
                "says why (<!-- docs-test: skip REASON -->)"
            )
    return problems


def _name(page: Path) -> str:
    return page.relative_to(ROOT).as_posix() if page.is_relative_to(ROOT) else str(page)


@pytest.mark.parametrize("page", PAGES, ids=[_name(p) for p in PAGES])
def test_every_block_of_the_page_runs_as_shown(page: Path, tmp_path: Path) -> None:
    if any("fishbot graph" in b.text for b in blocks(page) if b.skip is None):
        require_tool("dot", "graphviz")  # urdf_to_graphviz's way: the PDF too
    problems = run_page(page, tmp_path)
    assert not problems, "\n\n".join(problems)


def test_the_blocks_that_do_not_run_are_these() -> None:
    skipped = {
        _name(page): [b.skip or "" for b in blocks(page) if b.skip is not None] for page in PAGES
    }
    skipped = {page: reasons for page, reasons in skipped.items() if reasons}
    assert skipped.keys() == SKIPPED.keys(), skipped
    for page, reasons in skipped.items():
        assert len(reasons) == len(SKIPPED[page]), (page, reasons)
        for words, reason in zip(SKIPPED[page], reasons, strict=True):
            assert reason.startswith(words), (page, reason)


def test_blocks_are_found() -> None:
    found = [b for page in PAGES for b in blocks(page)]
    kinds = {b.kind for b in found}
    assert {"console", "python", "yaml", "toml"} <= kinds
    assert sum(b.kind == "console" for b in found) >= 20


# ------------------------------------------------------------------ the runner itself


def test_a_session_that_prints_something_else_fails(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(
        "```console\n$ fishbot check robots/fishbot/urdf/first_robot.urdf\nrobot name is: x\n```\n"
    )
    problems = run_page(page, tmp_path / "run")
    assert len(problems) == 1
    assert "robot name is: first_robot" in problems[0]


def test_ellipsis_cd_and_python_blocks(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(
        "```console\n$ cd robots/fishbot/urdf\n"
        "$ fishbot check first_robot.urdf\nrobot name is: first_robot\n...\n$ echo $?\n0\n```\n\n"
        '```python\nimport fishbot_urdf\nassert fishbot_urdf.load("first_robot.urdf")\n```\n\n'
        "```pycon\n>>> 1 + 1\n2\n```\n\n"
        "<!-- docs-test: skip needs a network -->\n```bash\npip install x\n```\n\n"
        "```text\nnot run\n```\n"
    )
    problems = run_page(page, tmp_path / "run")
    assert len(problems) == 1
    assert "a text block that neither runs nor says why" in problems[0]
    assert [b.skip for b in blocks(page)] == [None, None, None, "needs a network", None]


def test_matching_with_ellipses() -> None:
    assert matches(["a", "...", "d"], ["a", "b", "c", "d"])
    assert matches(["a", "..."], ["a"])
    assert not matches(["a", "d"], ["a", "b", "d"])
    assert not matches(["...", "x"], ["a", "b"])


# ------------------------------------------------------------------ the site


def _require_mkdocs() -> None:
    for module in ("mkdocs", "material", "mkdocstrings_handlers.python"):
        if importlib.util.find_spec(module) is None:
            message = f"{module} is not installed (pip install -e '.[docs]')"
            if REQUIRE_TOOLS:
                pytest.fail(message + "; FISHBOT_REQUIRE_TOOLS=1 forbids skipping")
            pytest.skip(message)


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site, built with ``mkdocs build --strict`` from this checkout."""
    _require_mkdocs()
    folder = tmp_path_factory.mktemp("site")
    src = str(Path(fishbot_urdf.__file__).parent.parent)
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")]),
        "NO_MKDOCS_2_WARNING": "1",
    }
    proc = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(folder)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
        check=False,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "WARNING" not in proc.stderr, proc.stderr
    return folder


def _html(site: Path, page: str) -> str:
    return (site / page / "index.html").read_text(encoding="utf-8")


def _text(html: str) -> str:
    """The words of a page, tags and entities aside, white space as single spaces."""
    import html as entities

    inline = re.sub(r"</?(?:code|a|em|strong|span|abbr)\b[^>]*>", "", html)
    return " ".join(entities.unescape(re.sub(r"<[^>]+>", " ", inline)).split())


def test_the_site_builds_strictly(site: Path) -> None:
    home = (site / "index.html").read_text(encoding="utf-8")
    assert "fishbot-urdf" in home
    assert (site / "fishbot.png").exists()


def test_every_rule_has_its_page_made_from_the_registry(site: Path) -> None:
    table = _text(_html(site, "rules"))
    for rule in all_rules():
        page = _text(_html(site, f"rules/{rule.id}"))
        assert rule.id in page
        assert " ".join(rule.summary.replace("`", "").split()) in page.replace("`", ""), rule.id
        assert rule.id in table
        assert f'href="{rule.id}/"' in _html(site, "rules"), rule.id


def test_the_configuration_page_has_one_table_of_rules_and_programs(site: Path) -> None:
    """Made from the catalogue: a row per rule that names programs, linked to its page, a
    column per program, ticked where the rule names it."""
    html = _html(site, "configuration")
    tables = [t for t in re.findall(r"<table>.*?</table>", html, re.S) if "xml-tools" in t]
    assert len(tables) == 1
    rows = re.findall(r"<tr>(.*?)</tr>", tables[0], re.S)
    header = re.findall(r"<th[^>]*>(.*?)</th>", rows[0])
    assert header == ["rule", "severity", *(c.value for c in Consumer)]
    named = [rule for rule in all_rules() if rule.consumers]
    assert len(rows) == 1 + len(named)
    for rule, row in zip(named, rows[1:], strict=True):
        cells = re.findall(r"<td[^>]*>(.*?)</td>", row, re.S)
        assert f'href="../rules/{rule.id}/"' in cells[0], rule.id
        ticked = [c for c, cell in zip(Consumer, cells[2:], strict=True) if cell == "✓"]
        assert ticked == [c for c in Consumer if c in rule.consumers], rule.id


def _summary(name: str) -> str:
    obj = getattr(fishbot_urdf, name)
    doc = inspect.getdoc(obj) if callable(obj) else None
    return (doc or "").strip().split("\n\n", 1)[0].replace("\n", " ")


def test_the_api_page_lists_every_public_name_with_its_summary(site: Path) -> None:
    page = _text(_html(site, "api"))
    for name in fishbot_urdf.__all__:
        assert name in page, name
        summary = _summary(name)
        if summary:
            assert " ".join(summary.replace("`", "").split()) in page.replace("`", ""), name


def test_each_command_has_its_page(site: Path) -> None:
    from fishbot_urdf.cli import cli

    commands = set(cli.list_commands(None))  # type: ignore[arg-type]
    assert commands == {
        "check",
        "expand",
        "graph",
        "inertia",
        "lsp",
        "mjcf",
        "sim",
        "render",
        "rules",
        "sdf",
        "tf",
        "view",
    }
    pages = {"lsp": "editors"}  # a server, set up in each editor
    for command in commands:
        page = pages.get(command, f"commands/{command}")
        assert f"fishbot {command}" in _text(_html(site, page))


def test_every_rule_page_is_in_the_navigation(site: Path) -> None:
    """No page is left for the search box alone: the navigation lists each rule's page,
    under its family."""
    nav = _html(site, "commands/check").split('class="md-content"', 1)[0]
    for rule in all_rules():
        assert f'href="../../rules/{rule.id}/"' in nav, rule.id
    families = _text(nav)
    for family in ("XML", "Structure", "Joints", "Meshes", "Physics", "Xacro"):
        assert f" {family} " in families, family


def _browse(site: Path, page: str, script: str) -> Any:
    """What ``script`` returns on ``page`` of the site, open in headless Chromium at a
    laptop's window size (1280 x 900)."""
    from test_view import headless_chromium

    driver = headless_chromium()
    try:
        driver.set_window_size(1280, 900)
        driver.get((site / page).as_uri())
        return driver.execute_script(script)
    finally:
        driver.quit()


def test_the_home_page_shows_the_link_tree_large_enough_to_read(site: Path) -> None:
    # Graphviz's labels are 14-point text: drawn at less than 60% they are 8 pixels high.
    width, natural = _browse(
        site,
        "index.html",
        "const img = [...document.images].find(i => i.src.endsWith('fishbot-graph.png'));"
        "return [img.getBoundingClientRect().width, img.naturalWidth];",
    )
    assert natural > 1000
    assert width >= 0.6 * natural


@pytest.mark.parametrize("page", ["index.html", "commands/check/index.html"])
def test_long_lines_of_code_wrap_instead_of_running_off_the_page(site: Path, page: str) -> None:
    blocks, beyond = _browse(
        site,
        page,
        "const codes = [...document.querySelectorAll('pre > code')];"
        "return [codes.length, codes.filter(c => c.scrollWidth > c.clientWidth + 1).length];",
    )
    assert blocks > 3
    assert beyond == 0
