"""Regenerate the golden SDF files: ``python tests/golden/regenerate_sdf.py``.

tests/test_sdf.py compares ``fishbot_urdf.to_sdf`` with what sdformat's own URDF converter
prints (``ign sdf -p ROBOT.urdf``, sdformat 12 as Gazebo Fortress ships it); this command
runs it on each input below and keeps what it prints in tests/golden/sdf/NAME.sdf, so that
the tests run on any machine. It needs the converter (Debian/Ubuntu: ``apt-get install
ignition-tools libsdformat-dev``) and refuses to run without it; run it after changing,
adding or removing an input, and commit what it changed. A xacro input is expanded first
(by fishbot's expansion, which tests/test_parity.py holds to the real xacro's).
tests/golden/sdf/index.json records each input's sha256 and the converter's version, so a
changed input with a stale golden file fails the tests. Files are written only when their
content changed; golden files no input needs any more are removed.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent.parent
OUT = Path(__file__).resolve().parent / "sdf"
CORPUS_OUT = OUT / "corpus"

# name -> input, relative to the repository
INPUTS = {
    "first_robot": "robots/fishbot/urdf/first_robot.urdf",
    "fishbot": "robots/fishbot/urdf/fishbot/fishbot.urdf.xacro",
    "fixed_chain": "tests/data/sdf/fixed_chain.urdf",
    "gazebo_fishbot_ament": "tests/data/gazebo/fishbot_description/urdf/fishbot.urdf.xacro",
    "gazebo_fishbot_catkin": "tests/data/gazebo/fishbot_ros1/urdf/fishbot.urdf.xacro",
    "gazebo_joint_lumping": "tests/data/sdf/gazebo_joint_lumping.urdf",
    "gazebo_joints": "tests/data/sdf/gazebo_joints.urdf",
    "gazebo_links": "tests/data/sdf/gazebo_links.urdf",
    "gazebo_lumped": "tests/data/sdf/gazebo_lumped.urdf",
    "gazebo_model": "tests/data/sdf/gazebo_model.urdf",
    "gazebo_reader": "tests/data/sdf/gazebo_reader.urdf",
    "gazebo_sensor": "tests/data/sdf/gazebo_sensor.urdf",
    "lumping": "tests/data/sdf/lumping.urdf",
    "materials": "tests/data/sdf/materials.urdf",
    "world_root": "tests/data/sdf/world_root.urdf",
}


def _corpus() -> list[Any]:
    """The check_urdf golden files' robots that are URDF files (tests/conftest.py's
    golden_inputs: their ids name them on any machine)."""
    sys.path.insert(0, str(ROOT / "tests"))
    from conftest import golden_inputs

    return [item for item in golden_inputs() if not item.is_xacro]


def urdf_text(path: Path) -> str:
    """The URDF the converter is given: the file, or the xacro file expanded."""
    if path.suffix != ".xacro":
        return path.read_text(encoding="utf-8")
    sys.path.insert(0, str(ROOT / "src"))
    from fishbot_urdf import expand

    return expand(path).text


def digest(text: str) -> str:
    """The sha256 of a converter's input without its comments: xacro's banner names the file
    it expanded by the path it was given, which is another on every checkout."""
    return hashlib.sha256(re.sub(r"<!--.*?-->", "", text, flags=re.S).encode("utf-8")).hexdigest()


def file_digest(path: Path) -> str:
    """The sha256 of a file, as it is on disk."""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def version() -> str:
    """libsdformat's Debian version, where dpkg can tell."""
    try:
        asked = subprocess.run(
            ["dpkg-query", "-W", "-f", "${Version}", "libsdformat-dev"],
            capture_output=True,
            text=True,
            check=False,
        )
    except OSError:
        return "unknown"
    return asked.stdout.strip() if asked.returncode == 0 and asked.stdout else "unknown"


def _write(path: Path, text: str) -> bool:
    if path.exists() and path.read_text(encoding="utf-8") == text:
        return False
    with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=path.parent, delete=False) as f:
        f.write(text)
    os.replace(f.name, path)
    return True


def main() -> int:
    ign = shutil.which("ign")
    if ign is None:
        print(
            "regenerate_sdf.py: ign not found: the golden files are what sdformat's converter "
            "prints (Debian/Ubuntu: apt-get install ignition-tools libsdformat-dev)",
            file=sys.stderr,
        )
        return 2
    OUT.mkdir(exist_ok=True)
    index: dict[str, object] = {
        "about": "What `ign sdf -p` prints for each input. Written by python "
        "tests/golden/regenerate_sdf.py; never edit by hand.",
        "libsdformat": version(),
        "inputs": {},
    }
    changed = []
    corpus: dict[str, object] = {}
    index["corpus"] = corpus
    kept: set[Path] = set()
    for item in _corpus():
        run = subprocess.run(
            [ign, "sdf", "-p", str(item.path)], capture_output=True, text=True, timeout=120
        )
        entry: dict[str, object] = {"sha256": file_digest(item.path)}
        if run.returncode != 0:
            entry["refused"] = run.returncode
        else:
            out = CORPUS_OUT / f"{item.id}.sdf"
            out.parent.mkdir(parents=True, exist_ok=True)
            kept.add(out)
            if _write(out, run.stdout):
                changed.append(f"corpus/{item.id}.sdf")
        corpus[item.id] = entry
    with tempfile.TemporaryDirectory() as folder:
        for name, relative in INPUTS.items():
            text = urdf_text(ROOT / relative)
            urdf = Path(folder) / f"{name}.urdf"
            urdf.write_text(text, encoding="utf-8")
            run = subprocess.run(
                [ign, "sdf", "-p", str(urdf)], capture_output=True, text=True, timeout=120
            )
            if run.returncode != 0:
                print(f"regenerate_sdf.py: {relative}: {run.stderr.strip()}", file=sys.stderr)
                return 1
            index["inputs"][name] = {"input": relative, "sha256": digest(text)}  # type: ignore[index]
            if _write(OUT / f"{name}.sdf", run.stdout):
                changed.append(f"{name}.sdf")
    if _write(OUT / "index.json", json.dumps(index, indent=2, sort_keys=True) + "\n"):
        changed.append("index.json")
    removed = [p.name for p in OUT.glob("*.sdf") if p.stem not in INPUTS]
    for name in removed:
        (OUT / name).unlink()
    for path in CORPUS_OUT.rglob("*.sdf"):
        if path not in kept:
            path.unlink()
            removed.append(str(path.relative_to(OUT)))
    for name in changed:
        print(f"written: {name}")
    for name in removed:
        print(f"removed: {name}")
    print(f"{len(changed)} written, {len(removed)} removed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
