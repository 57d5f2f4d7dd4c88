"""Drawing figures fast without changing them (issue 26, 29): the figures drawn in forked workers are the
SVGs this process draws (flyopt.report.figure_cores), the texts remembered from figure to figure draw as
matplotlib's own TextToPath draws them (flyopt.report.html.remembered_text_to_path), and the collector's pause
leaves it as it was (flyopt.report.plots.standard.collector_paused).

Every reference is drawn by another path: the figures in this process alone, the texts with matplotlib's
TextToPath methods put back.
"""

from __future__ import annotations

import gc
import os
import threading

import numpy as np
import pytest
from matplotlib.textpath import TextToPath

from flyopt.report import figure_cores, html
from flyopt.report.plots import standard

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="workers are forked (POSIX)")


@pytest.fixture(autouse=True)
def figures_drawn_in_the_tests_process():
    """The rule of how many workers to fork is what this module tests: tests/conftest.py's fixture of this name,
    which gives none under pytest-xdist, does not apply here."""


@pytest.fixture(autouse=True)
def _closed():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def figures():
    """Three different figures: a dense curve with a legend, two axes with texts out of ASCII, a bar chart."""
    ax, _own = standard.axes(None, figsize=(6, 3.5))
    x = np.linspace(0.0, 360.0, 721)
    ax.plot(x, np.sin(np.radians(x)) * 1600.0, label="M_r")
    ax.fill_between(x, 0.0, np.cos(np.radians(x)) * 400.0, alpha=0.3, label="surplus")
    ax.set(xlabel="crank angle θ [°]", ylabel="torque [N·m]", title="turning moment")
    ax.legend()
    first = standard.figure_of(ax)
    second = standard.new_figure(figsize=(6, 4), layout="constrained")
    top, bottom = second.subplots(2, 1)
    top.plot([1.0, 2.0, 3.0], [2.0, 1.0, 3.0], "o-")
    top.set_ylabel("ΔE [kJ]")
    bottom.semilogy([1.0, 10.0, 100.0], [5.0, 50.0, 500.0])
    bottom.set_xlabel("δ – fluctuation ²")
    third = standard.new_figure(figsize=(4, 3), layout="constrained")
    axis = third.add_subplot()
    axis.bar(["rim", "web", "hub"], [12.0, 3.5, 2.0], color=["C0", "C1", "C2"])
    axis.set_title("mass [kg]")
    return [(first, "a-"), (second, "b-"), (third, "c-")]


def test_the_figures_drawn_in_workers_are_those_drawn_here():
    here = figure_cores.draw_each(figures(), html.svg_of, workers=0)
    import matplotlib.pyplot as plt

    plt.close("all")
    there = figure_cores.draw_each(figures(), html.svg_of, workers=2)
    assert len(there) == 3
    assert [len(svg) for svg in there] == [len(svg) for svg in here]  # in their order
    assert there == here
    assert all(svg.startswith("<svg") for svg in there)


def test_a_pdfs_figures_drawn_in_workers_play_onto_the_page_as_those_drawn_here(tmp_path):
    """The PDF's figures (flyopt.report.pdf_figure.record, as flyopt.report.pdf.render draws them) drawn in
    forked workers and pickled back play onto a page as those drawn in this process do: the same page, byte for
    byte (reportlab's invariant mode: no date, no random id), an image among them."""
    import matplotlib.pyplot as plt
    from reportlab.pdfgen.canvas import Canvas

    from flyopt.report import pdf_figure

    def page(name, workers):
        made = figures()
        image = standard.new_figure(figsize=(3, 3), layout="constrained")
        image.add_subplot().imshow(np.arange(12.0).reshape(3, 4))
        drawings = figure_cores.draw_each([*made, (image, "d-")], pdf_figure.record, workers=workers)
        plt.close("all")
        canvas = Canvas(str(tmp_path / name), invariant=1)
        for k, drawing in enumerate(drawings):
            pdf_figure.draw(drawing, canvas, 20, 20 + 190 * k, 0.4)
        canvas.save()
        return drawings, (tmp_path / name).read_bytes()

    here, page_here = page("here.pdf", 0)
    there, page_there = page("there.pdf", 2)
    assert [len(d.calls) for d in there] == [len(d.calls) for d in here]  # in their order
    assert [name for d in here for name, _args in d.calls].count("image") == 1
    assert page_there == page_here
    assert b"/Subtype /Image" in page_here


PARENT = os.getpid()


@pytest.mark.parametrize("how", ["fails", "dies"])
def test_a_figure_a_worker_cannot_draw_is_drawn_here(how):
    drawable = standard.figure_class()

    class HereOnly(drawable):  # draws in the test's process only
        def draw(self, renderer):
            if os.getpid() != PARENT:
                if how == "dies":
                    os._exit(3)
                raise RuntimeError("not in a worker")
            super().draw(renderer)

    def made():
        out = []
        for k in range(3):
            figure = HereOnly(figsize=(3, 2), layout="constrained")
            figure.add_subplot().plot([0.0, 1.0], [k, 2.0 * k + 1.0])
            out.append((figure, f"h{k}-"))
        return out

    here = figure_cores.draw_each(made(), html.svg_of, workers=0)
    assert figure_cores.draw_each(made(), html.svg_of, workers=1) == here


def test_no_worker_is_forked_beside_threads_or_for_one_figure():
    assert figure_cores.workers_for(1) == 0
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert figure_cores.workers_for(8) == 0  # fork beside threads: not (flyopt.studies.processes' rule)
    finally:
        stop.set()
        other.join()


def test_the_cpus_counted_are_those_the_sweeps_count():
    from flyopt.studies.processes import cpu_count

    assert figure_cores.cpu_count() == cpu_count()
    if hasattr(os, "sched_setaffinity"):
        allowed = os.sched_getaffinity(0)
        try:
            os.sched_setaffinity(0, {min(allowed)})
            assert figure_cores.cpu_count() == cpu_count() == 1
            assert figure_cores.workers_for(8) == 0  # one CPU: no worker
        finally:
            os.sched_setaffinity(0, allowed)


def test_texts_remembered_draw_as_matplotlib_draws_them(monkeypatch):
    remembered = html.remembered_text_to_path()
    figure_cores.draw_each(figures()[1:], html.svg_of, workers=0)  # the texts remembered
    assert remembered._glyphs and remembered._measures
    again = figure_cores.draw_each(figures()[1:], html.svg_of, workers=0)  # drawn from what was remembered
    kind = type(remembered)
    monkeypatch.setattr(kind, "get_glyphs_with_font", TextToPath.get_glyphs_with_font)
    monkeypatch.setattr(kind, "get_text_width_height_descent", TextToPath.get_text_width_height_descent)
    assert (
        figure_cores.draw_each(figures()[1:], html.svg_of, workers=0) == again
    )  # matplotlib's own, nothing remembered


def test_the_collector_is_paused_and_left_as_it_was():
    was = gc.isenabled()
    try:
        gc.enable()
        with standard.collector_paused():
            assert not gc.isenabled()
            with standard.collector_paused():
                assert not gc.isenabled()
            assert not gc.isenabled()  # the inner pause leaves it to the outer one
        assert gc.isenabled()
        gc.disable()
        with standard.collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()  # paused by someone else: still
    finally:
        (gc.enable if was else gc.disable)()


def test_the_pdf_figures_remembered_measures_draw_as_matplotlib_measures(monkeypatch, tmp_path):
    from matplotlib.backend_bases import RendererBase
    from reportlab.pdfgen.canvas import Canvas

    from flyopt.report import pdf_figure

    def page(name):
        canvas = Canvas(str(tmp_path / name), invariant=1)  # no date, no random id: the same figure, the same bytes
        figure, _prefix = figures()[1]  # two axes, texts out of ASCII
        pdf_figure.draw(figure, canvas, 20, 300, 0.8)
        canvas.save()
        return (tmp_path / name).read_bytes()

    page("warm.pdf")
    assert pdf_figure._MEASURES
    remembered = page("remembered.pdf")
    monkeypatch.setattr(
        pdf_figure.CanvasRenderer, "get_text_width_height_descent", RendererBase.get_text_width_height_descent
    )
    assert page("matplotlib.pdf") == remembered
