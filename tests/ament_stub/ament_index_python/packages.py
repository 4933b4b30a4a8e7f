"""get_package_share_directory for the reference runs of the xacro command (tests only)."""

from __future__ import annotations

import os


class PackageNotFoundError(KeyError):
    """The package is not in FISHBOT_TEST_PACKAGES."""


def get_package_share_directory(package_name: str) -> str:
    entries = os.environ.get("FISHBOT_TEST_PACKAGES", "").split(os.pathsep)
    for entry in entries:
        name, _, path = entry.partition("=")
        if name == package_name:
            return path
    raise PackageNotFoundError(package_name)
