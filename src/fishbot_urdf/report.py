"""Findings for people and machines: JSON, SARIF 2.1.0 for code scanning, and GitHub
Actions workflow annotations. (One finding per line of text is `Diagnostic.format`.)"""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import quote

from .catalog import all_rules
from .catalog.docs import explanation, markdown_explanation
from .diagnostics import Diagnostic, Severity, escape_controls, shown_path

__all__ = ["FileReport", "github_annotations", "json_report", "sarif_report"]

INFORMATION_URI = "https://pypi.org/project/fishbot-urdf/"
SARIF_SCHEMA = (
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
)
SRCROOT = "%SRCROOT%"
"""The base of the relative URIs of a SARIF log: the folder ``fishbot check`` ran in."""


@dataclass(frozen=True, slots=True)
class FileReport:
    """What checking one file found, for a report.

    Attributes:
        path: The file checked.
        ok: Whether it passed (no error; with strict, no warning either).
        diagnostics: Its findings.
        suppressed: The findings comments silenced.
        robot: The robot's name, when one was read.
        root: Its root link, when it has one.
        links: How many links it has, when one was read.
        joints: How many joints it has, when one was read.
        config: The configuration file that applied, if any.
        targets: The programs it was checked for (none for a file that was not read).
        skipped: Why the file was not checked as a robot (``--skip-includes``), if it was not.
    """

    path: str
    ok: bool
    diagnostics: tuple[Diagnostic, ...]
    suppressed: tuple[Diagnostic, ...] = ()
    robot: str | None = None
    root: str | None = None
    links: int | None = None
    joints: int | None = None
    config: str | None = None
    skipped: str | None = None
    targets: tuple[str, ...] = ()


def json_report(files: Sequence[FileReport]) -> dict[str, Any]:
    """The report of ``fishbot check --format json``, as a dict.

    ``ok`` overall, then per file its robot, the programs it was checked for, its findings
    and how many comments silenced, by rule."""
    return {
        "ok": all(f.ok for f in files),
        "files": [
            {
                "path": f.path,
                "ok": f.ok,
                "robot": f.robot,
                "root": f.root,
                "links": f.links,
                "joints": f.joints,
                "config": f.config,
                "targets": list(f.targets),
                "skipped": f.skipped,
                "diagnostics": [d.to_dict() for d in f.diagnostics],
                "suppressed": {
                    "count": len(f.suppressed),
                    "rules": dict(sorted(Counter(d.rule for d in f.suppressed).items())),
                },
            }
            for f in files
        ],
    }


_LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "note"}


def sarif_report(files: Sequence[FileReport], *, version: str) -> dict[str, Any]:
    """A SARIF 2.1.0 log of one run, for code scanning (GitHub, GitLab, Azure DevOps).

    Every rule of the registry is described (id, summary, explanation, default level,
    family and consumers); every finding is a result with its file, line and column;
    findings that comments silenced are results with an in-source suppression. A file
    inside the current folder is a URI relative to ``%SRCROOT%`` (that folder: the
    checkout, in CI), any other an absolute file: URI.
    """
    rules = all_rules()
    index = {rule.id: i for i, rule in enumerate(rules)}
    results: list[dict[str, Any]] = []
    for report in files:
        for finding, silenced in (
            *((d, False) for d in report.diagnostics),
            *((d, True) for d in report.suppressed),
        ):
            results.append(_result(finding, index, silenced))
    descriptors = [
        {
            "id": rule.id,
            "name": "".join(part.capitalize() for part in rule.id.split("-")),
            "shortDescription": {"text": rule.summary},
            "fullDescription": {"text": rule.explanation or rule.summary},
            "help": {"text": explanation(rule), "markdown": markdown_explanation(rule)},
            "defaultConfiguration": {"level": _LEVELS[rule.severity]},
            "properties": {
                "tags": [rule.family.value],
                "consumers": [c.value for c in rule.consumers],
            },
        }
        for rule in rules
    ]
    return {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "fishbot",
                        "informationUri": INFORMATION_URI,
                        "version": version,
                        "rules": descriptors,
                    }
                },
                "originalUriBaseIds": {SRCROOT: {"uri": Path.cwd().as_uri().rstrip("/") + "/"}},
                "columnKind": "unicodeCodePoints",
                "results": results,
            }
        ],
    }


def _result(finding: Diagnostic, index: dict[str, int], silenced: bool) -> dict[str, Any]:
    text = finding.message + (f" ({finding.hint})" if finding.hint else "")
    location: dict[str, Any] = {"artifactLocation": _artifact(finding.path)}
    if finding.line is not None:
        region: dict[str, int] = {"startLine": finding.line}
        if finding.column is not None:
            region["startColumn"] = finding.column
        if finding.end_line is not None and finding.end_column is not None:
            region["endLine"] = finding.end_line
            region["endColumn"] = finding.end_column
        location["region"] = region
    result: dict[str, Any] = {
        "ruleId": finding.rule,
        "level": _LEVELS[finding.severity],
        "message": {"text": text},
        "locations": [{"physicalLocation": location}],
    }
    if finding.rule in index:
        result["ruleIndex"] = index[finding.rule]
    if finding.subject is not None:
        result["properties"] = {
            "subject": {"kind": finding.subject.kind.value, "name": finding.subject.name}
        }
    if silenced:
        result["suppressions"] = [{"kind": "inSource"}]
    return result


def _artifact(path: str) -> dict[str, str]:
    """Where a file is: a URI relative to the current folder (``%SRCROOT%``, the checkout
    in CI) for a file inside it, else an absolute file: URI."""
    if path.startswith("<"):  # <stdin>, <string>: no file
        return {"uri": quote(path.strip("<>"))}
    shown = shown_path(path)
    if os.path.isabs(shown):
        return {"uri": Path(shown).as_uri()}
    # As bytes: a file name that is no UTF-8 is percent-encoded byte for byte.
    return {
        "uri": quote(os.fsencode(Path(os.path.normpath(shown)).as_posix())),
        "uriBaseId": SRCROOT,
    }


_ANNOTATIONS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.NOTE: "notice"}


def github_annotations(findings: Iterable[Diagnostic]) -> str:
    """GitHub Actions workflow commands, one per finding.

    Each is ``::error file=F,line=L,col=C,title=RULE::message``, which the run's summary
    and the pull request show at the line.

    Each command is one line, with no terminal escape sequence in it: a newline or a
    carriage return is written as GitHub's ``%0A`` and ``%0D`` (which GitHub reads back:
    the annotation finds the file, its message keeps its lines), any other control
    character as in the text format (:func:`fishbot_urdf.diagnostics.escape_controls`:
    ESC as ``\\x1b``)."""
    lines: list[str] = []
    for finding in findings:
        fields = [f"file={_property(shown_path(finding.path))}"]
        if finding.line is not None:
            fields.append(f"line={finding.line}")
            if finding.column is not None:
                fields.append(f"col={finding.column}")
        fields.append(f"title={_property(f'fishbot {finding.rule}')}")
        text = finding.message + (f" ({finding.hint})" if finding.hint else "")
        message = f"{text} [{finding.rule}]"
        lines.append(f"::{_ANNOTATIONS[finding.severity]} {','.join(fields)}::{_data(message)}\n")
    return "".join(lines)


def _data(text: str) -> str:
    encoded = text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    return escape_controls(encoded)


def _property(text: str) -> str:
    return _data(text).replace(":", "%3A").replace(",", "%2C")
