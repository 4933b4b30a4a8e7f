"""The trust model of expansion: every expression is interpreted by an allowlist, at every
depth, and each file is expanded with evaluation state of its own.

Each escape attempt below would, if it ran as Python, create a canary file or reach an
object that leads to one (a frame, a function's globals, the list of every class). The
property: the expansion stops with one located error and the canary never appears.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner
from conftest import xacro_command

from fishbot_urdf.cli import cli
from fishbot_urdf.expansion import ExpansionLimitError, XacroError, expand
from fishbot_urdf.expansion._allowlist import UnsafeExpression, prepare_symbols
from fishbot_urdf.expansion._interpreter import evaluate

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
CANARY = "CANARY"

# Runs `touch CANARY` in the current folder through os.system, reached from a lambda.
SYSTEM = (
    "(lambda: [c for c in ().__class__.__base__.__subclasses__() "
    "if c.__name__ == '_wrap_close'][0].__init__.__globals__['system']('touch CANARY'))()"
)


def _symbols() -> dict[str, object]:
    """xacro's global symbol table, prepared as an expansion prepares it, with a YAML-like
    property."""
    import xacro  # type: ignore[import-untyped]

    symbols = xacro.create_global_symbols()
    prepare_symbols(symbols)
    table = xacro.Table(symbols)
    table._setitem("props", xacro.YamlDictWrapper({"wheel": {"radius": 0.03}}), False)
    return table  # type: ignore[no-any-return]


# Expressions refused by the interpreter, each with what it names first.
REFUSED = [
    (SYSTEM, "__class__"),
    ("[c for c in ().__class__.__bases__[0].__subclasses__()]", "__class__"),
    ("[g.gi_frame.f_back.f_globals for g in [(x for x in [1])]]", "gi_frame"),
    ("(x for x in []).gi_code.co_consts", "gi_code"),
    ("(lambda: 0).__globals__", "__globals__"),
    ("(lambda f=(lambda: 0): f.__code__)()", "__code__"),
    ("[[y.__class__ for y in [x]] for x in [1]]", "__class__"),
    ("f'{().__class__}'", "__class__"),
    ("'{0.__class__.__base__}'.format(1)", "format field"),
    ("'{0[__x]}'.format(python.dict())", "format field"),
    ("'{0[0]}'.format([1])", "format field"),
    ("'{0.real}'.format(1)", "format field"),
    ("'{0:{1.real}}'.format(1, 2)", "format field '{1.real}'"),
    ("python.str.format('{0.__class__}', 1)", "format field"),
    ("python.str.format.__call__('{0.x}', 1)", "__call__"),
    ("'{x}'.format_map(python.dict())", "format_map"),
    ("python.dict(__class__=1)", "__class__"),
    ("(lambda __x: 0)(1)", "__x"),
    ("python.type(1)", "python.type"),
    ("python.vars()", "python.vars"),
    ("python.list.mro()", "mro"),
    ("xacro.arg.func_globals", "func_globals"),
    ("python.list(python.map(python.type, [1]))", "python.type"),
    ("math.parent", "'parent' is not defined"),
    ("python.list(python.map('{0.__globals__[os]}'.format, [xacro.tokenize]))", "format field"),
    ("python.sorted([1], key='{0.__class__}'.format)", "format field"),
    ("None.__class__", "__class__"),
    ("xacro.load_yaml.__globals__", "__globals__"),
    ("xacro.arg.__closure__", "__closure__"),
    ("xacro.arg.func_globals", "func_globals"),
    ("[].__class__.__mro__", "__class__"),
    ("(y := ().__class__)", ":="),
    ("[*().__class__.__mro__]", "__class__"),
    ("__import__('os')", "__import__"),
    ("math._private", "_private"),
    ("python.len.__self__", "__self__"),
]


@pytest.mark.parametrize(("expression", "what"), REFUSED, ids=[r[0][:40] for r in REFUSED])
def test_the_interpreter_refuses_each_escape_naming_what_it_refused(
    expression: str, what: str
) -> None:
    with pytest.raises((UnsafeExpression, NameError, AttributeError)) as caught:
        evaluate(expression, _symbols())
    shown = caught.value.what if isinstance(caught.value, UnsafeExpression) else str(caught.value)
    assert what in shown
    assert (
        caught.value.expression == expression
        if isinstance(caught.value, UnsafeExpression)
        else True
    )


@pytest.mark.parametrize(
    "expression",
    [
        "math.pi / 2",
        "xacro.arg('x') if False else 1",
        "python.dict(a=1)['a']",
        "'{}_link'.format('left')",
        "'{0}_{1:.2f}'.format('w', 0.5)",
        "[x * 2 for x in python.range(3)]",
        "(lambda r: r * r)(2)",
        "props.wheel.radius",
        "python.sorted([3, 1])",
    ],
)
def test_what_robot_descriptions_write_is_allowed(expression: str) -> None:
    expected = {
        "math.pi / 2": 1.5707963267948966,
        "xacro.arg('x') if False else 1": 1,
        "python.dict(a=1)['a']": 1,
        "'{}_link'.format('left')": "left_link",
        "'{0}_{1:.2f}'.format('w', 0.5)": "w_0.50",
        "[x * 2 for x in python.range(3)]": [0, 2, 4],
        "(lambda r: r * r)(2)": 4,
        "props.wheel.radius": 0.03,
        "python.sorted([3, 1])": [1, 3],
    }
    assert evaluate(expression, _symbols()) == expected[expression]


def _expand_in(folder: Path, files: dict[str, str], monkeypatch: pytest.MonkeyPatch) -> Path:
    for name, text in files.items():
        (folder / name).write_text(text)
    monkeypatch.chdir(folder)
    return folder / "robot.xacro"


def _robot(body: str) -> str:
    return f'<robot name="r" {NS}>\n{body}\n</robot>\n'


# The same escape, placed wherever xacro evaluates an expression.
PLACES = {
    "attribute": _robot(f'<link name="${{{SYSTEM}}}"/>'),
    "if": _robot(f'<xacro:if value="${{{SYSTEM}}}"><link name="a"/></xacro:if>'),
    "property": _robot(f'<xacro:property name="p" value="${{{SYSTEM}}}"/>\n<link name="${{p}}"/>'),
    "macro default": _robot(
        f'<xacro:macro name="m" params="x:=${{{SYSTEM}}}"><link name="${{x}}"/></xacro:macro>\n'
        "<xacro:m/>"
    ),
    "macro argument": _robot(
        '<xacro:macro name="m" params="x"><link name="${x}"/></xacro:macro>\n'
        f'<xacro:m x="${{{SYSTEM}}}"/>'
    ),
    "element name": _robot(f'<xacro:element xacro:name="${{{SYSTEM}}}"/>'),
    "attribute name": _robot(
        f'<link name="a"><xacro:attribute name="${{{SYSTEM}}}" value="1"/></link>'
    ),
    "argument default": _robot(
        f'<xacro:arg name="a" default="${{{SYSTEM}}}"/>\n<link name="$(arg a)"/>'
    ),
}


@pytest.mark.parametrize("place", sorted(PLACES))
def test_an_escape_fails_located_and_runs_nothing_wherever_it_is_written(
    place: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _expand_in(tmp_path, {"robot.xacro": PLACES[place]}, monkeypatch)
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.rule == "xacro-unsafe"
    assert caught.value.path == str(robot) or caught.value.path == "robot.xacro"
    assert caught.value.line is not None
    assert not (tmp_path / CANARY).exists()


def test_the_escape_is_real_the_xacro_command_runs_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The corpus is not toothless: the xacro command itself runs the attack.
    robot = _expand_in(tmp_path, {"robot.xacro": PLACES["attribute"]}, monkeypatch)
    xacro_command(robot, cwd=tmp_path)
    assert (tmp_path / CANARY).exists()


@pytest.mark.parametrize(
    "value",
    [
        f'"{SYSTEM}"',
        '"xacro.arg.__closure__"',
        '"().__class__"',
    ],
)
def test_yaml_unit_tags_are_checked_like_expressions(
    value: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _expand_in(
        tmp_path,
        {
            "robot.xacro": _robot(
                '<xacro:property name="p" value="${xacro.load_yaml(\'p.yaml\')}"/>\n'
                '<link name="${p.a}"/>'
            ),
            "p.yaml": f"a: !degrees {value}\n",
        },
        monkeypatch,
    )
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.rule == "xacro-unsafe"
    assert not (tmp_path / CANARY).exists()


def test_yaml_unit_tags_still_convert(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    files = {
        "robot.xacro": _robot(
            '<xacro:property name="p" value="${xacro.load_yaml(\'p.yaml\')}"/>\n'
            '<link name="${p.a}_${p.b}"/>'
        ),
        "p.yaml": "a: !degrees 180\nb: !millimeters 2 * 500\n",
    }
    robot = _expand_in(tmp_path, files, monkeypatch)
    assert expand(robot).text == xacro_command(robot, cwd=tmp_path).stdout


@pytest.mark.parametrize(
    ("expression", "message"),
    [
        (
            "python.vars(python.type)['_' + '_subclasses' + '__']",
            "uses python.vars, which xacro expressions may not here",
        ),
        ("python.type('X', (), python.dict())", "uses python.type, which"),
        ("python.type(python.int)('X', (), python.dict())", "uses python.type, which"),
        ("python.len([k for k in python.vars(python.int)])", "uses python.vars, which"),
    ],
)
def test_type_and_vars_are_refused_where_they_are_called(
    expression: str, message: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _expand_in(
        tmp_path, {"robot.xacro": _robot(f'<link name="${{{expression}}}"/>')}, monkeypatch
    )
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.rule == "xacro-unsafe"
    assert message in str(caught.value)
    assert "trust_expressions=True" in (caught.value.hint or "")


@pytest.mark.parametrize(
    ("eval_text", "refused"),
    [("$(eval [].__class__)", "xacro-unsafe"), ("$(eval open)", "xacro-undefined")],
)
def test_eval_substitution_is_checked_and_has_no_builtins_beyond_xacros(
    eval_text: str, refused: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # xacro's own $(eval) runs with every Python builtin, `open` among them.
    robot = _expand_in(
        tmp_path, {"robot.xacro": _robot(f'<link name="{eval_text}"/>')}, monkeypatch
    )
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.rule == refused


def test_eval_substitution_keeps_what_robots_use(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    text = _robot(
        '<xacro:arg name="r" default="0.5"/>\n'
        '<link name="a"><visual><geometry><sphere radius="$(eval 2 * r)"/>'
        "</geometry></visual></link>"
    )
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    assert expand(robot).text == xacro_command(robot, cwd=tmp_path).stdout


def test_one_file_cannot_change_the_next(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    changes = {
        "c.xacro": _robot('<link name="${python.dict.update(math, pi=3)}"/>'),
        "d.xacro": _robot('<link name="${math.pi}_${pi}"/>'),
    }
    _expand_in(tmp_path, changes, monkeypatch)
    result = CliRunner().invoke(cli, ["expand", "c.xacro"])
    assert result.exit_code == 0, result.output
    after = expand(tmp_path / "d.xacro").text
    assert 'name="3.141592653589793_3.141592653589793"' in after


def test_check_of_two_files_evaluates_each_afresh(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    files = {
        "c.xacro": _robot('<link name="a${python.dict.update(math, pi=3)}"/>'),
        "d.xacro": _robot(
            '<link name="b"/><xacro:if value="${math.pi == 3}"><link name="b"/></xacro:if>'
        ),
    }
    _expand_in(tmp_path, files, monkeypatch)
    result = CliRunner().invoke(cli, ["check", "c.xacro", "d.xacro"])
    assert result.exit_code == 0, result.output


def _recursive(depth: int) -> str:
    return _robot(
        '<xacro:macro name="m" params="n"><xacro:if value="${n > 0}">'
        '<xacro:m n="${n-1}"/></xacro:if></xacro:macro>\n'
        f'<xacro:m n="{depth}"/><link name="a"/>'
    )


def test_macros_nest_as_deep_as_the_xacro_command_lets_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # 240 nested calls: the xacro command expands them (it stops a few levels deeper, where
    # Python's recursion limit is), and so does expand, called from deep in a test runner.
    robot = _expand_in(tmp_path, {"robot.xacro": _recursive(240)}, monkeypatch)
    real = xacro_command(robot, cwd=tmp_path)
    assert real.returncode == 0
    assert expand(robot).text == real.stdout


def test_macros_without_end_are_one_located_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _expand_in(tmp_path, {"robot.xacro": _recursive(100_000)}, monkeypatch)
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.message == "macros or properties call each other without end"
    assert (caught.value.line, caught.value.column) == (2, 61)


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("<xacro:include/>", "<xacro:include> has no filename attribute"),
        ('<xacro:macro params="a"/>', "<xacro:macro> has no name attribute"),
        ("<xacro:property/>", "<xacro:property> has no name attribute"),
    ],
)
def test_an_element_without_its_name_is_one_located_error(
    body: str, message: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robot = _expand_in(tmp_path, {"robot.xacro": _robot(body)}, monkeypatch)
    result = CliRunner().invoke(cli, ["expand", "robot.xacro"])
    assert result.exit_code == 1
    tag = message.split(">")[0] + " " + message.split(" has no ")[1].split()[0]
    assert (
        result.stderr
        == f'robot.xacro:2:1: error: {message} (write it: {tag}="...">) [xacro-error]\n'
    )
    assert robot.exists()


def test_an_include_the_system_will_not_let_be_looked_at_is_one_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # As a user who may not search a folder sees it (root may search any, so the refusal
    # is made here): opening and looking at the file are both refused.
    import errno
    import os

    locked = str(tmp_path / "locked" / "x.xacro")
    _expand_in(
        tmp_path,
        {"robot.xacro": _robot('<xacro:include filename="locked/x.xacro"/>')},
        monkeypatch,
    )

    def refusing_for(function: Any) -> Any:
        def run(path: Any, *args: Any, **kwargs: Any) -> Any:
            if isinstance(path, str | os.PathLike) and os.path.abspath(path) == locked:
                raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
            return function(path, *args, **kwargs)

        return run

    with monkeypatch.context() as refusing:
        for name in ("open", "lstat", "stat"):
            refusing.setattr(os, name, refusing_for(getattr(os, name)))
        result = CliRunner().invoke(cli, ["expand", "robot.xacro"])
    assert result.exit_code == 1, (result.output, result.exception)
    assert result.stderr == (
        "robot.xacro:2:1: error: cannot read included file locked/x.xacro: Permission denied "
        "(give the user running the command the right to read it, or include another) "
        "[xacro-include]\n"
    )


@pytest.mark.skipif(not hasattr(__import__("os"), "mkfifo"), reason="this system has no FIFOs")
def test_a_fifo_or_a_device_included_is_refused_not_waited_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import os

    os.mkfifo(tmp_path / "pipe.xacro")
    for target, kind in (("pipe.xacro", "a FIFO (named pipe)"), ("/dev/zero", "a device")):
        robot = _expand_in(
            tmp_path, {"robot.xacro": _robot(f'<xacro:include filename="{target}"/>')}, monkeypatch
        )
        with pytest.raises(XacroError) as caught:
            expand(robot, allow_read=["/dev"])  # a device is outside any robot's tree
        assert caught.value.line == 2
        assert f"{kind}, not a regular file" in caught.value.message


@pytest.mark.skipif(not hasattr(__import__("os"), "mkfifo"), reason="this system has no FIFOs")
def test_a_yaml_file_that_is_a_fifo_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import os

    os.mkfifo(tmp_path / "p.yaml")
    text = _robot("<link name=\"${xacro.load_yaml('p.yaml').a}\"/>")
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert "a FIFO (named pipe), not a regular file" in caught.value.message


def test_expansion_leaves_stderr_to_the_other_threads(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import sys
    import threading

    # Each expansion gives a warning (a property named like math's pi).
    text = _robot('<xacro:property name="pi" value="3.14"/><link name="a${pi}"/>')
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    stop = threading.Event()
    written = [0]

    def chatter() -> None:
        while not stop.is_set():
            sys.stderr.write("other thread\n")
            written[0] += 1

    thread = threading.Thread(target=chatter)
    thread.start()
    try:
        expansions = [expand(robot) for _ in range(20)]
    finally:
        stop.set()
        thread.join()
    assert all(e.messages == ("warning: redefining global symbol: pi",) for e in expansions)
    assert capsys.readouterr().err.count("other thread\n") == written[0] > 0


def _doubling(levels: int) -> str:
    """Each call of m calls m twice: 2^levels links."""
    return _robot(
        '<xacro:macro name="m" params="n"><xacro:if value="${n > 0}">'
        '<xacro:m n="${n-1}"/><xacro:m n="${n-1}"/></xacro:if><link name="l"/></xacro:macro>\n'
        f'<xacro:m n="{levels}"/>'
    )


def test_an_expansion_that_doubles_without_end_stops_at_the_size_limit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _expand_in(tmp_path, {"robot.xacro": _doubling(60)}, monkeypatch)
    result = CliRunner().invoke(cli, ["expand", "robot.xacro", "--max-size", "0.01"])
    assert result.exit_code == 2
    assert result.stderr.startswith("robot.xacro:2:")
    assert (
        ": error: the expansion would make more than 10,485 bytes in all, the size limit "
        "(reached making elements), in macro m called from robot.xacro:2,"
    ) in result.stderr
    assert result.stderr.endswith(
        "(raise the limits with --timeout SECONDS and --max-size MIB) [limit]\n"
    )


def test_an_expansion_that_doubles_without_end_stops_at_the_time_limit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf.expansion import ExpansionLimitError
    from fishbot_urdf.inputs import time_limit

    robot = _expand_in(tmp_path, {"robot.xacro": _doubling(60)}, monkeypatch)
    with time_limit(0.2), pytest.raises(ExpansionLimitError) as caught:
        expand(robot)
    assert caught.value.message.startswith("the expansion takes longer than 0.2 s, in macro m")
    # and the same file within its bounds expands
    (tmp_path / "small.xacro").write_text(_doubling(3))
    assert expand(tmp_path / "small.xacro").text.count("<link") == 15


@pytest.mark.parametrize(
    ("expression", "what"),
    [
        ("10**10**8", "a number of more than 1,000,000 bits"),
        ("1 << 10**9", "a number of more than 1,000,000 bits"),
        ("(10**200000) * (10**200000)", "a number of more than 1,000,000 bits"),
        ("'a' * 10**10", "a value of more than 10,000,000 items"),
        ("[0] * 10**8", "a value of more than 10,000,000 items"),
        ("python.sum(python.range(10**12))", "a range of more than 10,000,000 items"),
        ("math.factorial(10**7)", "a math.factorial of a number past 100,000"),
        ("factorial(10**7)", "a math.factorial of a number past 100,000"),
        (
            "[x for x in python.range(10**6) for y in python.range(10**6)]",
            "takes more than 1,000,000 steps, more than a xacro expression may",
        ),
        ("(lambda f: f(f))(lambda f: f(f))", "takes more than 100 nested lambda calls"),
        (
            "python.str([[[0] * 1000] * 1000] * 1000)",
            "would make a value of more than 10,000,000 items when written out",
        ),
        ("'x'.ljust(10**9)", "would make a value of more than 10,000,000 items"),
        ("'%999999999d' % 1", "would make a value of more than 10,000,000 items"),
        ("'\\t'.expandtabs(10**9)", "would make a value of more than 10,000,000 items"),
        ("('a' * 10**6).replace('a', 'b' * 20)", "would make a value of more than 10,000,000"),
        ("'-'.join(['a' * 10**6] * 11)", "would make a value of more than 10,000,000 items"),
        (
            "[('a' * 9000000) + python.str(i) for i in python.range(3)]",
            "a value of more than 10,000,000 items when written out",
        ),
        ("math.prod(python.range(1, 10**5))", "a number of more than 1,000,000 bits"),
    ],
)
def test_an_expression_that_would_build_a_huge_value_stops_before_it_does(
    expression: str, what: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    text = _robot(f'<link name="${{{expression.replace("<", "&lt;")}}}"/>')
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    with pytest.raises(ExpansionLimitError) as caught:
        expand(robot)
    assert caught.value.rule == "limit"
    assert what in caught.value.message
    assert caught.value.message.endswith(", more than a xacro expression may")


def test_arithmetic_within_the_bounds_is_what_xacro_makes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    parts = [
        "2**10",
        "'ab' * 3",
        "[0] * 4",
        "3 * 0.5",
        "1 &lt;&lt; 4",
        "python.len(python.range(5))",
    ]
    text = _robot("".join(f'<link name="l{i}_${{{p}}}"/>' for i, p in enumerate(parts)))
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    assert expand(robot).text == xacro_command(robot, cwd=tmp_path).stdout


@pytest.mark.parametrize(
    "command",
    [
        ["check"],
        ["graph", "-o", "-"],
        ["inertia"],
        ["expand"],
        ["inertia", "--fill", "--density", "1", "-o", "out.urdf"],
    ],
)
def test_the_escape_runs_through_no_command(
    command: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _expand_in(tmp_path, {"robot.urdf.xacro": PLACES["attribute"]}, monkeypatch)
    result = CliRunner().invoke(cli, [command[0], "robot.urdf.xacro", *command[1:]])
    assert result.exit_code == 1
    assert result.stderr.endswith("[xacro-unsafe]\n")
    assert not (tmp_path / CANARY).exists()


def test_the_escape_runs_through_no_library_call(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import fishbot_urdf

    _expand_in(tmp_path, {"robot.urdf.xacro": PLACES["attribute"]}, monkeypatch)
    for call in (fishbot_urdf.load, fishbot_urdf.check_file):
        with pytest.raises(XacroError):
            call("robot.urdf.xacro")
    assert not (tmp_path / CANARY).exists()


def test_a_yaml_alias_bomb_stops_before_its_values_are_walked(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Nine levels of ten aliases each: a billion items when written out, 300 bytes on disk.
    levels = ["a0: &a0 [x, x, x, x, x, x, x, x, x, x]"]
    for i in range(1, 9):
        levels.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 10) + "]")
    files = {
        "robot.xacro": _robot(
            '<xacro:property name="p" value="${xacro.load_yaml(\'bomb.yaml\')}"/>\n'
            '<link name="${python.str(p)}"/>'
        ),
        "bomb.yaml": "\n".join(levels) + "\n",
    }
    robot = _expand_in(tmp_path, files, monkeypatch)
    result = CliRunner().invoke(cli, ["expand", str(robot)])
    assert result.exit_code == 2
    assert "the YAML file's aliases name more than 10,000,000 items" in result.stderr
    assert result.stderr.count("\n") == 1


def test_yaml_aliases_within_the_bound_load_as_xacro_loads_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    files = {
        "robot.xacro": _robot(
            '<xacro:property name="p" value="${xacro.load_yaml(\'p.yaml\')}"/>\n'
            '<link name="l_${p.b[1][0]}_${python.len(p.b)}_${p.c.r}"/>'
        ),
        "p.yaml": "a: &a [1, 2]\nb: [*a, *a, *a]\nc: {r: !degrees 90}\n",
    }
    robot = _expand_in(tmp_path, files, monkeypatch)
    assert expand(robot).text == xacro_command(robot, cwd=tmp_path).stdout


@pytest.mark.parametrize(
    "pattern",
    ["parts/*.xacro", "parts/*/*.xacro", "parts/[ab]*.xacro", "parts/?.xacro", "parts/.*", "*/x*"],
)
def test_include_patterns_match_what_glob_matches(
    pattern: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import glob

    from fishbot_urdf.expansion._budget import Budget
    from fishbot_urdf.expansion._files import Globbing

    for name in ("a.xacro", "b1.xacro", ".hidden.xacro", "c.txt", "d/x.xacro", "d/.y.xacro"):
        (tmp_path / "parts" / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / "parts" / name).write_text("<robot/>")
    monkeypatch.chdir(tmp_path)
    assert sorted(Globbing(Budget()).glob(pattern)) == sorted(glob.glob(pattern))
    absolute = str(tmp_path / pattern)
    assert sorted(Globbing(Budget()).glob(absolute)) == sorted(glob.glob(absolute))


def test_an_include_pattern_stops_at_the_deadline(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf.expansion import ExpansionLimitError
    from fishbot_urdf.inputs import time_limit

    for i in range(50):
        (tmp_path / f"d{i}" / "e").mkdir(parents=True)
    robot = _expand_in(
        tmp_path,
        {"robot.xacro": _robot('<xacro:include filename="*/*/*/none.xacro"/>')},
        monkeypatch,
    )
    with time_limit(1e-6), pytest.raises(ExpansionLimitError) as caught:
        expand(robot)
    assert "the expansion takes longer than 1e-06 s" in caught.value.message


def test_an_expression_stops_at_the_deadline(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from fishbot_urdf.expansion import ExpansionLimitError
    from fishbot_urdf.inputs import time_limit

    text = _robot('<link name="${python.len([x for x in python.range(900000)])}"/>')
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    with time_limit(0.01), pytest.raises(ExpansionLimitError) as caught:
        expand(robot)
    assert caught.value.message == "the expansion takes longer than 0.01 s"
    assert caught.value.line == 2


def test_a_format_field_in_an_argument_is_refused_as_written_in_the_expression(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # $(arg) text is put into the expression before it is read: the field is still seen.
    text = _robot(
        '<xacro:arg name="f" default="{0.__class__}"/>\n<link name="${\'$(arg f)\'.format(1)}"/>'
    )
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert caught.value.rule == "xacro-unsafe"
    assert "the format field '{0.__class__}'" in caught.value.message


def test_a_macro_parameter_named_like_a_function_cannot_be_called(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    text = _robot(
        '<xacro:macro name="m" params="len"><link name="${len([1])}"/></xacro:macro>\n'
        '<xacro:m len="x"/>'
    )
    robot = _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    with pytest.raises(XacroError) as caught:
        expand(robot)
    assert "'str' object is not callable" in caught.value.message


def test_format_widths_are_measured_before_they_are_made() -> None:
    for expression in (
        "f'{1:>999999999}'",
        "'{0:>999999999}'.format(1)",
        "'{:{}}'.format(1, 10**9)",
    ):
        with pytest.raises(UnsafeExpression) as caught:
            evaluate(expression, _symbols())
        assert caught.value.too_big or "format field" in caught.value.what


def test_bytes_have_the_methods_of_str_within_the_same_bounds() -> None:
    assert evaluate("b'xy'.upper().decode()", _symbols()) == "XY"
    for expression in (
        "b'x'.ljust(10**9)",
        "b'\\t'.expandtabs(10**9)",
        "(b'a' * 10**6).replace(b'a', b'b' * 20)",
        "b'-'.join([b'a' * 10**6] * 11)",
    ):
        with pytest.raises(UnsafeExpression) as caught:
            evaluate(expression, _symbols())
        assert caught.value.too_big, expression


def test_trust_expressions_runs_the_file_as_the_xacro_command_does(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    text = _robot('<link name="l_${python.type(1) is python.int}"/>')
    _expand_in(tmp_path, {"robot.urdf.xacro": text}, monkeypatch)
    refused = CliRunner().invoke(cli, ["expand", "robot.urdf.xacro"])
    assert refused.exit_code == 1
    assert refused.stderr == (
        "robot.urdf.xacro:2:1: error: expression ${python.type(1) is python.int} uses "
        "python.type, which xacro expressions may not here (write it with properties, "
        "arguments and the math, python and xacro functions, or, for a file you trust, run "
        "its code as Python with --trust-expressions) [xacro-unsafe]\n"
    )
    trusted = CliRunner().invoke(cli, ["expand", "robot.urdf.xacro", "--trust-expressions"])
    assert trusted.exit_code == 0, trusted.stderr
    assert trusted.stdout == xacro_command("robot.urdf.xacro", cwd=tmp_path).stdout
    assert 'name="l_True"' in trusted.stdout


@pytest.mark.parametrize("signal_name", ["SIGTERM", "SIGINT"])
def test_a_signal_stops_an_expansion_within_a_second(
    signal_name: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import signal
    import subprocess
    import sys
    import time

    # Elements doubling without end, and an expression of a million steps per element:
    # the work would go on for the whole (raised) time limit.
    text = _robot(
        '<xacro:macro name="m" params="n"><xacro:if value="${n > 0}">'
        '<xacro:m n="${n-1}"/><xacro:m n="${n-1}"/></xacro:if>'
        '<link name="${python.len([x for x in python.range(300000)])}"/></xacro:macro>\n'
        '<xacro:m n="40"/>'
    )
    _expand_in(tmp_path, {"robot.xacro": text}, monkeypatch)
    process = subprocess.Popen(
        [sys.executable, "-m", "fishbot_urdf", "expand", "robot.xacro", "--timeout", "300"],
        cwd=tmp_path,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    try:
        time.sleep(2.0)  # well into the expansion
        assert process.poll() is None
        sent = time.monotonic()
        process.send_signal(getattr(signal, signal_name))
        process.wait(timeout=10)
        waited = time.monotonic() - sent
    finally:
        process.kill()
        _, said = process.communicate()
    assert process.returncode != 0
    assert waited < 1.0, waited  # what the limits promise of a signal, not a speed
    assert b"Traceback" not in said


@pytest.mark.parametrize("trust", [False, True])
@pytest.mark.parametrize("expression", ["-" * 100_000 + "1", "not " * 50_000 + "1"])
def test_an_expression_nested_deeper_than_python_reads_is_one_limit_line(
    expression: str, trust: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Python's parser gives up with a MemoryError, which xacro wraps with no message.
    _expand_in(tmp_path, {"robot.xacro": _robot(f'<link name="${{{expression}}}"/>')}, monkeypatch)
    options = ["--trust-expressions"] if trust else []
    result = CliRunner().invoke(cli, ["expand", "robot.xacro", *options])
    assert result.exit_code == 2
    shown = expression[:57]
    assert result.stderr.startswith(f"robot.xacro:2:1: error: expression ${{{shown}...}} ")
    assert "parser can read" in result.stderr
    assert result.stderr.endswith("(write it with fewer nested brackets and operators) [limit]\n")
    assert result.stderr.count("\n") == 1
