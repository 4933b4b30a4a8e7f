"""URDF's solid shapes as triangles (T, 3, 3) in their own frame, centred on it, and 4x4
placements applied to them: what the scene and the marks of a link's inertial are drawn
from."""

from __future__ import annotations

import math
from typing import Any

from ..model import Origin
from ..spatial import rpy_matrix

__all__ = ["apply", "box", "cylinder", "origin_matrix", "sphere"]

_SEGMENTS = 48  # around a cylinder or sphere


def apply(np: Any, matrix: Any, triangles: Any) -> Any:
    return triangles @ matrix[:3, :3].T + matrix[:3, 3]


def origin_matrix(np: Any, origin: Origin) -> Any:
    out = np.eye(4)
    out[:3, :3] = np.array(rpy_matrix(origin.rpy))
    out[:3, 3] = origin.xyz
    return out


def box(np: Any, x: float, y: float, z: float) -> Any:
    c = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)])
    c = c * np.array([x, y, z])
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1)]
    faces += [(2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return c[np.array(faces)]


def cylinder(np: Any, radius: float, length: float) -> Any:
    angles = np.linspace(0.0, 2 * math.pi, _SEGMENTS + 1)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    half = length / 2
    out = []
    for k in range(_SEGMENTS):
        (x0, y0), (x1, y1) = ring[k], ring[k + 1]
        out.append([[x0, y0, -half], [x1, y1, -half], [x1, y1, half]])
        out.append([[x0, y0, -half], [x1, y1, half], [x0, y0, half]])
        out.append([[0, 0, half], [x0, y0, half], [x1, y1, half]])
        out.append([[0, 0, -half], [x1, y1, -half], [x0, y0, -half]])
    return np.array(out, dtype=float)


def sphere(np: Any, radius: float) -> Any:
    rows = _SEGMENTS // 2
    theta = np.linspace(0.0, math.pi, rows + 1)
    phi = np.linspace(0.0, 2 * math.pi, _SEGMENTS + 1)
    grid = (
        np.stack(
            [
                np.outer(np.sin(theta), np.cos(phi)),
                np.outer(np.sin(theta), np.sin(phi)),
                np.outer(np.cos(theta), np.ones_like(phi)),
            ],
            axis=-1,
        )
        * radius
    )
    out = []
    for i in range(rows):
        for j in range(_SEGMENTS):
            a, b = grid[i, j], grid[i, j + 1]
            c, d = grid[i + 1, j], grid[i + 1, j + 1]
            out.append([a, c, d])
            out.append([a, d, b])
    return np.array(out, dtype=float)
