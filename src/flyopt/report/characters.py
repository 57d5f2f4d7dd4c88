"""What a person reads of a name shows every character: control and bidirectional-override characters as escapes.

A scene's title, a shaft's or a material's name are the user's text, and
reach a terminal (the text report), a browser (the HTML report), a PDF and
the figures. A character that is not drawn but acts (NUL, BEL, ESC that
starts a terminal sequence, U+202E that reverses the text after it) is shown
as the escape Python writes for it (``\\x1b``, ``\\u202e``), so that what is
read is what the file holds. Every renderer passes its text through
:func:`visible`.
"""

from __future__ import annotations

import re
import unicodedata

__all__ = ["ACTING", "visible"]

#: Unicode categories of characters that act rather than show: control (Cc), format (Cf: the
#: bidirectional overrides and isolates, zero-width characters), surrogates (Cs), private use (Co),
#: unassigned (Cn).
ACTING = frozenset({"Cc", "Cf", "Cs", "Co", "Cn"})

#: Kept as they are: the line break and the tab lay text out and do nothing else.
LAYOUT = frozenset("\n\t")

_SAFE = re.compile(r"[\x20-\x7e\n\t]*")


def visible(text: str) -> str:
    """``text`` with every acting character (:data:`ACTING`) but the line break and the tab written as its escape.

    >>> visible("a\\x00b\\u202eevil")
    'a\\\\x00b\\\\u202eevil'
    """
    if _SAFE.fullmatch(text) or _SHOWN.issuperset(text):  # nothing to look at: ASCII, or characters seen to show
        return text
    out = "".join(ascii(c)[1:-1] if c not in LAYOUT and unicodedata.category(c) in ACTING else c for c in text)
    _SHOWN.update(c for c in text if c in LAYOUT or unicodedata.category(c) not in ACTING)
    return out


#: Characters :func:`visible` has found to show as they are (the report's ω, δ, ·, ² ...): a text made of them
#: only is returned at once, without a look at each character (the PDF passes every paragraph through here).
_SHOWN: set[str] = set()
