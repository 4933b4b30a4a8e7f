"""MkDocs hooks: the pages the site makes, as it builds, from the project itself.

- the home page is README.md (its links into docs/ made relative to the site), shown
  without the side bars so that its pictures have the page's width;
- the rule list and one page per rule come from the rule registry (`fishbot_urdf.catalog`),
  the text `fishbot rules --format markdown` prints, and the navigation lists those pages by
  family; so does the configuration page's table of the programs each rule matters to;
- the API page lists every name of `fishbot_urdf.__all__` with its one-line summary, then
  each one's reference from its docstring (mkdocstrings).

Nothing here is written into docs/: no copy of the registry or the docstrings can go stale.
"""

from __future__ import annotations

import ast
import inspect
import re
import types
import typing
from pathlib import Path
from typing import Any

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import File, Files
from mkdocs.structure.pages import Page

import fishbot_urdf
from fishbot_urdf.catalog import Rule, all_rules
from fishbot_urdf.catalog.docs import (
    markdown_explanation,
    with_consumer_table,
    with_rule_table,
)

ROOT = Path(__file__).resolve().parent.parent
API_MARKER = "<!-- api: the names of fishbot_urdf.__all__, made by docs/hooks.py -->"

# The API page's sections, by the module a name comes from, in a reader's order.
SECTIONS = {
    "parsing": "Reading a robot",
    "expansion": "Expanding xacro",
    "model": "The robot model",
    "lint": "Checking",
    "diagnostics": "Findings",
    "config": "Configuration",
    "report": "Reports for programs",
    "catalog": "Rules",
    "graph": "The link tree",
    "analysis": "Analysis",
    "kinematics": "Kinematics",
    "spatial": "Poses",
    "inertia": "Mass and inertia",
    "write": "Writing URDF",
    "drawing": "Drawing",
    "packages": "ROS packages without ROS",
    "location": "Places in files",
    "errors": "Errors",
}


# Family names the navigation writes in capitals; the others are capitalised.
ACRONYMS = {"xml": "XML", "urdf": "URDF"}


def on_config(config: MkDocsConfig) -> MkDocsConfig:
    """The navigation's Rules entry becomes the list of rules, by family, each under its id,
    so that every generated rule page is in the navigation."""
    nav = config.nav or []
    for index, entry in enumerate(nav):
        if isinstance(entry, dict) and entry.get("Rules") == "rules/index.md":
            nav[index] = {"Rules": [{"All rules": "rules/index.md"}, *_rule_sections()]}
    return config


def _rule_sections() -> list[dict[str, list[dict[str, str]]]]:
    families: dict[str, list[dict[str, str]]] = {}
    for rule in all_rules():
        title = ACRONYMS.get(rule.family.value, rule.family.value.capitalize())
        families.setdefault(title, []).append({rule.id: f"rules/{rule.id}.md"})
    return [{title: entries} for title, entries in families.items()]


def on_files(files: Files, config: MkDocsConfig) -> Files:
    """One page per rule, rules/ID.md, from the registry."""
    for rule in all_rules():
        files.append(File.generated(config, f"rules/{rule.id}.md", content=_rule_page(rule)))
    return files


def on_page_markdown(markdown: str, page: Page, config: MkDocsConfig, files: Files) -> str:
    if page.file.src_uri == "index.md":
        # The page's whole width for the pictures: the link tree is 1,700 pixels wide.
        page.meta["hide"] = ["navigation", "toc"]
        return _home()
    if page.file.src_uri == "rules/index.md":
        return _linked_rule_table(with_rule_table(markdown, all_rules()))
    if page.file.src_uri == "configuration.md":
        return _linked_rule_table(with_consumer_table(markdown, all_rules()), "rules/")
    if page.file.src_uri == "api.md":
        return markdown.replace(API_MARKER, _api())
    return markdown


def _home() -> str:
    """README.md, its links into docs/ made relative to the site's root."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    return re.sub(r"\]\(docs/", "](", readme)


def _rule_page(rule: Rule) -> str:
    heading, body = markdown_explanation(rule).split("\n", 1)
    title = heading.removeprefix("## ")
    back = f"[All rules](index.md). In a terminal: `fishbot rules {rule.id}`."
    return f"# {title}\n{body}\n{back}\n"


def _linked_rule_table(markdown: str, folder: str = "") -> str:
    """Each rule id of the table linked to its page (in ``folder``, from the page's own)."""
    link = rf"| [`\1`]({folder}\1.md) |"
    return re.sub(r"^\| `([a-z0-9-]+)` \|", link, markdown, flags=re.MULTILINE)


def _sources() -> dict[str, str]:
    """Each public name -> the module it is imported from (the package's own list, read from
    its `if TYPE_CHECKING:` imports)."""
    tree = ast.parse(Path(fishbot_urdf.__file__).read_text(encoding="utf-8"))
    found: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
            for alias in node.names:
                found[alias.asname or alias.name] = node.module
    return found


def summary(name: str) -> str:
    """The first paragraph of the docstring of `fishbot_urdf.<name>`, on one line."""
    if name == "__version__":
        return "The installed version of fishbot-urdf (from the package's metadata)."
    value: Any = getattr(fishbot_urdf, name)
    if isinstance(value, types.UnionType):
        return "Any of " + ", ".join(f"`{t.__name__}`" for t in typing.get_args(value)) + "."
    doc = inspect.getdoc(value) or ""
    return " ".join(doc.strip().split("\n\n", 1)[0].split())


def _markdown(text: str) -> str:
    """A summary in a Markdown table: a bare tag such as <inertial> shown as code (Markdown
    would drop it as HTML), a | escaped."""
    return re.sub(r"(?<!`)(<[^<>`]+>)(?!`)", r"`\1`", text).replace("|", "\\|")


def _kind(name: str) -> str:
    value: Any = getattr(fishbot_urdf, name, None)
    if isinstance(value, type):
        if issubclass(value, BaseException):
            return "exception"
        return "enum" if issubclass(value, __import__("enum").Enum) else "class"
    if callable(value):
        return "function"
    return "type" if isinstance(value, types.UnionType) else "constant"


def _api() -> str:
    sources = _sources()
    groups: dict[str, list[str]] = {}
    for name in fishbot_urdf.__all__:
        if name == "__version__":
            continue
        top = sources.get(name, "other").split(".")[0]
        groups.setdefault(top, []).append(name)
    order = [g for g in SECTIONS if g in groups] + sorted(g for g in groups if g not in SECTIONS)
    lines = ["| name | kind | summary |", "| --- | --- | --- |"]
    for group in order:
        for name in groups[group]:
            text = _markdown(summary(name))
            lines.append(f"| [`{name}`][fishbot_urdf.{name}] | {_kind(name)} | {text} |")
    lines.append(f"| `__version__` | constant | {summary('__version__')} |")
    parts = ["\n".join(lines)]
    for group in order:
        parts.append(f"## {SECTIONS.get(group, group)}")
        parts.extend(f"::: fishbot_urdf.{name}" for name in groups[group])
    return "\n\n".join(parts) + "\n"
