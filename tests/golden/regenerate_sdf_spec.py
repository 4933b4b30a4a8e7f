"""Regenerate what the SDF reader knows of SDFormat 1.9: ``python
tests/golden/regenerate_sdf_spec.py``.

`fishbot_urdf.to_sdf` prints a converted robot as sdformat's reader prints it, and that
reader completes what it reads from its description of SDFormat: the attributes and
elements it knows, in its order, required ones added with their default text, unknown
elements copied after the rest. This command reads that description from the files sdformat
12 installs (Debian/Ubuntu: ``apt-get install libsdformat-dev``, in
/usr/share/sdformat12/1.9) and keeps what the reader uses of it (names, required, types,
default texts, bounds, which element copies its children as they are) in
src/fishbot_urdf/analysis/sdf_1.9.json, from ``model.sdf`` down. Descriptions are left out.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from lxml import etree

ROOT = Path(__file__).resolve().parent.parent.parent
OUT = ROOT / "src" / "fishbot_urdf" / "analysis" / "sdf_1.9.json"
SPEC = Path("/usr/share/sdformat12/1.9")


def element(node: etree._Element) -> dict[str, object]:
    """One ``<element>`` of the description, without its texts for people."""
    found: dict[str, object] = {"name": node.get("name"), "required": node.get("required")}
    if node.get("type") is not None:
        found["type"] = node.get("type")
        found["default"] = node.get("default", "")
        for bound in ("min", "max"):
            if node.get(bound) is not None:
                found[bound] = node.get(bound)
    attributes = [
        [a.get("name"), a.get("required"), a.get("default", "")] for a in node.findall("attribute")
    ]
    if attributes:
        found["attributes"] = attributes
    children: list[dict[str, object]] = []
    for child in node:
        if child.tag == "element" and child.get("copy_data") == "true":
            found["copy"] = True
        elif child.tag == "element" and child.get("ref"):
            children.append(
                {"include": f"{child.get('ref')}.sdf", "required": child.get("required")}
            )
        elif child.tag == "element":
            children.append(element(child))
        elif child.tag == "include":
            children.append({"include": child.get("filename"), "required": child.get("required")})
    if children:
        found["children"] = children
    return found


def main() -> int:
    if not SPEC.is_dir():
        print(
            f"regenerate_sdf_spec.py: {SPEC} not found (Debian/Ubuntu: apt-get install "
            "libsdformat-dev)",
            file=sys.stderr,
        )
        return 2
    files: dict[str, object] = {}
    todo = ["model.sdf"]
    while todo:
        name = todo.pop()
        if name in files or not (SPEC / name).exists():
            continue  # one sdformat keeps inside its library only (navsat.sdf)
        files[name] = description = element(etree.parse(str(SPEC / name)).getroot())
        stack = [description]
        while stack:
            for child in stack.pop().get("children", []):  # type: ignore[attr-defined]
                if "include" in child:
                    todo.append(child["include"])
                else:
                    stack.append(child)
    text = json.dumps(files, indent=None, separators=(",", ":"), sort_keys=True) + "\n"
    if not OUT.exists() or OUT.read_text(encoding="utf-8") != text:
        OUT.write_text(text, encoding="utf-8")
        print(f"written: {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
