"""What every element reader shares: findings, attribute values, skipping unread elements."""

from __future__ import annotations

from dataclasses import replace

from lxml import etree

from ..catalog import Rule
from ..catalog.reading import BAD_NUMBER, BAD_VECTOR, MISSING_ATTRIBUTE, UNKNOWN_ELEMENT
from ..diagnostics import Diagnostic, Kind, Severity, Subject
from ..expansion import EXPAND_HINT, unexpanded
from ..extensions import Reference
from ..location import call_chain, calls_of
from ..model import ZERO3, Location, Vector3
from ..xml.locator import Locator
from .values import to_double, to_doubles

Owner = Subject | str  # what a message names: a link, a joint, ... (or just "link")


def xml_text(element: etree._Element) -> str:
    """An element URDF does not define, as compact XML text (layout white space dropped, so
    that a robot written out with another indentation reads back equal).

    The white space is dropped from ``element`` itself: the reader's tree is read once, and
    nothing reads layout white space (serialising a copy took four times as long).
    """
    for node in element.iter():
        if node.text is not None and not node.text.strip():
            node.text = None
        if node.tail is not None and node is not element and not node.tail.strip():
            node.tail = None
    # As text, not bytes: ASCII bytes would write a name like <grün> as a character reference.
    return etree.tostring(element, encoding="unicode", with_tail=False)


class ReaderBase:
    """Collects findings while the model is built; reads attribute values."""

    def __init__(self, locator: Locator) -> None:
        self.locator = locator
        self.diagnostics: list[Diagnostic] = []
        self.references: list[Reference] = []  # names extension elements give
        # What the element being read belongs to: the robot, a link, a joint, a material.
        self.subject = Subject(Kind.ROBOT, "")

    # -- findings ---------------------------------------------------------------------------
    def error(
        self,
        rule: Rule,
        message: str,
        location: Location | None,
        hint: str | None = None,
        severity: Severity | None = None,
    ) -> None:
        self.diagnostics.append(
            rule.report(
                message,
                location,
                path=self.locator.path,
                subject=self.subject,
                hint=hint,
                severity=severity,
            )
        )

    def about(self, found: int, element: str) -> None:
        """Mark the findings made since there were ``found`` as about ``element`` alone (see
        `fishbot_urdf.diagnostics.Diagnostic.element`)."""
        if len(self.diagnostics) > found:
            self.diagnostics[found:] = [
                replace(d, element=element) for d in self.diagnostics[found:]
            ]

    def missing(
        self, el: etree._Element, at: Location, attr: str, owner: Owner, value: str
    ) -> None:
        self.error(
            MISSING_ATTRIBUTE,
            f"{owner}: <{el.tag}> has no {attr!r} attribute",
            at,
            f'write <{el.tag} {attr}="{value}">',
        )

    def extra(self, el: etree._Element) -> str:
        """Keep an element URDF does not define, as XML text."""
        self.locator.skip(el)
        return xml_text(el)

    def passed_over(
        self, el: etree._Element, rule: Rule, message: str, hint: str, *, made: bool = False
    ) -> None:
        """Warn about an element that is read no further, and skip what it holds; with
        ``made``, the message names the macro calls that made it, if any (its location is
        in the macro's body, which may hold the element for many calls)."""
        at = self.locator.locate(el)
        self.locator.skip_children(el)
        calls = calls_of(at) if made else ()
        if calls:
            message += f"; it is made by {call_chain(calls)}"
        self.error(rule, message, at, hint)

    def ignored(self, el: etree._Element, owner: Owner, parent: str, allowed: str) -> None:
        """Warn about an element that has no meaning where it stands, and pass over it."""
        self.passed_over(
            el,
            UNKNOWN_ELEMENT,
            f"{owner}: <{el.tag}> is not allowed inside <{parent}> and is ignored",
            allowed,
        )

    # -- attributes -------------------------------------------------------------------------
    def text(self, el: etree._Element, at: Location, attr: str, owner: Owner) -> str | None:
        """A required string attribute; reports ``missing-attribute`` when absent or empty."""
        value = el.get(attr)
        if not value:
            self.missing(el, at, attr, owner, "...")
            return None
        return value

    def number(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: Owner,
        default: float = 0.0,
        *,
        required: bool = False,
    ) -> float:
        value = el.get(attr)
        if value is None:
            if required:
                self.missing(el, at, attr, owner, "NUMBER")
            return default
        number = to_double(value) if value else None
        if number is None:
            self.error(
                BAD_NUMBER,
                f'{owner}: <{el.tag} {attr}="{value}"> is not a number',
                self.locator.attribute(at, attr),
                unexpanded_hint(value)
                or "write a finite decimal like 0.5 or 1e-3, with no units or trailing spaces",
            )
            return default
        return number

    def optional_number(
        self, el: etree._Element, at: Location, attr: str, owner: Owner
    ) -> float | None:
        return None if el.get(attr) is None else self.number(el, at, attr, owner)

    def numbers(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: Owner,
        count: int,
        meaning: str,
    ) -> list[float] | None:
        """``count`` numbers separated by spaces; None (and a finding) when malformed."""
        value = el.get(attr, "")
        if self.locator.raw_whitespace:
            # XML made the file's tabs and line breaks spaces; urdfdom sees them as written.
            value = self.locator.raw_attribute(at, attr) or value
        # urdfdom splits on spaces and drops empty pieces.
        pieces = value.split(" ")
        if "" in pieces:
            pieces = [p for p in pieces if p]
        if len(pieces) != count:
            self.error(
                BAD_VECTOR,
                f'{owner}: <{el.tag} {attr}="{value}"> has {len(pieces)} '
                f"value{'' if len(pieces) == 1 else 's'}, {count} are needed",
                self.locator.attribute(at, attr),
                unexpanded_hint(value) or f'write {attr}="{meaning}" separated by spaces',
            )
            return None
        numbers = to_doubles(pieces)
        if numbers is None:
            bad = next(p for p in pieces if to_double(p) is None)
            self.error(
                BAD_NUMBER,
                f'{owner}: <{el.tag} {attr}="{value}">: {bad!r} is not a number',
                self.locator.attribute(at, attr),
                unexpanded_hint(value)
                or f'write {attr}="{meaning}" as finite decimals separated by spaces',
            )
            return None
        return numbers

    def vector3(
        self,
        el: etree._Element,
        at: Location,
        attr: str,
        owner: Owner,
        default: Vector3 = ZERO3,
        *,
        required: bool = False,
    ) -> Vector3:
        value = el.get(attr)
        if value is None:
            if required:
                self.missing(el, at, attr, owner, "x y z")
            return default
        # Nearly always three numbers one space apart, which need none of `numbers`' care:
        # printable ASCII holds no tab or line break, and a finite sum, no inf or nan.
        pieces = value.split(" ")
        if (
            len(pieces) == 3
            and value.isascii()
            and value.isprintable()
            and "_" not in value
            and not self.locator.raw_whitespace
        ):
            try:
                x, y, z = float(pieces[0]), float(pieces[1]), float(pieces[2])
            except ValueError:
                pass
            else:
                total = x + y + z
                if total - total == 0.0:
                    return (x, y, z)
        found = self.numbers(el, at, attr, owner, 3, "x y z")
        return default if found is None else (found[0], found[1], found[2])


def unexpanded_hint(value: str) -> str | None:
    """The hint for a value that holds a xacro substitution nobody expanded, if it does."""
    if unexpanded(value) is None:
        return None
    return f"this is a xacro substitution left unexpanded: {EXPAND_HINT}"
