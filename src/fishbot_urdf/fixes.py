"""The fixes of findings, as text edits of the files that wrote them.

Each fix edits only the file that wrote the element a finding is about, and only a file of
the robot's own package (the nearest folder above the robot file with a ``package.xml``,
else the robot's tree): an include from another package is never edited. What is offered:

- **did you mean**: a name the finding says is unknown, where a close one exists, replaced
  (a link, joint or material name, a Gazebo reference, a mesh file name in the wrong case, a
  xacro property or parameter in ``${...}``): where the name is written literally;
- **mesh-case**: a mesh's file name written as the file is named;
- **mesh-units**: ``scale="0.001 0.001 0.001"`` on the ``<mesh>``;
- **missing-inertial**: the ``<inertial>`` of the link's collision shapes by common_inertia's
  formulas, at water's density (1000 kg/m^3; a guess at the mass: not applied by ``--fix``
  unless unsafe fixes are asked for);
- **a suppression comment** before the element, for any finding that can be silenced
  (offered to an editor; ``--fix`` never silences).

`attach` gives the findings of a check their fixes; ``fishbot check --fix`` applies the safe
ones (`apply`), and the language server offers them all as code actions.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import replace

from .analysis import Analysis
from .catalog.meshes import MESH_CASE, MESH_UNITS
from .catalog.physics import MISSING_INERTIAL
from .diagnostics import Diagnostic, Edit, Fix, from_error
from .errors import FishbotUrdfError
from .location import MacroLocation
from .sourcetext import SourceText, Texts, with_ranges

__all__ = ["WATER", "apply", "attach", "error_finding", "package_folder"]

WATER = 1000.0
"""The density (kg/m^3) the offered ``<inertial>`` is computed at."""

_MEANT = re.compile(r"did you mean (['\"])(.+?)\1\?")
_QUOTED = re.compile(r"'([^']+)'|\"([^\"]+)\"")
_MESH_SCALE = ' scale="0.001 0.001 0.001"'


def package_folder(robot_file: str) -> str:
    """The folder of the robot's own package: the nearest above ``robot_file`` with a
    ``package.xml``, else the folder of the robot file."""
    folder = os.path.dirname(os.path.abspath(robot_file))
    above = folder
    while True:
        if os.path.isfile(os.path.join(above, "package.xml")):
            return above
        parent = os.path.dirname(above)
        if parent == above:
            return folder
        above = parent


def attach(
    findings: Iterable[Diagnostic],
    texts: Texts,
    robot_file: str,
    analysis: Analysis | None,
) -> list[Diagnostic]:
    """``findings``, each with the fixes that apply to it in ``texts`` (files of the package of
    ``robot_file`` only; ``analysis`` for the fixes that compute)."""
    inside = os.path.join(os.path.realpath(package_folder(robot_file)), "")
    findings = list(findings)
    sources = [_source(finding, texts, inside) for finding in findings]
    # A name missed in several places is more likely misspelt where it is defined: replacing
    # each use is offered, not applied. (Two calls of one macro miss it in one place.)
    places: dict[str, set[Edit]] = {}
    for finding, source in zip(findings, sources, strict=True):
        fix = None if source is None else _did_you_mean(finding, source)
        if fix is not None:
            places.setdefault(fix.title, set()).update(fix.edits)
    names = _names(analysis)
    found = []
    for finding, source in zip(findings, sources, strict=True):
        if source is not None:
            fixes = tuple(_fixes(finding, source, analysis, places, names))
            if fixes:
                finding = replace(finding, fixes=finding.fixes + fixes)
        found.append(finding)
    return found


def _names(analysis: Analysis | None) -> frozenset[str]:
    """Every name of the robot's links, joints and materials (what a name mistyped may be
    close to besides the one meant)."""
    if analysis is None:
        return frozenset()
    robot = analysis.robot
    return frozenset(
        [*(link.name for link in robot.links), *(joint.name for joint in robot.joints)]
        + [material.name for material in robot.materials]
    )


def error_finding(
    exc: FishbotUrdfError, texts: Texts, robot_file: str, path: str = "<input>"
) -> Diagnostic:
    """The finding for an error that stopped the robot's reading (a xacro property
    misspelt), with its range and its fixes."""
    (found,) = with_ranges([from_error(exc, path)], texts)
    return attach([found], texts, robot_file, None)[0]


def _source(finding: Diagnostic, texts: Texts, inside: str) -> SourceText | None:
    """The text of the file that wrote the finding's element, if it may be edited."""
    if not (finding.path.startswith("<") or os.path.realpath(finding.path).startswith(inside)):
        return None  # (links resolved: another package's file reached through a link)
    return texts.get(finding.path)


def _fixes(
    finding: Diagnostic,
    source: SourceText,
    analysis: Analysis | None,
    places: Mapping[str, set[Edit]],
    names: frozenset[str],
) -> Iterable[Fix]:
    placed = finding.line is not None and finding.column is not None
    for make in _MAKERS.get(finding.rule, ()) if placed else ():
        fix = make(finding, source, analysis)
        if fix is not None:
            yield fix
    meant = _did_you_mean(finding, source)
    if meant is not None:
        if len(places.get(meant.title, ())) > 1:
            meant = replace(meant, title=f"{meant.title} (or rename what defines it)", safe=False)
        elif not _sure(meant, names):
            meant = replace(meant, safe=False)
        yield meant
    if finding.definition is not None and not finding.definition.fatal:
        silencing = _silencing(finding, source)
        if silencing is not None:
            yield silencing


def _did_you_mean(finding: Diagnostic, source: SourceText) -> Fix | None:
    """The name the hint suggests, in the place of the unknown one the message quotes,
    where the element at the finding writes it literally (a whole attribute value, a name
    in ``${...}``, or the element's text)."""
    meant = _MEANT.search(finding.hint or "")
    if meant is None or finding.line is None or finding.column is None:
        return None
    better = meant.group(2)
    quoted = [a or b for a, b in _QUOTED.findall(finding.message)]
    wrong = [name for name in quoted if name != better and _typo(name, better)]
    attributes = source.attributes(finding.line, finding.column)
    for name in wrong:
        for attribute in attributes:
            if attribute.value == name:
                return _replacing(source, attribute.start, attribute.end, name, better)
        for attribute in attributes:
            for match in re.finditer(r"\$\{[^}]*\}", attribute.value):
                word = re.search(rf"(?<![\w.]){re.escape(name)}(?!\w)", match.group())
                if word is not None:
                    start = attribute.start + match.start() + word.start()
                    return _replacing(source, start, start + len(name), name, better)
        text = _element_text(source, finding.line, finding.column)
        if text is not None and source.text[text[0] : text[1]] == name:
            return _replacing(source, text[0], text[1], name, better)
    return None


def _sure(fix: Fix, names: frozenset[str]) -> bool:
    """Whether a replacement is the only name meant: the names differ in more than a number
    (``link4`` for ``link1`` is a guess among numbered names), and no other name of the
    robot is as close to the one written."""
    found = _REPLACING.match(fix.title)
    if found is None:
        return False
    wrong, better = found.group(1), found.group(2)
    if re.sub(r"\d+", "#", wrong) == re.sub(r"\d+", "#", better):
        return False
    distance = _distance(wrong, better)
    return not any(
        _distance(wrong, name) <= distance for name in names if name not in (wrong, better)
    )


_REPLACING = re.compile(r"replace '(.*)' with '(.*)'$")


def _typo(wrong: str, better: str) -> bool:
    """Whether ``wrong`` is ``better`` mistyped: at most one edit in four characters (a
    letter left out, added, changed, or two swapped), and at least one."""
    return _distance(wrong, better) <= max(1, len(better) // 4)


def _distance(a: str, b: str) -> int:
    """The edits (insert, delete, change, swap two neighbours) that make ``a`` into ``b``."""
    before: list[int] = []
    row = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        now = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = a[i - 1] != b[j - 1]
            now[j] = min(row[j] + 1, now[j - 1] + 1, row[j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                now[j] = min(now[j], before[j - 2] + 1)
        before, row = row, now
    return row[len(b)]


def _element_text(source: SourceText, line: int, column: int) -> tuple[int, int] | None:
    """The span of an element's text (white space around it left out), when the element
    holds text only."""
    tag = source.start_tag(line, column)
    if tag is None or source.text[tag[1] - 2 : tag[1]] == "/>":
        return None
    close = source.text.find("<", tag[1])
    if close < 0:
        return None
    inner = source.text[tag[1] : close]
    start = tag[1] + len(inner) - len(inner.lstrip())
    end = tag[1] + len(inner.rstrip())
    return (start, end) if end > start else None


def _replacing(source: SourceText, start: int, end: int, wrong: str, better: str) -> Fix:
    return Fix(f"replace {wrong!r} with {better!r}", (_edit(source, start, end, better),))


def _edit(source: SourceText, start: int, end: int, text: str) -> Edit:
    line, column = source.position(start)
    end_line, end_column = source.position(end)
    return Edit(source.path, line, column, end_line, end_column, text)


def _mesh_case(finding: Diagnostic, source: SourceText, _: Analysis | None) -> Fix | None:
    """The mesh's file name as the file is named (the message quotes it last)."""
    assert finding.line is not None and finding.column is not None
    quoted = [a or b for a, b in _QUOTED.findall(finding.message)]
    if len(quoted) < 3:
        return None
    wrong, better = quoted[-2], quoted[-1]
    for attribute in source.attributes(finding.line, finding.column):
        if attribute.name == "filename" and attribute.value == wrong:
            return _replacing(source, attribute.start, attribute.end, wrong, better)
    return None


def _mesh_scale(finding: Diagnostic, source: SourceText, _: Analysis | None) -> Fix | None:
    """``scale="0.001 0.001 0.001"`` on a ``<mesh>`` that has no scale (or scale 1)."""
    assert finding.line is not None and finding.column is not None
    tag = source.start_tag(finding.line, finding.column)
    if tag is None or not source.text.startswith("<mesh", tag[0]):
        return None
    scale = [a for a in source.attributes(finding.line, finding.column) if a.name == "scale"]
    title = "scale the mesh from millimetres to metres"
    if scale:
        if [float(v) for v in scale[0].value.split()] != [1.0, 1.0, 1.0]:
            return None
        return Fix(title, (_edit(source, scale[0].start, scale[0].end, "0.001 0.001 0.001"),))
    end = tag[1] - (2 if source.text[tag[1] - 2 : tag[1]] == "/>" else 1)
    while end > tag[0] and source.text[end - 1].isspace():
        end -= 1
    return Fix(title, (_edit(source, end, end, _MESH_SCALE),))


def _inertial(finding: Diagnostic, source: SourceText, analysis: Analysis | None) -> Fix | None:
    """The link's ``<inertial>`` from its collision shapes at water's density, written on the
    line of the link's first child (a link a macro makes is left: its sizes differ by call)."""
    from .inertia import link_inertial, suggest_inertials  # the formulas load only here

    subject = finding.subject
    if analysis is None or subject is None or subject.name not in analysis.links:
        return None
    link = analysis.links[subject.name]
    if isinstance(link.source, MacroLocation) and link.source.calls:
        return None
    if link.inertial is not None or not link.collisions:
        return None
    try:
        inertial = link_inertial(
            link, density=WATER, resolve=analysis.mesh_paths.file, meshes=analysis.meshes
        )
    except FishbotUrdfError:  # a mesh that cannot be read, trimesh not installed
        return None
    (suggestion,) = suggest_inertials(analysis, {subject.name: inertial})
    if suggestion.line is None or suggestion.source is None:
        return None
    line_text = source.line_text(suggestion.line)
    indent = line_text[: len(line_text) - len(line_text.lstrip())]
    unit = "\t" if "\t" in indent else "  "  # the inertial's own rows are indented by two
    rows = []
    for row in suggestion.text.splitlines():
        inner = row.lstrip(" ")
        rows.append(indent + unit * ((len(row) - len(inner)) // 2) + inner + source.newline)
    body = "".join(rows)
    at = source.offset(suggestion.line, 1)
    if at is None:
        return None
    return Fix(
        f"add an <inertial> for {inertial.mass:.3g} kg (its collision shapes at {WATER:g} "
        "kg/m^3: set the real mass)",
        (_edit(source, at, at, body),),
        safe=False,
    )


def _silencing(finding: Diagnostic, source: SourceText) -> Fix | None:
    """A ``fishbot: ignore[RULE]`` comment right before the element the finding is in (or,
    for one with no element, before the root element: for the whole file)."""
    tag = None
    if finding.line is not None and finding.column is not None:
        tag = source.start_tag(finding.line, finding.column)
    where = " in every call of its macro" if finding.calls else ""
    if tag is None:
        root = _ROOT.search(source.text)
        if root is None:
            return None
        tag, where = (root.start(), root.end()), " in the whole file"
    line, column = source.position(tag[0])
    before = source.line_text(line)[: column - 1]
    comment = f"<!-- fishbot: ignore[{finding.rule}] -->"
    text = f"{comment}{source.newline}{before}" if not before.strip() else f"{comment} "
    return Fix(
        f"silence {finding.rule} here{where}",
        (_edit(source, tag[0], tag[0], text),),
        safe=False,
        silences=True,
    )


_ROOT = re.compile(r"<[^\s/>!?][^\s/>]*")  # the first start tag: the root element's


_Maker = Callable[[Diagnostic, SourceText, Analysis | None], Fix | None]
_MAKERS: Mapping[str, tuple[_Maker, ...]] = {
    MESH_CASE.id: (_mesh_case,),
    MESH_UNITS.id: (_mesh_scale,),
    MISSING_INERTIAL.id: (_inertial,),
}


def apply(text: str, edits: Iterable[Edit]) -> str:
    """``text`` with ``edits`` (of this one file) made; an edit that overlaps one made
    before it in the file is left out."""
    source = SourceText("", text)
    spans = []
    for edit in edits:
        start = source.offset(edit.line, edit.column)
        end = source.offset(edit.end_line, edit.end_column)
        if start is not None and end is not None and start <= end:
            spans.append((start, end, edit.text))
    spans.sort(key=lambda span: (span[0], span[1]))
    pieces, at = [], 0
    for start, end, new in spans:
        if start < at:  # overlaps the one before
            continue
        pieces += [text[at:start], new]
        at = end
    pieces.append(text[at:])
    return "".join(pieces)
