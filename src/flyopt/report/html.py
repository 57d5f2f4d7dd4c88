"""The engineering report as one self-contained HTML file: inline CSS, inline SVG, no links, no scripts.

:func:`render` turns a :class:`flyopt.report.document.Document` into the
text of an HTML5 page that prints on A4 (print CSS: sections start on their
own rules, figures, tables and equations are not split across pages). Every
diagram is the matplotlib figure saved as SVG (text as paths, so no font is
needed) and placed inline, its element ids prefixed so that the figures of
one page never share an id. A number the report shows carries its JSON name
and SI value (``data-q``, ``data-si``), an equation its step (``data-eq``),
so that the page can be checked against the solver's results.
"""

from __future__ import annotations

import functools
import html
import io
import re
from typing import TYPE_CHECKING, Any

from flyopt.report.characters import visible
from flyopt.report.document import Code, Document, Equation, Facts, Figure, Paragraph, Quantity, Table, anchor

if TYPE_CHECKING:
    from matplotlib.figure import Figure as MplFigure

CSS = """
:root { --ink: #1d232b; --rule: #c9ced6; --shade: #f3f5f8; --ok: #1e7a46; --warn: #b3261e; --note: #6b5800; }
* { box-sizing: border-box; }
body { font-family: "DejaVu Sans", "Segoe UI", Helvetica, Arial, sans-serif; color: var(--ink);
       max-width: 60rem; margin: 1.5rem auto; padding: 0 1.2rem; line-height: 1.45; font-size: 15px; }
header.title { border: 2px solid var(--ink); padding: 0.8rem 1rem; margin-bottom: 1.5rem; }
header.title h1 { margin: 0 0 0.2rem 0; font-size: 1.55rem; }
header.title .kind { text-transform: uppercase; letter-spacing: 0.08em; font-size: 0.8rem; color: #555; }
header.title table { margin: 0.6rem 0 0 0; font-size: 0.85rem; }
header.title td { padding: 0.1rem 0.8rem 0.1rem 0; border: none; vertical-align: top; }
header.title td:first-child { color: #555; white-space: nowrap; }
h2 { font-size: 1.25rem; border-bottom: 2px solid var(--ink); padding-bottom: 0.15rem; margin-top: 2.2rem; }
h3 { font-size: 1.05rem; margin-top: 1.6rem; }
p { margin: 0.5rem 0; }
p.ok, p.warning, p.note { padding: 0.45rem 0.7rem; border-left: 4px solid; background: var(--shade); }
p.ok { border-color: var(--ok); } p.warning { border-color: var(--warn); font-weight: bold; }
p.note { border-color: var(--note); }
p.display { margin: 0.3rem 0 0.3rem 2rem; }
table { border-collapse: collapse; margin: 0.2rem 0 1rem 0; font-size: 0.84rem; max-width: 100%; }
th, td { border: 1px solid var(--rule); padding: 0.22rem 0.5rem; vertical-align: top; }
th { background: var(--shade); text-align: left; font-weight: 600; }
td.r, th.r { text-align: right; }
td.r { white-space: nowrap; }
tr.total td { border-top: 2px solid var(--ink); font-weight: 600; }
table.facts { width: 100%; }
table.facts td:first-child { color: #444; width: 32%; }
table.facts td { border: none; border-bottom: 1px solid var(--rule); }
p.caption { font-style: italic; color: #444; margin: 0.8rem 0 0.2rem 0; font-size: 0.88rem; }
div.eq { border-left: 3px solid #4a6fa5; background: var(--shade); padding: 0.4rem 0.8rem; margin: 0.6rem 0;
         font-family: "DejaVu Sans", "Cambria Math", serif; }
div.eq div.line { white-space: normal; }
div.eq div.sym { font-weight: 600; }
div.eq div.res { font-weight: 600; }
div.eq div.ref { font-size: 0.78rem; color: #555; margin-top: 0.15rem; }
figure { margin: 1rem 0; text-align: center; }
figure svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.85rem; color: #333; margin-top: 0.3rem; }
figure.missing { border: 1px dashed var(--rule); padding: 0.6rem; color: #555; text-align: left; }
figure.code { text-align: left; }
pre { background: var(--shade); border: 1px solid var(--rule); padding: 0.6rem 0.8rem; font-size: 0.78rem;
      overflow-x: auto; white-space: pre-wrap; word-break: break-all;
      font-family: "DejaVu Sans Mono", Consolas, monospace; }
ul.contents { list-style: none; padding-left: 0.4rem; }
ul.contents a { color: #1d3f73; text-decoration: none; }
footer { margin-top: 2.5rem; font-size: 0.78rem; color: #666; border-top: 1px solid var(--rule); padding-top: 0.4rem; }
@media print {
  @page { size: A4; margin: 15mm 14mm 16mm 14mm; }
  body { max-width: none; margin: 0; padding: 0; font-size: 10pt; }
  h2 { break-after: avoid; page-break-after: avoid; }
  h3 { break-after: avoid; page-break-after: avoid; }
  figure, div.eq, table, p.ok, p.warning, p.note { break-inside: avoid; page-break-inside: avoid; }
  p.caption { break-after: avoid; page-break-after: avoid; }
  figure.code { break-inside: auto; page-break-inside: auto; }
  pre { white-space: pre-wrap; font-size: 7.5pt; }
  a { color: inherit; text-decoration: none; }
}
"""


def render(document: Document) -> str:
    """The HTML page of a :class:`~flyopt.report.document.Document`.

    Returns
    -------
    str
        A complete HTML5 document with no external reference.
    """
    out = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{_escape(document.title)}: {_escape(document.kind)}</title>",
        f"<style>{CSS}</style>",
        "</head>",
        "<body>",
    ]
    out.append(f'<header class="title" data-status="{_escape(document.status)}">')
    out.append(f'<div class="kind">{_escape(document.kind[:1].upper() + document.kind[1:])}</div>')
    out.append(f"<h1>{_escape(document.title)}</h1>")
    out.append("<table>")
    for label, value in document.title_block:
        out.append(f"<tr><td>{_escape(label)}</td><td>{_text(value)}</td></tr>")
    out.append("</table></header>")
    out.append('<nav><h2 id="contents">Contents</h2><ul class="contents">')
    for section in document.sections:
        if section.level == 1:
            out.append(
                f'<li><a href="#{anchor(section.number)}">{_escape(section.number)} {_escape(section.title)}</a></li>'
            )
    out.append("</ul></nav>")
    from flyopt.report.figure_cores import drawings

    # every figure drawn before the page is written, on each core this process may run on
    made = drawings(document.drawn(), svg_of)
    figures = 0
    for section in document.sections:
        tag = "h2" if section.level == 1 else "h3"
        out.append(f'<section data-section="{_escape(section.key)}">')
        out.append(f'<{tag} id="{anchor(section.number)}">{_escape(section.number)} {_escape(section.title)}</{tag}>')
        for block in section.blocks:
            svg = made.get(id(block))
            if svg is not None:  # the figures numbered as drawn, in the page's order
                figures += 1
            out.append(_block(block, figures, svg))
        out.append("</section>")
    out.append(
        f"<footer>{_escape(document.title)}: written by flyopt. Equations in SI; tables in "
        f"{_escape(document.units)} units.</footer>"
    )
    out += ["</body>", "</html>"]
    return "\n".join(out) + "\n"


def _block(block, figure_number, svg=None):
    """The HTML of ``block``; a drawn figure's SVG given (``svg``, :func:`render` draws them all first) or drawn here."""
    if isinstance(block, Paragraph):
        kind = "" if block.kind == "text" else f' class="{block.kind}"'
        return f"<p{kind}>{_text(block.text)}</p>"
    if isinstance(block, Facts):
        rows = "".join(f"<tr><td>{_text(label)}</td><td>{_text(value)}</td></tr>" for label, value in block.rows)
        return f'<table class="facts" data-table="{_escape(block.name or "")}">{rows}</table>'
    if isinstance(block, Table):
        return _table(block)
    if isinstance(block, Equation):
        lines = [f'<div class="line sym">{_text(block.lines[0])}</div>']
        lines += [f'<div class="line num">{_text(line)}</div>' for line in block.lines[1:-1]]
        lines.append(f'<div class="line res">{_text(block.lines[-1])}</div>')
        lines.append(f'<div class="ref">{_escape(block.reference)}</div>')
        return f'<div class="eq" data-eq="{_escape(block.key)}">{"".join(lines)}</div>'
    if isinstance(block, Figure):
        if block.figure is None:
            state = "failed" if block.failed else "refused"
            return (
                f'<figure class="missing" data-figure="{_escape(block.key)}" data-state="{state}">'
                f"<figcaption>{_text(block.caption)}. {_text(block.note)}</figcaption></figure>"
            )
        if svg is None:
            svg = svg_of(block.figure, f"f{figure_number}-")
        return (
            f'<figure data-figure="{_escape(block.key)}" data-state="drawn">{svg}'
            f"<figcaption>Figure {figure_number}: {_text(block.caption)}.</figcaption></figure>"
        )
    if isinstance(block, Code):
        caption = f"<figcaption>{_escape(block.caption)}</figcaption>" if block.caption else ""
        note = f'<p class="caption">{_escape(block.note)}</p>' if block.note else ""
        return f'<figure class="code">{caption}<pre>{_escape(block.text)}</pre>{note}</figure>'
    raise TypeError(f"no HTML for a {type(block).__name__}")


def _table(table):
    out = [f'<p class="caption">{_text(table.caption)}</p>'] if table.caption else []
    out.append(f'<table data-table="{_escape(table.name or "")}">')
    head = "".join(f"<th{_align(a)}>{_text(h)}</th>" for h, a in zip(table.head, table.align))
    out.append(f"<thead><tr>{head}</tr></thead><tbody>")
    for k, row in enumerate(table.rows):
        total = ' class="total"' if table.total and k == len(table.rows) - 1 else ""
        cells = "".join(f"<td{_align(a)}>{_text(cell)}</td>" for cell, a in zip(row, table.align))
        out.append(f"<tr{total}>{cells}</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def _align(align):
    return ' class="r"' if align == ">" else ""


def _escape(text: object) -> str:
    """Text as HTML, the one way every text reaches the page: markup escaped, and every control or
    bidirectional-override character written as its escape (:func:`~flyopt.report.characters.visible`)."""
    return html.escape(visible(str(text)), quote=True)


def _text(text):
    """A Text (string with ``_{}``/``^{}`` markup, Quantity, or a tuple of them) as HTML."""
    if isinstance(text, tuple):
        return "".join(_text(t) for t in text)
    if isinstance(text, Quantity):
        attributes = f' data-dimension="{_escape(text.dimension)}"'
        if text.name:
            attributes += f' data-q="{_escape(text.name)}"'
        if text.si is not None:
            attributes += f' data-si="{text.si!r}"'
        return f'<span class="q"{attributes}>{_escape(text.text)}</span>'
    escaped = _escape(text)
    escaped = re.sub(r"_\{([^{}]*)\}", r"<sub>\1</sub>", escaped)
    return re.sub(r"\^\{([^{}]*)\}", r"<sup>\1</sup>", escaped)


def svg_of(figure: MplFigure, prefix: str, text_as_text: bool = False) -> str:
    """A matplotlib figure as an inline ``<svg>`` element, its ids prefixed with ``prefix``.

    The XML declaration, the DOCTYPE (which names an external DTD) and the
    metadata block are left out; text is drawn as paths (matplotlib's
    default ``svg.fonttype``), so the figure needs no font: a report is read
    anywhere. With ``text_as_text`` a text is a ``<text>`` element in the
    figure's font instead (``svg.fonttype = "none"``), set where matplotlib
    measured it; the page must have the font (``flyopt app`` serves it: its
    diagrams are drawn some 10 % faster and are 55 % smaller, for the browser
    to receive and read). The figure is drawn
    once, by matplotlib's SVG renderer (:func:`~flyopt.report.plots.output.draw_vector`:
    ``savefig`` would draw it twice, once to lay it out), its paths' coordinates
    written to :data:`PATH_DECIMALS` decimals (:func:`rounded_svg_renderer`) and the
    elements not indented.
    """
    import matplotlib
    from matplotlib.backends.backend_mixed import MixedModeRenderer

    from flyopt.report.plots import standard
    from flyopt.report.plots.output import VECTOR_DPI, draw_vector

    RendererSVG = rounded_svg_renderer()

    buffer = io.StringIO()
    width, height = figure.get_size_inches()
    dpi = figure.dpi  # as matplotlib's print_svg: a rasterised part (a colour bar's solids) at the figure's own dpi
    made: list[MixedModeRenderer] = []

    def renderer() -> MixedModeRenderer:
        svg = RendererSVG(width * VECTOR_DPI, height * VECTOR_DPI, buffer, image_dpi=dpi, metadata={"Date": None})
        made.append(MixedModeRenderer(figure, width, height, dpi, svg))
        return made[-1]

    fonttype = "none" if text_as_text else "path"
    with standard.collector_paused(), matplotlib.rc_context({"svg.fonttype": fonttype, "svg.hashsalt": prefix}):
        draw_vector(figure, renderer)
        made[0].finalize()
    text = buffer.getvalue()
    text = text[text.index("<svg") :]
    text = re.sub(r"<metadata>.*?</metadata>\s*", "", text, flags=re.S)
    # matplotlib indents each element by its depth: spaces between elements and inside path data, which
    # neither SVG nor the page reads (a text, as paths or as one <text> a line, holds no line break)
    text = re.sub(r"\n +", "\n", text)
    seen: dict[str, Any] = {}

    def unique(match):
        # an artist's gid may name several elements (a plot's "area" labels): the second and later get a
        # number, so that ids stay unique; references (#...) only ever name matplotlib's own unique ids
        name = match.group(1)
        seen[name] = seen.get(name, 0) + 1
        suffix = "" if seen[name] == 1 else f"-{seen[name]}"
        return f' id="{prefix}{name}{suffix}"'

    text = re.sub(r'\sid="([^"]+)"', unique, text)
    text = re.sub(r'href="#([^"]+)"', lambda m: f'href="#{prefix}{m.group(1)}"', text)
    return re.sub(r"url\(#([^)]+)\)", lambda m: f"url(#{prefix}{m.group(1)})", text)


#: Decimals of the coordinates of an SVG path (the SVG's user unit is a point, 1/72 in): 0.01 pt is 3.5 µm on
#: paper, some 1/75 of a pixel on a screen. matplotlib writes six, which a curve of many points (a filled area
#: of the turning-moment diagram) spends most of its SVG on: two (and no indentation) make shear-press's seven
#: diagrams 13 % smaller (625 to 542 kB; the turning moment 24 %, 220 to 168 kB), to send to the browser and
#: for it to parse, and draw the same picture. (Text drawn as glyph references, not paths, is the rest.)
PATH_DECIMALS = 2


@functools.cache
def rounded_svg_renderer() -> type[Any]:
    """matplotlib's SVG renderer, writing its paths' coordinates to :data:`PATH_DECIMALS` decimals.

    The one change is the precision matplotlib's ``RendererSVG._convert_path`` passes to its own path writer
    (``matplotlib._path.convert_to_string``, six decimals there); every path goes through it (lines, fills,
    markers' shapes, the glyphs of text drawn as paths). Made once, as matplotlib is imported only to draw.
    """
    from matplotlib import _path
    from matplotlib.backends.backend_svg import RendererSVG

    text_to_path = remembered_text_to_path()

    class RoundedSVG(RendererSVG):
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self._text2path = text_to_path  # what a text measures and its glyphs, kept from figure to figure

        def _convert_path(
            self, path: Any, transform: Any = None, clip: Any = None, simplify: Any = None, sketch: Any = None
        ) -> str:
            box = (0.0, 0.0, self.width, self.height) if clip else None
            codes = [b"M", b"L", b"Q", b"C", b"z"]
            written = _path.convert_to_string(  # type: ignore[attr-defined]
                path, transform, box, simplify, sketch, PATH_DECIMALS, codes, False
            )
            return str(written.decode("ascii"))

    return RoundedSVG


#: Texts :func:`remembered_text_to_path` keeps (measures and glyphs of each): a report's or an app page's
#: diagrams show a few hundred different texts (tick labels, titles, legends), the same from edit to edit.
REMEMBERED_TEXTS = 4096


@functools.cache
def remembered_text_to_path() -> Any:
    """matplotlib's ``TextToPath`` (what the SVG renderer measures a text with and turns its glyphs into
    paths with: text drawn as paths), remembering both per text, from one figure and one renderer to the next.

    Both are functions of the text, its font and (measure) its font properties alone: matplotlib lays each
    text out in its font at a fixed size (``FONT_SCALE``, scaled when drawn) and measures it with the
    properties' size, whatever the figure. Its own cache of measures lasts one renderer (one figure), and it
    lays a text out again to draw it; a diagram's texts (its ticks' numbers, its labels) come back in the next
    figure and at the next edit. Text read as mathtext or TeX is not remembered (flyopt's texts escape ``$``:
    :func:`~flyopt.report.plots.standard.drawable`). Made once, as matplotlib is imported only to draw.
    """
    from collections import OrderedDict

    from matplotlib.textpath import TextToPath

    class RememberingTextToPath(TextToPath):
        def __init__(self) -> None:
            super().__init__()
            self._measures: dict[tuple[Any, ...], tuple[float, float, float]] = {}
            self._glyphs: dict[tuple[Any, ...], tuple[list[Any], dict[str, Any]]] = {}

        def get_text_width_height_descent(self, s: str, prop: Any, ismath: Any) -> Any:
            if ismath:
                return super().get_text_width_height_descent(s, prop, ismath)
            key = (s, prop.copy())  # a copy: the properties' hash follows their (mutable) state
            found = self._measures.get(key)
            if found is None:
                if len(self._measures) >= REMEMBERED_TEXTS:
                    self._measures.clear()
                found = self._measures[key] = super().get_text_width_height_descent(s, prop, ismath)
            return found

        def get_glyphs_with_font(
            self,
            font: Any,
            s: str,
            glyph_map: Any = None,
            return_new_glyphs_only: bool = False,
            *,
            features: Any = None,
            language: Any = None,
        ) -> Any:
            # the font object itself in the key (matplotlib keeps one per file list; the key holds it, so that
            # its id is never another's), its size the fixed one _get_font sets before every call
            key = (font, s, features, language)
            found = self._glyphs.get(key)
            if found is None:
                # a font's features and language as matplotlib 3.10 and later take them (none: as 3.9 and before)
                shaping = {} if features is None and language is None else {"features": features, "language": language}
                info, paths, rects = super().get_glyphs_with_font(font, s, **shaping)
                if rects:  # pragma: no cover - matplotlib draws no rectangle for a plain text
                    return super().get_glyphs_with_font(font, s, glyph_map, return_new_glyphs_only, **shaping)
                if len(self._glyphs) >= REMEMBERED_TEXTS:
                    self._glyphs.clear()
                found = self._glyphs[key] = (info, dict(paths))
            info, paths = found
            if glyph_map is None:
                glyph_map = OrderedDict()
            new = OrderedDict() if return_new_glyphs_only else glyph_map
            for glyph, *_place in info:  # in the order matplotlib adds them
                if glyph not in glyph_map:
                    new[glyph] = paths[glyph]
            return list(info), new, []

    return RememberingTextToPath()
