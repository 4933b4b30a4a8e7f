"""Rules about names and the link tree: what urdfdom refuses, and what it lets through."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from .. import catalog
from ..analysis import Analysis
from ..catalog import Rule, rules_in
from ..catalog.reading import MISSING_ATTRIBUTE, MISSING_ELEMENT
from ..catalog.structure import (
    CYCLE,
    DUPLICATE_JOINT,
    DUPLICATE_LINK,
    DUPLICATE_MATERIAL,
    JOINT_SELF_LOOP,
    LIMIT_RANGE,
    MISSING_LIMIT,
    MULTIPLE_PARENTS,
    MULTIPLE_ROOTS,
    NEGATIVE_LIMIT,
    NO_LINKS,
    NO_ROOT,
    UNDEFINED_LINK,
    UNDEFINED_MIMIC,
    UNREACHABLE_LINK,
    ZERO_AXIS,
    LoopFacts,
    RootsFacts,
    UndefinedLinkFacts,
)
from ..diagnostics import Diagnostic, Kind, Subject
from ..location import call_chain, calls_of
from ..model import Joint, Location, Robot
from ..wording import did_you_mean, listing

__all__ = ["REPORTS", "structure"]


def structure(analysis: Analysis) -> Iterator[Diagnostic]:
    """Every finding about the robot's names, joints and link tree."""
    yield from _names(analysis)
    yield from _joints(analysis)
    yield from _tree(analysis)


def _robot(robot: Robot) -> str:
    """How findings name the robot (a nameless one is reported separately)."""
    return f"robot {robot.name!r}" if robot.name else "the robot"


def _the_robot(robot: Robot) -> Subject:
    return Subject(Kind.ROBOT, robot.name)


_DUPLICATES = {
    Kind.LINK: DUPLICATE_LINK,
    Kind.JOINT: DUPLICATE_JOINT,
    Kind.MATERIAL: DUPLICATE_MATERIAL,
}


def _names(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, path = analysis.robot, analysis.path
    if not robot.links:
        yield NO_LINKS.report(
            f"{_robot(robot)} has no links",
            robot.source,
            path=path,
            subject=_the_robot(robot),
            hint='a robot needs at least one <link name="...">',
        )
    for kind, items in (
        (Kind.LINK, robot.links),
        (Kind.JOINT, robot.joints),
        (Kind.MATERIAL, robot.materials),
    ):
        first: dict[str, Location | None] = {}
        for item in items:
            if not item.name:
                continue
            if item.name in first:
                where = first[item.name]
                seen = f" (first defined at line {where.line})" if where else ""
                hint = f"every {kind.value} needs a unique name"
                made, again = calls_of(where), calls_of(item.source)
                if made or again:  # made by macro calls: the calls tell the two apart
                    seen = f" (first {_made(where, made)}; again {_made(item.source, again)})"
                    if made and again and where == item.source:  # one element, two calls
                        hint += (
                            f": make it from a parameter of macro {made[0][0]} that each "
                            "call gives its own value"
                        )
                subject = Subject(kind, item.name)
                yield _DUPLICATES[kind].report(
                    f"{subject} is defined twice{seen}",
                    item.source,
                    path=path,
                    subject=subject,
                    hint=hint,
                )
            else:
                first[item.name] = item.source


def _made(where: Location | None, calls: tuple[tuple[str, Location], ...]) -> str:
    """Where an element was written: the macro calls that made it, else its line."""
    if calls:
        return "by " + call_chain(calls)
    return f"at {where.path}:{where.line}" if where else "somewhere unknown"


def _suggest(name: str, candidates: Iterable[str]) -> str:
    names = set(candidates)
    guess = did_you_mean(name, names)
    return f"{guess}links: {listing(names, near=name)}" if names else "the robot defines no links"


def _joints(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, path = analysis.robot, analysis.path
    link_names = analysis.links.keys()
    joint_names = analysis.joints.keys()
    for joint in robot.joints:
        owner = Subject(Kind.JOINT, joint.name)
        parent, child = joint.parent, joint.child
        ends: tuple[tuple[str, str, Location | None], ...] = ()  # none undefined, nearly always
        if (parent and parent not in link_names) or (child and child not in link_names):
            ends = (("parent", parent, joint.parent_source), ("child", child, joint.child_source))
        for end, name, where in ends:
            if name and name not in link_names:
                yield UNDEFINED_LINK.report(
                    f"{owner}: {end} link {name!r} is not defined",
                    where or joint.source,
                    path=path,
                    subject=owner,
                    hint=_suggest(name, link_names),
                    data=UndefinedLinkFacts(end=end, link=name),
                )
        if joint.parent and joint.parent == joint.child:
            yield JOINT_SELF_LOOP.report(
                f"{owner}: parent and child are the same link {joint.parent!r}",
                joint.child_source or joint.source,
                path=path,
                subject=owner,
                hint="a joint connects two different links",
            )
        yield from _limits(joint, owner, path)
        if joint.type.uses_axis and joint.axis == (0.0, 0.0, 0.0):
            yield ZERO_AXIS.report(
                f"{owner}: the axis is 0 0 0, so the joint cannot move",
                joint.source,
                path=path,
                subject=owner,
                hint='give a unit vector, e.g. <axis xyz="0 0 1"/>',
            )
        mimic = joint.mimic
        if mimic is not None and mimic.joint:
            if mimic.joint not in joint_names:
                guess = did_you_mean(mimic.joint, joint_names).strip()
                yield UNDEFINED_MIMIC.report(
                    f"{owner}: mimics joint {mimic.joint!r}, which is not defined",
                    mimic.source,
                    path=path,
                    subject=owner,
                    hint=guess or "name an existing joint",
                )
            elif mimic.joint == joint.name:
                yield UNDEFINED_MIMIC.report(
                    f"{owner}: mimics itself",
                    mimic.source,
                    path=path,
                    subject=owner,
                    hint="name another joint",
                )
    yield from _mimic_loops(analysis)


def _mimic_loops(analysis: Analysis) -> Iterator[Diagnostic]:
    """Joints that mimic each other round a loop (a -> b -> a): none of them leads."""
    follows = {
        joint.name: joint.mimic.joint
        for joint in analysis.robot.joints
        if joint.mimic is not None and joint.mimic.joint and joint.mimic.joint != joint.name
    }
    done: set[str] = set()
    for start in follows:
        if start in done:
            continue
        trail: list[str] = []
        at: str | None = start
        while at is not None and at not in done and at not in trail:
            trail.append(at)
            at = follows.get(at)
        done.update(trail)
        if at is None or at not in trail:
            continue  # the chain ends at a joint that leads, or joins one seen before
        loop = trail[trail.index(at) :]
        shown = " -> ".join([*loop, loop[0]])
        for name in loop:
            joint = analysis.joints[name]
            owner = Subject(Kind.JOINT, name)
            assert joint.mimic is not None
            yield UNDEFINED_MIMIC.report(
                f"{owner}: mimics in a loop ({shown}), so no joint of it leads",
                joint.mimic.source,
                path=analysis.path,
                subject=owner,
                hint="let one joint of the loop mimic none",
            )


def _limits(joint: Joint, owner: Subject, path: str) -> Iterator[Diagnostic]:
    limit = joint.limit
    if limit is None:
        if joint.type.needs_limit:
            yield MISSING_LIMIT.report(
                f"{owner}: a {joint.type.value} joint needs <limit>",
                joint.source,
                path=path,
                subject=owner,
                hint='write <limit lower=".." upper=".." effort=".." velocity=".."/>',
            )
        return
    # (a bound left out makes it so: limit-unset says that, as this rule's error)
    if joint.type.needs_limit and limit.lower > limit.upper and not limit.unset:
        yield LIMIT_RANGE.report(
            f"{owner}: lower limit {limit.lower:g} is above upper limit {limit.upper:g}",
            limit.source,
            path=path,
            subject=owner,
            hint="swap them, lower <= upper",
        )
    for name in ("effort", "velocity"):
        value = getattr(limit, name)
        if value < 0:
            yield NEGATIVE_LIMIT.report(
                f"{owner}: {name} limit {value:g} is negative",
                limit.source,
                path=path,
                subject=owner,
                hint=f"{name} is a magnitude, >= 0",
            )


def _broken_ends(analysis: Analysis) -> list[str]:
    """The rules that report a joint whose parent or child is missing or misspelt: such a
    joint leaves its child as an extra root, which is their consequence, not news."""
    causes: set[str] = set()
    for joint in analysis.robot.joints:
        for name in (joint.parent, joint.child):
            if not name:
                causes.update((MISSING_ELEMENT.id, MISSING_ATTRIBUTE.id))
            elif name not in analysis.links:
                causes.add(UNDEFINED_LINK.id)
    return sorted(causes)


def _tree(analysis: Analysis) -> Iterator[Diagnostic]:
    robot, topo, path = analysis.robot, analysis.topology, analysis.path
    if not robot.links:
        return
    by_name = analysis.links
    for name, joints in topo.parents.items():
        if len(joints) > 1:
            listed = ", ".join(repr(j.name) for j in joints)
            yield MULTIPLE_PARENTS.report(
                f"link {name!r} is the child of {len(joints)} joints: {listed}",
                joints[1].child_source or joints[1].source,
                path=path,
                subject=Subject(Kind.LINK, name),
                hint="a link has one parent joint; in a URDF tree loops are not allowed",
            )
    if len(topo.roots) > 1:
        listed = ", ".join(repr(r) for r in topo.roots)
        yield MULTIPLE_ROOTS.report(
            f"{_robot(robot)} has {len(topo.roots)} root links: {listed}",
            by_name[topo.roots[1]].source,
            path=path,
            subject=_the_robot(robot),
            hint="connect every link but one to a parent with a joint",
            data=RootsFacts(roots=tuple(topo.roots)),
            follows=_broken_ends(analysis),
        )
    if not topo.roots:
        yield NO_ROOT.report(
            f"{_robot(robot)} has no root link: every link is some joint's child",
            robot.source,
            path=path,
            subject=_the_robot(robot),
            hint="one link must be no joint's child; look for a joint loop",
        )
    in_loop: set[str] = set()
    for loop in analysis.loops:
        links = [j.parent for j in loop]
        in_loop.update(links)
        first = min(loop, key=lambda j: j.source.line if j.source else 0)
        yield CYCLE.report(
            f"joints {', '.join(repr(j.name) for j in loop)} form a loop: "
            + " -> ".join([*links, links[0]]),
            first.source,
            path=path,
            subject=Subject(Kind.JOINT, first.name),
            hint="URDF is a tree; break the loop or model it with a mimic joint",
            data=LoopFacts(joints=tuple(j.name for j in loop)),
        )
    if len(topo.roots) <= 1:
        for link in robot.links:
            if link.name not in topo.reachable and link.name not in in_loop:
                yield UNREACHABLE_LINK.report(
                    f"link {link.name!r} is not connected to the root",
                    link.source,
                    path=path,
                    subject=Subject(Kind.LINK, link.name),
                    hint="it hangs below a joint loop",
                )


REPORTS: tuple[Rule, ...] = rules_in(catalog.structure)
"""Every rule this module's check may report: the check runs only when one is selected."""
