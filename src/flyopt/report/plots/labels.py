"""Labels placed where nothing else is: the areas of the turning-moment diagram written inside their shading."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.report.plots import standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.text import Text
    from matplotlib.transforms import BboxBase

# --------------------------------------------------------------------------
# Labels placed where nothing else is
# --------------------------------------------------------------------------


def _to_pixels(ax: Axes, x: npt.ArrayLike, y: npt.ArrayLike) -> npt.NDArray[np.float64]:
    return ax.transData.transform(np.column_stack([x, y]))


def _boxes_overlap(a: BboxBase, b: BboxBase, pad: float = 0.0) -> bool:
    return not (a.x1 + pad <= b.x0 or b.x1 + pad <= a.x0 or a.y1 + pad <= b.y0 or b.y1 + pad <= a.y0)


def lay_out(ax: Axes, keep: bool) -> None:
    """Put ``ax`` where its figure will draw it, so that data map to the pixels they will be drawn at, and,
    with ``keep``, keep it there.

    The figure's texts are made drawable (:func:`~flyopt.report.plots.standard.make_drawable`, as its
    class does before a draw) and its layout engine (constrained layout), if it has one, is run, as the
    figure's own draw runs it before drawing anything; the view limits are settled. With ``keep`` (the
    plot made the figure, and nothing is added to it after this call) the engine is then set aside
    (``"none"``: the axes stay where it put them), so that no draw lays the figure out again: what is
    placed by its pixels after this call (the areas' labels) is drawn where it was placed, and the layout,
    two measuring passes over every tick label, is paid once rather than at every draw. A caller's own
    figure keeps its engine: the caller may add panels, legends or a title the layout must make room for.
    Nothing is drawn: a whole draw without rendering (``Figure.draw_without_rendering``) lays the figure
    out just so and then walks every artist and tick for nothing, which cost the turning-moment diagram as
    much again as its layout.
    """
    figure = standard.figure_of(ax)
    standard.make_drawable(figure)
    engine = figure.get_layout_engine()
    if figure.axes and engine is not None:
        try:
            with standard.settled(figure):
                engine.execute(figure)
        except ValueError:  # as Figure.draw: the layout gives up on a figure too small, the draw goes on
            pass
        else:
            if keep:
                figure.set_layout_engine("none")
    ax.viewLim  # noqa: B018 -- reading it settles the autoscaled limits transData maps from


def place_area_labels(
    ax: Axes,
    x: npt.ArrayLike,
    lower: npt.ArrayLike,
    upper: npt.ArrayLike,
    spans: Sequence[tuple[float, float, str, str]],
    obstacles_x: Sequence[float] = (),
    obstacles_y: Sequence[float] = (),
    keep_layout: bool = False,
) -> list[Text]:
    """Write each area's text inside its shading where it clears both curves, else just above (or below) them.

    The marks of the cycle (vertical lines) and horizontal levels are avoided
    too; where an area is too narrow between its marks, its text is written
    across a mark, on a white ground that interrupts the mark.

    Parameters
    ----------
    x, lower, upper : ndarray
        The drawn angle and the two envelopes (min and max of the curves), in data units.
    spans : list of (x_left, x_right, text, colour)
    obstacles_x, obstacles_y : sequence of float
        Vertical and horizontal lines (data x, data y) a label should not cover.
    keep_layout : bool
        Keep the figure's layout as the labels are placed in it (:func:`lay_out`'s ``keep``): the plot made
        the figure and adds nothing to it afterwards.

    Returns
    -------
    list of Text
        The labels placed (gid ``area``); a label that finds no free place is left out.
    """
    from matplotlib.transforms import Bbox

    lay_out(ax, keep_layout)
    lo_px, hi_px = _to_pixels(ax, x, lower), _to_pixels(ax, x, upper)
    px = lo_px[:, 0]
    axes_box = ax.get_window_extent()
    lines_px = [ax.transData.transform((v, 0.0))[0] for v in obstacles_x]
    levels_px = [ax.transData.transform((0.0, v))[1] for v in obstacles_y]
    placed: list[Bbox] = []
    texts: list[Text] = []
    pad = 2.0
    for left, right, text, colour in spans:
        label = ax.text(0, 0, text, ha="center", va="center", fontsize=standard.FONT, color=colour, gid="area")
        box = label.get_window_extent()
        w, h = box.width + 2 * pad, box.height + 2 * pad
        a, b = ax.transData.transform((left, 0))[0], ax.transData.transform((right, 0))[0]
        middle = 0.5 * (a + b)
        centres = np.linspace(a + w / 2, b - w / 2, 61) if b - a > w else np.array([middle])
        best = None
        for mode in ("inside", "above", "below", "across"):
            for cx in centres:
                window = (px >= cx - w / 2) & (px <= cx + w / 2)
                if not window.any() or (
                    mode != "across" and any(cx - w / 2 - 3 <= v <= cx + w / 2 + 3 for v in lines_px)
                ):
                    continue
                top, bottom = hi_px[window, 1], lo_px[window, 1]
                if mode in ("inside", "across"):
                    slack = float(top.min() - bottom.max()) - h
                    cy, score = 0.5 * float(top.min() + bottom.max()), slack
                    if slack < 0:
                        continue
                elif mode == "above":
                    cy, score = float(top.max()) + 1.0 + h / 2, -abs(cx - middle)
                else:
                    cy, score = float(bottom.min()) - 1.0 - h / 2, -abs(cx - middle)
                candidate = Bbox.from_bounds(cx - w / 2, cy - h / 2, w, h)
                if (
                    candidate.y0 < axes_box.y0
                    or candidate.y1 > axes_box.y1
                    or any(candidate.y0 <= v <= candidate.y1 for v in levels_px)
                    or any(_boxes_overlap(candidate, other) for other in placed)
                ):
                    continue
                if best is None or score > best[0]:
                    best = (score, cx, cy, candidate)
            if best is not None:
                break
        if best is None:
            label.remove()
            continue
        if mode == "across":
            label.set_bbox({"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 0.5})
            label.set_zorder(5)
        placed.append(best[3])
        at = ax.transData.inverted().transform((best[1], best[2]))
        label.set_position((float(at[0]), float(at[1])))
        texts.append(label)
    return texts
