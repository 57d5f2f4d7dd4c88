"""A document's figures drawn on every core this process may run on: forked workers.

Drawing a report's figures (matplotlib's layout and a vector renderer: :func:`flyopt.report.html.svg_of` for
the HTML page, :func:`flyopt.report.pdf_figure.record` for the PDF's pages) is most of the time
``flyopt report`` takes after its one solve (README "Benchmarks", issue 26), and the figures are independent
of each other. :func:`draw_each` draws them in this process and in worker processes forked from it once the
figures are made: a worker inherits them (and matplotlib, already imported) without a copy, takes the next
figure still to draw from a shared queue (a pipe of figure numbers, the heaviest first by an estimate:
:func:`_cost`), and sends each drawing back pickled (an SVG's text, a PDF figure's canvas operations). A
figure's drawing is the same whichever process draws it: neither way writes anything that depends on the
process (an SVG's ids are made from the prefix, its glyphs' from the font; a PDF figure names its fonts by
their files, registered with reportlab where the page is laid out).

Workers are forked only where fork is safe and can pay: a process running a single thread (as
:mod:`flyopt.studies.processes` decides; the app's server, with its threads, draws in its own process) that
may run on more than one CPU (:func:`cpu_count`), with more than one figure. A
worker that fails or dies leaves its figures to this process, which draws them as it would have alone (an
error is then raised here, as without workers).
"""

from __future__ import annotations

import os
import pickle
import struct
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, NoReturn, TypeVar

if TYPE_CHECKING:
    from matplotlib.figure import Figure as MplFigure

__all__ = ["Draw", "cpu_count", "draw_each", "drawings", "workers_for"]

#: One figure's number in the queue: 2 bytes, so that a read of one is whole (a pipe's reads of at most
#: PIPE_BUF bytes are atomic) and a document may have up to 65535 figures.
_ENTRY = struct.Struct("<H")


def workers_for(count: int) -> int:
    """How many worker processes to fork for ``count`` figures: one per further CPU this process may run on,
    at most one per figure beyond this process's own; none in a process running more than one thread or
    without fork."""
    if count < 2 or not hasattr(os, "fork") or threading.active_count() != 1:
        return 0
    return max(0, min(cpu_count(), count) - 1)


def cpu_count() -> int:
    """CPUs this process may run on: :func:`flyopt.studies.processes.cpu_count`'s rule (a test holds the two
    together), not imported from there, as that module brings pandas (some 0.4 s of a report that needs none)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


#: What one figure's drawing is: an SVG's text, a PDF figure's recorded canvas operations (picklable).
T = TypeVar("T")

#: How a figure is drawn, given the prefix of its ids: :func:`flyopt.report.html.svg_of`,
#: :func:`flyopt.report.pdf_figure.record` (passed in by their modules, which this one does not import).
Draw = Callable[["MplFigure", str], T]


def draw_each(figures: Sequence[tuple[MplFigure, str]], draw: Draw[T], workers: int | None = None) -> list[T]:
    """``draw(figure, prefix)`` of each ``(figure, prefix)``, in their order.

    Parameters
    ----------
    figures : sequence of (Figure, str)
        The figures and the prefix of each one's ids.
    draw : callable
        How one figure is drawn (:func:`flyopt.report.html.svg_of`, :func:`flyopt.report.pdf_figure.record`);
        what it returns is pickled where a worker drew it.
    workers : int, optional
        Worker processes to fork (default :func:`workers_for`; 0 draws every figure in this process).
    """
    count = len(figures)
    if workers is None:
        workers = workers_for(count)
    drawn: dict[int, T] = {}
    if workers > 0:
        drawn = _in_workers(figures, draw, workers)
    return [drawn[k] if k in drawn else draw(*figures[k]) for k in range(count)]


def drawings(blocks: Sequence[Any], draw: Draw[T]) -> dict[int, T]:
    """{id of a block: its figure's drawing} of a document's drawn figure blocks
    (:meth:`flyopt.report.document.Document.drawn`), each drawn by :func:`draw_each` with the prefix of its
    number in the document's order ("f1-", "f2-", ...): what a renderer places where it meets the block."""
    made = draw_each([(block.figure, f"f{number}-") for number, block in enumerate(blocks, start=1)], draw)
    return dict(zip(map(id, blocks), made))


def _cost(figure: MplFigure) -> int:
    """An estimate of the time ``figure`` takes to draw: its axes and their artists (texts and ticks are laid
    out per axes, lines and patches drawn per artist)."""
    return sum(10 + len(ax.get_children()) for ax in figure.axes)


def _in_workers(figures: Sequence[tuple[MplFigure, str]], draw: Draw[T], workers: int) -> dict[int, T]:
    """{number: drawing} of the figures drawn by this process and ``workers`` forked ones, taking turns at a queue;
    a figure whose worker failed is missing."""
    order = sorted(range(len(figures)), key=lambda k: -_cost(figures[k][0]))
    queue_read, queue_write = os.pipe()
    os.write(queue_write, b"".join(_ENTRY.pack(k) for k in order))  # a few bytes: within the pipe's buffer
    os.close(queue_write)  # the queue ends where its numbers do
    children: list[tuple[int, int]] = []  # (pid, the read end of its answers)
    drawn: dict[int, T] = {}
    try:
        for _ in range(workers):
            answer_read, answer_write = os.pipe()
            try:
                pid = os.fork()
            except OSError:  # no process to be had: the figures left are this process's
                os.close(answer_read)
                os.close(answer_write)
                break
            if pid == 0:  # pragma: no cover - the worker (its coverage is not collected)
                os.close(answer_read)
                _work(figures, draw, queue_read, answer_write)
            os.close(answer_write)
            children.append((pid, answer_read))
        for k in _taken(queue_read):
            drawn[k] = draw(*figures[k])
    finally:
        os.close(queue_read)
        for pid, answer_read in children:
            drawn.update(_answers(answer_read))
            os.waitpid(pid, 0)
    return drawn


def _taken(queue_read: int) -> Iterator[int]:
    """The figures' numbers taken from the queue, one at a time, until it is empty."""
    while True:
        entry = os.read(queue_read, _ENTRY.size)
        if len(entry) < _ENTRY.size:
            return
        yield _ENTRY.unpack(entry)[0]


def _work(
    figures: Sequence[tuple[MplFigure, str]], draw: Draw[T], queue_read: int, answer_write: int
) -> NoReturn:  # pragma: no cover
    """The worker: draw the figures it takes from the queue, send {number: drawing} of those drawn (pickled) and
    exit without running the parent's exit handlers. A figure that fails is not sent (the parent draws it)."""
    status = 1
    try:
        drawn: dict[int, T] = {}
        try:
            for k in _taken(queue_read):
                drawn[k] = draw(*figures[k])
        except BaseException:  # the figures not drawn are the parent's to draw, and to raise about
            pass
        with os.fdopen(answer_write, "wb") as answers:
            answers.write(pickle.dumps(drawn, protocol=pickle.HIGHEST_PROTOCOL))
        status = 0
    finally:
        os._exit(status)


def _answers(answer_read: int) -> dict[int, Any]:
    """What a worker sent: {number: drawing}; empty if it sent nothing whole (it died)."""
    with os.fdopen(answer_read, "rb") as answers:
        data = answers.read()
    try:
        drawn = pickle.loads(data)
    except Exception:  # a worker killed while it wrote
        return {}
    return drawn if isinstance(drawn, dict) else {}
