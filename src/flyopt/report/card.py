"""The answer card: what a solve answers, as a few rows under the scene's title, the one card the app and a
notebook show.

The card is the report's answer section read out (section 1, "Summary": its
first paragraph the verdict, its facts the rows), so that the card, the report
and the text say the same thing: :func:`card_of` reads it from a built
:class:`~flyopt.report.document.Document` (the app, which builds the report
anyway), :func:`solution_card` builds that one section alone from a
:class:`~flyopt.pipeline.Solution` by the report's own builder
(:class:`flyopt.report.builder.summary.Summary`; no diagram is drawn) and
:func:`analysis_card` from an :class:`~flyopt.analysis.Analysis` (the cycle's
answer without a design). :func:`card_html` writes every card, every string
escaped. A notebook's ``Solution._repr_html_`` and ``Analysis._repr_html_``
are these, registered through :mod:`flyopt.views` by
:mod:`flyopt.report.notebook`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from html import escape
from typing import TYPE_CHECKING, cast

from flyopt.report import display
from flyopt.report.characters import visible
from flyopt.report.document import Document, Facts, Paragraph, Quantity, plain

if TYPE_CHECKING:
    from flyopt.analysis import Analysis
    from flyopt.io.scene import Scene
    from flyopt.pipeline import Solution

__all__ = ["GOOD", "Card", "Row", "analysis_card", "card_html", "card_of", "solution_card"]

#: The statuses a card shows as an answer that holds (any other, or a flagged one, as one that does not).
GOOD = ("designed", "not_needed", "analysed", "checked", "calculated")


@dataclass(frozen=True)
class Row:
    """One line of the answer card: a label and its value as the report shows it.

    ``name``/``si`` are those of the first number in the value (its JSON field and SI value), for checks.
    """

    label: str
    value: str
    name: str | None = None
    si: float | None = None
    markup: str = ""  # the label with the report's ``_{sub}`` and ``^{sup}`` markup, for the HTML


@dataclass(frozen=True)
class Card:
    """The answer card: the scene's title, the status, the verdict in one sentence, and the rows."""

    title: str
    status: str
    verdict: str
    rows: tuple[Row, ...]
    warned: bool = False  # the report's answer warns (a wheel too thin to make as sized, a book rim over its allowable)

    @property
    def good(self) -> bool:
        """Whether the answer holds (a design, no flywheel needed, an analysis, a flywheel given that holds, a
        calculation) and the report's answer section gives no warning (a wheel too thin to be made as sized, the
        courses' rim over its allowable at ω_max)."""
        return self.status in GOOD and not self.warned


def card_of(document: Document) -> Card:
    """The card of a built report: its first section's first paragraph is the verdict, its facts the rows (the
    report's answer section, of a solution or of a calculation alike)."""
    rows: list[Row] = []
    verdict, warned = "", False
    section = document.sections[0] if document.sections else None
    for block in section.blocks if section is not None else ():
        if isinstance(block, Paragraph):
            verdict = verdict or plain(block.text)
            warned = warned or block.kind == "warning"  # any warning of the answer section, as the report shows it
        if isinstance(block, Facts):
            for label, value in block.rows:
                parts = value if isinstance(value, tuple) else (value,)
                first = next((p for p in parts if isinstance(p, Quantity)), None)
                markup = label if isinstance(label, str) else ""
                rows.append(
                    Row(
                        plain(label),
                        plain(value),
                        first.name if first else None,
                        first.si if first else None,
                        markup,
                    )
                )
    return Card(document.title, document.status, verdict, tuple(rows), warned)


def solution_card(solution: Solution, units: str = display.DEFAULT, digits: int = display.DEFAULT_DIGITS) -> Card:
    """The card of a solution: the report's answer section built alone (:class:`~flyopt.report.builder.summary.Summary`,
    the builder of the report's section 1), read by :func:`card_of`."""
    from flyopt.report.builder.inputs import ReportInputs
    from flyopt.report.builder.summary import Summary

    display.check_system(units)
    display.check_digits(digits)
    inputs = ReportInputs("", "", (), solution.scene, solution)
    builder = Summary(inputs, units, digits)
    builder.summary()
    return card_of(Document(solution.analysis.title, (), builder.sections, units, builder.document_status()))


def analysis_card(analysis: Analysis, units: str = display.DEFAULT, digits: int = display.DEFAULT_DIGITS) -> Card:
    """The card of a cycle's analysis (``flyopt.analyse``): the solution with no design, status "analysed"; the
    answer section reads nothing of the scene but its analysis."""
    from flyopt.pipeline import Solution

    return solution_card(Solution(cast("Scene", None), analysis), units, digits)


def card_html(card: Card, busy: str = "") -> str:
    """The card as HTML (``<div class="card ...">``: the title and status, the verdict, a table of the rows), every
    string escaped; ``busy`` a note after the status ("solving…")."""
    rows = "".join(
        f'<tr><th style="text-align:left">{_marked(r.markup or r.label)}</th>'
        f'<td style="text-align:left" data-name="{escape(r.name or "")}">{escape(visible(r.value))}</td></tr>'
        for r in card.rows
    )
    return (
        f'<div class="card flyopt-answer {"ok" if card.good else "bad"}"><div class="status">'
        f"<b>{escape(visible(card.title))}</b>: status <b>{escape(card.status.replace('_', ' '))}</b>"
        f"{' — ' + escape(busy) if busy else ''}</div><p>{escape(visible(card.verdict))}</p><table>{rows}</table></div>"
    )


def _marked(text: str) -> str:
    """The report's ``_{sub}`` and ``^{sup}`` markup as HTML, the rest escaped."""
    shown = escape(text)
    shown = re.sub(r"_\{([^}]*)\}", r"<sub>\1</sub>", shown)
    return re.sub(r"\^\{([^}]*)\}", r"<sup>\1</sup>", shown)
