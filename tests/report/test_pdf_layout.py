"""The PDF report as a customer reads it (issue 29, outputs to hand on): no two runs of text overlap.

Each run of text's box is read back from the PDF by :mod:`pdf_reading` (pypdf's operator walk, the
file's own font widths and metrics), not from reportlab, which wrote it. A subscript that reached
into the next line of a table cell, or a wrapped column heading under its own subscript, is two
boxes that overlap.
"""

import pytest
from conftest import PROBLEMS
from pdf_reading import collisions, text_boxes


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


def test_a_report_pdf_has_no_text_over_text(tmp_path):
    """slider-crank-press's whole report (tables, equations, the eight diagrams' own words) in the default run;
    the other representative scenes below in the slow run."""
    out = _report_pdf("slider-crank-press", tmp_path / "r.pdf")
    hits = collisions(out)
    assert not hits, _described(hits)


@pytest.mark.slow
@pytest.mark.parametrize("scene", ["punch-press-wheel", "press-arms-wheel", "four-cylinder-engine", "press-drive"])
def test_every_representative_report_pdf_has_no_text_over_text(scene, tmp_path):
    # slider-crank-press stays in the default run (above); these add the ranking table, the arms, an engine, a drive
    hits = collisions(_report_pdf(scene, tmp_path / "r.pdf"))
    assert not hits, _described(hits)
