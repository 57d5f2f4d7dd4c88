"""The PDF report's diagrams are vectors (issue 26): drawn onto the page as paths and text, not as images.

Read back by pypdf (the test extra), an independent reader of what reportlab wrote: the pages hold
no image at all, and the diagrams' own words (axis labels, legends, titles) are text in the PDF.
The renderer itself (:mod:`flyopt.report.pdf_figure`) is checked on a figure with each kind of
mark it must carry: a dashed line, a marker, a hatched patch, a clip path, text at an angle and
mathtext (drawn as outlines).
"""

import re

import pytest
from conftest import PROBLEMS
from pdf_reading import assert_vector_diagrams

from flyopt.cli.main import main


def _pdf(path):
    from pypdf import PdfReader

    return PdfReader(str(path))


@pytest.mark.slow
def test_the_diagrams_are_vectors_with_their_words_as_text(tmp_path):
    # slider-crank-press's is checked in the default run with its layout (test_pdf_layout.py: one PDF, three checks)
    out = tmp_path / "r.pdf"
    assert main(["report", str(PROBLEMS / "punch-press-wheel.toml"), "-o", str(out), "-q"]) == 0
    assert_vector_diagrams(out)


def test_the_renderer_draws_every_kind_of_mark(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, Rectangle
    from reportlab.pdfgen.canvas import Canvas

    from flyopt.report.pdf_figure import draw

    fig = Figure(figsize=(4, 3), layout="constrained")
    ax = fig.add_subplot()
    ax.plot([0, 1], [0, 1], "--", label="dashed")
    ax.plot([0.2], [0.2], "o", label="marker")
    ax.add_patch(Rectangle((0.6, 0.1), 0.2, 0.2, facecolor="#e8ebf0", edgecolor="black", hatch="////"))
    disc = Circle((0.5, 0.5), 0.2, alpha=0.5)
    ax.add_patch(disc)
    (clipped,) = ax.plot([0, 1], [1, 0])
    clipped.set_clip_path(disc)
    ax.set_ylabel("upright label")
    ax.text(0.1, 0.9, r"$x^2$ outlined")
    ax.legend()
    out = tmp_path / "f.pdf"
    canvas = Canvas(str(out))
    draw(fig, canvas, 20, 300, 0.8)
    canvas.save()
    assert fig.dpi == 100  # the figure's own dpi again
    page = _pdf(out).pages[0]
    assert not page.images
    text = page.extract_text()
    assert "upright label" in text and "dashed" in text and "marker" in text
    assert "outlined" not in text and "x^2" not in text  # a mathtext string is drawn whole as outlines
    stream = page.get_contents().get_data().decode("latin-1")
    assert re.search(r"\[[\d. ]+\] [\d.]+ d", stream), "no dash pattern"
    assert re.search(r"W n", stream), "no clipping"
    assert re.search(r" c\n", stream), "no curve (the circle, the marker)"
    assert "/GS" in stream or "gs" in stream, "no transparency state (alpha 0.5)"


@pytest.mark.slow  # 10 s: every diagram drawn twice over; the PDF and HTML layouts are held by test_pdf_layout by default
def test_an_html_figure_is_laid_out_and_placed_as_savefig_places_it():
    """The HTML's figures are drawn once (flyopt.report.plots.output.draw_vector) where savefig draws twice: every
    text, mark and image stands where matplotlib's own savefig puts it, to the digit it writes, on each diagram of
    slider-crank-press (the energy–mass diagram has a colour bar whose solids are rasterised, after which the
    figure must be back at the vector dpi). Each is compared on its first draw, with the same diagram of a second
    build (a second draw of a figure may move a text: matplotlib's layout starts from the last one). The figure
    keeps its own dpi and canvas."""
    import io

    import matplotlib

    from flyopt.cli.report import collect
    from flyopt.report.builder import build
    from flyopt.report.document import Figure
    from flyopt.report.html import svg_of

    inputs = collect(PROBLEMS / "slider-crank-press.toml")
    ours, theirs = build(inputs, "engineering"), build(inputs, "engineering")
    try:
        pairs = [
            (a.figure, b.figure)
            for x, y in zip(ours.sections, theirs.sections)
            for a, b in zip(x.blocks, y.blocks)
            if isinstance(a, Figure) and a.figure is not None
        ]
        assert len(pairs) == 8  # the seven diagrams and the manufacturing drawing
        place = re.compile(r'translate\([^)]*\)| x="[^"]*" y="[^"]*"| width="[^"]*" height="[^"]*"')
        for figure, twin in pairs:
            canvas, dpi = figure.canvas, figure.dpi
            drawn = place.findall(svg_of(figure, "p"))
            assert (figure.canvas, figure.dpi) == (canvas, dpi)
            buffer = io.StringIO()
            with matplotlib.rc_context({"svg.fonttype": "path"}):
                twin.savefig(buffer, format="svg")
            assert drawn == place.findall(buffer.getvalue())
            assert len(drawn) > 50
    finally:
        ours.close()
        theirs.close()
