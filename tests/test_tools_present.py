"""The corpus and the real tools that the parity tests depend on are there."""

from __future__ import annotations

from conftest import CORPUS, require_tool


def test_corpus_is_installed() -> None:
    # example-robot-data is a test dependency: without it the parity sweep would be empty.
    assert len(CORPUS) >= 50, "pip install -e '.[test]' installs example-robot-data"


def test_check_urdf_is_available() -> None:
    assert require_tool("check_urdf", "liburdfdom-tools").endswith("check_urdf")


def test_ign_sdf_is_available() -> None:
    # sdformat's URDF converter, the reference of tests/test_sdf.py
    assert require_tool("ign", "ignition-tools libsdformat-dev").endswith("ign")
