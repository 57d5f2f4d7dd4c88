"""An answer's diagrams drawn one at a time, those the visitor has in view first, those the page shows already
kept (docs/app.md "Latency").

The page shows the card of an edit first (:func:`flyopt.app.model.numbers`), then its diagrams, each sent as
soon as it is drawn. Drawing them all takes most of the time from an edit to its last diagram (the report's
document with its figures, then each figure's SVG: :mod:`flyopt.report.plots`), and the diagram an engineer
is looking at is one of them: :class:`Diagrams` draws those in view first, from a document that makes their
figures alone (:func:`flyopt.report.builder.build` with their keys), and the others after, from a second
document that makes the rest; the answer keeps one document, the second with the first one's figures in their
places (what the downloads render). Nothing is solved again: both documents are built from the answer's one
solve.

A diagram the edit does not change is not drawn at all: each diagram split into what it draws and how
(:class:`flyopt.report.plots.digest.Plot`) has the digest of its data (read in the drawing worker, once for
every document of the answer: :func:`flyopt.app.model.digests`), and where the page shows, in that diagram's
place, one of the same key and digest, it keeps it (a δ edit leaves the turning-moment and energy diagrams as
they were). The same digest draws the same SVG to the byte; the answer's document leaves that figure undrawn,
and a report downloaded draws its figures afresh (:func:`flyopt.app.model.report_bytes`).

The page tells which diagrams are in view (the fraction of each, from the browser's IntersectionObserver:
:mod:`flyopt.app.hover`); with none in view (the first answer, or a page scrolled past its diagrams) the
diagrams are drawn from one document in their order on the page.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from flyopt.app import model

if TYPE_CHECKING:
    from flyopt.report.document import Document


def drawing_order(in_view: Mapping[str, float]) -> list[str]:
    """The keys of the diagrams in view, the most in view first (a tie in the page's order, as the mapping
    gives them); a diagram with no part in view is left out."""
    keys = [key for key, fraction in in_view.items() if fraction > 0.0]
    return sorted(keys, key=lambda key: -in_view[key])  # stable: ties keep the page's order


def kept(blocks: Sequence[Any], showing: Sequence[model.Shown]) -> dict[int, model.Shown]:
    """The diagrams of an answer (``blocks``: its document's Figure blocks, with their digests,
    :func:`flyopt.app.model.digests`) the page shows already, by their index among its figures: where the page
    shows, in that place, a diagram of the same key and the same digest of what it draws (``showing``: what each
    place shows), with this answer's caption."""
    from flyopt.report.document import plain

    found: dict[int, model.Shown] = {}
    for index, block in enumerate(blocks):
        shown = showing[index] if index < len(showing) else None
        if block.digest and shown is not None and shown.svg and (shown.key, shown.digest) == (block.key, block.digest):
            found[index] = shown._replace(caption=plain(block.caption))
    return found


class Diagrams:
    """``answer``'s diagrams, drawn one per :meth:`step`, those in view first, those the page shows kept.

    Call :meth:`step` until it returns None (each call draws one diagram under the drawing lock: the page runs
    it in its drawing worker and checks between two calls whether a newer edit came), then :meth:`document`
    for the answer's document with every figure drawn (but those kept); or :meth:`close` to drop what was made.
    ``showing``: what the page shows in each place (:func:`kept`). The first step reads the split diagrams'
    data and their digests (:func:`flyopt.app.model.digests`: in the drawing worker, after the card), once for
    every document of the answer.
    """

    def __init__(
        self,
        answer: model.Answer,
        in_view: Mapping[str, float] | None = None,
        showing: Sequence[model.Shown] = (),
    ) -> None:
        self.answer = answer
        self.in_view = dict(in_view or {})
        self.showing = list(showing)
        self.read: dict[str, Any] = {}  # the split diagrams' data, read once for every document of the answer
        self.shown: dict[int, model.Shown] = {}
        self.todo: list[str] = []  # the keys to draw, in the page's order (known at the first step)
        self.first: list[str] = []  # those in view, the most in view first
        self.documents: list[Document] = []
        self.queue: list[tuple[int, Any]] = []  # (index on the page, Figure block) still to draw
        self.order: list[int] = []  # the indices in the order drawn
        self._passes: list[list[str] | None] | None = None  # None: not planned yet (the first step plans)
        self._built = 0

    def _plan(self) -> list[list[str] | None]:
        """The documents to build, by their figures' keys (None: all): those in view, then the rest, but those the
        page keeps (:func:`kept`, of the answer's digests; none kept where the page shows nothing)."""
        keys = [block.key for block in model.figure_blocks(self.answer.document)]
        candidates = {shown.key for shown in self.showing if shown.digest and shown.svg}  # the only ones to keep
        if candidates:
            self.shown = kept(model.figure_blocks(model.digests(self.answer, self.read, candidates)), self.showing)
        self.todo = [key for index, key in enumerate(keys) if index not in self.shown]
        self.first = [key for key in drawing_order(self.in_view) if key in self.todo]
        if self.first:
            return [self.first]
        everything = None if len(self.todo) == len(keys) else self.todo  # None: every figure (no list to keep)
        return [everything] if self.todo else []

    def step(self) -> tuple[int, model.Shown] | None:
        """Draw the next diagram: (its index among the document's figures, as the page shows it), or None
        when every diagram is drawn."""
        with model.drawing():
            if self._passes is None:
                self._passes = self._plan()
            while not self.queue:
                if self._built == len(self._passes):
                    return None
                self._build(self._passes[self._built])
                self._built += 1
            index, block = self.queue.pop(0)
            shown = model.figure_svg(block)
        self.shown[index] = shown
        self.order.append(index)
        return index, shown

    def _build(self, keys: list[str] | None) -> None:
        """Build the document of ``keys``' figures (None: all) and queue them, ``keys``' order first."""
        document = model.draw(self.answer, keys, self.read)
        self.documents.append(document)
        blocks = model.figure_blocks(document)
        if keys is None:
            self.queue = list(enumerate(blocks))
            return
        found = [(index, block) for index, block in enumerate(blocks) if block.key in keys]
        found.sort(key=lambda pair: keys.index(pair[1].key))
        self.queue = found
        if keys is self.first and self._passes is not None:  # the rest, after those in view
            rest = [key for key in self.todo if key not in keys]
            if rest:
                self._passes.append(rest)

    def figures(self) -> list[model.Shown]:
        """Every diagram drawn or kept, in the page's order."""
        return [self.shown[index] for index in sorted(self.shown)]

    def document(self) -> Document:
        """The answer's document with every figure drawn: the last built, each figure drawn first in its place
        (the documents are built from the same solve: the same sections, blocks and keys); the answer's own
        document of numbers where every diagram was kept. A kept diagram's figure is left undrawn (a report
        draws its figures afresh, :func:`flyopt.app.model.report_bytes`)."""
        from flyopt.errors import BrokenInvariant

        if not self.documents:
            return self.answer.document
        *earlier, last = self.documents
        blocks = model.figure_blocks(last)
        for document in earlier:
            for index, block in enumerate(model.figure_blocks(document)):
                if block.key in self.first:
                    if blocks[index].key != block.key:
                        raise BrokenInvariant(f"the app's two documents of one answer differ at figure {index}")
                    _replace(last, blocks[index], block)
        self.documents = [last]
        return last

    def close(self) -> None:
        """Close every document made (under the drawing lock)."""
        for document in self.documents:
            model.close(document)
        self.documents = []


def _replace(document: Document, old: Any, new: Any) -> None:
    """Put the block ``new`` in the place of ``old`` in ``document``."""
    for section in document.sections:
        for k, block in enumerate(section.blocks):
            if block is old:
                section.blocks[k] = new
                return
