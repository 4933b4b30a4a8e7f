"""Turning what xacro raises into errors that say where, why and what to do."""

from __future__ import annotations

import ast
import glob
import itertools
import os
import re
from pathlib import Path
from typing import Any
from xml.parsers.expat import ExpatError

from ..catalog.xacro import (
    XACRO_CIRCULAR,
    XACRO_INCLUDE,
    XACRO_NAMESPACE,
    XACRO_SYNTAX,
    XACRO_UNDEFINED,
    XACRO_UNSAFE,
)
from ..diagnostics import shown_path
from ..errors import FishbotUrdfError, LimitError
from ..inputs import TimeLimitError, read_input
from ..location import Location
from ..packages import PackageNotFoundError
from ..wording import closest, listing
from ._bounds import UnsafeExpression
from ._interpreter import parsed
from ._result import ExpansionLimitError, XacroError
from ._scope import ReadOutsideError

_XACRO_NS = "http://www.ros.org/wiki/xacro"
# A number with a unit after it ("1kg", "0.5 m", "90deg"): the number, then the unit.
_NUMBER_AND_UNIT = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s.].*)")


def source(node: Any) -> Location | None:
    """Where an element was written, if the reader noted it."""
    if node is None or node.nodeType != node.ELEMENT_NODE:
        return None
    location = node.getUserData(SOURCE_KEY)
    return location if isinstance(location, Location) else None


SOURCE_KEY = "fishbot_urdf.source"


class Explaining:
    """The error side of a run: what the run noted, turned into one clear error."""

    xacro: Any
    subst: Any
    path: str
    args: dict[str, str]
    node: Any
    calls: list[tuple[str, Location | None]]
    symbols: Any
    macros: Any
    parsing: str | None
    unclosed: list[tuple[str, Location | None]]
    properties: dict[str, Location | None]

    # ----------------------------------------------------------------------------
    def _calls(self) -> tuple[tuple[str, Location | None], ...]:
        return tuple(reversed(self.calls))

    def _located(self, exc: PackageNotFoundError) -> PackageNotFoundError:
        where = source(self.node)
        if where is None:
            return exc
        return PackageNotFoundError(
            exc.package,
            exc.searched,
            given=exc.given,
            path=where.path,
            line=where.line,
            column=where.column,
        )

    def _syntax_error(self, exc: ExpatError) -> XacroError:
        name = self.parsing or self.path
        shown = shown_path(name)
        where = Location(shown, exc.lineno, exc.offset + 1)
        reason = str(exc).split(":", 1)[0]
        if reason == "unbound prefix":
            line = _line_of(os.path.join(self.xacro.root_dir, name), exc.lineno)
            prefix = line[exc.offset + 1 :].split(":", 1)[0]
            if prefix == "xacro":
                return XacroError(
                    "the xacro: prefix is used but not declared",
                    rule=XACRO_NAMESPACE,
                    hint=f'add xmlns:xacro="{_XACRO_NS}" to the root element',
                    where=where,
                )
            return XacroError(
                f"the {prefix}: prefix is used but not declared",
                rule=XACRO_NAMESPACE,
                hint=f'declare it on the root element: xmlns:{prefix}="..."',
                where=where,
            )
        detail = reason.removeprefix("not well-formed ").strip("()")
        left_open = self._left_open(detail, name, exc, where)
        if left_open is not None:
            return left_open
        return XacroError(f"not well-formed XML: {detail}", rule=XACRO_SYNTAX, where=where)

    def _left_open(
        self, detail: str, name: str, exc: ExpatError, where: Location
    ) -> XacroError | None:
        """For an end tag that ends another element, or a file that ends inside one: the
        error naming the elements still open and the lines they start on."""
        opened = [(tag, at.line) for tag, at in self.unclosed if at is not None]
        if not opened or detail not in ("mismatched tag", "no element found"):
            return None
        tag, since = opened[0]
        if detail == "no element found":  # the end of the file
            others = [f"<{t}> of line {n}" for t, n in opened[1:]]
            hint = f"close it with </{tag}>"
            if others:
                around = (
                    ", ".join(others[:-1]) + " and " + others[-1] if len(others) > 1 else others[0]
                )
                hint += f"; {around} {'are' if len(others) > 1 else 'is'} still open too"
            return XacroError(
                f"not well-formed XML: the file ends with <{tag}> of line {since} still open",
                rule=XACRO_SYNTAX,
                hint=hint,
                where=where,
            )
        text = _line_of(os.path.join(self.xacro.root_dir, name), exc.lineno)
        # expat points at the end tag's name
        closing = re.match(r"</\s*([^\s>]+)", text[text.rfind("</", 0, exc.offset + 1) :])
        end = f"</{closing.group(1)}>" if closing else "an end tag"
        return XacroError(
            f"not well-formed XML: mismatched tag: {end} ends <{tag}> of line {since}, "
            "which is still open",
            rule=XACRO_SYNTAX,
            hint=f"close it with </{tag}> before {end}",
            where=where,
        )

    def _xacro_error(self, outer: Any) -> FishbotUrdfError:
        exc = outer  # xacro wraps its errors in each other: the innermost says what happened
        while isinstance(exc.exc, self.xacro.XacroException):
            exc = exc.exc
        inner = exc.exc
        where = source(self.node)
        calls = self._calls()

        def undefined(message: str, hint: str | None, chain: tuple[Any, ...] = calls) -> XacroError:
            return XacroError(message, rule=XACRO_UNDEFINED, hint=hint, where=where, calls=chain)

        own = str(exc.args[0]) if exc.args and exc.args[0] else ""
        if own.startswith("circular variable definition: "):
            chain = own.removeprefix("circular variable definition: ").splitlines()[0]
            first = chain.split(" -> ")[0]
            return XacroError(
                f"property '{first}' is defined in terms of itself: {chain}",
                rule=XACRO_CIRCULAR,
                hint="give one property in the loop a value that does not refer back",
                where=self.properties.get(first) or where,
            )
        if isinstance(inner, PackageNotFoundError):
            return self._located(inner)
        if isinstance(inner, ReadOutsideError):  # a YAML file
            return inner.located(where, calls)
        if isinstance(inner, UnsafeExpression):
            return unsafe(inner, where, calls)
        if isinstance(inner, LimitError):
            return limited(inner, where, calls)
        if isinstance(inner, OSError) and self.node is not None:
            if self.node.tagName == "xacro:include":
                spec = self.node.getAttribute("filename")
                made = self._made_from_args(spec, str(inner.filename or spec))
                return _missing_include(inner, spec, where, calls, made)
            if getattr(inner, "filename", None):
                return XacroError(
                    f"cannot read {inner.filename}: {inner.strerror}",
                    rule=XACRO_INCLUDE,
                    where=where,
                    calls=calls,
                )
        if isinstance(inner, NameError):
            return self._undefined_name(inner, exc, where, calls)
        if isinstance(inner, MemoryError | RecursionError):  # xacro's own parse, trusted
            expression = str(exc.suffix or "").strip().removeprefix("when evaluating expression ")
            return ExpansionLimitError(
                f"expression {_shown(expression.strip(chr(39)))} nests deeper than Python's "
                "parser can read"
                if expression
                else f"xacro ran out of {'memory' if isinstance(inner, MemoryError) else 'stack'}",
                hint="write it with fewer nested brackets and operators" if expression else None,
                where=where,
                calls=calls,
            )
        if isinstance(inner, TypeError | ValueError | ArithmeticError):
            expression = str(exc.suffix or "").strip().removeprefix("when evaluating expression ")
            if expression:
                return self._not_computed(expression.strip("'"), inner, where, calls)
        if isinstance(inner, self.subst.ArgException):
            known = sorted(self.xacro.substitution_args_context.get("arg", {}))
            missing = str(inner)
            later = self._defined_later(missing, where, "arg")
            if later is not None:  # xacro reads <xacro:arg> in document order, as properties
                node = self.node
                on_root = node is not None and node.parentNode is node.ownerDocument
                fix = (
                    f"the root element's attributes are read before anything in it: give "
                    f"{missing}:=... on the command line"
                    if on_root
                    else f"move the declaration above the first use, or give {missing}:=... "
                    "on the command line"
                )
                return undefined(
                    f"argument '{missing}' is used before its <xacro:arg> declaration",
                    f"it is declared later, at {shown_path(later.path)}:{later.line}, and "
                    f"xacro needs the declaration first; {fix}",
                )
            return undefined(
                f"argument '{missing}' is not declared",
                _closest(missing, known, "arguments")
                or f'declare it with <xacro:arg name="{missing}" default="..."/>',
            )
        text = " ".join(part for part in (own, "" if inner is None else str(inner)) if part)
        text = " ".join(text.split())
        if text.startswith("unknown macro name: "):
            unknown = text.removeprefix("unknown macro name: ").removeprefix("xacro:")
            return undefined(
                f"macro '{unknown}' is not defined",
                _closest(unknown, _table_names(self.macros), "macros"),
                calls[1:] if calls and calls[0][0] == unknown else calls,
            )
        macro = exc.macros[0] if getattr(exc, "macros", None) else None
        if (
            macro is not None
            and calls
            and text.startswith(("Invalid parameter ", "Undefined parameters "))
        ):
            called, outer_calls = calls[0][0], calls[1:]  # the call itself is at fault
            if text.startswith("Invalid parameter "):
                param = text.removeprefix("Invalid parameter ").strip('"')
                return undefined(
                    f"macro {called} has no parameter '{param}'",
                    _closest(param, _params(macro), "parameters"),
                    outer_calls,
                )
            missing = ", ".join(text.removeprefix("Undefined parameters ").strip("[]").split(","))
            return undefined(
                f"the call of macro {called} gives no value for {missing}",
                "its parameters: " + ", ".join(_params(macro)),
                outer_calls,
            )
        said = text or (type(inner).__name__ if inner is not None else "xacro failed")
        return XacroError(said, where=where, calls=calls)

    def _made_from_args(self, spec: str, target: str) -> tuple[str, str] | None:
        """For an include whose path is made with ``$(arg ...)``: which arguments made it,
        with what values (those left at their defaults are the likely cause), and what to
        do: the values that name files there, when some do."""
        names = _arg_names(spec)
        if not names:
            return None
        values = self.xacro.substitution_args_context.get("arg", {})
        defaults = [name for name in names if name not in self.args]
        given = [name for name in names if name in self.args]
        found = _choices(spec, target, values)
        if not defaults:
            held = "argument" if len(given) == 1 else "arguments"
            fix = "check the value given" if len(given) == 1 else "check the values given"
            if found:
                fix += "; files there are named by " + _either(found, given)
            return f"its path is made from the {held} given: {_pairs(given, values)}", fix
        held = "argument" if len(defaults) == 1 else "arguments"
        its = "its default" if len(defaults) == 1 else "their defaults"
        what = f"its path is made from {held} left at {its}: {_pairs(defaults, values)}"
        if given:
            what += f", with {_pairs(given, values)} given"
        fitting = [c for c in found if all(c[n] == str(values.get(n)) for n in given)]
        if fitting:
            return what, "give " + _either(fitting, defaults)
        return what, "give " + " ".join(f"{name}:=VALUE" for name in defaults)

    def _undefined_name(
        self,
        inner: NameError,
        exc: Any,
        where: Location | None,
        calls: tuple[tuple[str, Location | None], ...],
    ) -> XacroError:
        name: str | None = getattr(inner, "name", None)
        if not isinstance(name, str):  # raised by hand: "name 'x' is not defined"
            parts = str(inner).split("'")
            name = parts[1] if len(parts) > 2 else str(inner)
        expression = str(exc.suffix or "").strip().removeprefix("when evaluating expression ")
        later = self._defined_later(name, where)
        if later is not None:
            return XacroError(
                f"'{name}' is used in ${{{expression.strip(chr(39))}}} before it is defined",
                rule=XACRO_UNDEFINED,
                hint=f"it is defined later, at {shown_path(later.path)}:{later.line}: "
                "move the definition above its first use",
                where=where,
                calls=calls,
            )
        return XacroError(
            f"'{name}' is not defined in ${{{expression.strip(chr(39))}}}",
            rule=XACRO_UNDEFINED,
            hint=_closest(name, _table_names(self.symbols), "properties"),
            where=where,
            calls=calls,
        )

    def _not_computed(
        self,
        expression: str,
        inner: Exception,
        where: Location | None,
        calls: tuple[tuple[str, Location | None], ...],
    ) -> XacroError:
        """An expression Python cannot compute (text in arithmetic, a division by zero):
        quoted, with the values at fault named in plain words."""
        said = " ".join(str(inner).split()) or type(inner).__name__
        texts = self._texts_in(expression) if isinstance(inner, TypeError | ValueError) else []
        hint = None
        if texts:
            why = "; ".join(
                f"{self._named(name)} is the text {value!r}, not a number" for name, value in texts
            )
            name, value = texts[0]
            defined = self.properties.get(name)
            at = (
                f"{self._named(name)} is defined at {defined.path}:{defined.line}"
                if defined
                else ""
            )
            number = _NUMBER_AND_UNIT.fullmatch(value)
            if number is not None:
                there = f"{at}; write" if at else "write"
                hint = f'{there} the number alone, value="{number[1]}": xacro values have no units'
            elif at:
                hint = at
        elif isinstance(inner, ZeroDivisionError):
            why = "it divides by zero"
        else:
            why = ""
        message = f"{_shown(expression)} cannot be computed: " + (
            f"{why} ({said})" if why else said
        )
        return XacroError(message, hint=hint, where=where, calls=calls)

    def _texts_in(self, expression: str) -> list[tuple[str, str]]:
        """The names of ``expression`` whose values are text, with their values."""
        try:
            tree = parsed(expression)
        except SyntaxError:
            return []
        found: dict[str, str] = {}
        for node in ast.walk(tree):
            if isinstance(node, ast.Name) and node.id not in found:
                try:
                    value = self.symbols[node.id]
                except Exception:  # not in the table (a lambda's), or failing to resolve
                    continue
                if isinstance(value, str):
                    found[node.id] = value
        return list(found.items())

    def _named(self, name: str) -> str:
        return f"property '{name}'" if name in self.properties else f"'{name}'"

    def _defined_later(
        self, name: str, where: Location | None, kind: str = "property"
    ) -> Location | None:
        """Where a ``<xacro:property name=...>`` (or ``<xacro:arg>``, for ``kind`` "arg") of
        ``name`` is written after ``where``, in its file or in another file read so far (one
        before it in the same file is in a scope the use cannot see)."""
        pattern = re.compile(
            rb"<[\w.-]+:"
            + kind.encode()
            + rb"\b[^>]*?\sname\s*=\s*([\"'])"
            + re.escape(name.encode("utf-8"))
            + rb"\1"
        )
        files = dict.fromkeys([self.path, *self.xacro.all_includes])
        for file in files:
            try:
                data = read_input(os.path.join(self.xacro.root_dir, file))
            except (FishbotUrdfError, OSError):
                continue
            for match in pattern.finditer(data):
                line = data.count(b"\n", 0, match.start()) + 1
                same = where is not None and os.path.abspath(where.path) == os.path.abspath(
                    os.path.join(self.xacro.root_dir, file)
                )
                if not same or where is None or line > where.line:
                    return Location(file, line, match.start() - data.rfind(b"\n", 0, match.start()))
        return None


TRUST_HINT = "or expand with trust_expressions=True, which runs the file's code as Python"
"""The end of the hint for an expression refused: the opt-in, in the library's words."""


def unsafe(
    inner: UnsafeExpression, where: Location | None, calls: tuple[tuple[str, Location | None], ...]
) -> XacroError:
    """One located error for an expression refused, or stopped by a bound (a ``limit``)."""
    shown = _shown(inner.expression)
    if inner.too_big:
        message = f"expression {shown} would make {inner.what}, more than a xacro expression may"
        return ExpansionLimitError(
            message, hint="a robot description needs no value that large", where=where, calls=calls
        )
    if inner.too_long:
        message = f"expression {shown} takes {inner.what}, more than a xacro expression may"
        hint = (
            "write it with fewer nested brackets and operators"
            if "nesting" in inner.what
            else "a robot description needs no loop that long"
        )
        return ExpansionLimitError(message, hint=hint, where=where, calls=calls)
    else:
        message = f"expression {shown} uses {inner.what}, which xacro expressions may not here"
        hint = (
            "write it with properties, arguments and the math, python and xacro functions, "
            + TRUST_HINT
        )
    return XacroError(message, rule=XACRO_UNSAFE, hint=hint, where=where, calls=calls)


def limited(
    inner: LimitError, where: Location | None, calls: tuple[tuple[str, Location | None], ...]
) -> ExpansionLimitError:
    """One located error for an expansion stopped by the deadline or a bound on files."""
    if isinstance(inner, TimeLimitError):
        message = f"the expansion takes longer than {inner.seconds:g} s"
    elif inner.message.startswith("the expansion "):
        message = inner.message
    else:
        message = f"the expansion stops: {inner.message}"
    return ExpansionLimitError(message, where=where, calls=calls[:3])


def _shown(expression: str) -> str:
    text = " ".join(expression.split())
    return "${" + (text if len(text) <= 60 else text[:57] + "...") + "}"


def _line_of(path: str, number: int) -> str:
    try:
        lines = Path(path).read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return ""
    return lines[number - 1] if 0 < number <= len(lines) else ""


def _missing_include(
    error: OSError,
    spec: str,
    where: Location | None,
    calls: tuple[tuple[str, Location | None], ...],
    made: tuple[str, str] | None = None,
) -> XacroError:
    """The error of an include that cannot be read; ``made``: for one whose path is made
    from arguments, what made it and what to do, said when the file does not exist."""
    target = Path(str(error.filename if error.filename is not None else spec))
    folder = target.parent
    if isinstance(error, PermissionError) or not _looked_at(target):
        return XacroError(
            f"cannot read included file {shown_path(str(target))}: "
            f"{error.strerror or 'permission denied'}",
            rule=XACRO_INCLUDE,
            hint="give the user running the command the right to read it, or include another",
            where=where,
            calls=calls,
        )
    if _is_folder(target):
        return XacroError(
            f"included path {shown_path(str(target))} is a folder, not a file",
            rule=XACRO_INCLUDE,
            hint="name a file in it",
            where=where,
            calls=calls,
        )
    if "package://" in spec:
        package = spec.split("package://", 1)[1].split("/", 1)[0]
        return XacroError(
            f"cannot include {spec}: xacro reads include paths as files, not package:// URIs",
            rule=XACRO_INCLUDE,
            hint=f"write $(find {package})/... instead",
            where=where,
            calls=calls,
        )
    if not _is_folder(folder):
        hint: str | None = f"there is no folder {shown_path(str(folder))}"
    else:
        try:
            close = closest(target.name, (p.name for p in folder.iterdir() if p.is_file()))
        except OSError:  # a folder that may not be listed
            close = None
        hint = f"did you mean '{close}'?" if close else None
    message = f"included file {shown_path(str(target))} does not exist"
    if made is not None:
        what, fix = made
        message, hint = f"{message}: {what}", f"{hint}; {fix}" if hint else fix
    return XacroError(message, rule=XACRO_INCLUDE, hint=hint, where=where, calls=calls)


def _arg_names(text: str) -> list[str]:
    """The arguments ``text`` reads with ``$(arg NAME)``, each once, in order."""
    return list(dict.fromkeys(_ARG.findall(text)))


_ARG = re.compile(r"\$\(arg\s+([^)\s]+)\s*\)")


def _choices(spec: str, target: str, values: dict[str, Any]) -> list[dict[str, str]]:
    """The values of the arguments in ``spec`` (an include's filename) that name files
    there, found by listing the folders its path is made in, at most `_MOST_CHOICES`:
    ``target``, the path made, is what the arguments' ``values`` made of the part of
    ``spec`` from its first ``$(arg ...)`` on, written after what the rest made."""
    tail = spec[spec.find("$(arg") :]
    pieces = _ARG.split(tail)  # text, name, text, name, ..., text
    texts, names = pieces[0::2], pieces[1::2]
    if any("$(" in text or "${" in text for text in texts):
        return []  # made by other substitutions too: not to be read back
    made = "".join(t + str(values.get(n, "")) for t, n in zip(texts[:-1], names, strict=True))
    made += texts[-1]
    if not target.endswith(made):
        return []
    base = target[: len(target) - len(made)]
    pattern = glob.escape(base) + "*".join(glob.escape(text) for text in texts)
    # Each argument's group, at its first place (numbered: an argument's name need not be
    # a Python name); the same value again at the others.
    groups: dict[str, int] = {}
    expression = re.escape(base)
    for text, name in zip(texts[:-1], names, strict=True):
        if name in groups:
            expression += re.escape(text) + f"(?:(?P={_group(groups[name])}))"
            continue
        groups[name] = len(groups) + 1
        expression += re.escape(text) + f"(?P<{_group(groups[name])}>[^/]+)"
    matching = re.compile(expression + re.escape(texts[-1]))
    found: list[dict[str, str]] = []
    for path in sorted(itertools.islice(glob.iglob(pattern), _MOST_LOOKED_AT)):
        match = matching.fullmatch(path)
        if match is None or not os.path.isfile(path):
            continue
        choice = {name: match.group(_group(number)) for name, number in groups.items()}
        if choice not in found:
            found.append(choice)
    return found[:_MOST_CHOICES]


def _group(number: int) -> str:
    return f"arg{number}"


_MOST_CHOICES = 4  # values offered for an include's arguments
_MOST_LOOKED_AT = 1000  # files looked at for them


def _either(choices: list[dict[str, str]], names: list[str]) -> str:
    said = [" ".join(f"{name}:={choice[name]}" for name in names) for choice in choices]
    return said[0] if len(said) == 1 else ", ".join(said[:-1]) + " or " + said[-1]


def _pairs(names: list[str], values: dict[str, Any]) -> str:
    said = [f"{name}:={values.get(name, '')}" for name in names]
    return said[0] if len(said) == 1 else ", ".join(said[:-1]) + " and " + said[-1]


def _closest(name: str, candidates: list[str], what: str) -> str | None:
    if not candidates:
        return None
    close = closest(name, candidates)
    return (
        f"did you mean '{close}'?" if close else f"defined {what}: {listing(candidates, near=name)}"
    )


def _table_names(table: Any) -> list[str]:
    """Every name a xacro symbol or macro table defines, its parents' included (the global
    symbols, Python's and math's, are left out)."""
    names: set[str] = set()
    while isinstance(table, dict) and hasattr(table, "parent"):
        names.update(key for key in dict.keys(table) if not key.startswith(("*", "__")))
        if table.parent is getattr(table, "root", None):
            break
        table = table.parent
    return sorted(names)


def _params(macro: Any) -> list[str]:
    return [p.lstrip("*") for p in macro.params]


def _looked_at(path: Path) -> bool:
    """Whether the system lets ``path`` be looked at (its folders may be searched)."""
    try:
        path.lstat()
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return True


def _is_folder(path: Path) -> bool:
    try:
        return path.is_dir()
    except OSError:
        return False
