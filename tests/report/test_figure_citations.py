"""A figure cites flyopt's notes the way the text around it does.

A report carries the sections of the notes it cites as Appendix A and its text cites them as "Appendix A.5"
(:func:`flyopt.report.method.with_appendix`). Its figures' legends said "(section 5)" and "(section 7)": in
the report, section 5 is "The design" and 7 "Verification", not the method the legend meant. In a report a
figure's text says the appendix's number, of a section the appendix carries; a figure drawn alone (no
appendix) names the notes' section ("section 5 of flyopt's notes"), never an appendix.
"""

import re

import pytest
from conftest import PROBLEMS

#: A section cited by its number ("section 5", "sections 3 and 7"), which in a report reads as its own section.
_BY_NUMBER = re.compile(r"\bsections? \d+")


def _figure_texts(document):
    """Every text of every figure drawn in the document (title, labels, legend entries and title, notes)."""
    from matplotlib.text import Text

    texts = []
    for section in document.sections:
        for block in section.blocks:
            figure = getattr(block, "figure", None)
            if figure is not None:
                texts += [t.get_text() for t in figure.findobj(Text) if t.get_text()]
    return texts


@pytest.mark.parametrize(
    ("scene", "cites"),
    [
        ("punch-press-wheel", "A.5"),  # J_F(δ) = A_max/(ω_m² δ) − J_c, the constant-inertia method
        ("motor-press", "A.7"),  # a torque of speed: the periodic solution
        ("slider-crank-press", "A.6"),  # J_e of φ: the energy–mass tangents
    ],
)
def test_a_reports_figures_cite_the_appendix_it_carries(scene, cites):
    from flyopt.cli.report import collect
    from flyopt.report.builder import build

    document = build(collect(str(PROBLEMS / f"{scene}.toml")))
    try:
        texts = _figure_texts(document)
    finally:
        document.close()
    assert texts, scene
    own = {section.number for section in document.sections}
    by_number = [t for t in texts if _BY_NUMBER.search(t)]
    assert not by_number, f"{scene}: a figure cites a section by a number the report gives its own: {by_number}"
    appendix = [n for t in texts for n in re.findall(r"\bA\.\d+(?:\.\d+)?", t)]
    assert all(n in own for n in appendix), (appendix, sorted(own))
    if cites is not None:
        assert cites in appendix, texts


def test_a_figure_drawn_alone_names_the_notes_and_no_appendix(close_figures):
    from matplotlib.text import Text

    from flyopt.io.scene import load
    from flyopt.pipeline import solve
    from flyopt.report.plots import plot_inertia_delta, standard

    solution = solve(load(PROBLEMS / "punch-press-wheel.toml"))
    figure = standard.figure_of(plot_inertia_delta(solution.scene, solution.analysis))
    said = " ".join(t.get_text() for t in figure.findobj(Text)).replace("\n", " ")
    assert "section 5 of flyopt's notes" in said, said
    assert "Appendix" not in said and "flywheel-design" not in said, said
