"""The page's order of work, in this process (Panel without a browser): the card of an edit is the first thing
the page changes, and it does not wait for the diagrams of an earlier edit, which are dropped."""

from __future__ import annotations

import asyncio
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "problems" / "shear-press.toml").read_text(encoding="utf-8")
#: Panel 1.9 deprecates parameters the page gives its widgets (``name``, ``button_type``), pandas 3.1 one Panel
#: uses: their warnings are errors under the test settings.
pytestmark = [
    pytest.mark.filterwarnings("ignore:The inplace keyword:Warning"),  # pandas 3.1's, inside Panel's Tabulator
]
#: Long enough for a loaded host; the waits end as soon as the page answers (no time is asserted).
PATIENCE = 120.0


def edited(delta: str) -> str:
    assert "delta = 0.05" in TEXT
    return TEXT.replace("delta = 0.05", f"delta = {delta}")


@pytest.fixture()
def session(monkeypatch):
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app.page import Session

    monkeypatch.setattr(pn.state, "onload", lambda _callback: None)  # no browser loads it: each test refreshes
    made = Session(pn)
    yield made
    made.close()
    import matplotlib.pyplot as plt

    plt.close("all")


async def until(condition, what: str) -> None:
    for _ in range(int(PATIENCE / 0.01)):
        if condition():
            return
        await asyncio.sleep(0.01)
    pytest.fail(f"{what} did not happen")


def test_a_fast_edit_changes_nothing_on_the_page_before_its_card(session, monkeypatch):
    """Each change is a message the browser lays the page out for: none before the numbers (no "solving…"
    card, no spinner), then the card first, and the spinner while the diagrams are drawn."""
    from flyopt.app import model

    seen: list[str] = []
    numbers = model.numbers

    def solved(*args, **kwargs):
        answer = numbers(*args, **kwargs)
        seen.append("numbers")
        return answer

    monkeypatch.setattr(model, "numbers", solved)
    monkeypatch.setattr(model, "figure_svg", lambda block: model.Shown(block.key, "caption", ""))
    session.card.param.watch(lambda event: seen.append("card: " + event.new), "html")
    session.busy.param.watch(lambda event: seen.append(f"busy: {event.new}"), "value")
    session.solve_button.param.watch(lambda event: seen.append(f"solve disabled: {event.new}"), "disabled")
    asyncio.run(session._refresh(edited("0.04"), solve=None))
    assert seen[0] == "numbers"
    assert "0.04 (1/25)" in seen[1] and "drawing the diagrams" in seen[1]
    assert "solving" not in " ".join(seen)
    assert seen[2:4] == ["busy: True", "solve disabled: True"]  # while the diagrams are drawn
    assert seen[-2:] == ["busy: False", "solve disabled: False"]  # the spinner stops after
    last = [change for change in seen if change.startswith("card: ")][-1]
    assert "0.04 (1/25)" in last and "drawing" not in last  # the card once they are drawn


def test_an_edit_s_card_does_not_wait_for_the_last_edit_s_diagrams_which_are_dropped(session, monkeypatch):
    """The first edit's first diagram is held in the drawing worker; the second edit's card comes meanwhile,
    and once released, nothing more of the first edit is drawn: the diagrams shown are the second's."""
    from flyopt.app import model

    held = threading.Event()
    release = threading.Event()
    drawn: list[tuple[str, str]] = []  # (the edit's δ, the diagram's key)
    draw = model.draw

    def drawing(answer, keys=None, read=None):
        document = draw(answer, keys, read)
        document.delta = answer.sha256  # which edit the document is of
        return document

    def svg(block):
        edit = "first" if block.figure is not None and owner.get(id(block)) == "first" else "second"
        if edit == "first":
            held.set()
            assert release.wait(PATIENCE), "the test did not release the first edit's diagram"
        drawn.append((edit, block.key))
        return model.Shown(block.key, f"{edit} {block.key}", "<svg></svg>")

    owner: dict[int, str] = {}
    first = edited("0.04")

    def draw_marked(answer, keys=None, read=None):
        document = drawing(answer, keys, read)
        for block in model.figure_blocks(document):
            owner[id(block)] = "first" if answer.sha256 == model.scene_digest(first) else "second"
        return document

    monkeypatch.setattr(model, "draw", draw_marked)
    monkeypatch.setattr(model, "figure_svg", svg)

    async def edits() -> None:
        one = asyncio.ensure_future(session._refresh(first, solve=None))
        await until(held.is_set, "the first edit's first diagram")
        two = asyncio.ensure_future(session._refresh(edited("0.02"), solve=None))
        await until(lambda: "0.02 (1/50)" in session.card.html, "the second edit's card, beside a held diagram")
        release.set()
        await asyncio.gather(one, two)

    asyncio.run(edits())
    firsts = [key for edit, key in drawn if edit == "first"]
    seconds = [key for edit, key in drawn if edit == "second"]
    assert len(firsts) == 1  # the one being drawn when the second edit came; the rest dropped
    assert len(seconds) >= 5 and seconds[-1] == "speed"
    assert [slot[1].object for slot in session.figure_slots] == [f"<b>second {key}</b>" for key in seconds]
    assert "0.02 (1/50)" in session.card.html and "drawing" not in session.card.html


def test_the_diagram_in_view_is_drawn_and_shown_first(session, monkeypatch):
    """The browser says how much of each diagram is in view (the component's ``seen``); on the next edit the
    page draws and shows the one most in view first, then the others in the page's order."""
    from flyopt.app import model

    asyncio.run(session._refresh(edited("0.04"), solve=None))
    keys = [slot[2].key for slot in session.figure_slots]
    assert keys[-1] == "speed" and len(keys) >= 5
    for _column, _title, pane in session.figure_slots:
        pane.seen = {"speed": 1.0, "stress": 0.25}.get(pane.key, 0.0)  # the page scrolled down to the speed
    shown: list[str] = []
    show = session._show_figure

    def showing(index, figure):
        shown.append(figure.key)
        return show(index, figure)

    monkeypatch.setattr(session, "_show_figure", showing)
    asyncio.run(session._refresh(edited("0.02"), solve=None))
    kept = {"turning_moment", "energy"}  # a δ edit leaves them as they were: kept, not drawn again
    rest = [key for key in keys if key not in ("speed", "stress", *kept)]
    drawn = len(keys) - len(kept)
    assert shown[:drawn] == ["speed", "stress", *rest]
    assert shown[drawn:] == keys  # then every place once more, as the answer's figures (the kept ones as they were)
    assert [slot[2].key for slot in session.figure_slots] == keys  # each in its place on the page
    assert "0.02 (1/50)" in session.card.html and "drawing" not in session.card.html
    blocks = model.figure_blocks(session.answer.document)
    assert all((block.figure is None) == (block.key in kept) for block in blocks if block.key in keys)


@pytest.mark.parametrize("then", ["a slow scene", "a broken scene"])
def test_an_edit_that_runs_nothing_while_diagrams_are_drawn_leaves_solve_offered(session, monkeypatch, then):
    """A fast scene's diagrams are being drawn (Solve greyed, the spinner on) when a slow template is picked or
    the text broken: the page then runs nothing for the new text, the old drawing is dropped, and Solve must be
    offered again (it stayed greyed, the spinner turning, until Cancel was pressed)."""
    from flyopt.app import model

    held, release = threading.Event(), threading.Event()

    def svg(block):
        held.set()
        assert release.wait(PATIENCE), "the test did not release the diagram"
        return model.Shown(block.key, block.key, "<svg></svg>")

    monkeypatch.setattr(model, "figure_svg", svg)
    slow = (ROOT / "problems" / "press-drive.toml").read_text(encoding="utf-8")
    text = slow if then == "a slow scene" else edited("-1")

    async def edits() -> None:
        one = asyncio.ensure_future(session._refresh(edited("0.04"), solve=None))
        await until(held.is_set, "the first edit's first diagram")
        assert session.solve_button.disabled and session.busy.value
        await session._refresh(text, solve=None)
        release.set()
        await one

    asyncio.run(edits())
    said = "press Solve" if then == "a slow scene" else "machine.delta"
    assert said in session.card.html
    assert not session.solve_button.disabled and not session.busy.value and session.cancel_button.disabled


def test_downloads_are_offered_only_when_there_is_something_to_give(session):
    """Before any answer no report or JSON is offered, and the drawing and solid only with a wheel: a click on a
    download with nothing to give failed silently in the browser (press-drive's answer needs no wheel)."""
    assert all(button.disabled for button in session.answer_downloads + session.wheel_downloads)
    asyncio.run(session._refresh(edited("0.04"), solve=None))
    assert not any(button.disabled for button in session.answer_downloads + session.wheel_downloads)
    conveyor = (ROOT / "problems" / "conveyor.toml").read_text(encoding="utf-8")
    asyncio.run(session._refresh(conveyor, solve=True))
    assert "no flywheel" in session.card.html.lower() or "not needed" in session.card.html.lower()
    assert not any(button.disabled for button in session.answer_downloads)
    assert session.wheel_downloads and all(button.disabled for button in session.wheel_downloads)


def test_the_stale_note_names_the_diagrams_only_where_some_are_shown(session, monkeypatch):
    """A broken edit while the first answer's first diagram is drawn: no diagram of the last scene solved is on
    the page, so the note names the downloads alone (it said 'the diagrams ... below' above none); once an
    answer's diagrams are shown, a broken edit's note names them."""
    from flyopt.app import model
    from flyopt.app.page import STALE, STALE_DOWNLOADS

    held, release = threading.Event(), threading.Event()
    draw = model.figure_svg

    def svg(block):
        if not release.is_set():
            held.set()
            assert release.wait(PATIENCE), "the test did not release the diagram"
        return draw(block)

    monkeypatch.setattr(model, "figure_svg", svg)

    async def edits() -> None:
        one = asyncio.ensure_future(session._refresh(edited("0.04"), solve=None))
        await until(held.is_set, "the first answer's first diagram")
        await session._refresh(edited("-1"), solve=None)
        assert session.stale.object == STALE_DOWNLOADS
        assert "The downloads on the right are those of the last scene solved" in session.card.html
        release.set()
        await one
        await session._refresh(edited("0.04"), solve=None)  # drawn in full
        await session._refresh(edited("-1"), solve=None)
        assert session.stale.object == STALE
        # said on the card too, under the problem: the diagrams beside it may be scrolled to, their note out of view
        assert "machine.delta" in session.card.html
        assert "The diagrams and downloads on the right are those of the last scene solved" in session.card.html

    asyncio.run(edits())


def test_the_first_scene_s_problems_say_nothing_of_a_last_scene(session):
    """Before any scene is solved, a broken text's card has its problems and no note of a last scene."""
    asyncio.run(session._refresh(edited("-1"), solve=None))
    assert "machine.delta" in session.card.html and "last scene solved" not in session.card.html
    assert session.stale.object == ""


def test_a_solve_that_fails_keeps_the_last_answer_and_says_so(session, monkeypatch):
    """A valid text whose solve fails (here made to fail) leaves the last answer's diagrams and downloads on the
    page: the card says the error and that they are the last scene's, and so does the note above them (it said
    nothing: the diagrams of the last design stood beside an error without a word)."""
    from flyopt.app import model
    from flyopt.app.page import STALE

    asyncio.run(session._refresh(edited("0.04"), solve=None))
    assert session.answer is not None and session.stale.object == ""

    def failing(*_args, **_kwargs):
        raise RuntimeError("the solver stopped")

    monkeypatch.setattr(model, "numbers", failing)
    asyncio.run(session._refresh(edited("0.03"), solve=None))
    assert "the solver stopped" in session.card.html
    assert "The diagrams and downloads on the right are those of the last scene solved" in session.card.html
    assert session.stale.object == STALE


def _open_figures() -> set[int]:
    """The figures open in matplotlib's registry (pyplot's), by identity: a figure's number is reused once closed."""
    from matplotlib._pylab_helpers import Gcf

    return {id(manager.canvas.figure) for manager in Gcf.get_all_fig_managers()}


def test_a_closed_session_leaves_no_figure_open(session):
    """A server serves one visitor after another: each session's figures close with it. Its answer's diagrams
    (open while shown: the downloads render them) stayed in matplotlib's registry for as long as the server
    ran, some 7 figures a visit ("More than 20 figures have been opened" in the terminal after three)."""
    before = _open_figures()
    asyncio.run(session._refresh(edited("0.04"), solve=None))
    assert len(_open_figures() - before) >= 5  # the answer's diagrams
    session.close()
    session.drawer.shutdown(wait=True)  # the closing runs in the drawing worker, after any diagram it draws
    assert _open_figures() <= before


def test_a_session_closed_while_a_diagram_is_drawn_drops_and_closes_that_drawing(session, monkeypatch):
    """The visitor leaves while an edit's first diagram is being drawn: the drawing is not finished (nothing more
    is drawn for a closed page) and every figure made for it is closed, as is the answer shown before."""
    from flyopt.app import model

    before = _open_figures()
    asyncio.run(session._refresh(edited("0.04"), solve=None))
    held, release = threading.Event(), threading.Event()
    svg = model.figure_svg
    drawn: list[str] = []

    def holding(block):
        held.set()
        assert release.wait(PATIENCE), "the test did not release the diagram"
        drawn.append(block.key)
        return svg(block)

    monkeypatch.setattr(model, "figure_svg", holding)
    shown = _open_figures() - before  # 0.04's diagrams

    async def edit_then_leave() -> None:
        one = asyncio.ensure_future(session._refresh(edited("0.02"), solve=None))
        await until(held.is_set, "the edit's first diagram")
        assert _open_figures() - before - shown  # the edit's figures, made and being drawn
        session.close()
        release.set()
        await one

    asyncio.run(edit_then_leave())
    session.drawer.shutdown(wait=True)
    assert len(drawn) == 1  # the one being drawn when the visitor left
    assert session.answer is None
    assert _open_figures() <= before  # neither the edit's nor the answer's shown before (0.04's)


def test_a_diagram_that_fails_to_draw_is_said_on_the_card_and_its_figures_closed(session, monkeypatch):
    """A diagram whose drawing raises (a plotting defect) left the card saying "drawing the diagrams…" and the
    spinner turning for good, with the edit's figures open; the card now says so, the spinner stops, Solve is
    offered, and the figures made for that drawing are closed. The next edit draws as usual."""
    from flyopt.app import model

    before = _open_figures()
    svg = model.figure_svg

    def failing(block):
        if block.key == "energy":
            raise ValueError("a plotting defect")
        return svg(block)

    monkeypatch.setattr(model, "figure_svg", failing)
    asyncio.run(session._refresh(edited("0.04"), solve=None))
    session.drawer.submit(lambda: None).result()  # the closing queued in the drawing worker is done
    assert "The diagrams could not be drawn: ValueError: a plotting defect" in session.card.html
    assert "0.04 (1/25)" in session.card.html and "drawing the diagrams" not in session.card.html
    assert not session.busy.value and not session.solve_button.disabled
    assert _open_figures() <= before
    monkeypatch.setattr(model, "figure_svg", svg)
    asyncio.run(session._refresh(edited("0.02"), solve=None))
    assert "0.02 (1/50)" in session.card.html and "could not be drawn" not in session.card.html
    assert len(_open_figures() - before) >= 5  # the answer's diagrams, drawn


def test_a_sweep_of_names_alone_replaces_the_last_sweeps_plot_with_a_word(session):
    """A sweep that varied δ and the material, then one that varied the material alone: the first one's diagram
    stayed beside the second one's table (its x is no number, and the plot was not drawn)."""
    import flyopt
    from flyopt.app import sweeps

    scene = flyopt.load(ROOT / "problems" / "shear-press.toml")
    tab = session.sweeps_tab
    tab.scene = scene
    first = flyopt.sweep(scene, {"delta": "0.02,0.05", "material": "cast_iron,cast_steel"})
    tab._show(sweeps.Run(first, None, True, {"seconds": 0.1, "mode": "serial"}))
    assert tab.x.value == "delta" and tab.by.value == "material" and "<svg" in tab.plot.svg
    second = flyopt.sweep(scene, {"material": "cast_iron,cast_steel"})
    tab._show(sweeps.Run(second, None, True, {"seconds": 0.1, "mode": "serial"}))
    assert tab.x.value is None and "<svg" not in tab.plot.svg and "varies no number to draw" in tab.plot.svg
