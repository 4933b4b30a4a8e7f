"""Control characters written visibly, so that a line of text stays one line on a terminal
and drives nothing there. Below every other module, so that the command line's first
messages need nothing else of the library (`fishbot --help` loads this and click)."""

from __future__ import annotations

import re

__all__ = ["escape_controls", "escape_line_controls"]


# C0 controls (newline, CR, tab, ESC, ...), DEL, C1 controls, the Unicode line and paragraph
# separators, and the C1 bytes of a file name that is no UTF-8 (kept as surrogates).
_CONTROLS = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\udc80-\udc9f]")
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escaped(match: re.Match[str]) -> str:
    char = match[0]
    named = _NAMED.get(char)
    if named is not None:
        return named
    code = ord(char)
    if 0xDC80 <= code <= 0xDC9F:  # a byte 0x80-0x9f of a name that is no UTF-8
        return f"\\x{code - 0xDC00:02x}"
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def escape_controls(text: str) -> str:
    """``text`` with every control character written visibly, as Python writes it in a
    string: newline ``\\n``, carriage return ``\\r``, tab ``\\t``, other C0 controls,
    DEL and C1 controls ``\\xHH`` (ESC is ``\\x1b``; so is a byte 0x80-0x9f of a file
    name that is no UTF-8), the line and paragraph separators
    ``\\u2028`` and ``\\u2029``. A line made of such text stays one line, and no
    terminal escape sequence is in it. Backslashes are left as they are (a name may hold
    the two characters ``\\n``: only a control character is ever escaped)."""
    return _CONTROLS.sub(_escaped, text)


_TERMINAL = re.compile("[\x00-\x08\x0a-\x1f\x80-\x9f\u2028\u2029\udc80-\udc9f]")


def escape_line_controls(text: str) -> str:
    """``text`` with the control characters that end a line or drive a terminal written as
    :func:`escape_controls` writes them; a tab and DEL, which do neither, are left as they
    are (for output that keeps another tool's bytes, such as check_urdf's tree)."""
    return _TERMINAL.sub(_escaped, text)
