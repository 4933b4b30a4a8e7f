"""The run of one expansion: its own copy of xacro, its hooks in place, one budget."""

from __future__ import annotations

import contextvars
import io
import os
import re
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any
from xml.dom import expatbuilder, minidom
from xml.parsers.expat import ExpatError

from ..catalog.xacro import XACRO_SYNTAX
from ..diagnostics import shown_path
from ..errors import FishbotUrdfError, InputError, LimitError
from ..escaping import escape_controls
from ..inputs import read_input
from ..location import Location, MacroLocation, calls_of
from ..packages import PackageFinder, PackageNotFoundError, find_package
from ._allowlist import allowed_callables, prepare_symbols
from ._budget import ELEMENT_BYTES, Budget
from ._errors import SOURCE_KEY, Explaining, limited, source
from ._files import Globbing, YamlError, load_yaml_bounded
from ._instance import Xacro, load_xacro
from ._interpreter import evaluate
from ._macros import MacroTable
from ._result import Expansion, XacroError
from ._scope import ReadOutsideError, ReadScope


class _Keeper:
    """Copies an element's source location to its clones (DOM user-data handler), and
    charges each element made, parsed or cloned, to the expansion's budget: macros that
    call each other twice per level double the document with every level, and an include
    made fifty times over fifty times makes as many copies of its file."""

    __slots__ = ("budget", "called", "count")

    def __init__(self, budget: Budget) -> None:
        self.budget = budget
        self.count = 0
        self.called: Callable[[Any], None] = lambda body: None  # a macro body cloned

    def made(self, text: int) -> None:
        """One element made, holding ``text`` characters of its own."""
        self.budget.spend(ELEMENT_BYTES + text, "elements")
        self.count += 1
        if not self.count & 63:
            self.budget.check()

    def handle(self, operation: int, key: str, data: Any, src: Any, dst: Any) -> None:
        # The clone shares the original's user data: it only ever holds this one entry and
        # is never replaced but by `Run._made_by_call` (a macro call clones thousands of
        # elements, so this is hot).
        dst._user_data = src._user_data
        text = 0
        for child in src.childNodes:
            if child.nodeType == _TEXT:
                text += len(child.data)
        self.made(text)
        if src.tagName == "xacro:macro":  # the last of a body's elements to be cloned
            self.called(dst)


_TEXT = minidom.Node.TEXT_NODE


class _LocatingBuilder(expatbuilder.ExpatBuilderNS):
    """minidom's builder, also noting where each element starts and charging it."""

    def __init__(self, path: str, keeper: _Keeper) -> None:
        super().__init__()
        self._path = path
        self._keeper = keeper

    def start_element_handler(self, name: str, attributes: Any) -> None:
        parser = self.getParser()
        line, column = parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        self._keeper.made(0)  # the file's text was charged as it was read
        super().start_element_handler(name, attributes)
        self.curNode.setUserData(SOURCE_KEY, Location(self._path, line, column), self._keeper)

    # The first element goes through another handler, which then calls the one above.


class Run(Explaining):
    """One expansion, on a copy of xacro of its own (see :mod:`._instance`)."""

    def __init__(
        self,
        path: str,
        args: dict[str, str],
        packages: dict[str, str | Path] | PackageFinder,
        *,
        trust: bool = False,
        reads: ReadScope,
        probe: Callable[[MacroTable], Any] | None = None,
    ) -> None:
        self.path, self.args, self.packages = path, args, packages
        self.probe = probe  # called with the top-level macros once the walk is done
        self.probed: Any = None  # what it gave
        self._top: tuple[Any, Any] | None = None  # the top level's macros and symbols
        # For a probe: the arguments each macro call gave (by its calls, innermost first),
        # as written and as evaluated.
        self._given: dict[tuple[tuple[str, Location], ...], dict[str, tuple[str, Any]]] = {}
        self.trust = trust  # expressions run as Python, as xacro runs them
        self.reads = reads  # where files may be read; $(find) adds each package found
        self.node: Any = None  # the element being worked on
        self.calls: list[tuple[str, Location | None]] = []  # macro calls, outermost first
        self.symbols: Any = None  # the symbol table of a failed expression
        self.macros: Any = None  # the macro table at the last macro call
        self.parsing: str | None = None  # the file being parsed
        self.unclosed: list[tuple[str, Location | None]] = []  # where its parse stopped
        self.given_attributes: list[Any] = []  # elements an <xacro:attribute> wrote to
        self.properties: dict[str, Location | None] = {}  # where each property was defined
        self._messages = io.StringIO()  # what xacro would have printed on stderr
        # One budget for the whole expansion: its steps, what it makes, and the deadline
        # in force where it was called.
        self.budget = Budget()
        self._keeper = _Keeper(self.budget)
        own = load_xacro(
            trust=trust,
            message=self._message,
            evaluate=self._evaluate,
            substitution_eval=self._substitution_eval,
        )
        self.xacro, self.subst = own.xacro, own.subst
        # The evaluators' code: a frame of one, in a traceback, holds the symbols of the
        # expression that failed (xacro's own, when trusted, or this run's).
        self._evaluating = (evaluate.__code__, own.xacro.safe_eval.__code__)
        self._calling = own.xacro.handle_macro_call.__code__  # the step that clones bodies
        self._install(own)
        self.allowed: frozenset[int] = allowed_callables(self.xacro._global_symbols)
        self._keeper.called = self._made_by_call

    # -- the hooks -------------------------------------------------------------------------
    def _install(self, own: Xacro) -> None:
        """Put this run's hooks into its own copy of xacro, for good: nothing is restored."""
        x, subst = own.xacro, own.subst
        # The element at fault and the macro calls that led to it are read off the stack
        # when an error comes (see _locate): no hook sits on xacro's recursion, which
        # keeps its depth the xacro command's.
        x.grab_property = self._property(x.grab_property)
        x.reqd_attrs = self._attributes(x.reqd_attrs)
        x.glob = Globbing(self.budget, lambda f, p: self.reads.check_pattern(f, p))
        x.eval_extension = self._extension(x.eval_extension)
        x.parse = self._parse
        x.print_location = lambda: None
        # Each run evaluates in a symbol table of its own: nothing one file does to
        # ``math`` or ``python`` reaches the next.
        x._global_symbols = self._fresh_symbols()
        subst._eval_find = self._find
        subst._eval_dict["find"] = self._find
        x.init_stacks(None)
        if self.probe is not None:
            walk = x.eval_all

            def top(node: Any, macros: Any, symbols: Any) -> Any:
                # The first call is process_doc's, with the top level's tables; the walk
                # below it is xacro's own, frame for frame.
                x.eval_all = walk
                self._top = (macros, symbols)
                return walk(node, macros, symbols)

            x.eval_all = top

    def _fresh_symbols(self) -> dict[str, Any]:
        x = self.xacro
        symbols: dict[str, Any] = x._global_symbols  # made when this copy of xacro was
        if not self.trust:
            prepare_symbols(symbols)
        exposed = symbols["xacro"]
        exposed["message"] = self._exposed_message
        exposed["load_yaml"] = self._load_yaml
        if "load_yaml" in symbols:  # the deprecated name outside the namespace
            message = "Using load_yaml() directly is deprecated. Use xacro.load_yaml() instead."

            def deprecated(filename: str) -> Any:
                x.warning(message)
                return self._load_yaml(filename)

            symbols["load_yaml"] = deprecated
        return symbols

    def _load_yaml(self, filename: str) -> Any:
        """xacro.load_yaml, reading only a regular file, with its aliases bounded."""
        x = self.xacro
        symbols = x._global_symbols
        name = x.abs_filename_spec(filename)
        self.reads.check(name)
        x.filestack.append(name)
        try:
            try:
                data = read_input(name)
            except InputError as exc:
                raise x.XacroException(f"cannot read {name}: {exc.message}") from exc
            self.budget.spend(len(data), "files read")

            def unit(value: str) -> float:
                try:
                    return float(self._evaluate(value, symbols))
                except SyntaxError as exc:
                    raise x.XacroException(f"invalid expression: {value}") from exc

            units = {u.value.tag: u.value.conversion_constant for u in x.ConstructUnits}
            try:
                loaded = load_yaml_bounded(data, units, unit, self.budget)
            except YamlError as exc:
                raise x.XacroException(f"{name} is not valid YAML: {exc.message}") from exc
            return x.YamlListWrapper.wrap(loaded)
        finally:
            x.filestack.pop()
            x.all_includes.append(name)

    def _evaluate(self, expression: str, globals: Any, locals: Any = None) -> Any:
        """xacro's ``safe_eval``, by allowlist (as xacro's own with --trust-expressions)."""
        if self.trust:
            return self.xacro.safe_eval(expression, globals, locals)
        return evaluate(expression, globals, locals, allowed=self.allowed, budget=self.budget)

    def _substitution_eval(self, text: str, context: dict[str, Any]) -> str:
        """``$(eval ...)``: the same check as ``${...}``, and no builtins either."""
        subst = self.subst
        args = context.setdefault("arg", {})
        functions = dict(subst._eval_dict)
        functions["arg"] = lambda name: subst.convert_value(
            subst._eval_arg(name, args=args), "auto"
        )
        functions["dirname"] = lambda: subst._eval_dirname(context["filename"])
        functions.pop("__builtins__", None)
        # xacro gives $(eval) all of Python's builtins; here, those ${...} has as python.*
        builtins = dict(self.xacro._global_symbols["python"])
        allowed = self.allowed | {id(f) for f in functions.values() if callable(f)}
        scope = subst._DictWrapper(args, functions)
        return str(evaluate(text, {}, scope, builtins, allowed=allowed, budget=self.budget))

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

    def _made_by_call(self, body: Any) -> None:
        """Note on each element of a macro body just cloned for a call the call that makes
        it (and the calls that made that call), for findings that tell apart what two
        calls of one macro make. The call is read off the stack: handle_macro_call is the
        caller of the clone."""
        frame: Any = sys._getframe(3)  # the clone's: above it, handle and minidom's handler
        step = self._calling
        while frame is not None and frame.f_code is not step:
            frame = frame.f_back
        if frame is None:
            return
        call = frame.f_locals["node"]
        site = source(call)
        if site is None:
            return
        calls = ((call.tagName[6:], Location(*site)), *calls_of(site))
        if self.probe is not None:
            self._given[calls] = self._arguments(call, frame.f_locals["symbols"])
        made: dict[int, dict[str, Any]] = {}  # one entry per element of the macro's text
        keeper = self._keeper
        element_node = body.ELEMENT_NODE
        stack = [body]
        while stack:
            element = stack.pop()
            stack += [c for c in element.childNodes if c.nodeType == element_node]
            shared = getattr(element, "_user_data", None)  # none: made by xacro itself
            if not shared:
                continue
            entry = made.get(id(shared))
            if entry is None:
                path, line, column = shared[SOURCE_KEY][0]
                entry = made[id(shared)] = {
                    SOURCE_KEY: (MacroLocation(path, line, column, calls), keeper)
                }
            element._user_data = entry

    def _arguments(self, call: Any, symbols: Any) -> dict[str, tuple[str, Any]]:
        """A call's arguments, as written and as xacro evaluates them next (in the caller's
        symbols, unchanged until then: the body is cloned first), or None where the
        evaluation fails (xacro then says why)."""
        given: dict[str, tuple[str, Any]] = {}
        for name, text in call.attributes.items():
            try:
                value = self.xacro.eval_text(text, symbols)
            except LimitError:
                raise
            except Exception:  # xacro's own evaluation, next, reports it
                value = None
            given[name] = (text, value)
        return given

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
        if isinstance(self.packages, PackageFinder):  # a workspace's: each answer kept
            found = self.packages.find(package, near=near)
        else:
            found = find_package(package, near=near, packages=self.packages)
        self.reads = self.reads.including(found)
        return str(found)

    def _parse(self, inp: Any, filename: str | None = None) -> Any:
        if inp is not None:
            return minidom.parseString(inp) if isinstance(inp, str) else inp
        assert filename is not None
        full = os.path.join(self.xacro.root_dir, filename)
        self.reads.check(full)
        try:
            data = read_input(full)
        except InputError as exc:
            if len(self.xacro.filestack) <= 1 and filename == self.path:
                raise  # the file expanded, not an include: the caller's input is at fault
            self.xacro.filestack.pop()  # as xacro does: the include, not the file, is at fault
            cause = exc.__cause__
            if isinstance(cause, OSError):  # missing, a folder, unreadable: as xacro says it
                raise self.xacro.XacroException(f"{cause.strerror}: {full}", exc=cause) from exc
            raise self.xacro.XacroException(f"cannot include {full}: {exc.message}") from exc
        if data.startswith((b"\xff\xfe", b"\xfe\xff")) or b"\0" in data[:4]:
            raise XacroError(  # xacro decodes every file as UTF-8, and fails on these
                "the file is UTF-16 or UTF-32, and xacro reads UTF-8 only",
                rule=XACRO_SYNTAX,
                hint="save it as UTF-8",
                where=Location(shown_path(filename), 1, 1),
            )
        self.budget.spend(len(data), "files read")
        self.parsing = filename
        builder = _LocatingBuilder(shown_path(filename), self._keeper)
        try:
            document = builder.parseString(data)
        except ExpatError:
            self.unclosed = _open_elements(builder.curNode)
            raise
        self.parsing = None
        return document

    def _stumbled(self, exc: Exception) -> XacroError:
        """xacro failed inside, on a value the file gave it (an include's name that is a
        number, say): one located error, with what Python said."""
        said = " ".join(str(exc).split()) or type(exc).__name__
        return XacroError(
            f"xacro cannot process this element: {said}",
            where=source(self.node),
            calls=self._calls(),
        )

    def _locate(self, error: BaseException) -> None:
        """The element at fault, and the macro calls that led to it, from the frames of an
        error: the innermost element one of xacro's steps was working on."""
        x = self.xacro
        steps = {
            x.eval_all.__code__: "node",
            x.handle_macro_call.__code__: "node",
            x.process_include.__code__: "elt",
            x.grab_macro.__code__: "elt",
            x.grab_property.__code__: "elt",
            x.check_attrs.__code__: "tag",
            x.xmlutils.reqd_attrs.__code__: "tag",
        }
        calls: list[tuple[str, Location | None]] = []
        # The symbols of the failing expression: its frame is in the error's traceback or,
        # when xacro wrapped the error, in the traceback of the one it wrapped.
        chained: BaseException | None = error
        while chained is not None:
            for frame in _frames(chained):
                if frame.f_code in self._evaluating:
                    self.symbols = frame.f_locals.get("globals")
            chained = chained.__context__
        for frame in _frames(error):
            local = steps.get(frame.f_code)
            node = frame.f_locals.get(local) if local else None
            if node is None:
                continue
            if node.nodeType != node.ELEMENT_NODE:  # a text: its element is at fault
                node = node.parentNode
            self.node = node
            if frame.f_code is x.handle_macro_call.__code__ and node.tagName.startswith("xacro:"):
                calls.append((node.tagName[6:], source(node)))
                self.macros = frame.f_locals.get("macros")
        self.calls = calls

    # -- the run ---------------------------------------------------------------------------
    def _walk(self) -> tuple[Any, str]:
        """xacro's processing of the file, and the document written out."""
        document = self.xacro.process_file(self.path, mappings=dict(self.args))
        if self.probe is not None and self._top is not None:
            self.probed = self.probe(MacroTable(self.xacro, *self._top, self._given))
        _stringify_attributes(self.given_attributes)
        _escape_banner(document, self.path)
        return document, document.toprettyxml(indent="  ")

    def expand(self) -> Expansion:
        x = self.xacro
        # What the caller's thread raises while it waits (a signal handler's exception, an
        # interrupt) is the caller's, and goes on as it is; only the walk's failures are
        # the file's, and explained.
        outcome, failure = _on_a_fresh_stack(self._walk, self.budget)
        try:
            if failure is not None:
                self._locate(failure)
                raise failure
            document, text = outcome
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
        except RuntimeError as exc:  # xacro's check of an element's attributes
            tag, _, missing = str(exc).partition(": missing attribute ")
            if not missing:
                raise self._stumbled(exc) from exc
            raise XacroError(
                f"<{tag}> has no {missing.strip(chr(39))} attribute",
                hint=f'write it: <{tag} {missing.strip(chr(39))}="...">',
                where=source(self.node),
                calls=self._calls(),
            ) from exc
        except LimitError as exc:  # the budget, the deadline, or too many files globbed
            raise limited(exc, source(self.node), self._calls()) from exc
        except ReadOutsideError as exc:  # an include, or its pattern
            raise exc.located(source(self.node), self._calls()) from exc
        except FishbotUrdfError:
            raise
        except Exception as exc:  # xacro stumbling on what the file gave it
            raise self._stumbled(exc) from exc
        seen: dict[str, None] = {}
        for name in x.all_includes:
            seen.setdefault(name, None)
        messages = tuple(line for line in self._messages.getvalue().splitlines() if line.strip())
        return Expansion(
            self.path, text, tuple(seen), tuple(_sources(document, self.path)), messages
        )


def _open_elements(node: Any) -> list[tuple[str, Location | None]]:
    """The elements a parse stopped inside, innermost first, with where each starts."""
    found = []
    while node is not None and node.nodeType == node.ELEMENT_NODE:
        found.append((node.tagName, source(node)))
        node = node.parentNode
    return found


def _frames(error: BaseException) -> Iterator[Any]:
    """The frames of an error's traceback, outermost first."""
    trace = error.__traceback__
    while trace is not None:
        yield trace.tb_frame
        trace = trace.tb_next


def _on_a_fresh_stack(work: Callable[[], Any], budget: Budget) -> tuple[Any, BaseException | None]:
    """Run ``work`` in a thread of its own, in the caller's context: xacro recurses once per
    nested macro call, and Python's recursion limit counts the frames of a thread, so the
    caller's frames (a command line, a test runner) do not shorten how deep macros may go.

    If the caller stops waiting (an interrupt, a signal handler that raises, an error), the
    work is cancelled through its budget and ends at its next step: it never goes on
    unwatched, and it runs on its own copy of xacro, whatever the caller does next.

    Gives what ``work`` returned, or what it raised."""
    worker = _Worker(work)
    try:
        worker.start()
        worker.join()
    except BaseException:
        budget.cancel()
        raise
    return worker.outcome, worker.failure


class _Worker(threading.Thread):
    def __init__(self, work: Callable[[], Any]) -> None:
        # A daemon: an interrupt in the caller's thread ends the program without waiting.
        super().__init__(name="fishbot-xacro", daemon=True)
        self.context = contextvars.copy_context()
        self.work = work
        self.outcome: Any = None
        self.failure: BaseException | None = None

    def run(self) -> None:  # as few frames under xacro's as its own command has
        try:
            self.outcome = self.context.run(self.work)
        except BaseException as exc:  # handed to the caller's thread, raised there
            self.failure = exc


def _escape_banner(document: Any, path: str) -> None:
    """The file's name in the banner xacro writes at the top, its control characters written
    visibly as in every finding (a terminal escape or a character XML refuses would pass
    raw); an ordinary name is left as xacro writes it."""
    shown = escape_controls(path)
    if shown == path:
        return
    written = re.sub(r"-+", "-", path)  # as xacro shortens dashes, for XML's comments
    for node in document.childNodes:
        if node.nodeType == node.COMMENT_NODE and written in node.data:
            node.data = node.data.replace(f"{written:<30}", f"{re.sub(r'-+', '-', shown):<30}", 1)
            return


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
