"""What to show about the name at a place, in Markdown."""

from __future__ import annotations

import os

from ..model import Joint, Link
from ..spatial import euler_ypr
from ._names import FileNames, Key
from ._scan import Tag
from ._table import Table
from ._value import evaluate

__all__ = ["hover"]


def hover(table: Table, path: str, line: int, column: int) -> str | None:
    entries = table.at(path, line, column)
    if not entries:
        return None
    parts = [_about(table, key) for key in dict.fromkeys(e.key for e in entries)]
    shown = [part for part in parts if part]
    return "\n\n---\n\n".join(shown) if shown else None


def _about(table: Table, key: Key) -> str | None:
    kind, name, scope = key
    if kind == "file":
        return f"**include** `{name}`"
    robot = table.analysis.robot if table.analysis else None
    where = _defined(table, key)
    if kind == "link":
        link = next((x for x in robot.links if x.name == name), None) if robot else None
        return _link(table, link, name, where)
    if kind == "joint":
        joint = next((x for x in robot.joints if x.name == name), None) if robot else None
        return _joint(joint, name, where)
    if kind == "macro":
        macro = table.macros().get(name)
        if macro is None:
            return f"**macro** `{name}` (not defined in the robot's files)"
        params = [
            f"- `{'*' if p.block else ''}{p.name}`"
            + (f" = `{p.default}`" if p.default is not None else "")
            for p in macro.params.values()
        ]
        return "\n".join([f"**macro** `{name}`", *params, "", where])
    if kind == "param":
        macro = table.macros().get(scope)
        param = macro.params.get(name) if macro else None
        if param is None:
            return f"**parameter** `{name}` of macro `{scope}`"
        default = f", default `{param.default}`" if param.default is not None else ""
        return f"**parameter** `{name}` of macro `{scope}`{default}\n\n{where}"
    if kind == "property":
        return _property(table, key, where)
    if kind == "arg":
        declared = table.args().get(name)
        given = declared.get("default") if declared else None
        shown = f", default `{given.value}`" if given is not None else ""
        return f"**arg** `{name}`{shown}\n\n{where}"
    if kind == "material":
        return f"**material** `{name}`{_colour(table, key)}\n\n{where}"
    return None


def _colour(table: Table, key: Key) -> str:
    """A material's colour or texture, as its definition writes it."""
    for entry in table.by_key.get(key, ()):
        if not entry.definition:
            continue
        doc = table.files[entry.path].document
        tag = doc.tag_at(*doc.position(entry.start))
        for index in tag.children if tag else ():
            child = doc.tags[index]
            value = child.get("rgba") or child.get("filename")
            if value is not None:
                return f": {child.name} `{value.value}`"
    return ""


def _defined(table: Table, key: Key) -> str:
    places = []
    for entry in table.by_key.get(key, ()):
        if entry.definition:
            line, _ = table.files[entry.path].document.position(entry.start)
            places.append(f"{os.path.basename(entry.path)}:{line}")
    return (
        f"defined at {', '.join(dict.fromkeys(places))}"
        if places
        else "not defined in the robot's files"
    )


def _numbers(values: tuple[float, ...]) -> str:
    return " ".join(f"{v:.6g}" for v in values)


def _link(table: Table, link: Link | None, name: str, where: str) -> str:
    lines = [f"**link** `{name}`", ""]
    if link is None:
        return "\n".join([*lines, where])
    inertial = link.inertial
    if inertial is None:
        lines.append("- no inertial")
    else:
        i = inertial.inertia
        lines.append(f"- mass: {inertial.mass:.6g} kg")
        lines.append(
            f"- inertia (kg·m²): ixx {i.ixx:.6g}, ixy {i.ixy:.6g}, ixz {i.ixz:.6g}, "
            f"iyy {i.iyy:.6g}, iyz {i.iyz:.6g}, izz {i.izz:.6g}"
        )
        lines.append(
            f"- inertial origin: xyz {_numbers(inertial.origin.xyz)}, "
            f"rpy {_numbers(inertial.origin.rpy)}"
        )
    pose = table.analysis.zero_poses.get(link.name) if table.analysis else None
    if pose is not None:
        rpy = euler_ypr([list(row) for row in pose.rotation])
        root = table.analysis.root if table.analysis else ""
        lines.append(
            f"- pose in `{root}` at zero: xyz {_numbers(pose.translation)}, rpy {_numbers(rpy)}"
        )
    return "\n".join([*lines, "", where])


def _joint(joint: Joint | None, name: str, where: str) -> str:
    if joint is None:
        return f"**joint** `{name}`\n\n{where}"
    lines = [
        f"**joint** `{name}` ({joint.type.value})",
        "",
        f"- parent `{joint.parent}` → child `{joint.child}`",
        f"- origin: xyz {_numbers(joint.origin.xyz)}, rpy {_numbers(joint.origin.rpy)}",
    ]
    if joint.type.value not in ("fixed", "floating"):
        lines.append(f"- axis: {_numbers(joint.axis)}")
    if joint.limit is not None:
        limit = joint.limit
        lines.append(
            f"- limits: lower {limit.lower:.6g}, upper {limit.upper:.6g}, "
            f"effort {limit.effort:.6g}, velocity {limit.velocity:.6g}"
        )
    return "\n".join([*lines, "", where])


def _property(table: Table, key: Key, where: str) -> str:
    _, name, scope = key
    found = _definition(table, key)
    if found is None:
        return f"**property** `{name}`\n\n{where}"
    names, tag = found
    written = _written(names, tag)
    lines = [f"**property** `{name}`" + (f" in macro `{scope}`" if scope else "")]
    if written is not None:
        lines.append(f"\n```\n{written}\n```")
        value = evaluate(written, _lookup(table))
        if value is not None and value != written.strip():
            lines.append(f"= `{value}`")
    return "\n".join([*lines, "", where])


def _definition(table: Table, key: Key) -> tuple[FileNames, Tag] | None:
    for names in table.files.values():
        tag = names.properties.get(key)
        if tag is not None:
            return names, tag
    return None


def _written(names: FileNames, tag: Tag) -> str | None:
    value = tag.get("value")
    if value is not None:
        return value.value
    text = names.document.inner_text(tag)
    if text is not None:
        return names.document.text[text.start : text.end].strip()
    return None


def _lookup(table: Table):  # type: ignore[no-untyped-def]
    properties = table.properties()

    def written(name: str) -> str | None:
        found = properties.get(name)
        return _written(*found) if found else None

    return written
