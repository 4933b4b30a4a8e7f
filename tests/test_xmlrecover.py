"""XML that check_urdf reads and strict parsers refuse (or read otherwise): read as urdfdom
reads it, one warning per rule, positions in the file as written; what urdfdom refuses,
refused. The fixtures are tests/data/xml/*.urdf; the wider survey is xml_survey.py."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import CORPUS, VALID, run_check_urdf, xacro_command
from hypothesis import given, settings
from hypothesis import strategies as st
from xml_survey import CASES

from fishbot_urdf import XmlSyntaxError, catalog, check_file
from fishbot_urdf.cli import cli
from fishbot_urdf.diagnostics import Severity
from fishbot_urdf.parsing import read
from fishbot_urdf.xml import recover as xmlrecover
from fishbot_urdf.xml.recover import UNDECLARED, needed

DATA = Path(__file__).parent / "data" / "xml"
FIXTURES = sorted(DATA.glob("*.urdf"))
REFUSED = sorted(DATA.glob("refused_*.urdf"))


def _position(data: bytes, offset: int, encoding: str) -> tuple[int, int]:
    """Line and column (in characters) of byte ``offset``, decoding as the file is encoded."""
    before = data[:offset].decode(encoding)
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def _between(old: bytes, new: bytes) -> Callable[[bytes], bytes]:
    def clean(data: bytes) -> bytes:
        assert old in data, old
        return data.replace(old, new)

    return clean


def _utf8(data: bytes) -> bytes:
    text = data.decode("latin-1").replace('encoding="ISO-8859-1"', 'encoding="UTF-8"')
    return text.encode("utf-8")


@dataclass(frozen=True)
class Case:
    rule: str
    at: bytes  # the warning points at the first byte of this (after ``after``)
    message: str  # part of the warning's message
    clean: Callable[[bytes], bytes]  # the file as strict XML, which must read the same
    after: int = 0
    encoding: str = "utf-8"


CASES_READ = {
    "declaration_version": Case(
        "xml-declaration",
        b"<?xml",
        'the XML declaration <?xml version="0.0" ?> is not valid XML 1.0 (urdfdom ignores it)',
        _between(b'version="0.0" ', b'version="1.0"'),
    ),
    "declaration_malformed": Case(
        "xml-declaration",
        b"<?xml",
        'the XML declaration <?xml encoding="UTF-8"?> is not valid XML 1.0',
        _between(b"<?xml encoding", b'<?xml version="1.0" encoding'),
    ),
    "declaration_after_blank_line": Case(
        "xml-declaration",
        b"<?xml",
        'XML declaration <?xml version="1.0"?> after the start of the file',
        lambda data: data[1:],
    ),
    "declaration_after_comment": Case(
        "xml-declaration",
        b"<?xml",
        "after the start of the file (urdfdom ignores it)",
        _between(b'<?xml version="1.0"?>\n', b""),
    ),
    "declaration_twice": Case(
        "xml-declaration",
        b"<?xml",
        "after the start of the file",
        lambda data: data[22:],
        after=1,
    ),
    "undeclared_prefix": Case(
        "xml-undeclared-prefix",
        b"<drake:",
        "prefix drake: used without an xmlns declaration",
        _between(
            b'name="xml_case"', b'name="xml_case" xmlns:drake="' + UNDECLARED.encode() + b'drake"'
        ),
    ),
    "default_namespace": Case(
        "xml-default-namespace",
        b"xmlns=",
        'xmlns="http://example.org/urdf" puts the URDF elements in a namespace',
        _between(b' xmlns="http://example.org/urdf"', b""),
    ),
    "encoding_declared_latin1": Case(
        "xml-encoding",
        b"\xe9",
        "the file is ISO-8859-1, not UTF-8: urdfdom does not convert it",
        _utf8,
        encoding="latin-1",
    ),
    "encoding_undeclared_latin1": Case(
        "xml-encoding",
        b"\xe0",
        "byte 0xE0 is not UTF-8",
        _utf8,
        encoding="latin-1",
    ),
    "encoding_mislabelled": Case(
        "xml-encoding",
        b"\xc3\xa4",
        "the declaration says ISO-8859-1 but the file is UTF-8",
        _between(b"ISO-8859-1", b"UTF-8"),
    ),
    "encoding_unknown_name": Case(
        "xml-encoding",
        b"<?xml",
        'declared encoding "latin-1", a name lxml does not know',
        _between(b'"latin-1"', b'"ISO-8859-1"'),
    ),
    "escape_ampersand": Case(
        "xml-escape",
        b"&chips",
        "'&' that starts no reference XML knows",
        _between(b"fish&chips", b"fishchips"),
    ),
    "escape_entity": Case(
        "xml-escape", b"&nbsp;", "urdfdom drops the '&'", _between(b"&nbsp;", b"nbsp;")
    ),
    "escape_lt": Case(
        "xml-escape",
        b"<1>",
        "'<' inside an attribute value",
        _between(b"grey<1>", b"grey&lt;1>"),
    ),
    "escape_doctype_entity": Case(
        "xml-escape",
        b"&case;",
        "&case; is an entity the file does not define: urdfdom drops the '&'",
        lambda data: data.split(b"\n", 1)[1].replace(b"xml&case;", b"xmlcase;"),
    ),
    "attribute_unquoted": Case(
        "xml-attribute",
        b"name=wrist",
        "attribute value without quotes: name=wrist",
        _between(b"name=wrist type=fixed", b'name="wrist" type="fixed"'),
    ),
    "attribute_unspaced": Case(
        "xml-attribute",
        b'type="fixed"',
        "no white space before attribute type=",
        _between(b'"wrist"type', b'"wrist" type'),
        after=300,
    ),
    "comment_dashes": Case(
        "xml-comment",
        b"<!-- tool --",
        "'--' inside a comment",
        _between(b"tool -- no inertia -", b"tool, no inertia "),
    ),
    "control_char": Case(
        "xml-control-char",
        b"\x1b",
        "control character 0x1B (urdfdom keeps it)",
        lambda data: data.replace(b"\x1b", b"").replace(b"\x0c", b"  "),
    ),
    "markup": Case(
        "xml-markup",
        b"<!ignored",
        "<!ignored here> is not XML (urdfdom skips it up to its first '>')",
        _between(b"<!ignored here><1st/>", b""),
    ),
    "name_colons": Case(
        "xml-markup",
        b"<sdf:",
        "'sdf:plugin:params' is not a name XML allows",
        _between(b"<sdf:plugin:params/>", b"<sdf.plugin.params/>"),
    ),
    "outside_root_after": Case(
        "xml-outside-root",
        b"trailing",
        "text after the <robot> element",
        lambda data: data[: data.index(b"</robot>") + 9],
    ),
    "outside_root_before": Case(
        "xml-outside-root",
        b"<export",
        '<export format="urdf"/> outside <robot>',
        lambda data: data.split(b"\n", 1)[1],
    ),
    "outside_root_nul": Case(
        "xml-outside-root",
        b"\x00",
        "NUL byte: urdfdom reads nothing after it",
        lambda data: data[: data.index(b"\x00")],
    ),
}


def test_every_recovered_fixture_has_a_case() -> None:
    names = {p.stem for p in FIXTURES} - {p.stem for p in REFUSED} - {"locations"}
    assert names == set(CASES_READ)
    assert {case.rule for case in CASES_READ.values()} == {
        rule.id for rule in catalog.rules_in(catalog.xml)
    }


@pytest.mark.parametrize("name", list(CASES_READ))
def test_one_warning_at_the_first_place(name: str) -> None:
    case = CASES_READ[name]
    path = DATA / f"{name}.urdf"
    data = path.read_bytes()
    parsed = read(path)
    assert len(parsed.diagnostics) == 1, parsed.diagnostics
    found = parsed.diagnostics[0]
    assert (found.rule, found.severity, found.path) == (case.rule, Severity.WARNING, str(path))
    assert (found.line, found.column) == _position(
        data, data.index(case.at, case.after), case.encoding
    )
    assert case.message in found.message
    assert found.hint is not None and ("lxml" in found.hint or "xacro" in found.hint)


@pytest.mark.parametrize("name", list(CASES_READ))
def test_reads_as_the_clean_file(name: str) -> None:
    data = (DATA / f"{name}.urdf").read_bytes()
    clean = CASES_READ[name].clean(data)
    assert clean != data
    strict = read(clean)
    assert strict.diagnostics == ()  # the clean file is plain XML: read with no recovery
    assert read(data).robot == strict.robot


def test_what_urdfdom_reads_where_lxml_would_not() -> None:
    # check_urdf prints these names (see the live tests below).
    names = {
        "escape_ampersand": "fishchips",
        "escape_doctype_entity": "xmlcase;",  # lxml alone reads an undefined entity as nothing
        "outside_root_after": "xml_case",  # the first <robot>, not the second
    }
    for name, robot_name in names.items():
        robot = read(DATA / f"{name}.urdf").robot
        assert robot is not None and robot.name == robot_name
    links = {"escape_entity": "toolnbsp;", "encoding_mislabelled": "tool_\u00e4"}
    for name, link in links.items():
        robot = read(DATA / f"{name}.urdf").robot
        assert robot is not None and link in {lk.name for lk in robot.links}
    robot = read(DATA / "default_namespace.urdf").robot  # lxml reads {namespace}robot
    assert robot is not None and len(robot.links) == 3


@pytest.mark.parametrize("path", REFUSED, ids=[p.stem for p in REFUSED])
def test_what_urdfdom_refuses_is_refused(path: Path) -> None:
    with pytest.raises(XmlSyntaxError) as info:
        read(path)
    assert info.value.rule == "xml-syntax"
    assert info.value.line is not None


def test_positions_are_those_of_the_file_as_written() -> None:
    path = DATA / "locations.urdf"
    data = path.read_bytes()  # ISO-8859-1 bytes, undeclared, before elements on their lines
    result = check_file(path)
    assert result.robot is not None

    def at(marker: bytes) -> tuple[int, int]:
        return _position(data, data.index(marker), "latin-1")

    robot = result.robot
    assert robot.source is not None and robot.source[1:] == at(b"<robot")
    for element, marker in (
        (robot.links[0], b'<link name="base_link"'),
        (robot.links[1], b"<link name=arm"),
        (robot.joints[0], b"<joint"),
    ):
        assert element.source is not None and element.source[1:] == at(marker)
    found = {(d.rule, d.line, d.column) for d in result.diagnostics}
    assert ("collision-material", *at(b'<material name="m&x"')) in found
    assert ("xml-escape", *at(b"&x")) in found
    assert ("xml-undeclared-prefix", *at(b"<drake:")) in found
    assert ("xml-encoding", *at(b"\xe9")) in found
    assert ("xml-declaration", *at(b"<?xml")) in found
    assert ("xml-outside-root", *at(b"exported")) in found
    assert len([d for d in result.diagnostics if d.rule.startswith("xml-")]) == len(
        {d.rule for d in result.diagnostics if d.rule.startswith("xml-")}
    )


# -- live, against check_urdf ----------------------------------------------------------------


def _ours(path: Path) -> tuple[int, bytes, str]:
    # The cases put odd characters into mesh names, of files that are not there: what is
    # compared here is how the file is read.
    result = CliRunner().invoke(cli, ["check", "--ignore", "meshes", str(path)])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result.exit_code, result.stdout_bytes, result.stderr


@pytest.mark.parametrize("path", FIXTURES, ids=[p.stem for p in FIXTURES])
def test_fixture_checks_like_check_urdf(path: Path) -> None:
    real = run_check_urdf(path)
    status, out, err = _ours(path)
    if real.returncode == 0:
        assert (status, out) == (0, real.stdout)
        assert all(": warning: " in line for line in err.splitlines()), err
    else:
        assert status == 1 and out == b"", err


# A name urdfdom holds as bytes that are not UTF-8 is read here as those bytes mean (ISO-8859-1
# where they are not UTF-8), and a control character XML cannot hold as U+FFFD: check_urdf
# prints the raw bytes, fishbot check the UTF-8 of what they mean.
_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f]")


def _meaning(raw: bytes) -> bytes:
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        table = {0xDC00 + b: b for b in range(0x80, 0x100)}
        text = raw.decode("utf-8", "surrogateescape").translate(table)
    return _CONTROL.sub("\ufffd", text).encode("utf-8")


@pytest.mark.parametrize("name", list(CASES))
def test_survey_case_checks_like_check_urdf(name: str, tmp_path: Path) -> None:
    path = tmp_path / f"{name}.urdf"
    path.write_bytes(CASES[name])
    real = run_check_urdf(path)
    status, out, err = _ours(path)
    if real.returncode != 0:
        assert status == 1, err
        return
    assert out == _meaning(real.stdout), err
    assert status == 0, err


def test_names_urdfdom_holds_as_raw_bytes(tmp_path: Path) -> None:
    """Where check_urdf prints bytes that are not UTF-8, they are what the name here means."""
    cases = {
        "latin1": b'<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="r\xe4">',
        "reference": b'<robot name="r&#8364;">',  # no declaration: urdfdom keeps 0xAC only
        "bad_utf8": b'<?xml version="1.0"?>\n<robot name="r\xc3(">',
    }
    for name, head in cases.items():
        path = tmp_path / f"{name}.urdf"
        path.write_bytes(head + b'<link name="a"/></robot>\n')
        real = run_check_urdf(path)
        assert real.returncode == 0
        printed = real.stdout.split(b"\n", 1)[0].removeprefix(b"robot name is: ")
        assert not _is_utf8(printed), name
        robot = read(path).robot
        assert robot is not None and robot.name.encode() == _meaning(printed), name


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


# -- cost ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("path", VALID + CORPUS, ids=[p.name for p in VALID + CORPUS])
def test_clean_files_take_the_plain_path(path: Path) -> None:
    # Plain XML read alike by lxml and urdfdom goes straight to lxml: no model of TinyXML.
    assert not needed(path.read_bytes())


def test_what_xacro_makes_of_the_fixtures() -> None:
    # xacro (expat) refuses every recovered fixture but these; of those, it reads an undefined
    # entity after a DOCTYPE as nothing, where urdfdom reads "xmlcase;".
    outputs = {}
    for path in FIXTURES:
        if not path.stem.startswith("refused_"):
            proc = xacro_command(path)
            if proc.returncode == 0:
                outputs[path.stem] = proc.stdout
    assert set(outputs) == {
        "declaration_version",
        "default_namespace",
        "encoding_mislabelled",
        "encoding_unknown_name",
        "escape_doctype_entity",
    }
    assert '<robot name="xml">' in outputs["escape_doctype_entity"]
    assert '<link name="tool_\u00e4"/>' in outputs["encoding_mislabelled"]


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet="<?>x ", max_size=30))
def test_instructions_holding_gt_are_found_as_the_pattern_finds_them(text: str) -> None:
    data = text.encode()
    found = any(b">" in m[0][2:-2] for m in xmlrecover._PI.finditer(data))
    assert xmlrecover._instruction_holding_gt(data) is found
