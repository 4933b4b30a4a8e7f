"""`fishbot_urdf.meshfile`: face counts and extents of STL and OBJ files, in plain Python,
against trimesh's reading of the same files; their triangles read strictly, and what a
malformed file is said to be."""

from __future__ import annotations

from pathlib import Path

import pytest
import trimesh
from conftest import binary_stl, box_stl

from fishbot_urdf.errors import ShapeError
from fishbot_urdf.inputs import TimeLimitError, time_limit
from fishbot_urdf.meshfile import (
    MeshFacts,
    mesh_bounds,
    mesh_closed,
    mesh_facts,
    mesh_triangles,
)


def _trimesh_facts(path: Path) -> MeshFacts:
    mesh = trimesh.load(path, force="mesh")
    low, high = mesh.bounds
    return MeshFacts(len(mesh.faces), tuple(low), tuple(high))  # type: ignore[arg-type]


@pytest.mark.parametrize("kind", ["stl", "obj", "stl_ascii"])
def test_the_facts_are_trimeshs(tmp_path: Path, kind: str) -> None:
    mesh = trimesh.creation.cylinder(radius=0.3, height=1.2, sections=24)
    mesh.apply_translation((1.0, -2.0, 0.5))
    path = tmp_path / f"part.{kind.split('_')[0]}"
    if kind == "stl_ascii":
        path.write_bytes(trimesh.exchange.stl.export_stl_ascii(mesh).encode())
    else:
        mesh.export(path)
    ours, theirs = mesh_facts(path), _trimesh_facts(path)
    assert ours is not None
    assert ours.faces == theirs.faces
    assert ours.low == pytest.approx(theirs.low, abs=1e-6)
    assert ours.high == pytest.approx(theirs.high, abs=1e-6)


def test_a_big_binary_stl_is_read_whole_and_its_count_comes_from_the_header(
    tmp_path: Path,
) -> None:
    # 100 000 slivers along x from 0 to 99.999, each 1 tall in y: the last one counts too.
    path = tmp_path / "fine.stl"
    path.write_bytes(
        binary_stl([(i / 1000, 0, 0, i / 1000, 1, 0, i / 1000, 0, 1) for i in range(100_000)])
    )
    facts = mesh_facts(path)
    assert facts is not None
    assert facts.faces == 100_000
    assert facts.high[0] == pytest.approx(99.999, abs=1e-4)
    assert facts.extent() == pytest.approx(99.999, abs=1e-4)
    assert facts.extent((0.001, 0.001, 0.001)) == pytest.approx(0.099999, abs=1e-7)


def test_what_is_not_read(tmp_path: Path) -> None:
    (tmp_path / "a.dae").write_bytes(b"<COLLADA/>")
    (tmp_path / "empty.stl").write_bytes(b"")
    (tmp_path / "none.stl").write_bytes(binary_stl([]))
    for name in ("a.dae", "empty.stl", "none.stl", "missing.stl"):
        assert mesh_facts(tmp_path / name) is None
    (tmp_path / "box.stl").write_bytes(box_stl(1, 2, 3))
    assert mesh_facts(tmp_path / "box.stl") == MeshFacts(12, (0, 0, 0), (1, 2, 3))


# -- mesh_triangles: the strict reader, and mesh_bounds: what a malformed file still gives --

_GOOD = box_stl(1, 2, 3)
_TRIANGLE = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"


@pytest.mark.parametrize(
    ("name", "data", "said"),
    [
        ("empty.stl", b"", "the file is empty"),
        ("blank.obj", b"\n  \n", "the file is empty"),
        (
            "truncated.stl",
            _GOOD[:-20],
            "not an ASCII STL, nor a binary one: a binary STL of 12 triangles is 684 bytes "
            "long, not 664",
        ),
        (
            "claims.stl",
            _GOOD[:80] + (1000).to_bytes(4, "little") + _GOOD[84:],
            "a binary STL of 1,000 triangles is 50,084 bytes long, not 684",
        ),
        ("short.stl", b"\x01\x02garbage", "no triangles in the STL file"),
        ("garbage.obj", bytes(range(256)) * 8, "no triangles in the OBJ file"),
        ("number.obj", b"v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", "vertex 'x' is not a number"),
        ("short_vertex.obj", b"v 0 0\n" + _TRIANGLE + b"f 2 3 4\n", "fewer than three numbers"),
        ("range.obj", _TRIANGLE + b"f 1 2 9\n", "line 4: a face names vertex 9, of 3"),
        ("zero.obj", _TRIANGLE + b"f 0 1 2\n", "line 4: a face names vertex 0, of 3 (OBJ"),
        ("negative.obj", _TRIANGLE + b"f -1 -2 -4\n", "line 4: a face names vertex -4, of 3"),
        ("word.obj", _TRIANGLE + b"f 1 a 3\n", "line 4: vertex 'a' of a face is not a whole"),
        ("two.obj", _TRIANGLE + b"f 1 2\n", "line 4: a face of fewer than three vertices"),
        ("nan.obj", b"v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "a vertex is not a finite"),
        ("inf.stl", binary_stl([(0, 0, 0, float("inf"), 0, 0, 0, 1, 0)]), "is not a finite"),
        (
            "ascii.stl",
            b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
            "2 vertices are not a whole number of triangles",
        ),
        ("part.ply", b"ply\n", ".ply: not an STL or OBJ file"),
    ],
)
def test_a_malformed_mesh_is_a_shape_error_that_says_why(
    tmp_path: Path, name: str, data: bytes, said: str
) -> None:
    path = tmp_path / name
    path.write_bytes(data)
    with pytest.raises(ShapeError) as info:
        mesh_triangles(path)
    assert info.value.rule == "shape"
    assert info.value.path == str(path)
    assert said in info.value.message


def test_triangles_are_read_from_stl_and_obj(tmp_path: Path) -> None:
    (tmp_path / "box.stl").write_bytes(_GOOD)
    box = mesh_triangles(tmp_path / "box.stl")
    assert box.shape == (12, 3, 3)
    assert box.min(axis=(0, 1)).tolist() == [0, 0, 0]
    assert box.max(axis=(0, 1)).tolist() == [1, 2, 3]
    # A quad is a fan of two triangles; indices with texture and normal parts, and
    # negative ones counted back from the face.
    (tmp_path / "quad.obj").write_bytes(
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2/2 3//3 4\nv 5 5 5\nf -5 -4 -1\n"
    )
    quad = mesh_triangles(tmp_path / "quad.obj")
    assert quad.tolist() == [
        [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
        [[0, 0, 0], [1, 1, 0], [0, 1, 0]],
        [[0, 0, 0], [1, 0, 0], [5, 5, 5]],
    ]


def test_mesh_bounds_finds_the_box_of_a_malformed_file(tmp_path: Path) -> None:
    (tmp_path / "truncated.stl").write_bytes(_GOOD[:-20])  # the last triangle cut short
    low, high = mesh_bounds(tmp_path / "truncated.stl") or ((), ())
    assert low == (0, 0, 0)
    assert high == (1, 2, 3)
    (tmp_path / "range.obj").write_bytes(b"v 0 0 0\nv 2 x 0\nv 0 1 3\nf 1 2 9\n")
    assert mesh_bounds(tmp_path / "range.obj") == ((0, 0, 0), (2, 1, 3))  # "x" left out
    for name, data in (("empty.stl", b""), ("inf.obj", b"v inf 0 0\n"), ("a.dae", b"<a/>")):
        (tmp_path / name).write_bytes(data)
        assert mesh_bounds(tmp_path / name) is None


def test_mesh_bounds_finds_the_box_of_a_collada_files_positions(tmp_path: Path) -> None:
    source = '<source id="positions"><float_array id="positions-array">{}</float_array>'
    (tmp_path / "part.dae").write_text(source.format("0 0 0 0.3 0.2 0.1 -1 0.5 0 7"))
    assert mesh_bounds(tmp_path / "part.dae") == ((-1, 0, 0), (0.3, 0.5, 0.1))  # 7 left over
    (tmp_path / "nan.dae").write_text(source.format("0 0 0 nan 0.2 0.1"))
    assert mesh_bounds(tmp_path / "nan.dae") is None
    reads: list[str] = []
    box = mesh_bounds(tmp_path / "part.dae", lambda path: reads.append(str(path)) or b"")
    assert (box, reads) == (None, [str(tmp_path / "part.dae")])  # the reader given


def test_reading_a_mesh_stops_at_the_deadline(tmp_path: Path) -> None:
    path = tmp_path / "big.obj"
    path.write_bytes(_TRIANGLE + b"f 1 2 3\n" * 10)
    with time_limit(1e-6), pytest.raises(TimeLimitError) as info:
        mesh_triangles(path)
    assert info.value.what == "reading meshes"


def test_a_files_facts_are_read_once_while_it_is_unchanged(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import os

    from fishbot_urdf import meshfile

    path = tmp_path / "box.stl"
    path.write_bytes(box_stl(1, 2, 3))
    reads: list[str] = []
    real = meshfile.read_input
    monkeypatch.setattr(meshfile, "read_input", lambda p: reads.append(str(p)) or real(p))
    first = mesh_facts(path)
    assert mesh_facts(path) == first and first is not None
    assert mesh_facts(str(path)) == first
    assert reads == [str(path)]
    path.write_bytes(box_stl(4, 2, 3))  # changed: read again
    os.utime(path, ns=(1, 1))
    changed = mesh_facts(path)
    assert changed is not None and changed.extent() == pytest.approx(4.0)
    assert len(reads) == 2


@pytest.mark.parametrize(
    ("vertices", "high"),
    [
        ([("0", "0", "0"), ("1", "2", "3"), ("-1", "0.5", "2")], (1.0, 2.0, 3.0)),
        ([("0", "0", "0"), ("x", "2", "3"), ("-1", "0.5", "2")], (0.0, 2.0, 3.0)),  # a word
    ],
)
def test_ascii_numbers_read_at_once_or_one_by_one_give_one_box(
    tmp_path: Path, vertices: list[tuple[str, str, str]], high: tuple[float, float, float]
) -> None:
    text = "solid s\nfacet normal 0 0 1\nouter loop\n"
    text += "".join(f"vertex {x} {y} {z}\n" for x, y, z in vertices)
    text += "endloop\nendfacet\nendsolid s\n"
    path = tmp_path / "one.stl"
    path.write_text(text)
    facts = mesh_facts(path)
    assert facts is not None
    assert facts.faces == 1
    assert facts.low == (-1.0, 0.0, 0.0)
    assert facts.high == high


def test_a_binary_stl_with_a_number_that_is_not_finite_has_no_facts(tmp_path: Path) -> None:
    path = tmp_path / "nan.stl"
    path.write_bytes(binary_stl([(0, 0, 0, 1, 0, 0, float("nan"), 1, 0)]))
    assert mesh_facts(path) is None
    with pytest.raises(ShapeError, match="not a finite number"):
        mesh_triangles(path)


# -- closedness, and the OBJ reader's two ways to one answer --


def test_closed_is_trimeshs_watertight(tmp_path: Path) -> None:
    box = trimesh.creation.box((1.0, 2.0, 3.0))
    opened = trimesh.Trimesh(box.vertices, box.faces[:-1])  # one triangle short
    cylinder = trimesh.creation.cylinder(radius=0.3, height=1.2, sections=24)
    for name, mesh in (("box", box), ("open", opened), ("cylinder", cylinder)):
        for kind in ("stl", "obj"):
            path = tmp_path / f"{name}.{kind}"
            mesh.export(path)
            facts = mesh_facts(path)
            assert facts is not None
            assert facts.closed is mesh.is_watertight, path.name
    assert box.is_watertight and not opened.is_watertight


def test_closed_welds_corners_at_one_place_and_reads_each_file_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf import meshfile

    # A tetrahedron whose corner (0, 0, 0) is written once as -0.0: one vertex all the same.
    a, b, c, d = (0.0, -0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)
    a0 = (0.0, 0.0, 0.0)
    path = tmp_path / "tetra.stl"
    path.write_bytes(binary_stl([(*a, *c, *b), (*a0, *b, *d), (*a0, *d, *c), (*b, *c, *d)]))
    reads: list[str] = []
    real = meshfile.mesh_triangles
    monkeypatch.setattr(
        meshfile, "mesh_triangles", lambda p, read=None: reads.append(str(p)) or real(p, read)
    )
    assert mesh_closed(path) is True
    assert mesh_closed(path) is True
    assert reads == [str(path)]
    (tmp_path / "bad.obj").write_bytes(b"v 0 0 0\nf 1 2 3\n")
    assert mesh_closed(tmp_path / "bad.obj") is None
    assert mesh_closed(tmp_path / "missing.stl") is None
    assert MeshFacts(1, (0, 0, 0), (1, 1, 1)).closed is None  # made here: no file to read


def test_closed_survives_a_hash_shared_by_two_places(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import numpy as np

    from fishbot_urdf import meshfile

    (tmp_path / "box.stl").write_bytes(box_stl(1, 2, 3))
    triangles = mesh_triangles(tmp_path / "box.stl")
    real = np.unique

    def colliding(values: object, *args: object, **kwargs: object) -> object:
        if not kwargs.get("axis") and isinstance(values, np.ndarray) and values.ndim == 1:
            values = values & np.uint64(1)  # every place shares one of two hashes
        return real(values, *args, **kwargs)

    monkeypatch.setattr(np, "unique", colliding)
    assert meshfile._closed(triangles) is True
    assert meshfile._closed(triangles[:-1]) is False


_CUBE_OBJ = (
    b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    b"f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
)


@pytest.mark.parametrize(
    ("data", "faces", "high"),
    [
        (_CUBE_OBJ, 6, (1.0, 1.0, 1.0)),  # numpy's reader
        (_CUBE_OBJ.replace(b"\n", b"\r\n"), 6, (1.0, 1.0, 1.0)),
        (b"# c\nvn 0 0 1\nv 1 2 3 0.5 0.5 0.5\no x\nv -1 0 0\nf 1 2 1\n", 1, (1.0, 2.0, 3.0)),
        (b"  v 1 2 3\nv -1 0 0\n\tf 1 2 1\nf 2 1 2\n", 2, (1.0, 2.0, 3.0)),  # indented
        (b"v\t1 2 3\nv -1 0 0\nf\t1 2 1\n", 1, (1.0, 2.0, 3.0)),  # tabs
        (b"v 1 2\nv 1 2 3\nv -1 0 0\nf 1 2 3\n", 1, (1.0, 2.0, 3.0)),  # a short line
        (b"v 1_0 2 3\nv -1 0 0\nf 1 2 3\n", 1, (10.0, 2.0, 3.0)),  # Python's number
        (b"v 1 x 3\nv -1 0 0\nf 1 2 3\n", 1, (1.0, 0.0, 3.0)),  # a word left out
        (b"v 1 2 3\rv 5 5 5\rf 1 2 3\n", 0, (1.0, 2.0, 3.0)),  # old Mac line ends: one line
        (b"v 1 2 3\nv 2 inf 0\nv 0 0 0\nf 1 2 3\n", 1, None),  # not finite: no box
    ],
)
def test_an_obj_is_read_as_the_patterns_read_it(
    tmp_path: Path, data: bytes, faces: int, high: tuple[float, float, float] | None
) -> None:
    from fishbot_urdf import meshfile

    path = tmp_path / "part.obj"
    path.write_bytes(data)
    facts = mesh_facts(path)
    vertices = meshfile._OBJ_VERTEX.findall(data)
    assert facts == meshfile._bounds(vertices, len(meshfile._OBJ_FACE.findall(data)))
    if high is None:
        assert facts is None
    else:
        assert facts is not None
        assert (facts.faces, facts.high) == (faces, high)


def test_the_facts_say_how_far_the_vertices_are_from_a_plane_and_a_line(tmp_path: Path) -> None:
    (tmp_path / "plate.stl").write_bytes(box_stl(1, 2, 0))
    (tmp_path / "box.stl").write_bytes(box_stl(1, 2, 3))
    plate, box = mesh_facts(tmp_path / "plate.stl"), mesh_facts(tmp_path / "box.stl")
    assert plate is not None and box is not None
    assert plate.spread is not None and plate.spread[0] == 0.0 < (plate.spread[1] or 0)
    assert box.spread is not None and box.spread[0] > 0.5
    assert box.spread[1] is None  # far from flat: the line is not measured
    assert (plate.vertices, box.vertices) == (None, None)  # counted only for a few corners
