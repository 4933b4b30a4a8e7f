"""Robot -> diagnostics: everything check_urdf rejects, then what it lets through."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from .diagnostics import Diagnostic, Severity, closest, listing, sort_key
from .graph import Topology, topology
from .model import Joint, Location, Robot
from .parse import read
from .physics import GROUND_TOLERANCE, physics
from .xmlsource import diagnostic

__all__ = ["CheckResult", "check", "check_file"]


@dataclass(frozen=True, slots=True)
class CheckResult:
    """The outcome of checking one file.

    Attributes:
        path: The file checked.
        robot: The robot as read (possibly faulty), or None if there was no <robot>.
        diagnostics: Every finding, sorted by position.
        topology: The link structure, when there is a robot.
        files: Every file the robot was read from (for xacro, with everything it includes).
        data: The URDF read: the file's bytes, or a xacro file's expansion.
    """

    path: str
    robot: Robot | None
    diagnostics: tuple[Diagnostic, ...]
    topology: Topology | None
    files: tuple[str, ...] = ()
    data: bytes = field(default=b"", repr=False)

    @property
    def ok(self) -> bool:
        """True when there is a robot and no finding is an error."""
        return self.robot is not None and not any(d.is_error for d in self.diagnostics)


def check_file(
    source: str | Path | bytes,
    *,
    path: str | None = None,
    args: Mapping[str, str] | None = None,
    packages: Mapping[str, str | Path] | None = None,
    ground_tolerance: float = GROUND_TOLERANCE,
) -> CheckResult:
    """Read and check one URDF or xacro file, collecting every finding.

    A xacro file is expanded with ``args`` and ``packages`` first; findings then point at the
    xacro source. ``ground_tolerance`` (m) is how far the lowest collision point may lie
    below or above the ground (z = 0 of a footprint root link) before it is reported.

    Raises:
        InputError: The file cannot be read.
        XmlSyntaxError: The file is not well-formed XML.
        XacroError: The xacro file cannot be expanded.
        PackageNotFoundError: The xacro file names a package that is not found.
    """
    parsed = read(source, path=path, args=args, packages=packages)
    if parsed.robot is None:
        return CheckResult(parsed.path, None, parsed.diagnostics, None, parsed.files, parsed.data)
    topo = topology(parsed.robot)
    found = list(parsed.diagnostics)
    # A link whose numbers could not be read has no trustworthy mass: its physics findings
    # would only repeat the fault (a mass of "1kg" read as none is no "massless link").
    unread = tuple(
        d.message.split("'", 2)[1]
        for d in parsed.diagnostics
        if d.is_error and d.message.startswith("link '")
    )
    for finding in _rules(parsed.robot, topo, parsed.path, ground_tolerance):
        if not (unread and finding.message.startswith(tuple(f"link {n!r}" for n in unread))):
            found.append(finding)
    found.sort(key=sort_key)
    return CheckResult(parsed.path, parsed.robot, tuple(found), topo, parsed.files, parsed.data)


def check(robot: Robot, *, ground_tolerance: float = GROUND_TOLERANCE) -> tuple[Diagnostic, ...]:
    """Check a robot's structure and values; returns every finding, sorted by position.

    ``ground_tolerance`` (m): see `check_file`.
    """
    path = robot.source.path if robot.source else "<robot>"
    found = _rules(robot, topology(robot), path, ground_tolerance)
    return tuple(sorted(found, key=sort_key))


def _rules(
    robot: Robot, topo: Topology, path: str, ground_tolerance: float = GROUND_TOLERANCE
) -> Iterator[Diagnostic]:
    yield from _names(robot, path)
    yield from _joints(robot, path)
    yield from _structure(robot, topo, path)
    yield from physics(robot, path, ground_tolerance=ground_tolerance)


def _at(
    rule: str,
    message: str,
    where: Location | None,
    path: str,
    hint: str | None = None,
    severity: Severity = Severity.ERROR,
) -> Diagnostic:
    return diagnostic(rule, message, where, hint=hint, severity=severity, path=path)


def _robot(robot: Robot) -> str:
    """How findings name the robot (a nameless one is reported separately)."""
    return f"robot {robot.name!r}" if robot.name else "the robot"


def _names(robot: Robot, path: str) -> Iterator[Diagnostic]:
    if not robot.links:
        yield _at(
            "no-links",
            f"{_robot(robot)} has no links",
            robot.source,
            path,
            'a robot needs at least one <link name="...">',
        )
    for kind, items in (
        ("link", robot.links),
        ("joint", robot.joints),
        ("material", robot.materials),
    ):
        first: dict[str, Location | None] = {}
        for item in items:
            if not item.name:
                continue
            if item.name in first:
                where = first[item.name]
                seen = f" (first defined at line {where.line})" if where else ""
                yield _at(
                    f"duplicate-{kind}",
                    f"{kind} {item.name!r} is defined twice{seen}",
                    item.source,
                    path,
                    f"every {kind} needs a unique name",
                )
            else:
                first[item.name] = item.source


def _suggest(name: str, candidates: Iterable[str]) -> str:
    names = set(candidates)
    close = closest(name, names)
    guess = f"did you mean {close!r}? " if close else ""
    return f"{guess}links: {listing(names)}" if names else "the robot defines no links"


def _joints(robot: Robot, path: str) -> Iterator[Diagnostic]:
    link_names = {link.name for link in robot.links}
    joint_names = {joint.name for joint in robot.joints}
    for joint in robot.joints:
        owner = f"joint {joint.name!r}"
        for end, name, where in (
            ("parent", joint.parent, joint.parent_source),
            ("child", joint.child, joint.child_source),
        ):
            if name and name not in link_names:
                yield _at(
                    "undefined-link",
                    f"{owner}: {end} link {name!r} is not defined",
                    where or joint.source,
                    path,
                    _suggest(name, link_names),
                )
        if joint.parent and joint.parent == joint.child:
            yield _at(
                "joint-self-loop",
                f"{owner}: parent and child are the same link {joint.parent!r}",
                joint.child_source or joint.source,
                path,
                "a joint connects two different links",
            )
        yield from _limits(joint, owner, path)
        if joint.type.uses_axis and joint.axis == (0.0, 0.0, 0.0):
            yield _at(
                "zero-axis",
                f"{owner}: the axis is 0 0 0, so the joint cannot move",
                joint.source,
                path,
                'give a unit vector, e.g. <axis xyz="0 0 1"/>',
            )
        if joint.mimic is not None and joint.mimic.joint:
            if joint.mimic.joint not in joint_names:
                close = closest(joint.mimic.joint, joint_names)
                yield _at(
                    "undefined-mimic",
                    f"{owner}: mimics joint {joint.mimic.joint!r}, which is not defined",
                    joint.mimic.source,
                    path,
                    f"did you mean {close!r}?" if close else "name an existing joint",
                )
            elif joint.mimic.joint == joint.name:
                yield _at(
                    "undefined-mimic",
                    f"{owner}: mimics itself",
                    joint.mimic.source,
                    path,
                    "name another joint",
                )


def _limits(joint: Joint, owner: str, path: str) -> Iterator[Diagnostic]:
    limit = joint.limit
    if limit is None:
        if joint.type.needs_limit:
            yield _at(
                "missing-limit",
                f"{owner}: a {joint.type.value} joint needs <limit>",
                joint.source,
                path,
                'write <limit lower=".." upper=".." effort=".." velocity=".."/>',
            )
        return
    if joint.type.needs_limit and limit.lower > limit.upper:
        yield _at(
            "limit-range",
            f"{owner}: lower limit {limit.lower:g} is above upper limit {limit.upper:g}",
            limit.source,
            path,
            "swap them, lower <= upper",
        )
    for name in ("effort", "velocity"):
        value = getattr(limit, name)
        if value < 0:
            yield _at(
                "negative-limit",
                f"{owner}: {name} limit {value:g} is negative",
                limit.source,
                path,
                f"{name} is a magnitude, >= 0",
            )


def _structure(robot: Robot, topo: Topology, path: str) -> Iterator[Diagnostic]:
    if not robot.links:
        return
    by_name = {link.name: link for link in robot.links}
    for name, joints in topo.parents.items():
        if len(joints) > 1:
            listed = ", ".join(repr(j.name) for j in joints)
            yield _at(
                "multiple-parents",
                f"link {name!r} is the child of {len(joints)} joints: {listed}",
                joints[1].child_source or joints[1].source,
                path,
                "a link has one parent joint; in a URDF tree loops are not allowed",
            )
    # A joint with a missing or misspelt end leaves its child as an extra root: report the
    # joint only, not the consequence.
    broken_joint = any(
        not j.parent or not j.child or j.parent not in by_name or j.child not in by_name
        for j in robot.joints
    )
    if len(topo.roots) > 1 and not broken_joint:
        listed = ", ".join(repr(r) for r in topo.roots)
        yield _at(
            "multiple-roots",
            f"{_robot(robot)} has {len(topo.roots)} root links: {listed}",
            by_name[topo.roots[1]].source,
            path,
            "connect every link but one to a parent with a joint",
        )
    if not topo.roots:
        yield _at(
            "no-root",
            f"{_robot(robot)} has no root link: every link is some joint's child",
            robot.source,
            path,
            "one link must be no joint's child; look for a joint loop",
        )
    loops = _loops(robot, topo)
    in_loop: set[str] = set()
    for loop in loops:
        links = [j.parent for j in loop]
        in_loop.update(links)
        first = min(loop, key=lambda j: j.source.line if j.source else 0)
        yield _at(
            "cycle",
            f"joints {', '.join(repr(j.name) for j in loop)} form a loop: "
            + " -> ".join([*links, links[0]]),
            first.source,
            path,
            "URDF is a tree; break the loop or model it with a mimic joint",
        )
    if len(topo.roots) <= 1:
        for link in robot.links:
            if link.name not in topo.reachable and link.name not in in_loop:
                yield _at(
                    "unreachable-link",
                    f"link {link.name!r} is not connected to the root",
                    link.source,
                    path,
                    "it hangs below a joint loop",
                )


def _loops(robot: Robot, topo: Topology) -> list[list[Joint]]:
    """Every joint loop, found once each by an iterative depth-first search over all links
    (in file order), whether or not the root reaches it."""
    state: dict[str, int] = {}  # 1 on the current path, 2 finished
    loops: list[list[Joint]] = []
    for start in (link.name for link in robot.links):
        if start in state:
            continue
        state[start] = 1
        path = [start]
        via: list[Joint] = []  # via[i] is the joint from path[i] to path[i + 1]
        pending = [iter(topo.children[start])]
        while pending:
            joint = next(pending[-1], None)
            if joint is None:
                state[path.pop()] = 2
                pending.pop()
                if via:
                    via.pop()
                continue
            child = joint.child
            if state.get(child) == 1:  # back to a link on the current path: a loop
                loops.append([*via[path.index(child) :], joint])
            elif child not in state:
                state[child] = 1
                path.append(child)
                via.append(joint)
                pending.append(iter(topo.children[child]))
    return loops
