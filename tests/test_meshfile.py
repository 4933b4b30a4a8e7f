"""`fishbot_urdf.meshfile`: face counts and extents of STL and OBJ files, in plain Python,
against trimesh's reading of the same files."""

from __future__ import annotations

from pathlib import Path

import pytest
import trimesh
from conftest import binary_stl, box_stl

from fishbot_urdf.meshfile import MeshFacts, mesh_facts


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


def test_a_big_binary_stl_is_sampled_and_its_count_comes_from_the_header(tmp_path: Path) -> None:
    # 100 000 slivers along x from 0 to 99.999, each 1 tall in y: every 5th is read.
    path = tmp_path / "fine.stl"
    path.write_bytes(
        binary_stl([(i / 1000, 0, 0, i / 1000, 1, 0, i / 1000, 0, 1) for i in range(100_000)])
    )
    facts = mesh_facts(path)
    assert facts is not None
    assert facts.faces == 100_000
    assert facts.high[0] == pytest.approx(99.995, abs=0.01)
    assert facts.extent() == pytest.approx(99.995, abs=0.01)
    assert facts.extent((0.001, 0.001, 0.001)) == pytest.approx(0.099995, abs=1e-5)


def test_what_is_not_read(tmp_path: Path) -> None:
    (tmp_path / "a.dae").write_bytes(b"<COLLADA/>")
    (tmp_path / "empty.stl").write_bytes(b"")
    (tmp_path / "none.stl").write_bytes(binary_stl([]))
    for name in ("a.dae", "empty.stl", "none.stl", "missing.stl"):
        assert mesh_facts(tmp_path / name) is None
    (tmp_path / "box.stl").write_bytes(box_stl(1, 2, 3))
    assert mesh_facts(tmp_path / "box.stl") == MeshFacts(12, (0, 0, 0), (1, 2, 3))
