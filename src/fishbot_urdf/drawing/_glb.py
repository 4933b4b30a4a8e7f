"""A shape as the bytes of a binary glTF 2.0 file (GLB): what the viewer sends for a
transparent shape.

viser draws its own meshes with three.js materials that write depth even when they are
transparent, so a transparent shape drawn first hides a transparent shape inside it.
three.js's glTF reader gives a material whose ``alphaMode`` is ``BLEND`` no depth writes:
every transparent shape is blended over what is behind it, nested or not.
"""

from __future__ import annotations

import json
import struct
from typing import Any

__all__ = ["glb"]

_MAGIC, _VERSION = b"glTF", 2
_JSON, _BIN = b"JSON", b"BIN\0"
_FLOAT, _ARRAY_BUFFER, _TRIANGLES = 5126, 34962, 4  # glTF's numbers for them


def glb(np: Any, triangles: Any, color: tuple[float, float, float, float]) -> bytes:
    """Triangles (T, 3, 3), in metres, as a GLB file of one mesh in ``color`` (red, green,
    blue, alpha, each 0..1, in sRGB as URDF and the viewer's other meshes give them),
    blended by its alpha and seen from both sides. The file has no normals: the reader
    shades each triangle flat, as the viewer's other meshes are."""
    points = np.ascontiguousarray(triangles, dtype="<f4").reshape(-1, 3)
    data = points.tobytes()
    red, green, blue, alpha = color
    document = {
        "asset": {"version": "2.0", "generator": "fishbot-urdf"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0}, "material": 0, "mode": _TRIANGLES}]}
        ],
        "materials": [
            {
                "pbrMetallicRoughness": {
                    # glTF's colours are linear; the viewer's others, as URDF's, are sRGB
                    "baseColorFactor": [*(_linear(c) for c in (red, green, blue)), alpha],
                    "metallicFactor": 0.0,  # (glTF's default is a metal)
                    "roughnessFactor": 1.0,
                },
                "alphaMode": "BLEND",
                "doubleSided": True,
            }
        ],
        "buffers": [{"byteLength": len(data)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(data), "target": _ARRAY_BUFFER}
        ],
        "accessors": [
            {
                "bufferView": 0,
                "componentType": _FLOAT,
                "count": len(points),
                "type": "VEC3",
                "min": [float(v) for v in points.min(axis=0)],
                "max": [float(v) for v in points.max(axis=0)],
            }
        ],
    }
    text = json.dumps(document, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)  # each chunk's length a multiple of 4
    data += b"\0" * (-len(data) % 4)
    body = _chunk(_JSON, text) + _chunk(_BIN, data)
    return _MAGIC + struct.pack("<II", _VERSION, 12 + len(body)) + body


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack("<I", len(data)) + kind + data


def _linear(value: float) -> float:
    """An sRGB colour component as a linear one (the sRGB transfer function)."""
    value = min(max(value, 0.0), 1.0)
    return value / 12.92 if value <= 0.04045 else ((value + 0.055) / 1.055) ** 2.4
