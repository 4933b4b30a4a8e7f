"""What a robot's mesh files hold has one owner, the analysis's ``meshes``: a file is read
once, and each answer made once, from any number of threads."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import pytest
from conftest import box_stl

from fishbot_urdf.analysis import meshcontents
from fishbot_urdf.analysis.meshcontents import MeshContents
from fishbot_urdf.errors import InputError, ShapeError


def _counted(monkeypatch: pytest.MonkeyPatch, name: str) -> list[str]:
    """The files meshcontents' ``name`` (its reader, or a format's) is called on."""
    calls: list[str] = []
    real = getattr(meshcontents, name)

    def counting(path: Path, *rest: object) -> object:
        calls.append(str(path))
        return real(path, *rest)

    monkeypatch.setattr(meshcontents, name, counting)
    return calls


def test_threads_asking_at_once_share_one_read(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    mesh = tmp_path / "part.stl"
    mesh.write_bytes(box_stl(0.2, 0.1, 0.1))
    real = meshcontents.read_input
    reads: list[str] = []

    def slow(path: Path) -> bytes:
        reads.append(str(path))
        time.sleep(0.05)  # long enough for every other thread to ask meanwhile
        return real(path)

    monkeypatch.setattr(meshcontents, "read_input", slow)
    contents = MeshContents()
    start = threading.Barrier(8)
    answers: list[object] = []

    def ask() -> None:
        start.wait()
        answers.append(contents.triangles(mesh))

    threads = [threading.Thread(target=ask) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert reads == [str(mesh)]
    assert len(answers) == 8 and all(answer is answers[0] for answer in answers)


def test_a_malformed_file_gives_its_error_each_time_from_one_read(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    mesh = tmp_path / "part.stl"
    mesh.write_bytes(box_stl(0.2, 0.1, 0.1)[:-10])  # shorter than its header says
    reads = _counted(monkeypatch, "read_input")
    contents = MeshContents()
    messages = []
    for _ in range(2):
        with pytest.raises(ShapeError) as raised:
            contents.triangles(mesh)
        messages.append(raised.value.message)
    assert messages[0] == messages[1]
    assert messages[0].startswith("not an ASCII STL, nor a binary one")
    assert contents.facts(mesh) is None
    assert contents.bounds(mesh) is not None  # the whole records it holds
    assert reads == [str(mesh)]


def test_a_file_that_cannot_be_read_is_tried_again(tmp_path: Path) -> None:
    mesh = tmp_path / "part.stl"
    contents = MeshContents()
    with pytest.raises(InputError, match="no such file"):
        contents.triangles(mesh)
    mesh.write_bytes(box_stl(0.2, 0.1, 0.1))
    assert contents.triangles(mesh).shape == (12, 3, 3)
