"""What a diagram's curves read at each abscissa: the read-outs ``flyopt app`` shows under the pointer.

A diagram names its x axis (:func:`abscissa`: "φ" in the angle's :class:`~flyopt.report.plots.standard.Scale`)
and the curves worth reading (:func:`curve`: "M_d" in the torque axis' Scale); nothing else changes in the figure,
which stays the report's one drawing. Once the figure has been drawn as SVG (:func:`flyopt.report.html.svg_of`:
one point a user unit, at :data:`~flyopt.report.plots.output.VECTOR_DPI`), :func:`record` reads, per Axes with a
named abscissa and at least one named curve (or named points, or a named ordinate: below):

- where the Axes sits in the SVG (its box in the SVG's user units, y downwards), its limits and whether each
  axis is logarithmic: the data-to-SVG transform (:func:`to_svg`, which the page's script mirrors);
- a grid of at most :data:`POINTS` abscissae over the curves' span, evenly spaced in the axis' scale, and at
  each the value of every curve as its drawn polyline gives it (interpolated in the axes' scales between the
  curve's own points, as matplotlib draws the segment; none beyond its ends or across a gap);
- each value written as the report writes numbers (:meth:`~flyopt.report.plots.standard.Scale.q`: the axis'
  own unit, ``digits`` significant figures, round-off against the axis' largest value written 0), as lines
  "φ = 131.8 deg", "M_d = 3.41 kN·m": the page shows these texts, it formats no number itself.

The page snaps the pointer to the nearest grid abscissa (a grid step is about two pixels of a diagram as wide
as a screen's half), so that what it shows is exactly a point of the curves, written by one rule.

Where a diagram's points are not a curve of its x (a Pareto front's designs, the energy–mass curve, which turns
back in J_e), :func:`points` names each drawn point by its own lines of text, written by the diagram; the record
carries the points as drawn (at most :data:`MARKS` an artist, every k-th) and the page shows, within
:data:`REACH` of the pointer, the nearest point drawn as a marker (a tangent point, a design), else the nearest
point of a named line, in preference to a curve's value. A drawing with no curve may name its y axis
(:func:`ordinate`: the radius r of an axial section): the page then shows the height under the pointer, on a
horizontal guide, snapped to a grid of :data:`POINTS` over the axis.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from flyopt.errors import BrokenInvariant
from flyopt.report.plots.standard import Scale

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

#: Most abscissae a read-out grid has, per Axes.
POINTS = 240

#: Most points one artist named by :func:`points` carries into a record (more are thinned to every k-th).
MARKS = 480

#: How near the pointer a named point must be for the page to show it [CSS pixels] (the script's ``REACH``).
REACH = 12

#: Significant figures of the positions a record carries (limits and box excepted: those are exact).
PLACES = 7

#: The attribute a named artist carries its :class:`Name` in (the artist's own: no registry shared by threads).
ATTRIBUTE = "_flyopt_readout"

#: The attribute an Axes carries the :class:`Name` of its y axis in (:func:`ordinate`).
ORDINATE = "_flyopt_readout_y"


@dataclass(frozen=True)
class Name:
    """What a read-out calls an axis or a curve, and the Scale its shown values are in; ``absolute``: the
    magnitude is read (a radius on a section drawn about its axis, both halves)."""

    symbol: str
    scale: Scale
    absolute: bool = False

    def text(self, shown: float) -> str:
        """ "symbol = value unit" of a value as drawn (in the scale's unit)."""
        value = abs(shown) if self.absolute else shown
        return f"{self.symbol} = {self.scale.q(value * self.scale.factor)}"


def abscissa(ax: Axes, symbol: str, scale: Scale) -> None:
    """Name the x axis of ``ax`` for the read-outs: ``symbol`` ("φ"), its values drawn in ``scale``'s unit."""
    setattr(ax, ATTRIBUTE, Name(symbol, scale))


def ordinate(ax: Axes, symbol: str, scale: Scale, absolute: bool = False) -> None:
    """Name the y axis of ``ax`` for a read-out of the height under the pointer, where no curve is to be read (a
    drawing): ``symbol`` ("r"), drawn in ``scale``'s unit, its magnitude where ``absolute``."""
    setattr(ax, ORDINATE, Name(symbol, scale, absolute))


def curve(line: Line2D, symbol: str, scale: Scale) -> Line2D:
    """Name a curve for the read-outs: ``symbol`` ("M_d"), its values drawn in ``scale``'s unit. Several lines
    of one symbol are one curve in pieces (a stress over the hub, the web and the rim). Returns the line."""
    setattr(line, ATTRIBUTE, Name(symbol, scale))
    return line


@dataclass(frozen=True)
class Marks:
    """The lines of text of each point an artist draws (:func:`points`)."""

    rows: tuple[tuple[str, ...], ...]


def points(artist: Artist, rows: Sequence[Sequence[str]]) -> Artist:
    """Name each point ``artist`` draws (a Line2D's points, a scatter's offsets, a LineCollection's pieces
    joined end to start) by its lines of text, in the artist's order: "material = cast iron", "mass = 312 kg",
    each number written by the diagram's Scale (:meth:`~flyopt.report.plots.standard.Scale.q`). Returns it."""
    found = len(_drawn(artist))
    if found != len(rows):
        raise BrokenInvariant(f"the read-out names {len(rows)} points of an artist that draws {found}")
    setattr(artist, ATTRIBUTE, Marks(tuple(tuple(r) for r in rows)))
    return artist


def named(artist: Artist) -> Name | None:
    """The read-out name of an axis' Axes or a curve, or None."""
    name = getattr(artist, ATTRIBUTE, None)
    return name if isinstance(name, Name) else None


def record(figure: Figure) -> dict[str, Any]:
    """The read-outs of a drawn figure (JSON-ready): its size in SVG user units and one entry per Axes that has them.

    Call it after the figure was drawn (its layout is then final). Each entry: ``box`` [left, top, right,
    bottom] in the SVG's user units, ``x`` and ``y`` each ``{"lim": [first, last], "log": bool}``, ``at`` the
    grid's abscissae as drawn, ``values`` per curve the values as drawn (None where the curve has none),
    ``colours`` per curve, and ``rows`` per abscissa its lines of text: the abscissa's, then each curve's (None
    where the curve has no value there); and ``marks``, the points named by :func:`points` inside the limits:
    ``xy`` each as drawn, ``rows`` its lines, ``colours`` its colour, ``ranks`` 0 for a marker, 1 for a point of
    a line (the page prefers the first within reach) (an Axes without curves has empty ``at``,
    ``values``, ``colours`` and ``rows``); and ``across`` where the y axis is named (:func:`ordinate`): ``at``
    a grid of :data:`POINTS` heights over its limits as drawn, ``rows`` the text of each.
    """
    width, height = (float(v) * 72.0 for v in figure.get_size_inches())  # VECTOR_DPI: one user unit a point
    entries = [entry for ax in figure.axes if (entry := _axes_record(ax, width, height)) is not None]
    return {"size": [width, height], "axes": entries}


def to_svg(entry: dict[str, Any], x: float, y: float) -> tuple[float, float]:
    """Where the data point (x, y), as drawn, is in the SVG's user units, by an entry of :func:`record`."""
    left, top, right, bottom = entry["box"]
    fx = _fraction(x, entry["x"])
    fy = _fraction(y, entry["y"])
    return left + fx * (right - left), bottom - fy * (bottom - top)


def _fraction(value: float, axis: dict[str, Any]) -> float:
    first, last = axis["lim"]
    if axis["log"]:
        return (math.log10(value) - math.log10(first)) / (math.log10(last) - math.log10(first))
    return (value - first) / (last - first)


def _axes_record(ax: Axes, width: float, height: float) -> dict[str, Any] | None:
    if not ax.get_visible():
        return None
    marks = _marks(ax)
    curves = _curves(ax)
    across = _across(ax)
    if curves is None and not marks["xy"] and across is None:
        return None
    box = ax.get_position()  # in the figure's fractions, as the layout of the last draw placed it
    return {
        "box": [
            float(box.x0 * width),
            float((1.0 - box.y1) * height),
            float(box.x1 * width),
            float((1.0 - box.y0) * height),
        ],
        "x": {"lim": [float(v) for v in ax.get_xlim()], "log": ax.get_xscale() == "log"},
        "y": {"lim": [float(v) for v in ax.get_ylim()], "log": ax.get_yscale() == "log"},
        **(curves or {"at": [], "values": [], "colours": [], "rows": []}),
        "marks": marks,
        **({"across": across} if across is not None else {}),
    }


def _across(ax: Axes) -> dict[str, list[Any]] | None:
    """The grid of a named ordinate (:func:`ordinate`) over the y limits and its texts, or None."""
    name = getattr(ax, ORDINATE, None)
    if not isinstance(name, Name):
        return None
    log = ax.get_yscale() == "log"
    low, high = sorted(_forward(np.asarray(ax.get_ylim(), dtype=float), log).tolist())
    at = _backward(np.linspace(low, high, POINTS), log)
    return {"at": [_short(v) for v in at], "rows": [name.text(float(v)) for v in at]}


def _curves(ax: Axes) -> dict[str, Any] | None:
    """The grid of a named abscissa and the named curves' values and texts on it, or None."""
    x_name = named(ax)
    if x_name is None:
        return None
    x_log, y_log = ax.get_xscale() == "log", ax.get_yscale() == "log"
    pieces: dict[str, list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]] = {}
    names: dict[str, Name] = {}
    colours: dict[str, str] = {}
    for line in ax.get_lines():
        name = named(line)
        if name is None or not line.get_visible():
            continue
        xs = np.asarray(line.get_xdata(), dtype=float)
        ys = np.asarray(line.get_ydata(), dtype=float)
        if xs.size < 2 or np.any(np.diff(xs) < 0):  # a curve read along x only where x never goes back
            continue
        pieces.setdefault(name.symbol, []).append((_forward(xs, x_log), _forward(ys, y_log)))
        names.setdefault(name.symbol, name)
        colours.setdefault(name.symbol, _colour(line))
    if not pieces:
        return None
    ends = [(np.nanmin(tx), np.nanmax(tx)) for found in pieces.values() for tx, _ty in found if np.isfinite(tx).any()]
    if not ends:
        return None
    low, high = (_forward(np.asarray(ax.get_xlim(), dtype=float), x_log)).tolist()
    low, high = min(low, high), max(low, high)
    start, stop = max(low, min(e[0] for e in ends)), min(high, max(e[1] for e in ends))
    if not stop > start:
        return None
    grid = np.linspace(start, stop, POINTS)
    values = {symbol: _values(found, grid) for symbol, found in pieces.items()}
    at = _backward(grid, x_log)
    shown = {symbol: _backward(v, y_log) for symbol, v in values.items()}
    rows: list[list[str | None]] = [
        [
            x_name.text(float(at[i])),
            *(names[s].text(float(v[i])) if np.isfinite(v[i]) else None for s, v in shown.items()),
        ]
        for i in range(len(at))
    ]
    return {
        "at": [_short(v) for v in at],
        "values": [[_short(v) if np.isfinite(v) else None for v in vs] for vs in shown.values()],
        "colours": list(colours.values()),
        "rows": rows,
    }


def _marks(ax: Axes) -> dict[str, list[Any]]:
    """The points named by :func:`points` on ``ax`` that it shows: finite, inside its limits (drawable on a log
    axis), at most :data:`MARKS` an artist."""
    from matplotlib.colors import to_hex

    xy: list[list[float]] = []
    rows: list[list[str]] = []
    colours: list[str] = []
    ranks: list[int] = []
    (x0, x1), (y0, y1) = sorted(ax.get_xlim()), sorted(ax.get_ylim())
    x_log, y_log = ax.get_xscale() == "log", ax.get_yscale() == "log"
    for artist in [*ax.get_lines(), *ax.collections]:
        marks = getattr(artist, ATTRIBUTE, None)
        if not isinstance(marks, Marks) or not artist.get_visible():
            continue
        drawn = _drawn(artist)
        tints = _tints(artist, len(drawn))
        rank = 0 if _markers(artist) else 1
        step = max(1, math.ceil(len(drawn) / MARKS))
        for i in range(0, len(drawn), step):
            x, y = (float(v) for v in drawn[i])
            if not (math.isfinite(x) and math.isfinite(y) and x0 <= x <= x1 and y0 <= y <= y1):
                continue
            if (x_log and x <= 0) or (y_log and y <= 0):
                continue
            xy.append([_short(x), _short(y)])
            rows.append(list(marks.rows[i]))
            colours.append(str(to_hex(tints[i])))
            ranks.append(rank)
    return {"xy": xy, "rows": rows, "colours": colours, "ranks": ranks}


def _markers(artist: Artist) -> bool:
    """Whether an artist draws its points as markers only (a scatter, a marker line), not as a line."""
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D

    if isinstance(artist, Line2D):
        return artist.get_linestyle() in ("None", "", " ") and artist.get_marker() not in ("None", "", " ", None)
    return not isinstance(artist, LineCollection)


def _drawn(artist: Artist) -> npt.NDArray[np.float64]:
    """The points an artist draws, as an (n, 2) array in data coordinates: a Line2D's, a LineCollection's pieces
    joined end to start (each piece's first point the previous one's last), a scatter's offsets."""
    from matplotlib.collections import Collection, LineCollection
    from matplotlib.lines import Line2D

    if isinstance(artist, Line2D):
        return np.column_stack(
            [np.asarray(artist.get_xdata(), dtype=float), np.asarray(artist.get_ydata(), dtype=float)]
        ).reshape(-1, 2)
    if isinstance(artist, LineCollection):
        pieces = [np.asarray(p, dtype=float).reshape(-1, 2) for p in artist.get_segments()]
        if not pieces:
            return np.empty((0, 2))
        return np.concatenate([pieces[0], *(p[1:] for p in pieces[1:])])
    if isinstance(artist, Collection):
        return np.asarray(artist.get_offsets(), dtype=float).reshape(-1, 2)
    raise BrokenInvariant(f"a read-out names the points of a Line2D or a Collection, not of a {type(artist).__name__}")


def _tints(artist: Artist, n: int) -> list[Any]:
    """Each drawn point's colour: a line's; a collection's piece or point, by its colour map where it has one."""
    from matplotlib.collections import Collection, LineCollection
    from matplotlib.lines import Line2D

    if isinstance(artist, Line2D):  # markers only: their edge's colour (a ring's), else the line's
        return [artist.get_markeredgecolor() if _markers(artist) else artist.get_color()] * n
    if not isinstance(artist, Collection):
        return ["black"] * n
    if isinstance(artist, LineCollection):
        array = artist.get_array()
        colours = artist.to_rgba(array) if array is not None else artist.get_edgecolor()
        ends = np.cumsum([0, *(max(len(p) - 1, 0) for p in artist.get_segments())])
        index = np.searchsorted(ends, np.arange(n), side="right") - 1  # the piece a point starts (the last ends)
    else:
        array = artist.get_array()
        colours = artist.to_rgba(array) if array is not None else artist.get_facecolor()
        index = np.arange(n)
    last = len(colours) - 1
    return [colours[int(min(max(k, 0), last))] for k in index]


def _short(value: float) -> float:
    """A position to :data:`PLACES` significant figures (a thousandth of a point on a page): the JSON's numbers
    place the pointer's guide, the texts carry the values."""
    return float(f"{float(value):.{PLACES}g}")


def _forward(values: npt.NDArray[np.float64], log: bool) -> npt.NDArray[np.float64]:
    """Values in the axis' scale (log10 on a log axis; a value a log axis cannot draw is nan)."""
    if not log:
        return values
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(values > 0, np.log10(np.where(values > 0, values, 1.0)), np.nan)


def _backward(values: npt.NDArray[np.float64], log: bool) -> npt.NDArray[np.float64]:
    return np.power(10.0, values) if log else values


def _values(
    found: list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]], grid: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """A curve's values (in the axes' scales) on the grid: each piece's polyline within its span (a gap where a
    point is nan, as matplotlib leaves one), the first piece that has a value there."""
    out = np.full(grid.shape, np.nan)
    for tx, ty in found:
        keep = np.isfinite(tx)
        tx, ty = tx[keep], ty[keep]
        if tx.size < 2:
            continue
        inside = (grid >= tx[0]) & (grid <= tx[-1]) & np.isnan(out)
        right = np.clip(np.searchsorted(tx, grid[inside], side="right"), 1, tx.size - 1)
        left = right - 1
        span = tx[right] - tx[left]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(span > 0, (grid[inside] - tx[left]) / span, 0.0)
        out[inside] = ty[left] + t * (ty[right] - ty[left])  # nan beside a nan point: the drawn gap
    return out


def _colour(line: Line2D) -> str:
    from matplotlib.colors import to_hex

    return str(to_hex(line.get_color()))
