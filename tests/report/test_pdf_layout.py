"""The PDF report as a customer reads it (issue 29, outputs to hand on): no two runs of text overlap, and
the contents list and the outline lead to each section.

Each run of text's box is read back from the PDF by :mod:`pdf_reading` (pypdf's operator walk, the
file's own font widths and metrics), not from reportlab, which wrote it. A subscript that reached
into the next line of a table cell, or a wrapped column heading under its own subscript, is two
boxes that overlap. The links are read back by pypdf too: each outline entry and each contents
entry's link annotation must land on the page, and just above the line, where that heading's text
stands; the page number the contents list prints must be that page.
"""

import re
from html.parser import HTMLParser

import pytest
from conftest import PROBLEMS
from pdf_reading import assert_vector_diagrams, collisions, text_boxes


def _report_pdf(scene, path):
    from flyopt.cli.main import main

    assert main(["report", str(PROBLEMS / f"{scene}.toml"), "-o", str(path), "-q"]) == 0
    return path


def _described(hits):
    return [
        f"page {a.page}: ({a.x0:.1f}, {a.y0:.1f}, {a.x1:.1f}, {a.y1:.1f}) and ({b.x0:.1f}, {b.y0:.1f}, {b.x1:.1f}, "
        f"{b.y1:.1f}) overlap {across:.2f} x {up:.2f} pt"
        for a, b, across, up in hits
    ]


def test_the_reader_finds_a_drawn_overlap_and_the_widths_the_font_gives(tmp_path):
    """The reader itself: two strings drawn across each other are found; two side by side are not; a run's
    width is the font's advance ('H', read from DejaVu Sans's file by fontTools: 1540/2048 em)."""
    import matplotlib
    from fontTools.ttLib import TTFont
    from pypdf import PdfReader
    from reportlab.pdfbase import pdfmetrics
    from reportlab.pdfbase.ttfonts import TTFont as RLFont
    from reportlab.pdfgen.canvas import Canvas

    file = f"{matplotlib.get_data_path()}/fonts/ttf/DejaVuSans.ttf"
    pdfmetrics.registerFont(RLFont("ReaderTestSans", file))
    out = tmp_path / "t.pdf"
    canvas = Canvas(str(out))
    canvas.setFont("ReaderTestSans", 10)
    canvas.drawString(100, 700, "HHHH")
    canvas.drawString(100 + 4 * 10 * 1540 / 2048 + 0.05, 700, "HHHH")  # edge to edge: not an overlap
    canvas.drawString(100, 500, "HHHH")
    canvas.drawString(110, 503, "HHHH")  # across the first
    canvas.save()
    font = TTFont(file)
    advance = font["hmtx"]["H"][0] / font["head"].unitsPerEm
    boxes = text_boxes(PdfReader(str(out)).pages[0], 1)
    assert len(boxes) == 4
    assert advance == 1540 / 2048
    assert boxes[0].x1 - boxes[0].x0 == pytest.approx(4 * 10 * advance, abs=0.02)  # widths to 1/1000 em
    hits = collisions(out)
    assert len(hits) == 1 and hits[0][0].y0 < 600


def test_subscripts_and_a_wrapped_heading_keep_off_the_next_line(tmp_path):
    """A column heading with a subscript that wraps in its narrow column (the ranking table's 'D_outer [mm]'),
    a table cell and an equation of subscripted symbols over several lines, and a superscript under a line:
    reportlab's own subscript (0.5 em down) reached 1.4 pt into the next line of a 7.6 pt cell."""
    from flyopt.report.document import Document, Equation, Section, Table
    from flyopt.report.pdf import render

    table = Table(
        head=("rank", "D_{outer} [mm]", "H [mm]", "J_{F} [kg·m²]", "binding"),
        rows=(
            ("1", "657", "25", "1.5", "castability_rim_web_ratio, castability_web_hub_ratio, hb_ratio " * 3),
            ("2", "624.912", "30.8315", "J_{F} over J_{c} and J_{F} over J_{c} " * 6, "n^{2} over n^{2} " * 12),
        ),
        align=("<", ">", ">", "<", "<"),
        caption="Every material × shaft combination",
    )
    equation = Equation(
        "delta",
        ("δ = (ω_{max} − ω_{min}) / ω_{m}", "= (ω_{max} − ω_{min}) / ω_{m} × J_{F}" * 8, "= 0.15"),
        "Appendix A.2",
    )
    document = Document(
        title="Layout",
        title_block=(("scene file", "x.toml"),),
        sections=[Section("1", "Tables", [table, equation])],
        units="engineering",
        status="designed",
    )
    out = tmp_path / "layout.pdf"
    out.write_bytes(render(document))
    assert not collisions(out), _described(collisions(out))


def test_a_long_title_in_the_footer_stops_short_of_the_page_number(tmp_path):
    """The footer holds the scene's title and the page number on one line: four-cylinder-engine-shaft's title
    ran into 'page 12'. A title far too long for the line is cut with an ellipsis, clear of the number."""
    from flyopt.report.document import Document, Paragraph, Section
    from flyopt.report.pdf import render

    title = "Four-cylinder engine from indicator data, generator set: the flywheel on a described crankshaft end " * 2
    document = Document(
        title=title,
        title_block=(("scene file", "x.toml"),),
        sections=[Section("1", "Text", [Paragraph("A paragraph.")])],
        units="engineering",
        status="designed",
    )
    out = tmp_path / "footer.pdf"
    out.write_bytes(render(document))
    assert not collisions(out), _described(collisions(out))


def test_a_report_pdf_is_vectors_without_text_over_text_and_leads_to_every_section(tmp_path):
    """slider-crank-press's whole report in the default run, written once for four checks (each PDF costs a
    solve and a layout): its diagrams are vectors; no run of text overlaps another (tables, equations, the
    eight diagrams' own words); the outline and the contents lead to every section; no page ends with a
    heading. The other representative scenes' overlaps are in the slow run below."""
    out = _report_pdf("slider-crank-press", tmp_path / "r.pdf")
    assert_vector_diagrams(out)
    hits = collisions(out)
    assert not hits, _described(hits)
    _check_outline_and_contents(out)
    assert not _ending_with_a_heading(out)


@pytest.mark.slow
@pytest.mark.parametrize("scene", ["punch-press-wheel", "press-arms-wheel", "four-cylinder-engine", "press-drive"])
def test_every_representative_report_pdf_has_no_text_over_text(scene, tmp_path):
    # slider-crank-press stays in the default run (above); these add the ranking table, the arms, an engine, a drive
    hits = collisions(_report_pdf(scene, tmp_path / "r.pdf"))
    assert not hits, _described(hits)


def _outline(reader):
    def flat(entries):
        for entry in entries:
            if isinstance(entry, list):
                yield from flat(entry)
            else:
                yield entry

    return list(flat(reader.outline))


def _lines(page):
    """Each run of text pypdf decodes on a page, with the height of its baseline [pt]."""
    found: list[tuple[float, str]] = []

    def visit(text, cm, tm, font, size):
        if text.strip():
            found.append((tm[4] * cm[1] + tm[5] * cm[3] + cm[5], text.strip()))

    page.extract_text(visitor_text=visit)
    return found


def _heading_below(lines, top):
    """The first run of text below a destination's top on its page: what a reader sees on arrival."""
    return max((y, text) for y, text in lines if y <= top + 0.5)[1]


def _check_outline_and_contents(path):
    from pypdf import PdfReader

    reader = PdfReader(str(path))
    lines: dict[int, list] = {}
    outline = _outline(reader)
    titles = [entry.title for entry in outline]
    # the headings as the pages print them, in order: "1 Summary", "4.2 The machine reduced to one shaft", ...
    assert titles[:2] == ["1 Summary", "2 The scene as given"] and "8 Provenance" in titles
    assert any(re.match(r"4\.2 ", t) for t in titles)
    places = {}
    for entry in outline:
        page = reader.get_destination_page_number(entry)
        if page not in lines:
            lines[page] = _lines(reader.pages[page])
        assert _heading_below(lines[page], float(entry.top)) == entry.title, entry.title
        places[entry.title] = (page, round(float(entry.top), 2))
    chapters = {places[t] for t in titles if re.match(r"(?:\d+|[A-Z]) ", t)}
    links = [a.get_object() for a in reader.pages[0].get("/Annots", [])]
    links = [a for a in links if a["/Subtype"] == "/Link"]
    targets = {(reader.get_page_number(a["/Dest"][0].get_object()), round(float(a["/Dest"][3]), 2)) for a in links}
    assert targets == chapters  # every chapter linked from the contents, and nothing else
    # self-contained: no path into the repository; each appendix section the text cites is a heading of the PDF
    text = " ".join(" ".join(page.extract_text() for page in reader.pages).split())
    assert "flywheel-design" not in text and "docs/" not in text
    cited = set(re.findall(r"\bA\.(\d+)\b", text))
    assert {"2", "5"} <= cited
    assert all(any(t.startswith(f"A.{n} ") for t in titles) for n in cited), cited
    assert len(links) == 3 * len(chapters)  # its number, its title and its page
    contents = " ".join(reader.pages[0].extract_text().split())
    for title in titles:
        if re.match(r"(?:\d+|[A-Z]) ", title):
            number, words = title.split(" ", 1)
            printed = re.search(rf"{number} {re.escape(words)} (\d+)", contents)
            assert printed and int(printed.group(1)) == places[title][0] + 1, title


class _Anchors(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links, self._in = {}, [], None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag in ("h2", "h3") and "id" in attrs:
            self._in = ("id", attrs["id"])
            self.ids[attrs["id"]] = ""
        elif tag == "a" and "href" in attrs:
            self._in = ("a", attrs["href"])
            self.links.append([attrs["href"], ""])

    def handle_endtag(self, tag):
        if tag in ("h2", "h3", "a"):
            self._in = None

    def handle_data(self, data):
        if self._in and self._in[0] == "id":
            self.ids[self._in[1]] += data
        elif self._in:
            self.links[-1][1] += data


def test_the_html_contents_link_every_section_to_its_heading():
    """The HTML's contents list: one link per numbered section, to the heading that carries its number and title
    (read back with the standard library's parser)."""
    from flyopt.report.document import Document, Paragraph, Section
    from flyopt.report.html import render

    sections = [
        Section("1", "Summary", [Paragraph("x")]),
        Section("1.1", "A part", [Paragraph("y")], level=2),
        Section("2", "J_{F} and <b>", [Paragraph("z")]),
        Section("A", "Method", [Paragraph("w")]),
    ]
    page = _Anchors()
    page.feed(render(Document("t", (), sections, "engineering", "designed")))
    assert [text for _, text in page.links] == ["1 Summary", "2 J_{F} and <b>", "A Method"]
    for href, text in page.links:
        assert href.startswith("#") and page.ids[href[1:]] == text


#: Below this height [pt] a page holds only its footer (at 9 mm; the text stops at the 17 mm margin).
_FOOTER = 40.0


def _squeezed(text):
    return "".join(text.split())


def _last_line(page):
    """The text of a page's last line above its footer, its runs in order across (None: no text)."""
    runs: list[tuple[float, float, str]] = []

    def visit(text, cm, tm, font, size):
        if text.strip():
            x = tm[4] * cm[0] + tm[5] * cm[2] + cm[4]
            runs.append((tm[4] * cm[1] + tm[5] * cm[3] + cm[5], x, text.strip()))

    page.extract_text(visitor_text=visit)
    body = [run for run in runs if run[0] > _FOOTER]
    if not body:
        return None
    low = min(y for y, _, _ in body)
    return " ".join(text for _, text in sorted((x, text) for y, x, text in body if y < low + 1))


def _ending_with_a_heading(path):
    """(page number, its last line) of each page of the PDF at ``path`` whose last line is a heading of its
    outline (a wrapped heading's last line counts)."""
    from pypdf import PdfReader

    reader = PdfReader(str(path))
    titles = [_squeezed(entry.title) for entry in _outline(reader)]
    assert titles
    ended = []
    for number, page in enumerate(reader.pages, 1):
        last = _last_line(page)
        if last is not None and any(title.endswith(_squeezed(last)) for title in titles):
            ended.append((number, last))
    return ended


# both in the slow set (the default run's five minutes): the default run holds slider-crank-press's whole report
# to the same rule (test_a_report_pdf_is_vectors_without_text_over_text_and_leads_to_every_section)
@pytest.mark.slow
@pytest.mark.parametrize("scene", ["punch-press-wheel", "motor-press"])
def test_no_page_ends_with_a_heading(scene, tmp_path):
    """A heading stays on the page of what follows it: punch-press-wheel's "2 The scene as given" was the last
    line of page 1, its facts on page 2 (reportlab keeps a heading with the next flowable, but not with one
    already kept together, as a short list of facts or a worked step is: motor-press's "4.1 Speeds and the
    allowed fluctuation" ended page 2, its first step on page 3)."""
    ended = _ending_with_a_heading(_report_pdf(scene, tmp_path / "r.pdf"))
    assert not ended, ended


def test_no_page_ends_with_a_tables_caption(main_cli, tmp_path):
    """A table's caption, written above it, stays on the page of its table: the press template's "Shafts a
    flywheel may sit on" was the last line of page 1, its table on page 2 (a new user's first report)."""
    from pypdf import PdfReader

    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Code, Table

    scene = tmp_path / "press.toml"
    assert main_cli("new", "press", "-o", scene)[0] == 0
    status, _, err = main_cli("report", scene, "-o", tmp_path / "r.pdf")
    assert status == 0, err
    document = build(collect(str(scene)), figures=False)
    try:
        captions = {
            _squeezed(block.caption)
            for section in document.sections
            for block in section.blocks
            if isinstance(block, (Table, Code)) and block.caption
        }
    finally:
        document.close()
    assert _squeezed("Shafts a flywheel may sit on") in captions
    last = [_last_line(page) for page in PdfReader(str(tmp_path / "r.pdf")).pages]
    ended = [(k, line) for k, line in enumerate(last, 1) if line is not None and _squeezed(line) in captions]
    assert not ended, ended
