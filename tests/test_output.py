"""`fishbot_urdf.output.write_atomic`: whole files or none, modes as any program gives them."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from fishbot_urdf import InputError, output
from fishbot_urdf.output import write_atomic

_WRITE = "import sys; from fishbot_urdf.output import write_atomic; write_atomic(sys.argv[1], 'x')"


def _mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


@pytest.mark.parametrize("umask", ["022", "027", "002", "077"])
def test_a_new_file_gets_the_mode_the_shell_gives_one(tmp_path: Path, umask: str) -> None:
    # The shell's own `>` creates a file the way every program does: 0o666 less the umask.
    subprocess.run(["sh", "-c", f"umask {umask}; : > shell.txt"], cwd=tmp_path, check=True)
    script = f'umask {umask}; exec {sys.executable} -c "{_WRITE}" ours.txt'
    subprocess.run(["sh", "-c", script], cwd=tmp_path, check=True)
    assert _mode(tmp_path / "ours.txt") == _mode(tmp_path / "shell.txt")
    assert (tmp_path / "ours.txt").read_text() == "x"


def test_the_umask_is_never_touched(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def refuse(mask: int) -> int:
        raise AssertionError("os.umask changes the whole process")

    monkeypatch.setattr(os, "umask", refuse)
    write_atomic(tmp_path / "new.urdf", "<robot/>")
    write_atomic(tmp_path / "new.urdf", "<robot/>")
    assert (tmp_path / "new.urdf").read_text() == "<robot/>"


@pytest.mark.parametrize("mode", [0o600, 0o640, 0o755, 0o644])
def test_a_file_replaced_keeps_its_mode(tmp_path: Path, mode: int) -> None:
    target = tmp_path / "robot.urdf"
    target.write_text("old")
    target.chmod(mode)
    before = target.stat().st_ino
    write_atomic(target, "new")
    assert target.read_text() == "new"
    assert _mode(target) == mode
    assert target.stat().st_ino != before  # replaced whole, by a rename
    assert sorted(p.name for p in tmp_path.iterdir()) == ["robot.urdf"]


def test_a_read_only_file_is_not_replaced(tmp_path: Path) -> None:
    target = tmp_path / "robot.urdf"
    target.write_text("old")
    target.chmod(0o444)
    with pytest.raises(InputError) as caught:
        write_atomic(target, "new")
    assert caught.value.message == f"{target} is read-only (make it writable to replace it)"
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["robot.urdf"]


def test_a_dangling_link_makes_no_folders(tmp_path: Path) -> None:
    link = tmp_path / "out.urdf"
    link.symlink_to(tmp_path / "nowhere" / "deeper" / "out.urdf")
    with pytest.raises(InputError) as caught:
        write_atomic(link, "new")
    assert caught.value.message.endswith("whose folder does not exist")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.urdf"]
    (tmp_path / "nowhere" / "deeper").mkdir(parents=True)  # its folder there: written through
    assert write_atomic(link, "new").read_text() == "new"


def test_an_interrupt_while_writing_leaves_no_temporary_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real_replace = os.replace

    def interrupted(*args: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_atomic(tmp_path / "out.urdf", "new")
    monkeypatch.setattr(os, "replace", real_replace)
    assert list(tmp_path.iterdir()) == []


def test_links_are_written_through_and_devices_directly(tmp_path: Path) -> None:
    real = tmp_path / "real.urdf"
    real.write_text("old")
    real.chmod(0o640)
    link = tmp_path / "link.urdf"
    link.symlink_to(real)
    assert write_atomic(link, b"new") == real
    assert link.is_symlink()
    assert (real.read_text(), _mode(real)) == ("new", 0o640)
    write_atomic(os.devnull, "nothing")
    assert Path(os.devnull).is_char_device()


def test_folders_are_made_and_long_names_fit(tmp_path: Path) -> None:
    name = "y" * 250 + ".gv"  # 253 bytes: legal, and the temporary file must fit too
    written = write_atomic(tmp_path / "a" / "b" / name, "text")
    assert written.read_text() == "text"
    assert os.listdir(tmp_path / "a" / "b") == [name]
    with pytest.raises(InputError, match="File name too long"):
        write_atomic(tmp_path / ("z" * 260), "text")


def test_a_failed_write_leaves_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    target = tmp_path / "robot.urdf"
    target.write_text("old")

    def full(source: object, destination: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", full)
    with pytest.raises(InputError, match="No space left on device"):
        write_atomic(target, "new")
    assert target.read_text() == "old"
    assert os.listdir(tmp_path) == ["robot.urdf"]


def test_what_is_refused(tmp_path: Path) -> None:
    source = tmp_path / "in.urdf"
    source.write_text("in")
    with pytest.raises(InputError, match="refusing to write over the input"):
        write_atomic(source, "out", inputs=[source])
    with pytest.raises(InputError, match="is a folder"):
        write_atomic(tmp_path, "out")
    with pytest.raises(InputError, match="names a folder"):
        write_atomic(f"{tmp_path}/new/", "out")
    with pytest.raises(InputError, match="empty"):
        write_atomic("", "out")
    assert source.read_text() == "in"


def test_no_free_temporary_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(output, "_token", lambda: "taken")
    (tmp_path / ".robot.urdf.taken").write_text("someone else's")
    with pytest.raises(InputError, match="File exists"):
        write_atomic(tmp_path / "robot.urdf", "new")
    assert sorted(os.listdir(tmp_path)) == [".robot.urdf.taken"]
    (tmp_path / ".robot.urdf.taken").unlink()
    write_atomic(tmp_path / "robot.urdf", "new")
    assert os.listdir(tmp_path) == ["robot.urdf"]


def test_an_input_is_known_by_its_identity_not_its_name(tmp_path: Path) -> None:
    source = tmp_path / "in.urdf"
    source.write_text("in")
    (tmp_path / "hard.urdf").hardlink_to(source)
    (tmp_path / "soft.urdf").symlink_to(source)
    (tmp_path / "sub").mkdir()
    for other in ("hard.urdf", "soft.urdf", "sub/../in.urdf"):
        with pytest.raises(InputError) as caught:
            write_atomic(tmp_path / other, "out", inputs=[str(source)])
        assert caught.value.message == f"refusing to write over the input {source}"
        with pytest.raises(InputError):  # and the other way round
            write_atomic(source, "out", inputs=[tmp_path / other])
    assert source.read_text() == "in"
    assert sorted(os.listdir(tmp_path)) == ["hard.urdf", "in.urdf", "soft.urdf", "sub"]
    # A file of the same name elsewhere, or one not there yet, is no input.
    write_atomic(tmp_path / "sub" / "in.urdf", "out", inputs=[source, tmp_path / "gone"])
    assert (tmp_path / "sub" / "in.urdf").read_text() == "out"


def test_an_input_open_as_a_file_descriptor(tmp_path: Path) -> None:
    source = tmp_path / "in.urdf"
    source.write_text("in")
    with open(source, "rb") as stream:
        with pytest.raises(InputError) as caught:
            write_atomic(source, "out", inputs=[stream.fileno()])
        assert caught.value.message == f"refusing to write over the input <fd {stream.fileno()}>"
    assert source.read_text() == "in"


def test_standard_input_is_named_as_such(tmp_path: Path) -> None:
    source = tmp_path / "in.urdf"
    source.write_text("in")
    code = (
        "import sys; from fishbot_urdf.output import write_atomic\n"
        "try:\n    write_atomic(sys.argv[1], 'out', inputs=[0])\n"
        "except Exception as exc:\n    print(exc)\n"
    )
    with open(source, "rb") as stream:
        done = subprocess.run(
            [sys.executable, "-c", code, str(source)], stdin=stream, capture_output=True, text=True
        )
    assert done.stdout == f"{source}: refusing to write over the input <stdin>\n"
    assert source.read_text() == "in"


def test_a_device_or_pipe_is_never_an_input(tmp_path: Path) -> None:
    # Standard input from /dev/null, output to /dev/null: the same file, and no input.
    with open(os.devnull, "rb") as stream:
        write_atomic(os.devnull, "nothing", inputs=[stream.fileno(), os.devnull])


def test_a_refusal_at_commit_leaves_nothing(tmp_path: Path) -> None:
    source = tmp_path / "in.urdf"
    source.write_text("in")
    with output.AtomicFile(source) as out:
        out.write("out")
        with pytest.raises(InputError, match="refusing to write over the input"):
            out.commit([source])
        assert sorted(os.listdir(tmp_path)) == ["in.urdf"]
    assert source.read_text() == "in"


@pytest.mark.skipif(os.name != "posix", reason="symbolic links and FIFOs")
def test_a_name_the_caller_made_is_never_written_through_a_link(tmp_path: Path) -> None:
    victim = tmp_path / "victim.txt"
    victim.write_text("kept")
    link = tmp_path / "made.gv"
    link.symlink_to(victim)
    with pytest.raises(InputError) as caught:
        write_atomic(link, "x", through_links=False)
    assert caught.value.message == f"{link} is a link: this output is not written through one"
    os.mkfifo(tmp_path / "fifo.gv")
    with pytest.raises(InputError, match="is no regular file: this output replaces only one"):
        write_atomic(tmp_path / "fifo.gv", "x", through_links=False)
    # A link made there while the file is written is replaced by the file, not followed.
    late = tmp_path / "late.gv"
    with output.AtomicFile(late, through_links=False) as out:
        out.write("drawn")
        late.symlink_to(victim)
        out.commit()
    assert (late.is_symlink(), late.read_text(), victim.read_text()) == (False, "drawn", "kept")
    # A regular file is replaced as always.
    write_atomic(tmp_path / "plain.gv", "one", through_links=False)
    write_atomic(tmp_path / "plain.gv", "two", through_links=False)
    assert (tmp_path / "plain.gv").read_text() == "two"
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "fifo.gv",
        "late.gv",
        "made.gv",
        "plain.gv",
        "victim.txt",
    ]
