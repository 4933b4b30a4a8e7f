"""Rewrite the README's rule list from the rule registry: ``python tests/readme_rules.py``.

The list between the ``<!-- rules: begin -->`` and ``<!-- rules: end -->`` markers is the
table ``fishbot rules --format markdown`` prints; ``tests/test_rules.py`` fails, naming this
command, when the two differ.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from fishbot_urdf.catalog import all_rules
from fishbot_urdf.catalog.docs import with_rule_table
from fishbot_urdf.errors import FishbotUrdfError


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python tests/readme_rules.py",
        description="Rewrite the rule list of a README from the rule registry.",
    )
    parser.add_argument(
        "readme",
        metavar="README",
        nargs="?",
        default=str(Path(__file__).resolve().parent.parent / "README.md"),
        help="the README to rewrite in place (default: the project's)",
    )
    path = Path(parser.parse_args(argv).readme)
    try:
        text = path.read_text(encoding="utf-8")
        new = with_rule_table(text, all_rules())
        if new != text:
            path.write_text(new, encoding="utf-8")
    except (OSError, FishbotUrdfError) as exc:
        sys.stderr.write(f"{path}: {exc}\n")
        return 1
    state = "updated" if new != text else "already up to date"
    sys.stdout.write(f"{path}: rule list {state} ({len(all_rules())} rules)\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
