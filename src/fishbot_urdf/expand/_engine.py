"""The run of one expansion: xacro's state reset and its hooks patched in, then restored."""

from __future__ import annotations

import io
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any
from xml.dom import expatbuilder, minidom
from xml.parsers.expat import ExpatError

from ..diagnostics import shown_path
from ..model import Location
from ..packages import PackageNotFoundError, find_package
from . import Expansion, XacroError
from ._errors import SOURCE_KEY, Explaining, source


class _KeepOnClone:
    """Copies an element's source location to its clones (DOM user-data handler)."""

    def handle(self, operation: int, key: str, data: Any, src: Any, dst: Any) -> None:
        # The clone shares the original's user data: it only ever holds this one entry and
        # is never changed (a macro call clones thousands of elements, so this is hot).
        dst._user_data = src._user_data


_KEEP = _KeepOnClone()


class _LocatingBuilder(expatbuilder.ExpatBuilderNS):
    """minidom's builder, also noting where each element starts."""

    def __init__(self, path: str) -> None:
        super().__init__()
        self._path = path

    def start_element_handler(self, name: str, attributes: Any) -> None:
        parser = self.getParser()
        line, column = parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        super().start_element_handler(name, attributes)
        self.curNode.setUserData(SOURCE_KEY, Location(self._path, line, column), _KEEP)

    # The first element goes through another handler, which then calls the one above.


class Run(Explaining):
    """One expansion: xacro's state reset, its hooks in place, for the time of a ``with``."""

    def __init__(self, path: str, args: dict[str, str], packages: dict[str, str | Path]) -> None:
        import xacro  # type: ignore[import-untyped]
        import xacro.substitution_args as subst  # type: ignore[import-untyped]

        self.xacro, self.subst = xacro, subst
        self.path, self.args, self.packages = path, args, packages
        self.node: Any = None  # the element being worked on
        self.calls: list[tuple[str, Location | None]] = []  # macro calls, outermost first
        self.symbols: Any = None  # the symbol table of a failed expression
        self.macros: Any = None  # the macro table at the last macro call
        self.parsing: str | None = None  # the file being parsed
        self.given_attributes: list[Any] = []  # elements an <xacro:attribute> wrote to
        self.properties: dict[str, Location | None] = {}  # where each property was defined
        self._saved: list[tuple[Any, str, Any]] = []
        self._messages = io.StringIO()  # what xacro would have printed on stderr

    # -- the hooks -------------------------------------------------------------------------
    def __enter__(self) -> Run:
        import xacro.color  # type: ignore[import-untyped]

        x, subst = self.xacro, self.subst
        for name in ("eval_all", "process_include", "grab_macro"):
            self._patch(x, name, self._tracked(getattr(x, name)))
        self._patch(x, "grab_property", self._property(self._tracked(x.grab_property)))
        # <xacro:if>, <xacro:arg>, <xacro:attribute> read their attributes through these and
        # then evaluate them: the element stays the one at fault until another takes over.
        self._patch(x, "check_attrs", self._noted(x.check_attrs))
        self._patch(x, "reqd_attrs", self._attributes(self._noted(x.reqd_attrs)))
        self._patch(x, "handle_macro_call", self._macro_call(x.handle_macro_call))
        self._patch(x, "safe_eval", self._safe_eval(x.safe_eval))
        self._patch(x, "eval_extension", self._extension(x.eval_extension))
        self._patch(x, "parse", self._parse)
        self._patch(x, "print_location", lambda: None)
        # xacro prints its warnings and errors through xacro.color.message (the functions
        # xacro.warning and xacro.error call it by name); ${xacro.message(...)} in a file
        # holds the original function, so its entry in the symbol table is replaced too.
        self._patch(xacro.color, "message", self._message)
        self._patch(x._global_symbols["xacro"], "message", self._exposed_message)
        self._patch(subst, "_eval_find", self._find)
        self._patch(subst._eval_dict, "find", self._find)
        # the state a previous run may have left
        self._patch(x, "all_includes", [])
        self._patch(x, "root_dir", os.curdir)
        self._patch(x, "verbosity", 1)
        self._patch(x, "substitution_args_context", {})
        x.init_stacks(None)
        return self

    def __exit__(self, *exc: object) -> None:
        for owner, name, value in reversed(self._saved):
            if isinstance(owner, dict):
                owner[name] = value
            else:
                setattr(owner, name, value)
        self.xacro.init_stacks(None)

    def _patch(self, owner: Any, name: str, value: Any) -> None:
        if isinstance(owner, dict):
            self._saved.append((owner, name, owner[name]))
            owner[name] = value
        else:
            self._saved.append((owner, name, getattr(owner, name)))
            setattr(owner, name, value)

    def _message(self, msg: Any, *args: Any, **kwargs: Any) -> None:
        # As xacro.color.message writes to a stream that is not a terminal: no colour, the
        # alt_text ('warning: ', 'error: ') in front.
        alt_text = kwargs.get("alt_text")
        text = "%s%s" % (alt_text, msg) if alt_text else msg  # noqa: UP031  # as xacro does
        self._messages.write(" ".join(map(str, (text, *args))) + "\n")  # as print() does

    def _exposed_message(self, *args: Any, **kwargs: Any) -> str:
        # ${xacro.message(...)}: as xacro's own wrapper, less the location (never printed here).
        kwargs.pop("print_location", None)
        kwargs.pop("file", None)
        self._message(*args, **kwargs)
        return ""

    def _tracked(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(node: Any, *rest: Any) -> Any:
            outer = self.node
            self.node = node
            result = function(node, *rest)
            self.node = outer  # on an error, the failing element stays
            return result

        return run

    def _noted(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(node: Any, *rest: Any) -> Any:
            self.node = node
            return function(node, *rest)

        return run

    def _property(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(node: Any, table: Any) -> Any:
            self.properties[node.getAttribute("name")] = source(node)
            return function(node, table)

        return run

    def _attributes(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(node: Any, names: Any) -> Any:
            if node.tagName == "xacro:attribute":
                self.given_attributes.append(node.parentNode)
            return function(node, names)

        return run

    def _macro_call(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(node: Any, macros: Any, symbols: Any) -> Any:
            tag = node.tagName
            if not tag.startswith("xacro:"):
                return False
            outer = self.node
            self.node, self.macros = node, macros
            self.calls.append((tag[6:], source(node)))
            result = function(node, macros, symbols)
            self.calls.pop()
            self.node = outer
            return result

        return run

    def _safe_eval(self, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(expr: str, globals: Any, locals: Any = None) -> Any:
            try:
                return function(expr, globals, locals)
            except NameError:
                self.symbols = globals
                raise

        return run

    def _extension(self, function: Callable[[str], Any]) -> Callable[[str], Any]:
        def run(text: str) -> Any:
            # xacro 2.1.1 never tells $(dirname) which file it is in.
            stack = self.xacro.filestack
            if stack and stack[-1]:
                self.xacro.substitution_args_context["filename"] = stack[-1]
            return function(text)

        return run

    def _find(self, package: str) -> str:
        stack = self.xacro.filestack
        near = stack[-1] if stack and stack[-1] else self.path
        return str(find_package(package, near=near, packages=self.packages))

    def _parse(self, inp: Any, filename: str | None = None) -> Any:
        if inp is not None:
            return minidom.parseString(inp) if isinstance(inp, str) else inp
        assert filename is not None
        full = os.path.join(self.xacro.root_dir, filename)
        try:
            data = Path(full).read_bytes()
        except OSError as exc:
            self.xacro.filestack.pop()  # as xacro does: the include, not the file, is at fault
            raise self.xacro.XacroException(f"{exc.strerror}: {full}", exc=exc) from exc
        self.parsing = filename
        document = _LocatingBuilder(shown_path(filename)).parseString(data)
        self.parsing = None
        return document

    # -- the run ---------------------------------------------------------------------------
    def expand(self) -> Expansion:
        x = self.xacro
        try:
            document = x.process_file(self.path, mappings=dict(self.args))
            _stringify_attributes(self.given_attributes)
            text = document.toprettyxml(indent="  ")
        except ExpatError as exc:
            raise self._syntax_error(exc) from exc
        except PackageNotFoundError as exc:
            raise self._located(exc) from exc
        except x.XacroException as exc:
            raise self._xacro_error(exc) from exc
        except RecursionError as exc:
            raise XacroError(
                "macros or properties call each other without end", where=source(self.node)
            ) from exc
        seen: dict[str, None] = {}
        for name in x.all_includes:
            seen.setdefault(name, None)
        messages = tuple(line for line in self._messages.getvalue().splitlines() if line.strip())
        return Expansion(
            self.path, text, tuple(seen), tuple(_sources(document, self.path)), messages
        )


def _stringify_attributes(elements: list[Any]) -> None:
    """Attribute values must be text when written; ``<xacro:attribute>`` can leave a number."""
    for element in elements:
        for attr in list(element.attributes.values()):
            if not isinstance(attr.value, str):
                attr.value = str(attr.value)


def _sources(document: Any, path: str) -> Iterator[Location]:
    """Each element's source location, in document order."""
    fallback = Location(path, 1, 1)
    stack = [document.documentElement]
    while stack:
        node = stack.pop()
        yield source(node) or fallback
        children = [c for c in node.childNodes if c.nodeType == c.ELEMENT_NODE]
        stack.extend(reversed(children))
