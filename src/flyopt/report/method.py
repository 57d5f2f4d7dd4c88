"""The report's method appendix: the sections of flyopt's engineering notes that a report cites, inside it.

A report explains each step by a section of the notes (docs/flywheel-design.md,
the one source of the formulas flyopt implements). The reader of a report does
not have the repository, so the report carries those sections as Appendix A:
:func:`with_appendix` finds every citation a built :class:`Document` makes
(:data:`NOTES` and a section number, as the builders write it), rewrites it as the appendix's own number ("Appendix A.5"), and
appends the sections cited, each as the notes give it (its formulas, its
sources, its *flyopt notes*).

The notes are read from the package (``flyopt/data/flywheel-design.md``, a
link to docs/flywheel-design.md in the source tree that the build copies into
the wheel), so the appendix is the notes themselves, never a copy kept by
hand. What the notes say for flyopt's developers is left out of the report,
by two rules. First, the notes mark it: text between the HTML comments
``<!-- implementation -->`` and ``<!-- /implementation -->`` (:data:`IMPLEMENTATION`; where the code
lives, how it is solved, tested and timed, what it depends on) is not read
at all, and a part of a section (``###``) left with nothing is left out.
Second, as a net under what is not marked: the path of a file in the
repository (a test, a benchmark, a module or its dotted name, a scene of
problems/), the parenthesis that holds it, or the sentence that needs it;
a link's target (its words stay); markdown's emphasis marks. A
reference from one section to another becomes the appendix's number where
that section is in the appendix, and the notes' number where it is not
("section 20 of flyopt's notes").

A figure cites the notes by the same rule, through :func:`cite`: drawn for a
report (while :func:`citing`), by the appendix's number as the report's text
does, the section joining the appendix; drawn alone (``flyopt plot``, the
API), where no appendix is, by its number in the notes ("section 5 of flyopt's
notes").
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, replace
from functools import cache
from importlib import resources

from flyopt.report.document import Code, Document, Equation, Facts, Figure, Paragraph, Section, Table

__all__ = [
    "APPENDIX",
    "IMPLEMENTATION",
    "NOTES",
    "PATH",
    "MethodSection",
    "appendix",
    "cite",
    "citing",
    "notes_sections",
    "readable",
    "with_appendix",
]

#: How a builder names the notes in a citation: "(docs/flywheel-design.md, section 5)". Rewritten by
#: :func:`with_appendix`; never shown to the reader.
NOTES = "docs/flywheel-design.md"

#: The appendix's letter.
APPENDIX = "A"

_FILE = "flywheel-design.md"

#: A citation as the builders write it: the notes, then "section 5", "sections 3 and 14", "sections 15–21".
_CITATION = re.compile(
    re.escape(NOTES) + r"(?P<sep>,? )(?P<word>sections?) (?P<numbers>\d+(?:(?:–|-| and |, | to )\d+)*)"
)

#: The path of a file in the repository: a folder of it, a file name with a source or data extension, a
#: module of the source by its dotted name; or an issue of the project's tracker.
PATH = re.compile(
    r"(?:\b(?:src|docs|tests|benchmarks|problems|notebooks|flyopt|tools)/[\w./*{}-]*)"
    r"|(?:\b[\w*.-]+\.(?:toml|py|md|csv|json|ipynb|parquet)\b)"
    r"|(?:\bflyopt\.[a-z_]+\.[\w.]+)"  # a module of the source (flyopt.pipeline.solve_calculation)
    r"|(?:\bissues? \d+)"  # an issue of the project's tracker, which the reader does not have either
)


@dataclass(frozen=True)
class MethodSection:
    """One numbered section of the notes: its number, title and markdown text (without its heading)."""

    number: str
    title: str
    text: str


#: The notes' text for flyopt's developers, between these HTML comments (invisible where the notes are rendered),
#: which the report leaves out; a span ends where it is closed (or with the notes).
IMPLEMENTATION = re.compile(r"<!-- implementation -->.*?(?:<!-- /implementation -->|\Z)", re.S)


@cache
def _notes_text() -> str:
    """The notes as the report reads them: without their text for developers (:data:`IMPLEMENTATION`)."""
    return IMPLEMENTATION.sub("", resources.files("flyopt").joinpath("data", _FILE).read_text(encoding="utf-8"))


@cache
def notes_sections() -> dict[str, MethodSection]:
    """Every numbered section of the notes ("## 5. Title"), by its number, in order."""
    found: dict[str, MethodSection] = {}
    parts = re.split(r"^## (\d+)\. (.*)$", _notes_text(), flags=re.M)
    for k in range(1, len(parts) - 2, 3):
        found[parts[k]] = MethodSection(parts[k], parts[k + 1].strip(), parts[k + 2].strip("\n"))
    return found


def _numbers(text: str) -> list[str]:
    """The section numbers of a citation's list: "3 and 14" -> 3, 14; "15–21" -> 15 ... 21."""
    out: list[str] = []
    for part in re.split(r" and |, ", text):
        span = re.split(r"–|-| to ", part)
        if len(span) == 2:
            out += [str(n) for n in range(int(span[0]), int(span[1]) + 1)]
        else:
            out.append(part.strip())
    return out


def _in_notes(word: str, numbers: str) -> str:
    """A section the appendix does not carry, by its number in the notes: "section 20 of flyopt's notes"."""
    return f"{word} {numbers} of flyopt's notes"


def _cited_in(text: str, cited: dict[str, None] | None) -> str:
    """``text`` with each citation of the notes as the appendix's number; the numbers met join ``cited``.
    ``cited`` None: there is no appendix (a figure drawn alone), each citation names the notes' section."""

    def to_appendix(match: re.Match[str]) -> str:
        numbers = [n for n in _numbers(match.group("numbers")) if n in notes_sections()]
        if not numbers:
            return match.group(0)
        if cited is None:
            return _in_notes(match.group("word"), match.group("numbers"))
        for n in numbers:
            cited.setdefault(n)
        named = [f"{APPENDIX}.{n}" for n in numbers]
        if len(named) == 1:
            return f"Appendix {named[0]}"
        if re.search(r"–|-| to ", match.group("numbers")):
            return f"Appendices {named[0]} to {named[-1]}"
        return f"Appendices {', '.join(named[:-1])} and {named[-1]}"

    text = _CITATION.sub(to_appendix, text)
    return text.replace(NOTES, "flyopt's notes" if cited is None else f"Appendix {APPENDIX}")


#: The sections the figures drawn for the report being built cite (:func:`citing`); None: a figure is drawn
#: alone, with no appendix to cite.
_FIGURES_CITE: ContextVar[dict[str, None] | None] = ContextVar("figures_cite", default=None)


@contextmanager
def citing() -> Iterator[dict[str, None]]:
    """While a report is built: each figure drawn cites the notes by the appendix's number (:func:`cite`), as the
    report's text does; the sections the figures cite are collected in the dict yielded, for
    :func:`with_appendix` to carry them."""
    cited: dict[str, None] = {}
    token = _FIGURES_CITE.set(cited)
    try:
        yield cited
    finally:
        _FIGURES_CITE.reset(token)


def cite(text: str) -> str:
    """A figure's ``text`` citing the notes as a builder writes it ("({NOTES}, section 5)"), as the figure says it.

    A figure's texts are wrapped as it is drawn, so the citation is said when the text is made, by the rule
    of the report's text (:func:`with_appendix`): in a report being built (:func:`citing`), the appendix's
    number ("Appendix A.5"), the section joining the appendix; drawn alone, where there is no appendix, the
    section by its number in the notes ("section 5 of flyopt's notes", as the appendix names a section it
    does not carry).
    """
    return _cited_in(text, _FIGURES_CITE.get())


def _rewrite(value: object, cited: dict[str, None]) -> object:
    """A Text (str, Quantity or tuple of them) with its citations rewritten (a Quantity is a number: as it is)."""
    if isinstance(value, str):
        return _cited_in(value, cited)
    if isinstance(value, tuple):
        return _all(value, cited)
    return value


def _all(values: tuple, cited: dict[str, None]) -> tuple:
    """Each Text of a tuple (a table's rows, an equation's lines) with its citations rewritten."""
    return tuple(_rewrite(v, cited) for v in values)


def _joined(text: object) -> object:
    """A paragraph's Text with its neighbouring strings joined, so that a citation written across them ("(",
    NOTES, ", section 5)") is one citation to the rule; its numbers (Quantity) stay as they are."""
    if not isinstance(text, tuple):
        return text
    pieces: list[object] = []
    for piece in text:
        if isinstance(piece, str) and pieces and isinstance(pieces[-1], str):
            pieces[-1] = f"{pieces[-1]}{piece}"
        else:
            pieces.append(piece)
    return tuple(pieces)


def _block(block: object, cited: dict[str, None]) -> object:
    if isinstance(block, Paragraph):
        return replace(block, text=_rewrite(_joined(block.text), cited))
    if isinstance(block, Equation):
        return replace(block, lines=_all(block.lines, cited), reference=_cited_in(block.reference, cited))
    if isinstance(block, Facts):
        return replace(block, rows=_all(block.rows, cited))
    if isinstance(block, Table):
        return replace(block, rows=_all(block.rows, cited), caption=_cited_in(block.caption, cited))
    if isinstance(block, Figure):
        block.caption = _cited_in(block.caption, cited)
        block.note = _cited_in(block.note, cited)
        return block
    return block


def with_appendix(document: Document, figures: dict[str, None] | None = None) -> Document:
    """The document with every citation of the notes as its appendix number, and Appendix A appended: the
    sections cited, in the notes' order (nothing appended where nothing is cited). The sections' text is
    rewritten in place; the title block (the scene's own words, the date, the versions) cites nothing and is
    left as it is. ``figures``: the sections its figures cite (:func:`citing`), carried too."""
    cited: dict[str, None] = dict.fromkeys(figures or {})
    for section in document.sections:
        section.blocks = [_block(b, cited) for b in section.blocks]
        section.title = _cited_in(section.title, cited)
    if cited:
        document.sections += appendix(sorted(cited, key=int))
    return document


def appendix(numbers: list[str]) -> list[Section]:
    """Appendix A: an introduction, then each section of the notes in ``numbers`` as A.n (its parts as A.n.k)."""
    shown = set(numbers)
    out = [
        Section(
            APPENDIX,
            "Method: the sections of flyopt's notes cited here",
            [
                Paragraph(
                    "The formulas, conventions and sources this report's steps cite, as flyopt's engineering notes "
                    "give them (the notes are the source of what flyopt implements and is tested against). Every "
                    "formula is as published; a paragraph that starts 'flyopt note' says how flyopt reads, names or "
                    "extends it. A section of the notes that is not cited here is named by its number in the notes."
                )
            ],
            1,
            "appendix",
        )
    ]
    sections = notes_sections()
    for number in numbers:
        method = sections[number]
        parts = re.split(r"^### (.*)$", method.text, flags=re.M)
        title = readable(method.title, shown)
        out.append(Section(f"{APPENDIX}.{number}", title, _blocks(parts[0], shown), 2, f"notes-{number}"))
        for k in range(1, len(parts) - 1, 2):
            blocks = _blocks(parts[k + 1], shown)
            if blocks:  # a part that is all for developers is left out (its number stays the notes' own)
                title = readable(parts[k].strip(), shown)
                out.append(Section(f"{APPENDIX}.{number}.{k // 2 + 1}", title, blocks, 2, f"notes-{number}"))
    return out


def _blocks(markdown: str, shown: set[str]) -> list[object]:
    """Markdown of the notes as report blocks: paragraphs, list items, quoted notes, tables and code."""
    blocks: list[object] = []
    lines = markdown.split("\n")
    k = 0
    while k < len(lines):
        line = lines[k]
        if not line.strip():
            k += 1
        elif line.startswith("```"):
            end = next((j for j in range(k + 1, len(lines)) if lines[j].startswith("```")), len(lines))
            code = "\n".join(lines[k + 1 : end])
            if not PATH.search(code):
                blocks.append(Code(code))
            k = end + 1
        elif line.startswith("|"):
            end = k
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            blocks.append(_table(lines[k:end], shown))
            k = end
        elif line.startswith(">"):
            end = k
            while end < len(lines) and lines[end].startswith(">"):
                end += 1
            quoted = [q[1:].removeprefix(" ") for q in lines[k:end]]
            for _kind, paragraph in _paragraphs(quoted):
                _add(blocks, paragraph, shown, "note")
            k = end
        else:
            end = k
            while end < len(lines) and lines[end].strip() and not lines[end].startswith((">", "|", "```")):
                end += 1
            for kind, paragraph in _paragraphs(lines[k:end]):
                _add(blocks, paragraph, shown, kind)
            k = end
    return blocks


def _paragraphs(lines: list[str]) -> list[tuple[str, str]]:
    """Lines of one run as (kind, text) paragraphs: a list item ("- ", "1. ") starts its own and takes its
    indented lines; an indented line elsewhere is a formula on its own line ("display"); a wrapped line joins
    the paragraph before it."""
    out: list[list[str]] = []
    for line in lines:
        item = re.match(r"(?:[-*]|\d+\.) ", line.strip()) is not None and not line.startswith("  ")
        indented = line.startswith("  ")
        if not line.strip():
            out.append(["", ""])
        elif item or not out or not out[-1][1]:
            out.append(["display" if indented else "text", line.strip()])
        elif indented and not re.match(r"(?:[-*]|\d+\.) ", out[-1][1]):
            out.append(["display", line.strip()])
        elif out[-1][0] == "display":
            out.append(["text", line.strip()])
        else:
            out[-1][1] += " " + line.strip()
    return [(kind, text) for kind, text in out if text]


def _add(blocks: list[object], text: str, shown: set[str], kind: str) -> None:
    item = re.match(r"(?:[-*]|(\d+)\.) (.*)", text)
    if item:
        text = f"{item.group(1)}. {item.group(2)}" if item.group(1) else f"• {item.group(2)}"
    said = readable(text, shown)
    if said.strip(" •"):
        blocks.append(Paragraph(said, kind))


def _table(lines: list[str], shown: set[str]) -> Table:
    rows = [[readable(cell.strip(), shown) for cell in line.strip().strip("|").split("|")] for line in lines]
    body = [r for r in rows[1:] if not all(re.fullmatch(r":?-+:?", c) for c in r)]
    return Table(tuple(rows[0]), tuple(tuple(r) for r in body), tuple("<" for _ in rows[0]))


def readable(text: str, shown: set[str]) -> str:
    """A line of the notes as the report's reader gets it: no repository path (the parenthesis or sentence
    that holds one goes with it), no link target, no markdown emphasis, and another section named by its
    appendix number where the appendix holds it ("A.5"), else by its number in the notes."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    while True:  # a parenthesis that names a file goes whole; the innermost first
        shorter = re.sub(r"\s?\([^()]*\)", lambda m: "" if PATH.search(m.group(0)) else m.group(0), text)
        if shorter == text:
            break
        text = shorter
    if PATH.search(text):  # a sentence that needs a file goes whole
        text = " ".join(s for s in _sentences(text) if not PATH.search(s))
        if PATH.search(text):
            text = PATH.sub("", text)
    text = text.replace("`", "")
    text = re.sub(r"\*\*(.+?)\*\*", r"\1", text)
    text = re.sub(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])", r"\1", text)

    def section(match: re.Match[str]) -> str:
        numbers = _numbers(match.group(2))
        if all(n in shown for n in numbers):
            named = [f"{APPENDIX}.{n}" for n in numbers]
            return " and ".join(named) if len(named) <= 2 else ", ".join(named[:-1]) + f" and {named[-1]}"
        return _in_notes(match.group(1), match.group(2))

    return re.sub(r"\b(sections?) (\d+(?:(?: and |, )\d+)*)(?! of flyopt)", section, text).strip()


def _sentences(text: str) -> list[str]:
    """``text`` cut after each "." or ";" that ends a sentence or a clause, never inside a parenthesis (a ";" in
    "(327 kg; flyopt 326.59 kg)" does not cut it)."""
    out: list[str] = []
    for piece in re.split(r"(?<=[.;])\s+", text):
        if out and out[-1].count("(") > out[-1].count(")"):
            out[-1] += " " + piece
        else:
            out.append(piece)
    return out
