"""Shared test helpers: fixture paths, the real ROS tools, and the real-robot corpus."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DATA = Path(__file__).resolve().parent / "data"
VALID = sorted((DATA / "valid").glob("*.urdf"))
INVALID = sorted((DATA / "invalid").glob("*.urdf"))
FISHBOT = ROOT / "robots" / "fishbot"
STUB = Path(__file__).resolve().parent / "ament_stub"

# Set in CI: a missing tool is then a failure, never a skip.
REQUIRE_TOOLS = os.environ.get("FISHBOT_REQUIRE_TOOLS") == "1"


def require_tool(name: str, package: str) -> str:
    """The path of tool ``name``; skip (or, with FISHBOT_REQUIRE_TOOLS=1, fail) when missing."""
    found = shutil.which(name)
    if found is None:
        message = f"{name} is not installed (Debian/Ubuntu: apt-get install {package})"
        if REQUIRE_TOOLS:
            pytest.fail(message + "; FISHBOT_REQUIRE_TOOLS=1 forbids skipping")
        pytest.skip(message)
    return found


def run_check_urdf(path: Path) -> subprocess.CompletedProcess[bytes]:
    """Run the real check_urdf on ``path``."""
    tool = require_tool("check_urdf", "liburdfdom-tools")
    return subprocess.run([tool, str(path)], capture_output=True, timeout=120, check=False)


def xacro_command(
    path: str | Path,
    *args: str,
    cwd: Path | None = None,
    packages: dict[str, Path] | None = None,
) -> subprocess.CompletedProcess[str]:
    """Run the real xacro command (the PyPI package's), with $(find) answered by the stand-in."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(STUB), env.get("PYTHONPATH", "")])
    env["FISHBOT_TEST_PACKAGES"] = os.pathsep.join(
        f"{name}={folder}" for name, folder in (packages or {}).items()
    )
    code = "import sys, xacro; sys.exit(xacro.main())"
    return subprocess.run(
        [sys.executable, "-c", code, str(path), *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=300,
        check=False,
    )


def _site_packages() -> set[Path]:
    import sysconfig

    return {Path(sysconfig.get_paths()[key]) for key in ("purelib", "platlib")}


def corpus() -> list[Path]:
    """Every URDF shipped by example-robot-data (a test dependency)."""
    found: list[Path] = []
    for root in _site_packages():
        share = root / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
        found.extend(sorted(share.rglob("*.urdf")))
    return found


def xacro_corpus() -> list[Path]:
    """Every xacro file of the real robot packages in the test dependencies
    (example-robot-data, hpp-environments, cookie-description)."""
    found: list[Path] = []
    for root in _site_packages():
        found.extend(sorted((root / "cmeel.prefix" / "share").rglob("*.xacro")))
        found.extend(sorted((root / "cookie_description").rglob("*.xacro")))
    return found


CORPUS = corpus()
XACRO_CORPUS = xacro_corpus()
