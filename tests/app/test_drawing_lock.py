"""The app draws from worker threads; matplotlib is not: every draw of the app holds the report's one drawing lock,
and pyplot is reached through :mod:`flyopt.report.plots.standard` only (which makes and closes figures under it)."""

from __future__ import annotations

import re
import threading
from pathlib import Path
from types import SimpleNamespace

import pytest

from flyopt.report.plots import standard

SRC = Path(__file__).resolve().parents[2] / "src" / "flyopt"


def held_elsewhere() -> bool:
    """Whether some thread holds the lock: another thread cannot take it (an RLock is the holder's alone)."""
    taken: list[bool] = []

    def attempt() -> None:
        got = standard.LOCK.acquire(blocking=False)
        taken.append(got)
        if got:
            standard.LOCK.release()

    helper = threading.Thread(target=attempt)
    helper.start()
    helper.join()
    return not taken[0]


def test_pyplot_is_reached_through_the_standard_only():
    """A pyplot call elsewhere would make or close a figure outside the lock."""
    files = [*sorted((SRC / "app").glob("*.py")), *sorted((SRC / "report" / "plots").glob("*.py"))]
    offenders = [
        f"{path.relative_to(SRC)}:{number}"
        for path in files
        if path.name != "standard.py"
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if re.search(r"\bpyplot\b|\bplt\.", line) and "standard.pyplot" not in line
    ]
    assert offenders == []
    assert (SRC / "report" / "document.py").read_text(encoding="utf-8").count("plt.close") == 1  # the app wraps it


@pytest.mark.parametrize("call", ["figure_svg", "draw", "close"])
def test_the_apps_draws_hold_the_lock(monkeypatch, call):
    from flyopt.app import model
    from flyopt.report import builder, html
    from flyopt.report.plots import readout

    seen: list[bool] = []

    def record(*_args, **_kwargs):
        seen.append(held_elsewhere())
        return ""

    def read(*_args, **_kwargs):
        seen.append(held_elsewhere())
        return {"axes": []}

    monkeypatch.setattr(html, "svg_of", record)
    monkeypatch.setattr(builder, "build", record)
    monkeypatch.setattr(readout, "record", read)  # the read-outs are read off the figure as it was drawn
    assert not held_elsewhere()
    if call == "figure_svg":
        model.figure_svg(SimpleNamespace(figure=object(), key="k", caption="c", note=""))
    elif call == "draw":
        model.draw(SimpleNamespace(drawn=False, inputs=None, units="si"))
    else:
        model.close(SimpleNamespace(close=lambda: record()))
    assert seen == ([True, True] if call == "figure_svg" else [True])
    assert not held_elsewhere()


def test_the_tabs_draws_hold_the_lock(monkeypatch):
    """The sweep plot and the materials' chart are drawn in the tabs' worker threads."""
    import pandas as pd

    from flyopt.app import materials, sweeps
    from flyopt.report import html

    seen: list[bool] = []

    def record(*_args, **_kwargs):
        seen.append(held_elsewhere())
        return ""

    monkeypatch.setattr(html, "svg_of", record)
    frame = pd.DataFrame({"point": [0, 1], "speed": [100.0, 200.0], "mass": [3.0, 2.0], "status": "designed"})
    frame.attrs["flyopt"] = {"varied": ["speed"]}
    try:
        sweeps.plot_svg(frame, "speed", "mass")
    except ValueError:  # the plot refused the small frame: then it was not drawn
        pytest.fail("the sweep plot did not draw a two-point sweep")
    table = pd.DataFrame(
        {"material": ["a", "b"], "status": "designed", "mass": [1.0, 2.0], "d_outer": [0.3, 0.4], "cost": [1.0, 2.0]}
    )
    materials.chart_svg(table, "engineering")
    assert seen == [True, True]
