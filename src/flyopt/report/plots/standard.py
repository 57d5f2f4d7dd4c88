"""The visual standard every diagram shares: the figure, units on every axis, wrapped titles, legends outside the data."""

from __future__ import annotations

import os
import textwrap
import unicodedata
from collections.abc import Sequence
from types import ModuleType
from typing import TYPE_CHECKING, Any, overload

import numpy as np
import numpy.typing as npt

from flyopt.report import display

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.legend import Legend

SURPLUS, DEFICIT = "#2e8b57", "#c0392b"


#: Font size of legends and labels on the data [pt].
FONT = 8.5
#: Significant digits of the numbers written on a diagram.
DIGITS = 4


class NothingToDraw(Exception):
    """The diagram would be empty for this machine (no flywheel is needed): not an error."""


def pyplot() -> ModuleType:
    """matplotlib.pyplot, on the Agg backend unless the caller chose one (imported only when a diagram is drawn)."""
    import matplotlib

    if "MPLBACKEND" not in os.environ and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --------------------------------------------------------------------------
# The visual standard: figures, units, titles, legends
# --------------------------------------------------------------------------


def axes(ax: Axes | None, figsize: tuple[float, float] = (9, 5.2)) -> tuple[Axes, bool]:
    """(Axes, own): the caller's Axes, or one on a new figure of constrained layout (own True)."""
    if ax is not None:
        return ax, False
    plt = pyplot()
    return plt.figure(figsize=figsize, layout="constrained", FigureClass=figure_class()).add_subplot(), True


def figure_class() -> type[Figure]:
    """The class of every figure flyopt makes: a matplotlib Figure whose texts are made drawable
    (:func:`drawable`) each time it is drawn, wherever a text came from (a title, a material's or a
    shaft's name in a legend): a character the font lacks is drawn as a placeholder instead of a
    missing-glyph warning on stderr (and a blank), control and direction-override characters never."""
    global _FIGURE_CLASS
    if _FIGURE_CLASS is None:
        from matplotlib.figure import Figure
        from matplotlib.text import Text

        class DrawableFigure(Figure):
            def draw(self, renderer: Any) -> None:
                for text in self.findobj(Text):
                    shown = text.get_text()
                    made = drawable(shown)
                    if made != shown:
                        text.set_text(made)
                super().draw(renderer)

        _FIGURE_CLASS = DrawableFigure
    return _FIGURE_CLASS


_FIGURE_CLASS: type[Figure] | None = None
_GLYPHS: frozenset[int] | None = None


def drawable(text: str) -> str:
    """``text`` with every character the diagrams' font has no glyph for, and every control, format
    (bidirectional overrides) or private-use character, replaced by U+FFFD (or ``?``)."""
    global _GLYPHS
    if not text or (text.isascii() and text.isprintable()):
        return text
    if _GLYPHS is None:
        from matplotlib import font_manager
        from matplotlib.ft2font import FT2Font

        path = font_manager.findfont(font_manager.FontProperties())
        _GLYPHS = frozenset(FT2Font(path).get_charmap())
    placeholder = "\ufffd" if 0xFFFD in _GLYPHS else "?"
    return "".join(
        c
        if c == "\n" or (ord(c) in _GLYPHS and unicodedata.category(c) not in ("Cc", "Cf", "Co", "Cs"))
        else placeholder
        for c in text
    )


def figure_of(ax: Axes) -> Figure:
    """The figure an Axes is drawn on (the root figure, for an Axes of a subfigure)."""
    from matplotlib.figure import Figure

    fig = ax.figure
    return fig if isinstance(fig, Figure) else fig.figure


def unit(dimension: str, units: str) -> tuple[str, float]:
    """(label, factor) of a dimension in the unit system: shown = SI / factor."""
    return display.unit(dimension, units)


@overload
def show(value: float, dimension: str, units: str) -> float: ...
@overload
def show(value: npt.NDArray[np.floating] | Sequence[float], dimension: str, units: str) -> npt.NDArray[np.float64]: ...
def show(value: npt.ArrayLike, dimension: str, units: str) -> npt.NDArray[np.float64] | float:
    """An SI value or array in the system's unit of its dimension (a number for a number)."""
    array = np.asarray(value, dtype=float)
    factor = display.unit(dimension, units)[1]
    return array / factor if array.ndim else float(array) / factor


def q(value: float | None, dimension: str, units: str, digits: int = DIGITS) -> str:
    """A quantity as people read it, "0.4625 kN·m"."""
    return display.quantity_text(value, dimension, units, digits)


def axis_label(words: str, dimension: str, units: str) -> str:
    """ "words [unit]" ("[-]" for a ratio: every axis says its unit)."""
    return f"{words} [{display.label(dimension, units)}]"


def title(ax: Axes, own: bool, *lines: str | None, size: float = 11) -> None:
    """A title of several lines, each wrapped to the width it has (the figure's, or the Axes')."""
    fig = figure_of(ax)
    width = fig.get_size_inches()[0] * (1.0 if own else ax.get_position().width)
    chars = max(int(width * 72 / (0.6 * size)) - 4, 20)
    text = "\n".join(textwrap.fill(line, chars) for line in lines if line)
    ax.set_title(text, fontsize=size)


def legend(
    ax: Axes, own: bool, title: str | None = None, ncol: int = 2, handles: list[Artist] | None = None
) -> Legend | None:
    """The legend outside the data: below the figure the function made, right of a given Axes.

    Entries and title are wrapped to the width there is (the figure's, shared by ``ncol`` columns;
    about 40 characters beside a given Axes). Returns the Legend (``ax.figure.legends[-1]`` for an
    own figure, else ``ax.get_legend()``).
    """
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    else:
        labels = [h.get_label() for h in handles]
    if not handles:
        return None
    ncol = min(ncol, len(handles))
    if own:
        chars = int((figure_of(ax).get_size_inches()[0] - 0.4) * 72 / (0.6 * FONT))
        wrap, title_wrap = chars // ncol - 8, chars - 4
    else:
        ncol, wrap, title_wrap = 1, 40, 40
    labels = [fill(label, wrap) for label in labels]
    if title:
        title = fill(title, title_wrap)
    if own:
        return figure_of(ax).legend(
            handles,
            labels,
            loc="outside lower center",
            ncol=ncol,
            fontsize=FONT,
            title=title,
            title_fontsize=FONT,
            frameon=False,
        )
    return ax.legend(
        handles,
        labels,
        loc="upper left",
        bbox_to_anchor=(1.02, 1.0),
        borderaxespad=0.0,
        fontsize=FONT,
        title=title,
        title_fontsize=FONT,
        frameon=False,
    )


def fill(text: str, width: int) -> str:
    """Wrap a line to ``width`` characters, never between a number and its unit ("0 mm", "1,512 rpm"),
    nor inside "name = value"."""
    import re

    kept = re.sub(r"(\d) (?=[^\s(=+−-])", "\\1\u00a0", text).replace(" = ", "\u00a0=\u00a0")
    return textwrap.fill(kept, width).replace("\u00a0", " ")
