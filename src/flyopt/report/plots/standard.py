"""The visual standard every diagram shares: the figure, units on every axis, wrapped titles, legends outside the data."""

from __future__ import annotations

import contextlib
import functools
import gc
import os
import re
import textwrap
import threading
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import TYPE_CHECKING, Any, cast, overload

import numpy as np
import numpy.typing as npt

from flyopt.report import display
from flyopt.report.characters import visible

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.font_manager import FontProperties
    from matplotlib.legend import Legend
    from matplotlib.text import Text

SURPLUS, DEFICIT = "#2e8b57", "#c0392b"


#: Font size of legends and labels on the data [pt].
FONT = 8.5
#: Significant digits of the numbers written on a diagram, unless the caller asks for others (``--digits``).
DIGITS = display.DEFAULT_DIGITS


class NothingToDraw(Exception):
    """The diagram would be empty for this machine (no flywheel is needed): not an error."""


#: The one lock that serializes drawing. matplotlib is not thread-safe: pyplot's figure registry and current
#: figure, and the rcParams a renderer is drawn under (:func:`flyopt.report.html.svg_of`'s ``rc_context``), are
#: shared by every thread. Every figure made or closed through pyplot here holds it (:func:`axes`, :func:`new_figure`,
#: :func:`close`); a caller drawing from worker threads (``flyopt app``) holds it around a whole draw (making
#: the figures, rendering them, closing them). Re-entrant, so that a draw under it may make figures.
LOCK = threading.RLock()


@contextlib.contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector paused while figures are made or drawn (as it was before, after).

    A figure makes some 10^4 objects (artists, transforms, paths, dicts of properties), and the collector,
    counting them, runs its full collections in the middle of a report's figures: each scans every object
    of the process (numpy, matplotlib, the solution), some 0.1 s, 0.2 s of a report (issue 26). What the
    figures leave is collected as usual once the collector runs again. Reference counting frees what is not
    in a cycle meanwhile.

    The pauses of the whole process are counted (:data:`_PAUSES`): the collector is paused by the first one in
    (if it was running then) and runs again when the last one in flight ends, whichever thread or task each
    is in (the app holds it through each edit, :func:`flyopt.app.model.edit_held`, while its drawing worker
    pauses it around every figure: the first to end let it run under the others).
    """
    with _PAUSES_LOCK:
        if _PAUSES[0] == 0:
            _PAUSES[1] = gc.isenabled()
            gc.disable()
        _PAUSES[0] += 1
    try:
        yield
    finally:
        with _PAUSES_LOCK:
            _PAUSES[0] -= 1
            if _PAUSES[0] == 0 and _PAUSES[1]:
                gc.enable()


#: The pauses of :func:`collector_paused` in flight, and whether the collector ran before the first of them.
_PAUSES: list[Any] = [0, False]
_PAUSES_LOCK = threading.Lock()


def pyplot() -> ModuleType:
    """matplotlib.pyplot, on the Agg backend unless the caller chose one (imported only when a diagram is drawn).

    Its state is shared by every thread: a figure is made or closed under :data:`LOCK` (:func:`axes`,
    :func:`new_figure`, :func:`close`).
    """
    import matplotlib

    if "MPLBACKEND" not in os.environ and matplotlib.get_backend().lower() not in ("agg", "pdf", "svg"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


# --------------------------------------------------------------------------
# Drawable text: what a figure shows is what the font can draw
# --------------------------------------------------------------------------

#: What a diagram shows in place of a character its font cannot draw (an emoji): visible, so that nothing
#: of a name goes missing unseen.
PLACEHOLDER = "\ufffd"


@functools.lru_cache(maxsize=8)
def glyphs(font: str) -> frozenset[int]:
    """The code points the font file ``font`` has a glyph for."""
    from matplotlib import ft2font

    return frozenset(ft2font.FT2Font(font).get_charmap())


def font_file(properties: FontProperties | None = None) -> str:
    """The font file matplotlib draws text of these properties with (the default font without)."""
    from matplotlib import font_manager

    return str(font_manager.findfont(properties if properties is not None else font_manager.FontProperties()))


def in_font(text: str, font: str | None = None) -> str:
    """``text`` with every character the font has no glyph for (but the line break and the tab) as
    :data:`PLACEHOLDER`.

    Parameters
    ----------
    text : str
    font : str, optional
        The font file the text is drawn with (default: matplotlib's default font, DejaVu Sans).
    """
    covered = glyphs(font if font is not None else font_file())
    if covered.issuperset(map(ord, text)):  # every character drawn: the common case, checked without a loop here
        return text
    return "".join(c if c in "\n\t" or ord(c) in covered else PLACEHOLDER for c in text)


def drawable(text: str, font: str | None = None) -> str:
    """``text`` as a figure can draw it.

    A control or bidirectional-override character is its escape (:func:`flyopt.report.characters.visible`,
    as in every report), a tab a space, a character the font has no glyph for is :data:`PLACEHOLDER`
    (:func:`in_font`), and a ``$`` is escaped, so that a name is never read as mathtext (where ``$\\frac$`` would stop the drawing).

    Parameters
    ----------
    text : str
    font : str, optional
        The font file the text is drawn with (default: matplotlib's default font).
    """
    kept = in_font(visible(text).replace("\t", " "), font)
    return re.sub(r"(?<!\\)\$", r"\\$", kept)


def make_drawable(figure: Figure) -> Figure:
    """Make every text of the figure :func:`drawable` in its own font (titles, labels, legends, notes).

    Called before a figure is drawn (laid out or saved), so that whatever a scene names (its title, a
    shaft, a material) reaches the figure drawable, whichever way it came in; the text is changed
    only where it must be (a second call changes nothing).
    """
    for artist in _texts(figure):
        text = artist.get_text()
        if text:
            shown = drawable(text, font_file(artist.get_fontproperties()))
            if shown != text:
                artist.set_text(shown)
    return figure


def _texts(artist: Artist) -> Iterator[Text]:
    """Every Text of ``artist`` and its children, but the tick labels of an axis.

    A tick label is written by the axis' formatter as the figure is drawn, after
    :func:`make_drawable` ran, whatever it held before; the ticks are not asked
    for, so that they are not made (and their locations found) twice a draw.
    """
    from matplotlib.axis import Axis
    from matplotlib.text import Text

    if isinstance(artist, Text):
        yield artist
    children = [artist.label, artist.offsetText] if isinstance(artist, Axis) else artist.get_children()
    for child in children:
        yield from _texts(child)


# --------------------------------------------------------------------------
# The visual standard: figures, units, titles, legends
# --------------------------------------------------------------------------


def axes(ax: Axes | None, figsize: tuple[float, float] = (9, 5.2)) -> tuple[Axes, bool]:
    """(Axes, own): the caller's Axes, or one on a new figure of constrained layout (own True)."""
    if ax is not None:
        return ax, False
    plt = pyplot()
    with LOCK:
        return plt.figure(figsize=figsize, layout="constrained", FigureClass=figure_class()).add_subplot(), True


def new_figure(**kwargs: Any) -> Figure:
    """A new figure of :func:`figure_class` made by pyplot (so that a notebook shows it), under :data:`LOCK`."""
    plt = pyplot()
    with LOCK:
        return cast("Figure", plt.figure(FigureClass=figure_class(), **kwargs))


def close(figure: Figure) -> None:
    """Close ``figure`` in pyplot (its memory is freed with the last reference), under :data:`LOCK`."""
    plt = pyplot()
    with LOCK:
        plt.close(figure)


def figure_class() -> type[Figure]:
    """The class of every figure flyopt makes: a matplotlib Figure made drawable (:func:`make_drawable`)
    each time it is drawn (laid out, saved, rendered into a report), wherever a text came from (a title,
    a material's or a shaft's name in a legend)."""
    global _FIGURE_CLASS
    if _FIGURE_CLASS is None:
        from matplotlib.figure import Figure

        class DrawableFigure(Figure):
            def draw(self, renderer: Any) -> None:
                make_drawable(self)
                with settled(self):
                    super().draw(renderer)

        _FIGURE_CLASS = DrawableFigure
    return _FIGURE_CLASS


_FIGURE_CLASS: type[Figure] | None = None


@contextlib.contextmanager
def settled(figure: Figure) -> Iterator[None]:
    """What a draw or a layout of ``figure`` finds again and again, found once: its axes' ticks
    (:func:`settled_ticks`) and its texts' boxes (:func:`settled_texts`)."""
    with settled_ticks(figure), settled_texts():
        yield


@contextlib.contextmanager
def settled_ticks(figure: Figure) -> Iterator[None]:
    """Within the block, each axis of ``figure`` finds its ticks again only where what they are found from changed.

    matplotlib finds an axis' ticks (its locator's locations, its formatter's labels, each Tick moved and
    relabelled: ``Axis._update_ticks``) every time anything asks for them, and a draw asks some 25 times a
    figure: the constrained layout's two measuring passes (every spine, every axis' tight box, the label's
    place beside its siblings') and the draw itself. Between two of those asks nothing they are found from
    changes but the axes' place on the figure, between the layout's passes: the view interval, the axes' box
    in pixels (the locator's number of ticks follows the axis' length) and the figure's dpi. Here an axis
    remembers the last ticks it found with those three, and hands them back while the three are unchanged (its
    Ticks still hold what that search set: a search for other values replaces the one remembered). An axis
    whose locator or formatter another axis of the figure shares (whose state the other one's search would
    change) keeps matplotlib's own. Some 15 % of drawing the app's diagrams (issue 29); every SVG the same to
    the byte (tests/report/test_settled_ticks.py).
    """
    # a root figure's axes include its subfigures' (matplotlib 3.4 and later)
    axes_of: list[Any] = [axis for ax in figure.axes for axis in ax._axis_map.values()]

    def tickers(axis: Any) -> tuple[Any, ...]:
        return axis.major.locator, axis.major.formatter, axis.minor.locator, axis.minor.formatter

    owners: dict[int, int] = {}
    for axis in axes_of:
        for thing in tickers(axis):
            owners[id(thing)] = owners.get(id(thing), 0) + 1
    remembering = [
        axis
        for axis in axes_of
        if "_update_ticks" not in vars(axis)  # not already settled (a draw within a layout)
        and all(owners[id(thing)] == 1 for thing in tickers(axis))
    ]
    for axis in remembering:
        vars(axis)["_update_ticks"] = _remembering(axis)  # the instance's own: its class untouched
    try:
        yield
    finally:
        for axis in remembering:
            del vars(axis)["_update_ticks"]


@contextlib.contextmanager
def settled_texts() -> Iterator[None]:
    """Within the block, a text is laid out again (its lines measured, its box found: ``Text._get_layout``) only
    where what that is found from changed.

    A draw asks for each text's box several times: a tick label in each of the constrained layout's two passes
    (its axis' tight box, the spines, the label's place beside its siblings') and as it is drawn, some 900
    times an edit of the app, each measuring every line again. The box depends on the text, its font, size,
    rotation, alignments and line spacing, the figure's dpi and the renderer measuring it, not on where the text
    is (its place is added after): a text remembers its last box with all of them and hands it back while they
    are unchanged; a text wrapped to its place (``wrap``) is laid out each time. Every SVG the same to the byte
    (tests/report/test_settled_ticks.py). Nested, the outer block's memory serves.
    """
    from matplotlib.text import Text

    find = Text.__dict__["_get_layout"]
    if getattr(find, "settled", False):
        yield
        return
    remembered: dict[Any, tuple[tuple[Any, ...], Any]] = {}

    def get_layout(text: Any, renderer: Any) -> Any:
        if text._wrap:
            return find(text, renderer)
        font = text._fontproperties
        inputs = (
            renderer,  # the object, not its id, which a renderer made after this one's end may be given
            text._text,
            hash(font),
            font.get_size_in_points(),
            text.figure.dpi,  # a subfigure says its root's (Artist.get_figure(root=True) is matplotlib 3.10+)
            text._linespacing,
            text.get_usetex(),
            text._parse_math,
            text.get_rotation(),
            text._rotation_mode,
            text._horizontalalignment,
            text._verticalalignment,
            text._multialignment,
        )
        last = remembered.get(text)
        if last is not None and last[0] == inputs:
            return last[1]
        layout = find(text, renderer)
        remembered[text] = (inputs, layout)
        return layout

    get_layout.settled = True  # type: ignore[attr-defined]
    Text._get_layout = get_layout  # type: ignore[attr-defined]
    try:
        yield
    finally:
        Text._get_layout = find  # type: ignore[attr-defined]


def _remembering(axis: Any) -> Callable[[], list[Any]]:
    """``axis``'s ``_update_ticks``, handing back the last ticks it found while their inputs are unchanged."""
    find = type(axis)._update_ticks
    last: list[Any] = [None, None]  # (inputs, ticks)

    def update_ticks() -> list[Any]:
        inputs = (tuple(axis.get_view_interval()), axis.axes.bbox.bounds, axis.axes.figure.dpi)
        if last[0] != inputs:
            last[1] = find(axis)
            last[0] = inputs
        return list(last[1])

    return update_ticks


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
    """A quantity as people read it, "120 rpm", in the system's one unit of a dimension that has one (an angle, a
    speed, a length, a stress, an inertia). A dimension whose unit is chosen per value (torque, energy, power,
    force: :data:`flyopt.report.display.PREFIXED`) is written by the :class:`Scale` of the axis it is read
    against, which chose its prefix from the data (:func:`scale`)."""
    return display.quantity_text(value, dimension, units, digits, prefixed=False)


def digits_apart(values: Sequence[float], dimension: str, units: str, digits: int = DIGITS) -> int:
    """The fewest significant figures, ``digits`` or more (at most four more), that write ``values`` apart in
    the system's unit of ``dimension``: a diagram's ω_max, ω_m and ω_min of a small δ read as three speeds,
    and at the report's figures wherever those already tell them apart."""
    distinct = len({round(float(v), 12) for v in values})
    most = max(digits, min(digits + 4, display.MAX_DIGITS))
    for figures in range(digits, most):
        if len({q(v, dimension, units, figures) for v in values}) == distinct:
            return figures
    return most


@dataclass(frozen=True)
class Scale:
    """The unit one axis shows a dimension in, and the labels read against that axis.

    Chosen once from the SI values the axis draws (:func:`scale`), by the rule every number flyopt writes
    follows (:func:`flyopt.report.display.unit`: in the engineering system torque, energy, power and force take
    the prefix of the largest value, "536.7 J", "1.256 kJ"; every other dimension its system's one unit), so
    that an axis, the labels on it and the text report name a value in the same unit: one prefix per axis, as
    a table has one per column.
    """

    dimension: str
    units: str
    digits: int = DIGITS
    magnitude: float | None = None  # the largest SI magnitude the axis draws; None: the system's one unit

    @property
    def label(self) -> str:
        """The unit's label, "J"."""
        return display.unit(self.dimension, self.units, self.magnitude, self.digits)[0]

    @property
    def factor(self) -> float:
        """The SI value of one shown unit: shown = SI / factor."""
        return display.unit(self.dimension, self.units, self.magnitude, self.digits)[1]

    @overload
    def show(self, value: float) -> float: ...
    @overload
    def show(self, value: npt.NDArray[np.floating] | Sequence[float]) -> npt.NDArray[np.float64]: ...
    def show(self, value: npt.ArrayLike) -> npt.NDArray[np.float64] | float:
        """An SI value or array in the axis' unit (a number for a number)."""
        array = np.asarray(value, dtype=float)
        return array / self.factor if array.ndim else float(array) / self.factor

    def q(self, value: float | None) -> str:
        """A value with the axis' unit, "536.7 J" (round-off against the axis' largest value written 0)."""
        return self._write(value)

    @functools.cached_property
    def _write(self) -> Callable[[float | None], str]:
        """:func:`flyopt.report.display.quantity_text` of this axis, its unit found once (a read-out writes a
        value for every point drawn)."""
        among = None if self.magnitude is None else (self.magnitude,)
        return display.quantity_format(self.dimension, self.units, self.digits, among)

    def axis_label(self, words: str) -> str:
        """ "words [unit]" ("[-]" for a ratio)."""
        return f"{words} [{self.label}]"


def scale(
    dimension: str, units: str, values: Sequence[npt.ArrayLike | float | None] = (), digits: int = DIGITS
) -> Scale:
    """The :class:`Scale` of an axis that draws ``values`` (SI: numbers and arrays, None and nan left out): its
    unit chosen from their largest magnitude; without values the system's one unit."""
    found = [np.abs(np.asarray(v, dtype=float)).ravel() for v in values if v is not None]
    finite = np.concatenate(found) if found else np.empty(0)
    finite = finite[np.isfinite(finite)]
    magnitude = float(finite.max()) if finite.size else None
    return Scale(dimension, units, display.check_digits(digits), magnitude)


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
