"""The engineering report as a neutral document: what both renderers draw.

A :class:`Document` is a title block and numbered :class:`Section` s of
paragraphs, facts, tables, equations, figures and code, its numbers
:class:`Quantity` s that carry their SI value and JSON name beside the text
the reader sees. :func:`flyopt.report.builder.build` writes it from a solved
scene; :mod:`flyopt.report.html` and :mod:`flyopt.report.pdf` render it, so
that the two formats always say the same thing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "Code",
    "Document",
    "Equation",
    "Facts",
    "Figure",
    "Paragraph",
    "Quantity",
    "Section",
    "Table",
    "anchor",
    "listing",
    "plain",
]

MAX_LISTED_LINES = 2_000
"""Most lines of a file a report lists (about 25 PDF pages of the scene file)."""
MAX_LISTED_CHARACTERS = 200_000
"""Most characters of a file a report lists, however few its lines."""

# --------------------------------------------------------------------------
# The document: what both renderers draw
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Quantity:
    """A number as the report shows it, and what it is.

    ``text`` is what the reader sees (in the report's unit system); ``name``
    is the quantity's JSON name (docs/nomenclature.md) or None; ``si`` its
    value in SI; the HTML carries ``name`` and ``si`` as data attributes so
    that the shown number can be checked against the solver's.
    """

    text: str
    name: str | None
    si: float | None
    dimension: str


#: A run of text: a string (with ``_{sub}`` and ``^{sup}`` markup) or a Quantity, or a tuple of them.
Text = "str | Quantity | tuple"


@dataclass(frozen=True)
class Paragraph:
    """A paragraph; ``kind`` "text", "display" (a formula on its own line), "note", "ok" or "warning" (a verdict
    the reader must not miss)."""

    text: object
    kind: str = "text"


@dataclass(frozen=True)
class Facts:
    """Label–value pairs (a two-column table without a header)."""

    rows: tuple
    name: str | None = None


@dataclass(frozen=True)
class Table:
    """A table: ``head`` (column titles), ``rows`` (cells of Text), ``align`` ("<" or ">" per column).

    ``total`` marks the last row as a total (drawn with a rule above it).
    """

    head: tuple
    rows: tuple
    align: tuple
    caption: str = ""
    name: str | None = None
    total: bool = False


@dataclass(frozen=True)
class Equation:
    """One step: the formula, the numbers substituted, the result, and where the formula comes from.

    ``lines[0]`` is the formula, ``lines[1:-1]`` the numbers substituted (SI),
    ``lines[-1]`` the result; ``key`` names the step (the HTML carries it).
    """

    key: str
    lines: tuple
    reference: str


@dataclass
class Figure:
    """A diagram: a matplotlib Figure, or why it is not drawn (``note``); ``digest``: that of the data it draws
    (:mod:`flyopt.report.plots.digest`; "" where its diagram has none): the same digest, the same figure."""

    key: str
    caption: str
    figure: Any = None  # a matplotlib Figure
    note: str = ""
    failed: bool = False
    digest: str = ""


@dataclass(frozen=True)
class Code:
    """Text shown as given (the scene file); ``note`` says what of it is not shown."""

    text: str
    caption: str = ""
    note: str = ""


def listing(text: str, caption: str) -> Code:
    """A file as given, cut after :data:`MAX_LISTED_LINES` lines or :data:`MAX_LISTED_CHARACTERS` characters,
    the note saying what is left out: a scene of 5,000 comment lines made a 76-page PDF in 16 s, 8 MB of them
    took minutes, and one line of 13,000 characters no page could hold; the provenance's SHA-256 names the
    whole file."""
    end = -1
    for _ in range(MAX_LISTED_LINES):
        end = text.find("\n", end + 1)
        if end < 0:
            end = len(text)
            break
    end = min(end, MAX_LISTED_CHARACTERS)
    rest = text[end:]
    if not rest:
        return Code(text, caption)
    if not rest.strip():  # blank lines past the limit: left out without a word (6 MB of them were listed)
        return Code(text[:end].rstrip("\n") + "\n", caption)
    first = text.count("\n", 0, end) + 1  # the line the cut is in, or the first line left out
    last = text.rstrip("\n").count("\n") + 1
    if end > 0 and text[end - 1] != "\n" and rest[0] != "\n":
        column = end - (text.rfind("\n", 0, end) + 1) + 1
        what = f"the rest of line {first:,}, from its character {column:,}"
        what += f", and {_lines(first + 1, last)}" if last > first else ""
    else:
        what = _lines(first + (rest[0] == "\n"), last)
    note = (
        f"Not listed: {what} ({_characters(len(rest.strip(chr(10))))}); the provenance's SHA-256 names the whole file."
    )
    return Code(text[:end].rstrip("\n") + "\n", caption, note)


def _characters(n: int) -> str:
    return f"{n:,} character{'' if n == 1 else 's'}"


def _lines(first: int, last: int) -> str:
    return f"lines {first:,} to {last:,}" if last > first else f"line {first:,}"


@dataclass
class Section:
    """A numbered section (``level`` 1) or subsection (``level`` 2)."""

    number: str
    title: str
    blocks: list
    level: int = 1
    key: str = ""


@dataclass
class Document:
    """The whole report.

    Attributes
    ----------
    title : str
        The scene's title.
    title_block : tuple of (str, Text)
        Scene file, date, flyopt version, units, status.
    sections : list of Section
    units : str
        The unit system of the tables (:data:`flyopt.report.display.SYSTEMS`).
    status : str
        The solution's status ("designed", "not_needed", "infeasible", "analysed"),
        plus " flagged" when a verification flagged the design.
    failures : list of str
        Diagrams that could not be drawn because drawing raised (not a refusal
        for this scene): each ``"key: error"``.
    kind : str
        What the document is, in the words of its heading ("flywheel design report", or a calculation's).
    """

    title: str
    title_block: tuple
    sections: list
    units: str
    status: str
    failures: list = field(default_factory=list)
    kind: str = "flywheel design report"

    def drawn(self) -> list[Figure]:
        """The figure blocks the document shows drawn (not those refused or failed, which hold a note), in its
        order: what a renderer draws."""
        return [
            block
            for section in self.sections
            for block in section.blocks
            if isinstance(block, Figure) and block.figure is not None
        ]

    def close(self) -> None:
        """Close the figures' matplotlib windows (memory) once rendered (a document without any imports nothing)."""
        figures = [block.figure for block in self.drawn()]
        if not figures:
            return
        import matplotlib.pyplot as plt

        for figure in figures:
            plt.close(figure)


def plain(text: object) -> str:
    """A Text as plain characters (markup braces removed): for widths and for tests."""
    import re

    if isinstance(text, Quantity):
        return text.text
    if isinstance(text, tuple):
        return "".join(plain(t) for t in text)
    return re.sub(r"[_^]\{([^{}]*)\}", r"\1", str(text))


def anchor(number: str) -> str:
    """The name of a section's heading as a link target: the HTML's id and the PDF's destination, which the
    contents list and the outline point to ("section-4.2", "section-A.5")."""
    import re

    return "section-" + re.sub(r"[^A-Za-z0-9.]", "-", number)
