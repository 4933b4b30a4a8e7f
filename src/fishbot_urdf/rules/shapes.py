"""Rules about the sizes of a robot's shapes: boxes, cylinders and spheres of no size, and
meshes scaled to nothing."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..analysis import Analysis
from ..catalog import Rule
from ..catalog.meshes import SHAPE_SIZE
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..model import Box, Cylinder, Geometry, Mesh

__all__ = ["REPORTS", "shapes", "sizeless"]


def shapes(analysis: Analysis) -> Iterator[Diagnostic]:
    """Every collision shape of the robot whose size is 0 or less (a mesh: whose scale is
    0), and every visual whose size is negative."""
    for link in analysis.robot.links:
        parts = [("visual", v.geometry, False) for v in link.visuals]
        parts += [("collision", c.geometry, True) for c in link.collisions]
        for kind, shape, collides in parts:
            found = _size(shape)
            if found is None:
                continue
            what, first, negative = found
            if not collides:
                if not negative:
                    # A visual of size 0 is drawn as nothing: a placeholder (upkie's and
                    # laikago's frames), which no program minds.
                    continue
                then = "it is no shape"
            elif first is None:
                then = "MuJoCo refuses the robot ('mesh volume is too small')"
            else:
                then = f"MuJoCo refuses the robot ('size {first[0]} must be positive in geom')"
            yield SHAPE_SIZE.report(
                f"link {link.name!r}: <{kind}> {what}: {then}",
                shape.source,
                path=analysis.path,
                subject=Subject(Kind.LINK, link.name),
                hint="give the shape its real size (m), or delete it",
                severity=None if collides else Severity.WARNING,
            )


def sizeless(shape: Geometry) -> str | None:
    """What a shape of no size is (a box, cylinder or sphere with a size of 0 or less, a mesh
    scaled by 0), as `shape-size` says it, or None for a shape with a size."""
    found = _size(shape)
    return None if found is None else found[0]


def _size(shape: Geometry) -> tuple[str, tuple[int, float] | None, bool] | None:
    """What is wrong with a shape's size, the first size that is 0 or less (MuJoCo's index
    of it, and its value; None for a mesh), and whether one is negative; None if nothing is
    (a number that is no number is bad-number's)."""
    if isinstance(shape, Mesh):  # a negative scale mirrors a mesh, a scale of 0 flattens it
        if shape.scale is None or 0 not in shape.scale:
            return None
        return (
            f"mesh {shape.filename!r} is scaled by {_numbers(shape.scale)}, which flattens it",
            None,
            False,
        )
    if isinstance(shape, Box):
        values = list(zip("xyz", shape.size, strict=True))
    elif isinstance(shape, Cylinder):
        values = [("radius", shape.radius), ("length", shape.length)]
    else:
        values = [("radius", shape.radius)]
    bad = [(i, n, v) for i, (n, v) in enumerate(values) if v <= 0 and math.isfinite(v)]
    if not bad:
        return None
    if isinstance(shape, Box):
        what = f"box of size {_numbers(shape.size)}"
    else:
        kind = "cylinder" if isinstance(shape, Cylinder) else "sphere"
        what = f"{kind} of " + " and ".join(f"{n} {float(v):g}" for _, n, v in bad)
    return what, (bad[0][0], float(bad[0][2])), any(v < 0 for _, _, v in bad)


def _numbers(values: tuple[float, float, float]) -> str:
    """A size or scale as written: "0.2 0.2 0"."""
    return '"' + " ".join(f"{float(v):g}" for v in values) + '"'


REPORTS: tuple[Rule, ...] = (SHAPE_SIZE,)
"""Every rule this module's check may report: the check runs only when one is selected."""
