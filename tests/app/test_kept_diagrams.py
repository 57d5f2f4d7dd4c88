"""A diagram an edit does not change is kept, not drawn again (flyopt.app.diagrams.kept): what the page then
shows must be what drawing it afresh shows, to the byte, and the reports downloaded must still hold it.

The reference is the whole answer solved and drawn at once (flyopt.app.model.solve: every diagram made and
drawn from the new text), which keeps nothing.
"""

from __future__ import annotations

import pytest

from flyopt.app import model
from flyopt.app.diagrams import Diagrams

pytestmark = pytest.mark.usefixtures("close_figures")  # the app keeps figures open: none outlives a test


def _edited(delta):
    text = model.template_text("shear-press")
    return text.replace("delta = 0.05", f"delta = {delta}", 1)


def _drawn_keys(monkeypatch):
    """The keys of the diagrams drawn to SVG from now on."""
    drawn: list[str] = []
    svg = model.figure_svg

    def counted(block):
        drawn.append(block.key)
        return svg(block)

    monkeypatch.setattr(model, "figure_svg", counted)
    return drawn


def _all(diagrams):
    while diagrams.step() is not None:
        pass
    return diagrams.figures()


def test_a_delta_edit_keeps_the_diagrams_it_leaves_unchanged_and_they_are_the_fresh_ones(workspace, monkeypatch):
    before = model.solve(_edited("0.04"), workspace)
    fresh = model.solve(_edited("0.02"), workspace)  # the reference: every diagram drawn from the new text
    for done in (before, fresh):  # their SVGs are kept; their figures closed (matplotlib warns past 20 open)
        done.document.close()
    answer = model.numbers(_edited("0.02"), workspace)
    drawn = _drawn_keys(monkeypatch)
    diagrams = Diagrams(answer, {"inertia_delta": 1.0}, before.figures)
    figures = _all(diagrams)
    page = [f.key for f in fresh.figures]
    assert {"turning_moment", "energy"}.isdisjoint(drawn)  # kept: the δ edit leaves them as they were
    assert sorted(drawn) == sorted(k for k in page if k not in ("turning_moment", "energy"))
    assert drawn[0] == "inertia_delta"  # the one in view still first
    assert figures == fresh.figures  # every SVG, read-out and digest the same as drawn afresh
    # the answer's document leaves the kept ones undrawn; a report draws them from the same solve
    document = diagrams.document()
    assert [b.figure is None for b in model.figure_blocks(document)] == [
        k in ("turning_moment", "energy") for k in page
    ]
    html = model.report_bytes(model.drawn(answer, document, figures), "html").decode("utf-8")
    assert html.count("<svg") == sum(1 for f in fresh.figures if f.svg)
    # a report draws its figures afresh, once, as a report of the answer's card does (none drawn for the page)
    once = model.report_bytes(model.numbers(_edited("0.02"), workspace), "html").decode("utf-8")
    assert _figures_of(html) == _figures_of(once)
    document.close()


def _figures_of(html):
    """The report's SVG figures, in order."""
    import re

    return re.findall(r"<svg.*?</svg>", html, flags=re.S)


def test_nothing_is_kept_where_the_page_shows_another_diagram_or_other_data(workspace, monkeypatch):
    before = model.solve(_edited("0.04"), workspace)
    answer = model.numbers(_edited("0.02"), workspace)
    page = [f.key for f in before.figures]
    other = [f._replace(digest=f.digest[::-1]) for f in before.figures]  # the same keys, other data
    moved = before.figures[1:] + before.figures[:1]  # the same diagrams, each in another place
    for showing in (other, moved, []):
        drawn = _drawn_keys(monkeypatch)
        _all(Diagrams(answer, {}, showing))
        assert drawn == page
        monkeypatch.undo()


def test_an_edit_that_changes_no_diagrams_data_keeps_every_split_diagram(workspace, monkeypatch):
    """A comment typed: every diagram with a digest kept, and what the page shows the same as drawn afresh."""
    before = model.solve(_edited("0.04"), workspace)
    commented = _edited("0.04") + "\n# a comment\n"
    fresh = model.solve(commented, workspace)
    answer = model.numbers(commented, workspace)
    drawn = _drawn_keys(monkeypatch)
    diagrams = Diagrams(answer, {}, before.figures)
    figures = _all(diagrams)
    kept = {f.key for f in before.figures if f.digest}
    assert kept >= {"turning_moment", "energy"} and kept.isdisjoint(drawn)
    assert figures == fresh.figures  # the wheel's drawing names the scene's hash: drawn again, the rest the same


def test_the_card_reads_no_diagrams_data_and_the_digests_are_those_of_the_diagrams_drawn(workspace, monkeypatch):
    """The card (numbers only) reads none of the diagrams' data (ΔE(φ) of an expression's torque took the card of
    problems/compressor.toml from 30 to 200 ms); the digests read after it (in the drawing worker) are those of
    the diagrams drawn: what the page compares is what it would draw."""
    from flyopt.report.plots import cycle, energy, inertia_delta, speed, turning_moment

    def unread(*_args, **_kwargs):
        raise AssertionError("the card read a diagram's data")

    with monkeypatch.context() as patch:
        for kind in (
            turning_moment.TurningMoment,
            energy.EnergyDiagram,
            inertia_delta.InertiaDelta,
            speed.SpeedDiagram,
            cycle.Torques,
        ):
            patch.setattr(kind, "of", unread)
        answer = model.numbers(_edited("0.03"), workspace)
    whole = model.solve(_edited("0.03"), workspace)
    card = {b.key: b.digest for b in model.figure_blocks(model.digests(answer)) if b.digest}
    assert card.keys() == {"turning_moment", "energy", "inertia_delta", "speed"}
    assert card == {f.key: f.digest for f in whole.figures if f.digest}


def test_a_scene_whose_diagrams_are_all_kept_draws_none_and_its_report_has_them(workspace, monkeypatch):
    """A scene without a wheel (its diagrams all of the cycle) and an edit of a comment: nothing is drawn, the
    answer's document is its card's, and the report downloaded holds every diagram."""
    text = model.template_text("textbook/khurmi-16-6")
    before = model.solve(text, workspace)
    assert before.figures and all(f.digest for f in before.figures if f.svg)
    answer = model.numbers(text + "\n# a comment\n", workspace)
    drawn = _drawn_keys(monkeypatch)
    diagrams = Diagrams(answer, {}, before.figures)
    assert _all(diagrams) == [f._replace(caption=f.caption) for f in before.figures] and drawn == []
    document = diagrams.document()
    assert document is answer.document and diagrams.documents == []
    html = model.report_bytes(model.drawn(answer, document, diagrams.figures()), "html").decode("utf-8")
    assert html.count("<svg") == sum(1 for f in before.figures if f.svg) > 0


def test_an_envelope_edit_keeps_the_diagrams_of_the_cycle_and_redraws_the_wheels(workspace, monkeypatch):
    """A smaller envelope (max_outer_diameter binds shear-press's wheel) changes the wheel, not the cycle: the
    turning-moment, energy and J_F–δ diagrams are kept, the wheel's (stress, section, drawing) drawn again, and
    the speed (with the simulation of the designed wheel, whose J_F is the same to round-off) kept exactly when
    its digest is the same; what the page shows is the same edit drawn afresh."""
    text = _edited("0.04")
    smaller = text.replace('max_outer_diameter = "0.6 m"', 'max_outer_diameter = "0.55 m"', 1)
    assert smaller != text
    before = model.solve(text, workspace)
    fresh = model.solve(smaller, workspace)
    answer = model.numbers(smaller, workspace)
    drawn = _drawn_keys(monkeypatch)
    figures = _all(Diagrams(answer, {}, before.figures))
    cycle = {"turning_moment", "energy", "inertia_delta"}
    speed = [f.digest for f in (*before.figures, *fresh.figures) if f.key == "speed"]
    if speed[0] == speed[1]:
        cycle.add("speed")
    assert cycle.isdisjoint(drawn) and set(drawn) == {f.key for f in fresh.figures} - cycle
    assert figures == fresh.figures
