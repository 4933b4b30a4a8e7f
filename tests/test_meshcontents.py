"""What a robot's mesh files hold has one owner, the analysis's ``meshes``: a file that the
checks, a drawing and the mass computations all use is read once for each kind of answer
(main read it six times), and each answer is made once, from any number of threads."""

from __future__ import annotations

import gc
import threading
import time
import weakref
from pathlib import Path

import pytest
from conftest import box_stl

import fishbot_urdf
from fishbot_urdf.analysis import analyse, meshcontents
from fishbot_urdf.analysis.meshcontents import MeshContents
from fishbot_urdf.drawing.scene import build_scene
from fishbot_urdf.errors import InputError, ShapeError
from fishbot_urdf.inertia import fill_inertials
from fishbot_urdf.inputs import recording_inputs
from fishbot_urdf.lint import check, check_file
from fishbot_urdf.packages import PackageFinder


def _counted(monkeypatch: pytest.MonkeyPatch, name: str) -> list[str]:
    """The files meshcontents' ``name`` (its reader, or a format's) is called on."""
    calls: list[str] = []
    real = getattr(meshcontents, name)

    def counting(path: Path, *rest: object) -> object:
        calls.append(str(path))
        return real(path, *rest)

    monkeypatch.setattr(meshcontents, name, counting)
    return calls


def _robot(folder: Path, shapes: str, name: str = "r") -> Path:
    """A robot file of one link, ``a``, with ``shapes`` (its visual and collision elements)."""
    robot = folder / "robot.urdf"
    robot.write_text(f'<robot name="{name}"><link name="a">{shapes}</link></robot>\n')
    return robot


def test_a_mesh_checked_drawn_and_weighed_is_read_once_for_each_answer(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    trimesh = pytest.importorskip("trimesh")
    mesh = tmp_path / "part.stl"
    mesh.write_bytes(box_stl(200.0, 100.0, 100.0))  # in millimetres
    robot = _robot(
        tmp_path,
        '<visual><geometry><mesh filename="part.stl"/></geometry></visual>'
        '<collision><geometry><mesh filename="part.stl" scale="0.001 0.001 0.001"/>'
        "</geometry></collision>",
    )
    analysis = analyse(fishbot_urdf.load(robot))
    reads = _counted(monkeypatch, "read_input")
    parses = _counted(monkeypatch, "mesh_triangles")
    loads: list[object] = []
    load = trimesh.load
    monkeypatch.setattr(trimesh, "load", lambda *a, **k: loads.append(a) or load(*a, **k))
    with recording_inputs() as read:
        findings = check(analysis)
        scene = build_scene(analysis, show=("visual", "collision"))
        filled = fill_inertials(analysis, density=1000.0)
    # The mesh rules read its facts: the visual, unscaled, is 200 m across.
    assert [d.rule for d in findings if d.rule.startswith("mesh")] == ["mesh-units"]
    assert [part.layer for part in scene.parts] == ["visual", "collision"]
    assert filled.inertials["a"].mass == pytest.approx(2.0)  # 0.2 * 0.1 * 0.1 m^3 of water
    # Every read goes through read_input, and is recorded: one for the facts the mesh rules
    # read, one for the triangles (made once for both scales), one for the solid (made once
    # for the three questions the inertia asks of it: too large? its volume, its inertia).
    assert read.count(str(mesh)) == 3
    assert reads == [str(mesh)] * 3
    assert parses == [str(mesh)]
    assert len(loads) == 1
    # asked again, every answer is there: nothing more is read
    with recording_inputs() as again:
        check(analysis)
        build_scene(analysis, show=("visual", "collision"))
        fill_inertials(analysis, density=1000.0)
    assert again.count(str(mesh)) == 0


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


def test_a_malformed_file_gives_its_error_each_time(
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
    assert reads == [str(mesh)] * 4  # the error is not kept: read again to raise it again


def test_a_file_that_cannot_be_read_is_tried_again(tmp_path: Path) -> None:
    mesh = tmp_path / "part.stl"
    contents = MeshContents()
    with pytest.raises(InputError, match="no such file"):
        contents.triangles(mesh)
    mesh.write_bytes(box_stl(0.2, 0.1, 0.1))
    assert contents.triangles(mesh).shape == (12, 3, 3)


@pytest.mark.parametrize(
    ("name", "mesh", "data"),
    [
        ("r &amp; co", "part.stl", box_stl(0.2, 0.1, 0.1)),
        ("r & co", "part.stl", box_stl(0.2, 0.1, 0.1)),  # read by recovery: xml-escape
        ("r", "package://no_such_package/part.stl", b""),  # its error kept by the finder
        ("r", "part.stl", box_stl(0.2, 0.1, 0.1)[:-10]),  # not a mesh: mesh-invalid
    ],
)
def test_an_analysis_and_the_mesh_bytes_it_keeps_are_let_go_with_the_check(
    tmp_path: Path, name: str, mesh: str, data: bytes
) -> None:
    # Without the cycle collector: nothing may hold the analysis in a cycle (an error's
    # traceback holds the frames that made it), nor longer than a finder.
    (tmp_path / "part.stl").write_bytes(data)
    visual = f'<visual><geometry><mesh filename="{mesh}"/></geometry></visual>'
    robot = _robot(tmp_path, visual, name)
    finder = PackageFinder()
    collecting = gc.isenabled()
    gc.disable()
    try:
        result = check_file(str(robot), packages=finder)
        assert result.analysis is not None
        analysis = weakref.ref(result.analysis)
        del result
        assert analysis() is None
    finally:
        if collecting:
            gc.enable()
