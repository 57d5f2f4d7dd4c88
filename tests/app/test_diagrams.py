"""The app's diagrams drawn those in view first (:mod:`flyopt.app.diagrams`), without a browser: the order, and
the answer's document the same as one drawn at once."""

from __future__ import annotations

import pytest

from flyopt.app import model
from flyopt.app.diagrams import Diagrams, drawing_order

pytestmark = pytest.mark.usefixtures("close_figures")  # the app keeps figures open: none outlives a test


def test_the_order_is_the_most_in_view_first_ties_in_the_pages_order():
    in_view = {"turning_moment": 0.0, "energy": 0.5, "inertia_delta": 1.0, "stress": 0.5, "speed": 0.1}
    assert drawing_order(in_view) == ["inertia_delta", "energy", "stress", "speed"]
    assert drawing_order({}) == [] and drawing_order({"speed": 0.0}) == []


def drawn_all(diagrams):
    order = []
    while (step := diagrams.step()) is not None:
        order.append(step)
    return order


def test_the_diagrams_in_view_come_first_and_the_document_is_the_one_drawn_at_once(workspace, monkeypatch):
    """Two documents (the diagrams in view, then the rest) from the one solve, joined: the same figures in the
    same places as the report's one document, each SVG the same as drawn there."""
    import flyopt.cli.report as cli_report

    text = model.template_text("shear-press")
    whole = model.solve(text, workspace)
    page = [f.key for f in whole.figures]
    answer = model.numbers(text, workspace)

    def no_second_solve(*_args, **_kwargs):
        raise AssertionError("the diagrams solved the scene again")

    monkeypatch.setattr(cli_report, "collect", no_second_solve)
    diagrams = Diagrams(answer, {"turning_moment": 0.0, "energy": 0.3, "speed": 0.9, "inertia_delta": 0.3})
    order = drawn_all(diagrams)
    keys = [shown.key for _, shown in order]
    assert keys == [
        "speed",
        "energy",
        "inertia_delta",
        *[k for k in page if k not in ("speed", "energy", "inertia_delta")],
    ]
    assert [page[index] for index, _ in order] == keys  # each drawn with its place on the page
    assert len(diagrams.documents) == 2
    document = diagrams.document()
    blocks = model.figure_blocks(document)
    assert [b.key for b in blocks] == page
    assert [b.figure is not None for b in blocks] == [bool(f.svg) for f in whole.figures]
    assert diagrams.figures() == whole.figures  # SVG and read-outs: the same drawing
    html = model.report_bytes(model.drawn(answer, document, diagrams.figures()), "html").decode("utf-8")
    assert html.count("<svg") == sum(1 for f in whole.figures if f.svg)
    document.close()


def test_with_nothing_in_view_or_none_of_its_diagrams_the_pages_order_from_one_document(workspace):
    answer = model.numbers(model.template_text("shear-press"), workspace)
    for in_view in ({}, {"campbell": 1.0}):  # nothing, or a diagram this answer does not have
        diagrams = Diagrams(answer, in_view)
        order = drawn_all(diagrams)
        assert [index for index, _ in order] == list(range(len(order)))
        assert len(diagrams.documents) == 1
        diagrams.close()
        assert diagrams.documents == []
