"""The engineering report as a PDF, drawn by reportlab (no browser, no external program).

:func:`render` lays a :class:`flyopt.report.document.Document` out on A4
pages with reportlab's platypus: the title block, numbered sections, tables
that repeat their header across pages, equations in shaded boxes, every
diagram drawn as vectors onto its page (:mod:`flyopt.report.pdf_figure`), and a footer with the scene's title and the page
number. The text is set in DejaVu Sans, the font matplotlib ships (it has
the Greek letters, superscripts and the minus sign the engineering needs),
embedded in the file. reportlab is imported here only, when a PDF is asked
for, so that ``import flyopt`` and the other commands do not pay for it.
"""

from __future__ import annotations

import functools
import io
import os
import re
from collections.abc import Callable
from typing import Any
from xml.sax.saxutils import escape

from flyopt.report.characters import visible
from flyopt.report.document import (
    Code,
    Document,
    Equation,
    Facts,
    Figure,
    Paragraph,
    Quantity,
    Table,
    anchor,
    plain,
)
from flyopt.report.plots import standard

_FONT, _BOLD, _ITALIC, _MONO = "FlyoptSans", "FlyoptSans-Bold", "FlyoptSans-Oblique", "FlyoptMono"
_FILES = {
    _FONT: "DejaVuSans.ttf",
    _BOLD: "DejaVuSans-Bold.ttf",
    _ITALIC: "DejaVuSans-Oblique.ttf",
    _MONO: "DejaVuSansMono.ttf",
}


def render(document: Document) -> bytes:
    """The PDF of a :class:`~flyopt.report.document.Document`, as bytes.

    Laid out once. The contents list on the first page names the page each
    section starts on before that page is laid out: each of its page numbers
    is a form (a PDF XObject, :func:`_page_number`) that the first page refers
    to and that is written when the section's heading is placed
    (:func:`_page_form`). Every heading is a destination: the contents list
    links to it and the outline (the viewer's bookmarks) lists it.
    """
    from reportlab.lib.pagesizes import A4
    from reportlab.lib.units import mm
    from reportlab.platypus import SimpleDocTemplate

    _fonts()
    styles = _styles()
    buffer = io.BytesIO()
    margin = 16 * mm
    page = SimpleDocTemplate(
        buffer,
        pagesize=A4,
        leftMargin=margin,
        rightMargin=margin,
        topMargin=15 * mm,
        bottomMargin=17 * mm,
        title=f"{_shown(document.title)}: {document.kind}",
        author="flyopt",
        subject="Flywheel design report",
        creator="flyopt",
    )
    width = A4[0] - 2 * margin
    height = A4[1] - 32 * mm
    story = _title(document, styles, width) + _contents(document, styles, width)
    drawings = _drawings(document)
    for section in document.sections:
        style = styles["h1"] if section.level == 1 else styles["h2"]
        heading = _paragraph(f"{section.number} {section.title}", style, anchor=anchor(section.number))
        heading.flyopt_section = section
        story.append(heading)
        for block in section.blocks:
            story += _block(block, styles, width, height, drawings)
    story = _kept_with_next(story)

    def footer(canvas, doc):
        canvas.saveState()
        canvas.setFont(_FONT, 7.5)
        canvas.setFillGray(0.35)
        number = f"page {doc.page}"
        room = A4[0] - 2 * margin - canvas.stringWidth(number, _FONT, 7.5) - 4 * mm
        title = _fitted(f"{_shown(document.title)}: {document.kind} (flyopt)", room, canvas.stringWidth)
        canvas.drawString(margin, 9 * mm, title)
        canvas.drawRightString(A4[0] - margin, 9 * mm, number)
        canvas.restoreState()

    written: set[str] = set()

    def after(flowable):
        section = getattr(flowable, "flyopt_section", None)
        if section is not None:
            title = _shown(f"{section.number} {section.title}")
            page.canv.addOutlineEntry(plain(title), anchor(section.number), level=section.level - 1)
            if section.level == 1 and section.number not in written:
                _page_form(page.canv, section.number, page.page, styles["cell_r"])
                written.add(section.number)

    page.afterFlowable = after
    page.build(story, onFirstPage=footer, onLaterPages=footer)
    return buffer.getvalue()


def _kept_with_next(story: list[Any]) -> list[Any]:
    """The story with what keeps with the next flowable (a heading; a paragraph that ends in ":") kept with it
    where the next is itself kept together (a short list of facts, a worked step): its content follows
    instead of the KeepTogether that held it.

    reportlab keeps a flowable with the next by putting both in a KeepTogether, but not where the next is a
    KeepTogether already: punch-press-wheel's "2 The scene as given" was the last line of page 1, its facts
    on page 2. With the content following, the heading and the content are one KeepTogether, which keeps
    the content whole as its own did. The heading stays a flowable of its own, so that the outline entry
    and the contents' page are still written as it is placed.
    """
    from reportlab.platypus import KeepTogether

    out: list[Any] = []
    for flowable in story:
        if type(flowable) is KeepTogether and out and out[-1].getKeepWithNext():
            out += flowable._content
        else:
            out.append(flowable)
    return out


#: The colour of the contents list's links (its numbers, titles and pages).
_LINK = "#1d3f73"


def _page_form_name(number: str) -> str:
    """The name of the form that prints the page section ``number`` starts on."""
    return f"flyopt-page-{anchor(number)}"


def _page_form(canvas, number: str, at: int, style) -> None:
    """Write the form that prints page ``at``, where section ``number`` starts: right-aligned on its origin
    (the right end of the contents list's baseline), in the contents' type and link colour."""
    size = style.fontSize
    canvas.beginForm(_page_form_name(number), lowerx=-8 * size, lowery=-size, upperx=size, uppery=2 * size)
    canvas.setFont(style.fontName, size)
    canvas.setFillColor(_LINK)
    canvas.drawRightString(0, 0, str(at))
    canvas.endForm()


def _contents(document, styles, width):
    """The contents list: each numbered section (level 1) and its page, all three linked to its heading."""
    from reportlab.lib import colors
    from reportlab.platypus import Paragraph as RLParagraph
    from reportlab.platypus import Spacer
    from reportlab.platypus import Table as RLTable

    rows = []
    for section in document.sections:
        if section.level != 1:
            continue
        link = f'<a href="#{anchor(section.number)}" color="{_LINK}">'
        number = escape(section.number)
        title = _markup(section.title)
        rows.append(
            [
                RLParagraph(f"{link}{number}</a>", styles["cell"]),
                RLParagraph(f"{link}{title}</a>", styles["cell"]),
                _page_number()(section.number, styles["cell_r"]),
            ]
        )
    if not rows:
        return []
    table = RLTable(rows, colWidths=[0.06 * width, 0.84 * width, 0.1 * width], hAlign="LEFT")
    table.setStyle(
        [
            ("LINEBELOW", (0, 0), (-1, -1), 0.4, colors.HexColor("#c9ced6")),
            ("TOPPADDING", (0, 0), (-1, -1), 1.5),
            ("BOTTOMPADDING", (0, 0), (-1, -1), 1.5),
            ("LEFTPADDING", (0, 0), (-1, -1), 2),
        ]
    )
    return [_paragraph("Contents", styles["h1"]), table, Spacer(1, 4)]


@functools.cache
def _page_number():
    """The flowable class of a page number in the contents list (made once: reportlab is imported for a PDF only)."""
    from reportlab.platypus import Flowable

    class PageNumber(Flowable):
        """The page a section starts on, in the contents list: a reference to the form written once that page
        is known (:func:`_page_form`), on the baseline and with the link a one-line right-aligned paragraph of
        ``style`` would have."""

        def __init__(self, number: str, style) -> None:
            super().__init__()
            self.number, self.style = number, style

        def wrap(self, available_width, available_height):
            self.width, self.height = available_width, self.style.leading
            return self.width, self.height

        def draw(self):
            canvas, size = self.canv, self.style.fontSize
            baseline = self.height - _first_baseline(self.style)
            canvas.saveState()
            canvas.translate(self.width, baseline)
            canvas.doForm(_page_form_name(self.number))
            canvas.restoreState()
            low = baseline - size / 8.0  # where reportlab puts a linked line's box (paragraph.py)
            room = canvas.stringWidth("000", self.style.fontName, size)
            canvas.linkRect(
                "", anchor(self.number), (self.width - room, low, self.width, low + self.height), relative=1
            )

    return PageNumber


def _first_baseline(style) -> float:
    """How far below its top a one-line paragraph of ``style`` sets its baseline [pt], as reportlab does
    (its font size, or the font's ascent where ``rl_config.paraFontSizeHeightOffset`` is off)."""
    from reportlab import rl_config
    from reportlab.pdfbase.pdfmetrics import getAscent

    return style.fontSize if rl_config.paraFontSizeHeightOffset else getAscent(style.fontName, style.fontSize)


def _shown(text: str, font: str = _FONT) -> str:
    """Text as the PDF shows it: every control or bidirectional-override character as its escape
    (:func:`~flyopt.report.characters.visible`), every character the font lacks as
    :data:`~flyopt.report.plots.standard.PLACEHOLDER` (reportlab would write its empty glyph 0)."""
    return standard.in_font(visible(text), _font_file(font))


def _font_file(font: str) -> str:
    """The file of one of the report's fonts: matplotlib's own DejaVu."""
    import matplotlib

    return os.path.join(matplotlib.get_data_path(), "fonts", "ttf", _FILES[font])


def _fonts():
    """Register DejaVu Sans (regular, bold, oblique) and DejaVu Sans Mono from matplotlib's data, once."""
    from reportlab.pdfbase import pdfmetrics
    from reportlab.pdfbase.ttfonts import TTFont

    if _FONT in pdfmetrics.getRegisteredFontNames():
        return
    for name in _FILES:
        pdfmetrics.registerFont(TTFont(name, _font_file(name)))
    pdfmetrics.registerFontFamily(_FONT, normal=_FONT, bold=_BOLD, italic=_ITALIC, boldItalic=_BOLD)


def _styles():
    from reportlab.lib import colors
    from reportlab.lib.styles import ParagraphStyle

    base = ParagraphStyle("body", fontName=_FONT, fontSize=9, leading=12.2, spaceAfter=4)
    return {
        "body": base,
        "lead": ParagraphStyle("lead", base, keepWithNext=1),
        "display": ParagraphStyle("display", base, leftIndent=22, spaceBefore=1, spaceAfter=5),
        "title": ParagraphStyle("title", base, fontName=_BOLD, fontSize=17, leading=21, spaceAfter=2),
        "kind": ParagraphStyle("kind", base, fontSize=7.5, textColor=colors.HexColor("#555555"), spaceAfter=2),
        "h1": ParagraphStyle(
            "h1", base, fontName=_BOLD, fontSize=13, leading=16, spaceBefore=12, spaceAfter=6, keepWithNext=1
        ),
        "h2": ParagraphStyle(
            "h2", base, fontName=_BOLD, fontSize=10.5, leading=13, spaceBefore=9, spaceAfter=4, keepWithNext=1
        ),
        "cell": ParagraphStyle("cell", base, fontSize=7.6, leading=9.6, spaceAfter=0),
        "head": ParagraphStyle("head", base, fontName=_BOLD, fontSize=7.6, leading=9.6, spaceAfter=0),
        "cell_r": ParagraphStyle("cell_r", base, fontSize=7.6, leading=9.6, spaceAfter=0, alignment=2),
        "head_r": ParagraphStyle("head_r", base, fontName=_BOLD, fontSize=7.6, leading=9.6, spaceAfter=0, alignment=2),
        "caption": ParagraphStyle(
            "caption",
            base,
            fontName=_ITALIC,
            fontSize=8,
            leading=10,
            spaceAfter=3,
            textColor=colors.HexColor("#333333"),
        ),
        "eq": ParagraphStyle("eq", base, fontSize=9, leading=12, spaceAfter=0),
        "eq_b": ParagraphStyle("eq_b", base, fontName=_BOLD, fontSize=9, leading=12, spaceAfter=0),
        "ref": ParagraphStyle("ref", base, fontSize=7, leading=9, spaceAfter=0, textColor=colors.HexColor("#555555")),
        "code": ParagraphStyle("code", base, fontName=_MONO, fontSize=6.8, leading=8.2, spaceAfter=0),
        "ok": ParagraphStyle("ok", base, spaceBefore=2, spaceAfter=6),
        "warning": ParagraphStyle("warning", base, fontName=_BOLD, spaceBefore=2, spaceAfter=6),
        "note": ParagraphStyle("note", base, spaceBefore=2, spaceAfter=6),
    }


#: Subscripts and superscripts where the font puts them (DejaVu Sans's OS/2 table: a subscript 0.14 em
#: down, a superscript 0.48 em up, both 0.70 em high), not reportlab's default (0.5 em either way), whose
#: subscript reached 1.4 pt into the next line of a table cell (7.6 pt type on 9.6 pt lines leaves a
#: superscript 0.1 pt clear of the line above).
_SUB, _SUPER = 'rise="14%" size="70%"', 'rise="48%" size="70%"'


def _markup(text):
    """A Text as reportlab paragraph markup: escaped, ``_{}`` as subscript, ``^{}`` as superscript."""
    if isinstance(text, tuple):
        return "".join(_markup(t) for t in text)
    if isinstance(text, Quantity):
        return escape(_shown(text.text))
    escaped = escape(_shown(str(text)))
    escaped = re.sub(r"_\{([^{}]*)\}", rf"<sub {_SUB}>\1</sub>", escaped)
    return re.sub(r"\^\{([^{}]*)\}", rf"<super {_SUPER}>\1</super>", escaped)


def _paragraph(text, style, anchor: str | None = None):
    """A paragraph of a Text; ``anchor`` names it as a destination (a heading the contents list links to)."""
    from reportlab.platypus import Paragraph as RLParagraph

    target = f'<a name="{anchor}"/>' if anchor else ""
    return RLParagraph(target + _markup(text), style)


def _title(document, styles, width):
    from reportlab.lib import colors
    from reportlab.platypus import Spacer
    from reportlab.platypus import Table as RLTable

    rows = [
        [_paragraph(document.kind.upper(), styles["kind"]), ""],
        [_paragraph(document.title, styles["title"]), ""],
    ]
    rows += [
        [_paragraph(label, styles["cell"]), _paragraph(value, styles["cell"])] for label, value in document.title_block
    ]
    table = RLTable(rows, colWidths=[0.2 * width, 0.8 * width - 12])
    table.setStyle(
        [
            ("BOX", (0, 0), (-1, -1), 1.4, colors.black),
            ("SPAN", (0, 0), (1, 0)),
            ("SPAN", (0, 1), (1, 1)),
            ("VALIGN", (0, 0), (-1, -1), "TOP"),
            ("LEFTPADDING", (0, 0), (-1, -1), 6),
            ("TOPPADDING", (0, 0), (-1, -1), 1.5),
            ("BOTTOMPADDING", (0, 0), (-1, -1), 1.5),
            ("TEXTCOLOR", (0, 2), (0, -1), colors.HexColor("#555555")),
        ]
    )
    return [table, Spacer(1, 8)]


def _drawings(document: Document) -> dict[int, Any]:
    """{id of a block: its figure's drawing} of every figure ``document`` shows drawn (:meth:`Document.drawn`),
    each drawn once before the pages are laid out, on each core this process may run on
    (:func:`flyopt.report.figure_cores.draw_each`), and played onto its page where reportlab places it."""
    drawn = document.drawn()
    if not drawn:
        return {}  # matplotlib is not imported
    from flyopt.report.figure_cores import drawings
    from flyopt.report.pdf_figure import record

    return drawings(drawn, record)


def _block(block, styles, width, height, drawings):
    from reportlab.lib import colors
    from reportlab.platypus import KeepTogether, Spacer
    from reportlab.platypus import Table as RLTable

    if isinstance(block, Paragraph):
        if block.kind == "text":
            # a paragraph that introduces what follows ("...:") stays on its page
            lead = plain(block.text).rstrip().endswith(":")
            return [_paragraph(block.text, styles["lead"] if lead else styles["body"])]
        if block.kind == "display":
            return [_paragraph(block.text, styles["display"])]
        colour = {"ok": "#1e7a46", "warning": "#b3261e", "note": "#8a7300"}[block.kind]
        box = RLTable([[_paragraph(block.text, styles[block.kind])]], colWidths=[width])
        box.setStyle(
            [
                ("LINEBEFORE", (0, 0), (0, -1), 3, colors.HexColor(colour)),
                ("BACKGROUND", (0, 0), (-1, -1), colors.HexColor("#f3f5f8")),
                ("LEFTPADDING", (0, 0), (-1, -1), 7),
                ("TOPPADDING", (0, 0), (-1, -1), 3),
                ("BOTTOMPADDING", (0, 0), (-1, -1), 1),
            ]
        )
        return [box, Spacer(1, 4)]
    if isinstance(block, Facts):
        rows = [[_paragraph(label, styles["cell"]), _paragraph(value, styles["cell"])] for label, value in block.rows]
        table = RLTable(rows, colWidths=[0.33 * width, 0.67 * width])
        table.setStyle(
            [
                ("LINEBELOW", (0, 0), (-1, -1), 0.4, colors.HexColor("#c9ced6")),
                ("VALIGN", (0, 0), (-1, -1), "TOP"),
                ("TOPPADDING", (0, 0), (-1, -1), 1.5),
                ("BOTTOMPADDING", (0, 0), (-1, -1), 1.5),
                ("LEFTPADDING", (0, 0), (-1, -1), 2),
                ("TEXTCOLOR", (0, 0), (0, -1), colors.HexColor("#444444")),
            ]
        )
        return [KeepTogether([table]) if len(rows) <= 12 else table, Spacer(1, 6)]  # a short list is not cut
    if isinstance(block, Table):
        return _table(block, styles, width)
    if isinstance(block, Equation):
        rows = [[_paragraph(block.lines[0], styles["eq_b"])]]
        rows += [[_paragraph(line, styles["eq"])] for line in block.lines[1:-1]]
        rows += [[_paragraph(block.lines[-1], styles["eq_b"])], [_paragraph(block.reference, styles["ref"])]]
        table = RLTable(rows, colWidths=[width])
        table.setStyle(
            [
                ("LINEBEFORE", (0, 0), (0, -1), 2.2, colors.HexColor("#4a6fa5")),
                ("BACKGROUND", (0, 0), (-1, -1), colors.HexColor("#f3f5f8")),
                ("LEFTPADDING", (0, 0), (-1, -1), 8),
                ("TOPPADDING", (0, 0), (-1, -1), 0.8),
                ("BOTTOMPADDING", (0, 0), (-1, -1), 0.8),
            ]
        )
        return [KeepTogether([table]), Spacer(1, 5)]
    if isinstance(block, Figure):
        caption = f"{block.caption}." if block.figure is not None else f"{block.caption}. {block.note}"
        if block.figure is None:
            return [_paragraph(caption, styles["caption"]), Spacer(1, 4)]
        figure = _figure(drawings[id(block)], _paragraph(caption, styles["caption"]), width, 0.62 * height)
        return [figure, Spacer(1, 6)]
    if isinstance(block, Code):
        from reportlab.pdfbase.pdfmetrics import stringWidth

        # the characters a row holds inside its padding (5 pt left, reportlab's 6 pt right)
        chars = int((width - 11) / stringWidth("0", _MONO, styles["code"].fontSize))
        out = [_caption_over(block.caption, styles)] if block.caption else []
        out += _split_code(block.text, styles["code"], chars, width)
        return out + ([_paragraph(block.note, styles["caption"])] if block.note else []) + [Spacer(1, 5)]
    raise TypeError(f"no PDF layout for a {type(block).__name__}")


_CODE_ROWS = 40
"""Rows of the scene listing per reportlab table: a table is split over pages by measuring all its rows, so one
table of 5,000 rows took 13 s to lay out; tables of a few dozen rows lay out in linear time."""


def _split_code(text, style, chars, width):
    """The scene file as a shaded block that may run over pages: one table row per printed line, a line longer
    than ``chars`` broken over rows that begin with "↪ " (one line of 13,000 characters, wrapped in its one row,
    was taller than a page: reportlab's LayoutError), and the rows in tables of :data:`_CODE_ROWS`."""
    from reportlab.lib import colors
    from reportlab.platypus import Preformatted, Spacer
    from reportlab.platypus import Table as RLTable

    # a blank line is a space of one line (Preformatted drops a line of white space)
    rows = []
    for line in _shown(text, _MONO).rstrip("\n").split("\n"):
        if not line.strip():
            rows.append([Spacer(1, style.leading)])
            continue
        rows.append([Preformatted(line[:chars], style)])
        rows += [[Preformatted("↪ " + line[k : k + chars - 2], style)] for k in range(chars, len(line), chars - 2)]
    shade, rule = colors.HexColor("#f3f5f8"), colors.HexColor("#c9ced6")
    tables = []
    for start in range(0, len(rows), _CODE_ROWS):
        table = RLTable(rows[start : start + _CODE_ROWS], colWidths=[width], repeatRows=0)
        style_ = [
            ("BACKGROUND", (0, 0), (-1, -1), shade),
            ("LEFTPADDING", (0, 0), (-1, -1), 5),
            ("TOPPADDING", (0, 0), (-1, -1), 0),
            ("BOTTOMPADDING", (0, 0), (-1, -1), 0.4),
            ("LINEBEFORE", (0, 0), (0, -1), 0.5, rule),
            ("LINEAFTER", (-1, 0), (-1, -1), 0.5, rule),
        ]
        if start == 0:
            style_.append(("LINEABOVE", (0, 0), (-1, 0), 0.5, rule))
        if start + _CODE_ROWS >= len(rows):
            style_.append(("LINEBELOW", (0, -1), (-1, -1), 0.5, rule))
        table.setStyle(style_)
        tables.append(table)
    return tables


def _table(block, styles, width):
    from reportlab.lib import colors
    from reportlab.pdfbase.pdfmetrics import stringWidth
    from reportlab.platypus import Spacer
    from reportlab.platypus import Table as RLTable

    size = styles["cell"].fontSize
    pad = 8.0
    natural, least = [], []
    for k, align in enumerate(block.align):
        head = plain(block.head[k])
        body = [plain(row[k]) for row in block.rows]
        widest = max([stringWidth(t, _FONT, size) for t in body] + [0.0])
        natural.append(max(widest, stringWidth(head, _BOLD, size)) + pad)
        words = max(
            [stringWidth(w, _BOLD, size) for w in head.split() or [""]]
            + [stringWidth(w, _FONT, size) for t in body for w in t.split() or [""]]
        )
        # a number is never broken over lines: a right-aligned column keeps its cells' width
        least.append(max(words, widest if align == ">" else 0.0) + pad)
    widths = _fit(natural, least, width)
    heads = [_paragraph(h, styles["head_r" if a == ">" else "head"]) for h, a in zip(block.head, block.align)]
    rows = [heads] + [
        [_paragraph(cell, styles["cell_r" if a == ">" else "cell"]) for cell, a in zip(row, block.align)]
        for row in block.rows
    ]
    table = RLTable(rows, colWidths=widths, repeatRows=1, hAlign="LEFT")
    style = [
        ("GRID", (0, 0), (-1, -1), 0.4, colors.HexColor("#c9ced6")),
        ("BACKGROUND", (0, 0), (-1, 0), colors.HexColor("#f3f5f8")),
        ("VALIGN", (0, 0), (-1, -1), "TOP"),
        ("TOPPADDING", (0, 0), (-1, -1), 1.5),
        ("BOTTOMPADDING", (0, 0), (-1, -1), 1.5),
        ("LEFTPADDING", (0, 0), (-1, -1), 3),
        ("RIGHTPADDING", (0, 0), (-1, -1), 3),
    ]
    if block.total:
        style.append(("LINEABOVE", (0, -1), (-1, -1), 1.2, colors.black))
    table.setStyle(style)
    out = [_caption_over(block.caption, styles)] if block.caption else []
    return out + [table, Spacer(1, 6)]


def _caption_over(text, styles):
    """A caption written above what it names (a table, the scene file), kept on the page of its first lines:
    press-template's "Shafts a flywheel may sit on" ended page 1, its table on page 2."""
    caption = _paragraph(text, styles["caption"])
    caption.keepWithNext = 1
    return caption


def _fit(natural, least, width):
    """Column widths: each its natural width if all fit, else the wide ones shrunk (never below their longest word)."""
    if sum(natural) <= width:
        return natural
    widths = list(natural)
    fixed: set[int] = set()
    while True:
        free = [k for k in range(len(widths)) if k not in fixed]
        room = width - sum(widths[k] for k in fixed)
        share = room / max(sum(natural[k] for k in free), 1e-9)
        changed = False
        for k in free:
            widths[k] = natural[k] * share
            if widths[k] < least[k]:
                widths[k] = least[k]
                fixed.add(k)
                changed = True
        if not changed or not [k for k in range(len(widths)) if k not in fixed]:
            return widths


#: A diagram may shrink to this fraction of its size to finish a page rather than leave it half empty.
SHRINK = 0.72


def _figure(drawing, caption, width, height):
    """A figure's drawing (:func:`flyopt.report.pdf_figure.record`) as a vector flowable with its caption below,
    kept together.

    Scaled to fit ``width`` x ``height`` [pt] and never enlarged; where the rest
    of a page holds at least :data:`SHRINK` of that size the diagram shrinks to
    fit it, so that a page is not left half empty for want of a few points. The
    drawing is played onto the page itself (:func:`flyopt.report.pdf_figure.draw`,
    paths and text, no image), once, when reportlab places it.
    """
    from reportlab.platypus import Flowable

    from flyopt.report.pdf_figure import draw as draw_figure

    w, h = drawing.width, drawing.height  # [pt]
    scale = min(1.0, width / w, height / h)

    class FigureFlowable(Flowable):
        def wrap(self, available_width, available_height):
            self.caption_height = caption.wrap(available_width, available_height)[1]
            room = available_height - self.caption_height - 4
            self.scale = scale if h * scale <= room or room < SHRINK * h * scale else room / h
            self.width = available_width
            self.height = h * self.scale + self.caption_height + 4
            return self.width, self.height

        def split(self, available_width, available_height):
            return []  # a diagram is never cut: it goes to the next page whole

        def draw(self):
            shown_w = w * self.scale
            draw_figure(drawing, self.canv, (self.width - shown_w) / 2, self.caption_height + 4, self.scale)
            caption.drawOn(self.canv, 0, 0)

    return FigureFlowable()


def _fitted(text: str, room: float, width: Callable[[str, str, float], float]) -> str:
    """``text`` shortened with an ellipsis so that ``width(text, font, size)`` stays within ``room`` [pt]
    (the footer's title beside its page number: a long title ran into it)."""
    if width(text, _FONT, 7.5) <= room:
        return text
    while text and width(text + "…", _FONT, 7.5) > room:
        text = text[:-1]
    return text.rstrip() + "…"
