"""Benchmarks: every speed goal of fishbot-urdf, each a ratio measured side by side in one
run. Run by hand, in the venv fishbot-urdf is installed in (`pip install -e ".[test]"`), with
check_urdf on PATH (liburdfdom-tools), and sdformat's `ign` for the `fishbot sdf` rows
(ignition-tools and libsdformat-dev; without it they are left out):

    python benchmarks/run.py [--runs N] [--only WORD] [--pypi-corpus CACHE]

It prints one Markdown table for docs/performance.md: each measure, fishbot's figure, the
floor it is measured against, their ratio and the goal. Whole processes are timed
alternately, ours then the floor, and the medians compared, so that the machine's drift hits
both sides; in-process figures are the best of several passes. Robots: robots/fishbot's
first_robot.urdf and xacro (`fishbot sdf` on the fishbot against `ign sdf -p` on the URDF it
expands to, expanded once, untimed), every URDF the test dependencies ship (example-robot-data,
hpp-environments, cookie-description), and generated chains and trees (robots.py). Peak
memory is the process's maximum resident set, as the kernel counts it.

With --pypi-corpus CACHE (the cache of pypi_corpus.py, filled by it), the robots people have:
every URDF file of the pinned PyPI packages, meshes installed as the packages ship them.
Measured there: one `fishbot check` over every file against one check_urdf per file; each
file's check against the same file's with its meshes unavailable (the file alone in a
folder of its own: every rule runs, no mesh is found), in process, the worst ratio; and the
mesh facts of every STL and OBJ file those robots name against reading the same files'
bytes, the floor under any reader.
"""

from __future__ import annotations

import argparse
import compileall
import contextlib
import os
import shutil
import statistics
import subprocess
import sys
import sysconfig
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robots import ros_tool

ROOT = Path(__file__).resolve().parent.parent
FISHBOT_PACKAGE = ROOT / "robots" / "fishbot"
FIRST = FISHBOT_PACKAGE / "urdf" / "first_robot.urdf"
XACRO_FILE = FISHBOT_PACKAGE / "urdf" / "fishbot" / "fishbot.urdf.xacro"


def best(run: Callable[[], object], repeat: int) -> float:
    """The shortest of ``repeat`` timings of ``run()``, seconds."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def process(args: Sequence[str], env: dict[str, str] | None = None) -> float:
    """Run ``args`` once, output thrown away; its wall time, seconds."""
    start = time.perf_counter()
    subprocess.run(
        args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, cwd=ROOT, check=False
    )
    return time.perf_counter() - start


# A process's peak resident memory, as the kernel counts it, includes that of the process it
# was forked from; so a small Python forks it, waits for it and prints the count.
_PEAK = """
import os, sys
pid = os.fork()
if pid == 0:
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    os.execvp(sys.argv[1], sys.argv[1:])
print(os.wait4(pid, 0)[2].ru_maxrss * 1024)
"""


def peak(args: Sequence[str]) -> int:
    """Peak resident memory of one run of ``args``, bytes."""
    out = subprocess.run(
        [sys.executable, "-S", "-c", _PEAK, *args], capture_output=True, check=True, cwd=ROOT
    )
    return int(out.stdout)


def pair(
    ours: Sequence[str], floor: Sequence[str], runs: int, env: dict[str, str] | None = None
) -> tuple[float, float]:
    """Median seconds of each command, run alternately after one warm-up of each."""
    process(ours, env)
    process(floor, env)
    times: tuple[list[float], list[float]] = ([], [])
    for _ in range(runs):
        times[0].append(process(ours, env))
        times[1].append(process(floor, env))
    return statistics.median(times[0]), statistics.median(times[1])


def per_file(tool: str, files: Sequence[Path]) -> list[str]:
    """A command line that runs ``tool`` once per file (as a shell loop, one process; the
    files are its arguments, as a script of them could exceed the kernel's limit)."""
    return ["sh", "-c", 'for f do "$0" "$f"; done', tool, *map(str, files)]


def pypi_corpus(cache: Path) -> list[Path]:
    """Every URDF file of the packages pypi_corpus.py pins, from its cache."""
    import pypi_corpus as pins

    found = []
    for pin in pins.PINS:
        root = pins.extract(pins.download(pin, cache), cache)
        found += [root / path for path in pins.robot_files(root, ".urdf")]
    return found


def corpus() -> list[Path]:
    """Every URDF file the test dependencies ship."""
    share = Path(sysconfig.get_paths()["purelib"])
    found = sorted((share / "cmeel.prefix" / "share").rglob("*.urdf"))
    found += sorted((share / "cookie_description").rglob("*.urdf"))
    return found


def _tool(name: str) -> str:
    found = shutil.which(name, path=str(Path(sys.executable).parent))
    if found is None:
        sys.exit(f"{name} is not installed in this environment: pip install -e '.[test]'")
    return found


@dataclass(frozen=True)
class Row:
    measure: str
    ours: str
    floor: str
    ratio: str
    goal: str


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms"


def _s(seconds: float) -> str:
    return f"{seconds:.2f} s"


def _mib(size: float) -> str:
    return f"{size / 2**20:.0f} MiB"


def rows(runs: int, folder: Path, only: str | None, cache: Path | None = None) -> Iterator[Row]:
    """Measure every goal (those whose label holds ``only``, if given)."""
    from robots import robot

    def wanted(label: str) -> bool:
        return only is None or only.lower() in label.lower()

    fishbot, xacro, python = [_tool("fishbot")], [_tool("xacro")], sys.executable
    check_urdf = ros_tool("check_urdf")
    if check_urdf is None:
        sys.exit("check_urdf is not on PATH: apt-get install liburdfdom-tools")
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "tests" / "ament_stub")  # $(find) for the xacro command
    env["FISHBOT_TEST_PACKAGES"] = f"fishbot_description={FISHBOT_PACKAGE}"

    label = '`fishbot check first_robot.urdf` vs `python -c "import click, lxml.etree"`'
    if wanted(label):
        mine, floor = pair(
            [*fishbot, "check", str(FIRST)], [python, "-c", "import click, lxml.etree"], runs
        )
        yield Row(label, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 1.3x")
    # The same floor with the model's frozen dataclasses defined, and nothing else of ours.
    label = (
        '`python -c "import click, lxml.etree, fishbot_urdf.model"` vs the same without the model'
    )
    if wanted(label):
        floor_command = [python, "-c", "import click, lxml.etree"]
        mine, floor = pair(
            [python, "-c", "import click, lxml.etree, fishbot_urdf.model"], floor_command, runs
        )
        yield Row(label, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "")
    label = '`fishbot --help` vs `python -c "import click"`'
    if wanted(label):
        mine, floor = pair([*fishbot, "--help"], [python, "-c", "import click"], runs)
        yield Row(label, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 1.2x")
    label = "`fishbot expand` on the fishbot xacro vs the `xacro` command"
    if wanted(label):
        mine, floor = pair(
            [*fishbot, "expand", str(XACRO_FILE)], [*xacro, str(XACRO_FILE)], runs, env
        )
        yield Row(label, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 1.25x")
    # xacro's own command line run after importing click: what any click command running
    # xacro's engine costs, before a line of ours.
    label = "xacro's `main()` after `import click` vs the `xacro` command, on the fishbot xacro"
    if wanted(label):
        mine, floor = pair(
            [python, "-c", "import click, xacro; xacro.main()", str(XACRO_FILE)],
            [*xacro, str(XACRO_FILE)],
            runs,
            env,
        )
        yield Row(label, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "")
    yield from _sdf_rows(runs, folder, wanted, fishbot)

    files = corpus()
    label = f"in process, reading the {len(files)} corpus robots vs lxml's parse"
    label_check = f"in process, checking the {len(files)} corpus robots vs lxml's parse"
    label_floor = "in process, the read's floor (see _in_process) vs lxml's parse"
    label_scan = "in process, the read's floor and the start-tag scan vs lxml's parse"
    if any(map(wanted, (label, label_check, label_floor, label_scan))):
        parse, read, check, floor, scan = _in_process(files)
        if wanted(label_floor):
            yield Row(label_floor, _ms(floor), _ms(parse), f"{floor / parse:.1f}x", "")
        if wanted(label_scan):
            total = floor + scan
            yield Row(label_scan, _ms(total), _ms(parse), f"{total / parse:.1f}x", "")
        if wanted(label):
            yield Row(label, _ms(read), _ms(parse), f"{read / parse:.1f}x", "<= 4x")
        if wanted(label_check):
            yield Row(label_check, _ms(check), _ms(parse), f"{check / parse:.1f}x", "<= 5x")
    label = f"one `fishbot check` over the {len(files)} corpus robots vs one check_urdf per file"
    if wanted(label):
        mine, floor = pair(
            [*fishbot, "check", *map(str, files)], per_file(check_urdf, files), max(3, runs // 4)
        )
        yield Row(label, _s(mine), _s(floor), f"{mine / floor:.2f}x", "< 1x (faster)")
    label = f"the same in one process (`--jobs 1`; {os.cpu_count()} cores above)"
    if wanted(label):
        mine, floor = pair(
            [*fishbot, "check", "--jobs", "1", *map(str, files)],
            per_file(check_urdf, files),
            max(3, runs // 4),
        )
        yield Row(label, _s(mine), _s(floor), f"{mine / floor:.2f}x", "")

    if cache is not None:
        yield from _pypi_rows(cache, folder, runs, wanted, fishbot, check_urdf)

    generated: dict[str, Path] = {}

    def write(kind: str, size: int) -> Path:
        key = f"{kind}_{size}"
        if key not in generated:
            generated[key] = folder / f"{key}.urdf"
            generated[key].write_text(robot(kind, size), encoding="utf-8")
        return generated[key]

    big_runs = max(3, runs // 4)
    for kind, goal in (("tree", "<= 2x"), ("chain", "<= 0.67x (1.5x faster)")):
        label = f"10 000-link {kind}, `fishbot check` vs check_urdf"
        if wanted(label):
            path = str(write(kind, 10_000))
            mine, floor = pair([*fishbot, "check", path], [check_urdf, path], big_runs)
            yield Row(label, _s(mine), _s(floor), f"{mine / floor:.2f}x", goal)
    label = "100 000-link tree vs 10 000-link tree, `fishbot check`"
    if wanted(label):
        large, small = str(write("tree", 100_000)), str(write("tree", 10_000))
        mine, floor = pair([*fishbot, "check", large], [*fishbot, "check", small], big_runs)
        yield Row(label, _s(mine), _s(floor), f"{mine / floor:.1f}x", "<= 11x (linear)")
    for kind, size, goal in (("chain", 10_000, 256), ("tree", 100_000, 1024)):
        label = f"peak memory, {size:_}-link {kind} (`fishbot check`, tree to /dev/null)"
        label = label.replace("_", " ")
        if wanted(label):
            path = str(write(kind, size))
            mine_peak = max(peak([*fishbot, "check", path]) for _ in range(2))
            yield Row(
                label,
                _mib(mine_peak),
                f"check_urdf {_mib(peak([check_urdf, path]))}",
                "",
                f"<= {goal} MiB",
            )


def _sdf_rows(
    runs: int, folder: Path, wanted: Callable[[str], bool], fishbot: list[str]
) -> Iterator[Row]:
    """`fishbot sdf` against sdformat's converter, whole processes: on first_robot.urdf, and
    on the fishbot's xacro against `ign sdf -p` on the URDF it expands to."""
    labels = (
        "`fishbot sdf first_robot.urdf` vs `ign sdf -p first_robot.urdf`",
        "`fishbot sdf` on the fishbot xacro vs `ign sdf -p` on its URDF, expanded once, untimed",
    )
    if not any(map(wanted, labels)):
        return
    ign = shutil.which("ign")
    if ign is None:
        print("ign is not installed: the `fishbot sdf` rows are left out", file=sys.stderr)
        return
    if wanted(labels[0]):
        mine, floor = pair([*fishbot, "sdf", str(FIRST)], [ign, "sdf", "-p", str(FIRST)], runs)
        yield Row(labels[0], _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 1x")
    if wanted(labels[1]):
        xacro_file, urdf = _fishbot_for_sdf(folder)
        mine, floor = pair([*fishbot, "sdf", str(xacro_file)], [ign, "sdf", "-p", str(urdf)], runs)
        yield Row(labels[1], _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 1x")


def _fishbot_for_sdf(folder: Path) -> tuple[Path, Path]:
    """The fishbot xacro to time `fishbot sdf` on, and the URDF it expands to (for `ign sdf
    -p`), written into ``folder``."""
    import fishbot_urdf

    urdf = folder / "fishbot_for_ign.urdf"
    urdf.write_text(fishbot_urdf.expand(XACRO_FILE).text, encoding="utf-8")
    return XACRO_FILE, urdf


# The attributes URDF gives numbers in.
_NUMERIC = frozenset(
    [
        "xyz",
        "rpy",
        "value",
        "ixx",
        "ixy",
        "ixz",
        "iyy",
        "iyz",
        "izz",
        "size",
        "radius",
        "length",
        "scale",
        "rgba",
        "lower",
        "upper",
        "effort",
        "velocity",
        "damping",
        "friction",
        "rising",
        "falling",
        "multiplier",
        "offset",
        "k_velocity",
        "k_position",
        "soft_lower_limit",
        "soft_upper_limit",
    ]
)


def _in_process(files: Sequence[Path]) -> tuple[float, float, float, float, float]:
    """Best seconds of passes over ``files``: lxml's parse, fishbot_urdf.read,
    fishbot_urdf.check_file, the floor under any reader that builds the model (lxml's
    parse, then for every element its number attributes turned to numbers as the reader
    does, and one model object and one location made), and the scan that finds where each
    element starts, its line and its column (lxml gives neither: see locator.Locator), as
    the reader makes it. Each file's bytes are read from the page cache every time."""
    from lxml import etree

    import fishbot_urdf
    from fishbot_urdf.model import Location, Origin
    from fishbot_urdf.parsing.values import to_doubles
    from fishbot_urdf.xml.locator import Locator

    zero = (0.0, 0.0, 0.0)

    def floor() -> None:
        for path in files:
            parser = etree.XMLParser(resolve_entities=False, load_dtd=False, no_network=True)
            root = etree.fromstring(path.read_bytes(), parser)
            name = str(path)
            for element in root.iter(etree.Element):
                for key, value in element.items():
                    if key in _NUMERIC:
                        to_doubles(value.split())
                Origin(zero, zero, Location(name, 1, 1))

    def parse() -> None:
        for path in files:
            parser = etree.XMLParser(resolve_entities=False, load_dtd=False, no_network=True)
            etree.fromstring(path.read_bytes(), parser)

    def read() -> None:
        for path in files:
            fishbot_urdf.read(path)

    def check() -> None:
        for path in files:
            fishbot_urdf.check_file(path)

    def scan() -> None:
        for path in files:
            Locator(path.read_bytes(), str(path)).locations()

    check()  # every module loaded, every cache warm
    times: tuple[list[float], ...] = ([], [], [], [], [])
    for _ in range(5):
        for index, run in enumerate((parse, read, check, floor, scan)):
            start = time.perf_counter()
            run()
            times[index].append(time.perf_counter() - start)
    best = [min(each) for each in times]
    return best[0], best[1], best[2], best[3], best[4]


def _pypi_rows(
    cache: Path,
    folder: Path,
    runs: int,
    wanted: Callable[[str], bool],
    fishbot: list[str],
    check_urdf: str,
) -> Iterator[Row]:
    files = pypi_corpus(cache)
    size = sum(f.stat().st_size for f in files) / 1e6
    label = (
        f"PyPI corpus: one `fishbot check` over its {len(files)} URDF files ({size:.0f} MB, "
        "meshes installed) vs one check_urdf per file"
    )
    if wanted(label):
        command = [*fishbot, "check", *map(str, files)]
        mine, floor = pair(command, per_file(check_urdf, files), max(3, runs // 4))
        yield Row(label, _s(mine), _s(floor), f"{mine / floor:.2f}x", "< 1x (faster)")
    label = "PyPI corpus: the same in one process (`--jobs 1`)"
    if wanted(label):
        command = [*fishbot, "check", "--jobs", "1", *map(str, files)]
        mine, floor = pair(command, per_file(check_urdf, files), max(3, runs // 4))
        yield Row(label, _s(mine), _s(floor), f"{mine / floor:.2f}x", "")
    label_worst = "PyPI corpus, in process: the file whose check its meshes slow most"
    label_all = "PyPI corpus, in process: every file's check, with its meshes vs without"
    if wanted(label_worst) or wanted(label_all):
        worst, with_meshes, without = _mesh_ratios(files, folder)
        if wanted(label_all):
            ratio = f"{with_meshes / without:.2f}x"
            yield Row(label_all, _s(with_meshes), _s(without), ratio, "")
        if wanted(label_worst):
            name, mine, floor = worst
            label_worst += f" ({'/'.join(Path(name).parts[-2:])})"
            yield Row(label_worst, _ms(mine), _ms(floor), f"{mine / floor:.2f}x", "<= 2x")
    label = "PyPI corpus: the facts of the STL and OBJ files its robots name vs reading them"
    if wanted(label):
        meshes, facts, read, numbers = _mesh_facts(files)
        megabytes = sum(p.stat().st_size for p in meshes) / 1e6
        label += f" ({len(meshes)} files, {megabytes:.0f} MB)"
        yield Row(label, _s(facts), _s(read), f"{facts / read:.1f}x", "<= 2x")
        label = (
            "PyPI corpus: the same facts vs the least an exact reader does (the bytes read, "
            "the vertices' numbers alone parsed by numpy, their bounds)"
        )
        yield Row(label, _s(facts), _s(numbers), f"{facts / numbers:.2f}x", "")


def _check_seconds(path: Path, repeat: int) -> float:
    """Best seconds of ``repeat`` in-process checks of ``path``, no mesh facts kept."""
    from fishbot_urdf import meshfile
    from fishbot_urdf.errors import FishbotUrdfError
    from fishbot_urdf.lint import check_file

    def run() -> None:
        meshfile._KNOWN.clear()  # each check reads its meshes, as one process per file does
        with contextlib.suppress(FishbotUrdfError):  # a file that is no robot fails as fast
            check_file(path)

    return best(run, repeat)


def _mesh_ratios(
    files: Sequence[Path], folder: Path
) -> tuple[tuple[str, float, float], float, float]:
    """Each file checked where it is (meshes found) and alone in a folder of its own (none
    found), in process: the file with the largest ratio and its two times, and the sum of
    each. Every file is timed once; the twenty worst ratios again, best of five."""
    alone = folder / "alone"
    alone.mkdir(exist_ok=True)

    def times(path: Path, repeat: int) -> tuple[float, float]:
        copy = alone / path.name
        shutil.copyfile(path, copy)
        try:
            return _check_seconds(path, repeat), _check_seconds(copy, repeat)
        finally:
            copy.unlink()

    measured = {path: times(path, 1) for path in files}
    total = (sum(t[0] for t in measured.values()), sum(t[1] for t in measured.values()))
    worst = sorted(files, key=lambda p: measured[p][0] / measured[p][1])[-20:]
    again = {path: times(path, 5) for path in worst}
    name = max(again, key=lambda p: again[p][0] / again[p][1])
    return (str(name), *again[name]), *total


def _mesh_facts(files: Sequence[Path]) -> tuple[list[Path], float, float, float]:
    """The STL and OBJ files the robots' checks read, and the best seconds of three passes
    of each: their facts (none kept from one pass to the next), their bytes read, and their
    bytes read with the vertices' numbers parsed (`_numbers_floor`)."""
    from fishbot_urdf import meshfile
    from fishbot_urdf.analysis import meshpaths
    from fishbot_urdf.errors import FishbotUrdfError
    from fishbot_urdf.lint import check_file

    asked: list[str] = []
    real = meshfile.mesh_facts

    def facts(path: str | Path) -> meshfile.MeshFacts | None:
        asked.append(os.path.abspath(path))
        return real(path)

    meshpaths.mesh_facts = facts  # type: ignore[assignment]  # (where the analysis asks)
    try:
        for path in files:
            with contextlib.suppress(FishbotUrdfError):
                check_file(path)
    finally:
        meshpaths.mesh_facts = real  # type: ignore[assignment]
    meshes = [Path(p) for p in dict.fromkeys(asked) if Path(p).suffix.lower() in (".stl", ".obj")]
    meshes = [p for p in meshes if p.is_file()]

    def read_facts() -> None:
        meshfile._KNOWN.clear()
        for path in meshes:
            real(path)

    def read_bytes() -> None:
        for path in meshes:
            path.read_bytes()

    numbers = {path: _vertex_numbers(path.read_bytes(), path.suffix.lower()) for path in meshes}

    def read_numbers() -> None:
        for path in meshes:
            path.read_bytes()
            _bounds_of(numbers[path])

    return meshes, best(read_facts, 3), best(read_bytes, 3), best(read_numbers, 3)


def _vertex_numbers(data: bytes, kind: str) -> bytes | object:
    """What a reader of ``data``'s exact bounds cannot do without: a binary STL's numbers
    (viewed in place), or the text of the vertices' numbers alone (an OBJ's ``v`` lines, an
    ASCII STL's ``vertex`` lines), cut out here, before any timing."""
    import numpy as np

    if kind == ".stl" and len(data) >= 84:
        count = int.from_bytes(data[80:84], "little")
        if len(data) == 84 + 50 * count:
            record = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
            return np.frombuffer(data, record, count, 84)["v"].reshape(-1, 3)
    word = b"vertex " if kind == ".stl" else b"v "
    lines = (line.strip() for line in data.splitlines())
    return b" ".join(line[len(word) :] for line in lines if line.startswith(word))


def _bounds_of(numbers: bytes | object) -> object:
    """The least time from `_vertex_numbers`' output to bounds: text turned into floats by
    numpy's fastest parser (C's strtod, no Python per number), then the smallest and largest."""
    import numpy as np

    if isinstance(numbers, bytes):
        values = np.fromstring(numbers, sep=" ")
        numbers = values[: len(values) // 3 * 3].reshape(-1, 3)
    corners: Any = numbers
    return (corners.min(axis=0), corners.max(axis=0)) if len(corners) else None


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=21, help="runs per start-up measure")
    parser.add_argument("--only", metavar="WORD", help="only the measures whose label has WORD")
    parser.add_argument(
        "--pypi-corpus",
        metavar="CACHE",
        type=Path,
        help="measure the robots of pypi_corpus.py's cache too (filled by it)",
    )
    options = parser.parse_args(argv)
    # Bytecode written for every module first, as a first run writes it (unless
    # PYTHONDONTWRITEBYTECODE is set: then each process would compile what changed anew).
    compileall.compile_dir(ROOT / "src", quiet=1)
    print("| measure | fishbot | floor | ratio | goal |")
    print("| --- | ---: | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as folder:
        for row in rows(options.runs, Path(folder), options.only, options.pypi_corpus):
            print(f"| {row.measure} | {row.ours} | {row.floor} | {row.ratio} | {row.goal} |")
            sys.stdout.flush()
    print(f"\nMachine: {os.cpu_count()} cores, Python {sys.version.split()[0]}.")


if __name__ == "__main__":
    main()
