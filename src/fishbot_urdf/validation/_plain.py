"""A quick test that a robot's links and joints hold only what the reader gives them.

Every field is of the exact type the model declares (a float, not an int), every number
finite, every name printable ASCII. The test goes field by field over all links and joints
at once (``map``, ``set`` and ``sum`` loop in C), not object by object: 51 M instructions on
a 1,000-link tree where the careful walk of `fishbot_urdf.validation` takes 256 M.
Failing proves nothing: the walk then looks at every link and joint, and may find nothing
wrong (an int, a name with a line break or an é).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from itertools import chain
from operator import attrgetter
from typing import Any

from ..model import (
    Box,
    Calibration,
    Collision,
    Cylinder,
    Dynamics,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Location,
    Material,
    Mesh,
    Mimic,
    Origin,
    Robot,
    SafetyController,
    Sphere,
    Visual,
)

__all__ = ["bounds_named", "plain"]

_SOURCES = {Location, type(None)}
_get = attrgetter


def _only(items: Iterable[object], *kinds: type) -> bool:
    """Whether every item is exactly of one of ``kinds``."""
    return set(map(type, items)) <= set(kinds)


def _present(items: Iterable[object], kind: type) -> list[Any] | None:
    """The items that are not None, when each of them is exactly a ``kind``."""
    kept = [item for item in items if item is not None]
    return kept if _only(kept, kind) else None


def _fields(items: Iterable[object], *names: str) -> Iterator[Any]:
    """The fields ``names`` of every item, field by field (a map per field costs a third of
    one map fetching them all as tuples)."""
    items = items if isinstance(items, list | tuple) else list(items)
    return chain.from_iterable(map(_get(name), items) for name in names)


def _vectors(vectors: list[object], size: int) -> bool:
    """Whether each of ``vectors`` is a tuple of ``size`` (of numbers: see `_finite`).

    Raises:
        TypeError: One is no tuple (`plain` returns False).
    """
    return set(map(tuple.__len__, vectors)) <= {size}  # type: ignore[arg-type]


def _finite(numbers: Iterable[object]) -> bool:
    """Whether every number is an int or a float (or a bool, as for mypy) and all are
    finite: their sum is a finite float (rarely, it overflows: False)."""
    try:
        total = sum(numbers, 0.0)  # type: ignore[type-var]
    except Exception:  # a str, a tuple, None: the walk says which
        return False
    # Anything else that adds to a float gives another type (numpy's, a complex number).
    return type(total) is float and total - total == 0.0


def _texts(texts: list[object], *, empty: bool) -> bool:
    """Every text a str of printable ASCII (and not "", unless ``empty``)."""
    if not _only(texts, str) or (not empty and "" in texts):
        return False
    joined = "".join(texts)  # type: ignore[arg-type]
    return joined.isascii() and joined.isprintable()


def plain(robot: Robot) -> bool:
    """Whether the links and joints of ``robot`` hold only what the reader gives them (its
    own fields and materials are not looked at)."""
    try:
        return _plain(robot.links, robot.joints)
    except Exception:  # an object of another class, without the fields looked for
        return False


def _plain(links: object, joints: object) -> bool:
    if type(links) is not tuple or type(joints) is not tuple:
        return False
    if not _only(links, Link) or not _only(joints, Joint):
        return False
    names = [
        *map(_get("name"), links),
        *_fields(joints, "name", "parent", "child"),
    ]
    extras = [*map(_get("extras"), links), *map(_get("extras"), joints)]
    if not _texts(names, empty=False) or not _only(extras, tuple):
        return False
    if not _texts(list(chain.from_iterable(extras)), empty=True):
        return False
    if not _only(map(_get("type"), joints), JointType):
        return False
    groups = list(map(_get("visuals"), links))
    visuals = list(chain.from_iterable(groups)) if _only(groups, tuple) else None
    groups = list(map(_get("collisions"), links))
    collisions = list(chain.from_iterable(groups)) if _only(groups, tuple) else None
    inertials = _present(map(_get("inertial"), links), Inertial)
    if visuals is None or collisions is None or inertials is None:
        return False
    if not _only(visuals, Visual) or not _only(collisions, Collision):
        return False
    shapes = visuals + collisions
    inertias = list(map(_get("inertia"), inertials))
    if not _only(inertias, Inertia):
        return False
    limits = _present(map(_get("limit"), joints), Limit)
    dynamics = _present(map(_get("dynamics"), joints), Dynamics)
    calibrations = _present(map(_get("calibration"), joints), Calibration)
    mimics = _present(map(_get("mimic"), joints), Mimic)
    safeties = _present(map(_get("safety_controller"), joints), SafetyController)
    materials = _present(map(_get("material"), visuals), Material)
    if (
        limits is None
        or dynamics is None
        or calibrations is None
        or mimics is None
        or safeties is None
        or materials is None
    ):
        return False
    if not all(limit.unset == () or bounds_named(limit.unset) for limit in limits):
        return False
    parts = (limits, dynamics, calibrations, mimics, safeties, materials)
    geometries = list(map(_get("geometry"), shapes))
    if not _only(geometries, Box, Cylinder, Sphere, Mesh):
        return False
    boxes = [g for g in geometries if type(g) is Box]
    meshes = [g for g in geometries if type(g) is Mesh]
    origins = [
        *map(_get("origin"), inertials),
        *map(_get("origin"), shapes),
        *map(_get("origin"), joints),
    ]
    if not _only(origins, Origin):
        return False
    vectors = [
        *_fields(origins, "xyz", "rpy"),
        *map(_get("size"), boxes),
        *(scale for scale in map(_get("scale"), meshes) if scale is not None),
        *map(_get("axis"), joints),
    ]
    colors = [color for color in map(_get("color"), materials) if color is not None]
    if not _vectors(vectors, 3) or not _vectors(colors, 4):
        return False
    rest = [g for g in geometries if type(g) is Cylinder or type(g) is Sphere]
    calibrated = _fields(calibrations, "rising", "falling")
    numbers = chain(
        chain.from_iterable(vectors),
        map(_get("mass"), inertials),
        _fields(inertias, *_INERTIA),
        map(_get("radius"), rest),
        (g.length for g in rest if type(g) is Cylinder),
        _fields(limits, "effort", "velocity", "lower", "upper"),
        _fields(dynamics, "damping", "friction"),
        (number for number in calibrated if number is not None),
        _fields(mimics, "multiplier", "offset"),
        _fields(safeties, *_SAFETY),
    )
    if not _finite(numbers) or not all(0.0 <= c <= 1.0 for c in chain.from_iterable(colors)):
        return False
    texts = [*map(_get("name"), shapes), *map(_get("texture"), materials)]
    if not _texts(
        [*map(_get("name"), materials), *(t for t in texts if t is not None)], empty=True
    ):
        return False
    if not _texts([*map(_get("filename"), meshes), *map(_get("joint"), mimics)], empty=False):
        return False
    everything = chain(links, joints, inertials, inertias, shapes, geometries, origins, *parts)
    sources = chain(
        map(_get("source"), everything),
        _fields(joints, "parent_source", "child_source"),
    )
    return set(map(type, sources)) <= _SOURCES


_INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_SAFETY = ("k_velocity", "k_position", "soft_lower_limit", "soft_upper_limit")


def bounds_named(unset: object) -> bool:
    """Whether ``unset`` names bounds a `Limit` may leave out, once each."""
    return (
        type(unset) is tuple
        and len(set(unset)) == len(unset)
        and all(type(b) is str and b in ("lower", "upper") for b in unset)
    )
