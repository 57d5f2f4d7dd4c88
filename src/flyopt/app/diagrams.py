"""An answer's diagrams drawn one at a time, those the visitor has in view first (docs/app.md "Latency").

The page shows the card of an edit first (:func:`flyopt.app.model.numbers`), then its diagrams, each sent as
soon as it is drawn. Drawing them all takes most of the time from an edit to its last diagram (the report's
document with its figures, then each figure's SVG: :mod:`flyopt.report.plots`), and the diagram an engineer
is looking at is one of them: :class:`Diagrams` draws those in view first, from a document that makes their
figures alone (:func:`flyopt.report.builder.build` with their keys), and the others after, from a second
document that makes the rest; the answer keeps one document, the second with the first one's figures in their
places (what the downloads render). Nothing is solved again: both documents are built from the answer's one
solve.

The page tells which diagrams are in view (the fraction of each, from the browser's IntersectionObserver:
:mod:`flyopt.app.hover`); with none in view (the first answer, or a page scrolled past its diagrams) the
diagrams are drawn from one document in their order on the page.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from flyopt.app import model

if TYPE_CHECKING:
    from flyopt.report.document import Document


def drawing_order(in_view: Mapping[str, float]) -> list[str]:
    """The keys of the diagrams in view, the most in view first (a tie in the page's order, as the mapping
    gives them); a diagram with no part in view is left out."""
    keys = [key for key, fraction in in_view.items() if fraction > 0.0]
    return sorted(keys, key=lambda key: -in_view[key])  # stable: ties keep the page's order


class Diagrams:
    """``answer``'s diagrams, drawn one per :meth:`step`, those in view first.

    Call :meth:`step` until it returns None (each call draws one diagram under the drawing lock: the page runs
    it in its drawing worker and checks between two calls whether a newer edit came), then :meth:`document`
    for the answer's document with every figure; or :meth:`close` to drop what was made.
    """

    def __init__(self, answer: model.Answer, in_view: Mapping[str, float] | None = None) -> None:
        self.answer = answer
        self.first = drawing_order(in_view or {})
        self.documents: list[Document] = []
        self.queue: list[tuple[int, Any]] = []  # (index on the page, Figure block) still to draw
        self.shown: dict[int, model.Shown] = {}
        self.order: list[int] = []  # the indices in the order drawn
        self._passes: list[list[str] | None] = [self.first] if self.first else [None]
        self._built = 0

    def step(self) -> tuple[int, model.Shown] | None:
        """Draw the next diagram: (its index among the document's figures, as the page shows it), or None
        when every diagram is drawn."""
        with model.drawing():
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
        document = model.draw(self.answer, keys)
        self.documents.append(document)
        blocks = model.figure_blocks(document)
        if keys is None:
            self.queue = list(enumerate(blocks))
            return
        found = [(index, block) for index, block in enumerate(blocks) if block.key in keys]
        found.sort(key=lambda pair: keys.index(pair[1].key))
        self.queue = found
        if keys is not self.first:  # the rest, after those in view
            return
        rest = [block.key for block in blocks if block.key not in keys]
        if not found:  # none of the keys in view is a diagram of this answer: every one, in the page's order
            self.documents.pop().close()
            self._passes.append(None)
        elif rest:
            self._passes.append(rest)

    def figures(self) -> list[model.Shown]:
        """Every diagram drawn, in the page's order."""
        return [self.shown[index] for index in sorted(self.shown)]

    def document(self) -> Document:
        """The answer's document with every figure: the last built, each figure drawn first in its place (the
        documents are built from the same solve: the same sections, blocks and keys)."""
        from flyopt.errors import BrokenInvariant

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
