"""A matplotlib figure drawn straight onto a reportlab canvas, as vectors: the PDF report's diagrams.

:func:`record` lays the figure out and draws it once, with a matplotlib
renderer (:class:`CanvasRenderer`) that writes PDF path operators and
reportlab canvas calls into a :class:`Recording`: lines, areas, hatching and
markers stay paths, at any zoom and in print; text is PDF text in the font
matplotlib chose (DejaVu Sans, embedded by reportlab as for the rest of the
report), so that it can be searched and copied; mathtext, which the diagrams
never write (their texts are escaped by
:func:`flyopt.report.plots.standard.drawable`), would be drawn as outlines.
:func:`draw` plays a recording onto the page reportlab is building. A
recording is plain data, so a figure may be drawn in a forked worker
(:mod:`flyopt.report.figure_cores`, as :func:`flyopt.report.pdf.render`
draws a report's figures) and placed on its page by the process that lays
the pages out; its fonts are named by their files and registered with
reportlab where it is played. Nothing is rasterised, and nothing is written
twice: no PNG, no PDF of the figure to read back.

The figure is drawn at 72 dpi (one pixel a point, as matplotlib's own PDF
backend draws it), scaled on the page by the caller. Imported only for a PDF.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Literal, cast

import numpy as np
from matplotlib.backend_bases import GraphicsContextBase, RendererBase
from matplotlib.path import Path

from flyopt.report.html import REMEMBERED_TEXTS
from flyopt.report.plots import standard
from flyopt.report.plots.output import VECTOR_DPI, draw_vector

if TYPE_CHECKING:
    from matplotlib.figure import Figure
    from matplotlib.font_manager import FontProperties
    from matplotlib.transforms import Transform
    from reportlab.pdfgen.canvas import Canvas

_CAPS = {"butt": 0, "round": 1, "projecting": 2}
_JOINS = {"miter": 0, "round": 1, "bevel": 2}
#: Side of matplotlib's hatch tile [pt] (as its PDF backend: a 72 pt pattern, aligned to the figure's top left).
_HATCH_TILE = 72.0


#: The reportlab canvas methods a figure's drawing calls (:class:`Recording` records nothing else); a font is
#: recorded as ("font", (file, size)) and an image as ("image", (pixels, width, height)).
CANVAS_CALLS = frozenset(
    {
        "saveState",
        "restoreState",
        "translate",
        "rotate",
        "transform",
        "addLiteral",
        "setStrokeColorRGB",
        "setStrokeAlpha",
        "setLineWidth",
        "setLineCap",
        "setLineJoin",
        "setDash",
        "setFillColorRGB",
        "setFillAlpha",
        "drawString",
    }
)


class Recording:
    """One figure's drawing: its size [pt] and the reportlab canvas calls that draw it, in order.

    What :class:`CanvasRenderer` writes: a call to a method of :data:`CANVAS_CALLS` is recorded with its
    arguments (plain numbers, strings and lists), a font by its file (:meth:`font`) and an image by its pixels
    (:meth:`image`), so that a recording pickles whole and plays the same wherever it is played (:func:`draw`).
    """

    def __init__(self, width: float, height: float) -> None:
        self.width = width
        self.height = height
        self.calls: list[tuple[str, tuple[Any, ...]]] = []

    def __getattr__(self, name: str) -> Callable[..., None]:
        if name not in CANVAS_CALLS:
            raise AttributeError(name)
        return lambda *args: self.calls.append((name, args))

    def font(self, path: str, size: float) -> None:
        """Set the TrueType font of the file ``path`` at ``size`` [pt]."""
        self.calls.append(("font", (path, size)))

    def image(self, pixels: np.ndarray, width: float, height: float) -> None:
        """Draw the RGBA ``pixels`` (rows from the top) over ``width`` x ``height`` from the origin."""
        self.calls.append(("image", (np.asarray(pixels), width, height)))


def record(figure: Figure, prefix: str = "") -> Recording:
    """The drawing of ``figure`` (its layout engine, constrained layout, runs in this one draw; the figure's dpi
    is 72 while it draws and its own again afterwards). ``prefix`` is not used: a PDF has no ids to keep apart
    (it is the argument :func:`flyopt.report.figure_cores.draw_each` passes)."""
    width, height = (float(v) for v in figure.get_size_inches() * VECTOR_DPI)
    recording = Recording(width, height)
    with standard.collector_paused():
        draw_vector(figure, lambda: CanvasRenderer(recording, width, height))
    return recording


def draw(figure: Figure | Recording, canvas: Canvas, x: float, y: float, scale: float) -> None:
    """Draw ``figure`` (or its :func:`record`) on ``canvas`` with its lower left corner at (x, y) [pt],
    scaled by ``scale``."""
    recording = figure if isinstance(figure, Recording) else record(figure)
    canvas.saveState()
    canvas.translate(x, y)
    canvas.scale(scale, scale)
    try:
        for name, args in recording.calls:
            if name == "font":
                path, size = args
                canvas.setFont(font_name(path), size)
            elif name == "image":
                from PIL import Image
                from reportlab.lib.utils import ImageReader

                pixels, width, height = args
                canvas.drawImage(ImageReader(Image.fromarray(pixels)), 0, 0, width, height, mask="auto")
            else:
                getattr(canvas, name)(*args)
    finally:
        canvas.restoreState()


@functools.lru_cache(maxsize=16)
def font_name(path: str) -> str:
    """The reportlab name of the TrueType font file ``path``: the font already registered from that file
    (the report's own DejaVu, :func:`flyopt.report.pdf.render`), else the file registered once (a font is
    parsed in about 60 ms and embedded as one subset however many names it has)."""
    from reportlab.pdfbase import pdfmetrics
    from reportlab.pdfbase.ttfonts import TTFont

    for name in pdfmetrics.getRegisteredFontNames():
        if getattr(getattr(pdfmetrics.getFont(name), "face", None), "filename", None) == path:
            return name
    name = f"mpl-{len(pdfmetrics.getRegisteredFontNames())}-{path.rsplit('/', 1)[-1].rsplit('.', 1)[0]}"
    pdfmetrics.registerFont(TTFont(name, path))
    return name


def path_operators(
    path: Path, transform: Transform | None, clip: tuple[float, float, float, float] | None, simplify: bool
) -> str:
    """The PDF operators (m, l, c, h) of ``path`` transformed to the page, NaN segments removed.

    ``clip`` (x0, y0, x1, y1) cuts a stroked path at the page's edges and ``simplify``
    merges the points that fall on one line at the page's resolution (matplotlib's
    path simplification, as its PDF backend applies it to lines); quadratic curves
    become cubic ones (PDF has none).
    """
    cleaned = path.cleaned(transform=transform, remove_nans=True, clip=clip, simplify=simplify, curves=True)
    vertices = np.asarray(cleaned.vertices, dtype=float)
    if cleaned.codes is None:
        codes = np.full(len(vertices), Path.LINETO, dtype=np.uint8)
        codes[:1] = Path.MOVETO
    else:
        codes = np.asarray(cleaned.codes)
    keep = codes != Path.STOP
    points: list[list[float]] = vertices[keep].tolist()
    kinds: list[int] = codes[keep].tolist()
    if Path.CURVE3 not in kinds and Path.CURVE4 not in kinds:  # the common case, lines only
        ops = {int(Path.MOVETO): "m", int(Path.LINETO): "l"}
        return "\n".join(f"{x:.3f} {y:.3f} {ops[code]}" if code in ops else "h" for (x, y), code in zip(points, kinds))
    words = []
    k, n = 0, len(kinds)
    last = (0.0, 0.0)
    while k < n:
        code = kinds[k]
        if code == Path.MOVETO or code == Path.LINETO:
            last = (points[k][0], points[k][1])
            words.append(f"{last[0]:.3f} {last[1]:.3f} {'m' if code == Path.MOVETO else 'l'}")
            k += 1
        elif code == Path.CURVE3:
            (cx, cy), (ex, ey) = points[k], points[k + 1]
            c1 = (last[0] + 2.0 / 3.0 * (cx - last[0]), last[1] + 2.0 / 3.0 * (cy - last[1]))
            c2 = (ex + 2.0 / 3.0 * (cx - ex), ey + 2.0 / 3.0 * (cy - ey))
            words.append(f"{c1[0]:.3f} {c1[1]:.3f} {c2[0]:.3f} {c2[1]:.3f} {ex:.3f} {ey:.3f} c")
            last = (ex, ey)
            k += 2
        elif code == Path.CURVE4:
            (ax, ay), (bx, by), (ex, ey) = points[k], points[k + 1], points[k + 2]
            words.append(f"{ax:.3f} {ay:.3f} {bx:.3f} {by:.3f} {ex:.3f} {ey:.3f} c")
            last = (ex, ey)
            k += 3
        else:  # CLOSEPOLY
            words.append("h")
            k += 1
    return "\n".join(words)


def _rgba(colour: Any) -> tuple[float, float, float, float]:
    """(r, g, b, alpha) of a matplotlib colour tuple (alpha 1 where it has none)."""
    values = [float(v) for v in colour]
    return values[0], values[1], values[2], values[3] if len(values) > 3 else 1.0


#: The measures of the texts the PDF's figures drew: (text, font properties) -> (width, height, descent) [pt].
#: A function of the two alone at this renderer's fixed 72 dpi; matplotlib's own cache lasts one renderer (one
#: figure), and a report's figures share most of their texts (tick labels, units).
_MEASURES: dict[tuple[str, Any], tuple[float, float, float]] = {}


class CanvasRenderer(RendererBase):
    """A matplotlib renderer whose output is PDF operators and reportlab canvas calls, recorded (y up, one pixel
    a point).

    Paths (and the default collections and markers, drawn path by path) are filled
    and stroked with their colours, alphas, dashes, caps and joins, clipped to the
    Axes as matplotlib clips them; a hatched area is tiled with matplotlib's hatch
    pattern. Text is PDF text in the TrueType file matplotlib found for its
    properties; mathtext falls back to matplotlib's outlines.
    """

    def __init__(self, canvas: Recording, width: float, height: float) -> None:
        super().__init__()
        self.canvas = canvas
        self.width = width
        self.height = height

    def get_text_width_height_descent(self, s: str, prop: FontProperties, ismath: Any) -> Any:
        """matplotlib's measure of a text (RendererBase's: its font at its size, at 72 dpi here), remembered from
        one figure and one renderer to the next (:data:`_MEASURES`); mathtext and TeX are measured each time."""
        if ismath:
            return super().get_text_width_height_descent(s, prop, ismath)
        key = (s, prop.copy())  # a copy: the properties' hash follows their (mutable) state
        found = _MEASURES.get(key)
        if found is None:
            if len(_MEASURES) >= REMEMBERED_TEXTS:
                _MEASURES.clear()
            found = _MEASURES[key] = super().get_text_width_height_descent(s, prop, ismath)
        return found

    def flipy(self) -> bool:
        return False

    def get_canvas_width_height(self) -> tuple[float, float]:
        return self.width, self.height

    def points_to_pixels(self, points: Any) -> Any:
        return points

    def option_image_nocomposite(self) -> bool:
        return True

    # ------------------------------------------------------------------
    # The graphics state
    # ------------------------------------------------------------------

    def _clip(self, gc: GraphicsContextBase) -> None:
        """Clip to the gc's rectangle and path (within a saveState the caller restores)."""
        rect = gc.get_clip_rectangle()
        if rect is not None:
            x0, y0, w, h = rect.bounds
            self.canvas.addLiteral(f"{x0:.3f} {y0:.3f} {w:.3f} {h:.3f} re W n")
        clip_path, affine = gc.get_clip_path()  # a Path and its affine part (matplotlib's stubs say TransformedPath)
        if clip_path is not None:
            self.canvas.addLiteral(path_operators(cast("Path", clip_path), affine, None, False) + "\nW n")

    def _stroke_style(self, gc: GraphicsContextBase) -> bool:
        """Set the stroke of ``gc``; whether there is one to draw."""
        r, g, b, alpha = _rgba(gc.get_rgb())
        width = gc.get_linewidth()
        if width <= 0 or alpha <= 0:
            return False
        canvas = self.canvas
        canvas.setStrokeColorRGB(r, g, b)
        canvas.setStrokeAlpha(alpha)
        canvas.setLineWidth(width)
        canvas.setLineCap(_CAPS.get(gc.get_capstyle(), 0))
        canvas.setLineJoin(_JOINS.get(gc.get_joinstyle(), 0))
        offset, dashes = gc.get_dashes()
        pattern = [float(d) for d in np.atleast_1d(np.asarray(dashes, dtype=float))] if dashes is not None else []
        if pattern and sum(pattern) > 0:
            canvas.setDash(pattern, float(offset or 0.0))
        return True

    # ------------------------------------------------------------------
    # Paths
    # ------------------------------------------------------------------

    def draw_path(self, gc: GraphicsContextBase, path: Path, transform: Transform, rgbFace: Any = None) -> None:
        hatch = gc.get_hatch_path()
        fill_alpha = 0.0
        if rgbFace is not None:
            fill_alpha = gc.get_alpha() if gc.get_forced_alpha() else (rgbFace[3] if len(rgbFace) > 3 else 1.0)
        canvas = self.canvas
        canvas.saveState()
        self._clip(gc)
        stroke = self._stroke_style(gc)
        fill = rgbFace is not None and fill_alpha > 0
        if not (stroke or fill or hatch is not None):
            canvas.restoreState()
            return
        plain = rgbFace is None and hatch is None
        operators = path_operators(
            path, transform, (0.0, 0.0, self.width, self.height) if plain else None, plain and path.should_simplify
        )
        if not operators:
            canvas.restoreState()
            return
        if fill:
            canvas.setFillColorRGB(*rgbFace[:3])
            canvas.setFillAlpha(fill_alpha)
        if hatch is not None:
            if fill:
                canvas.addLiteral(operators + "\nf")
            self._hatch(gc, operators, path, transform)
            if stroke:
                canvas.addLiteral(operators + "\nS")
        else:
            canvas.addLiteral(operators + "\n" + ("B" if fill and stroke else "f" if fill else "S"))
        canvas.restoreState()

    def _hatch(self, gc: GraphicsContextBase, operators: str, path: Path, transform: Transform) -> None:
        """Tile the area of ``operators`` with the gc's hatch, matplotlib's 72 pt pattern from the top left."""
        from matplotlib.transforms import Affine2D

        canvas = self.canvas
        box = path.get_extents(transform)
        if not (np.isfinite(box.bounds).all() and box.width > 0 and box.height > 0):
            return
        tile = Path.hatch(gc.get_hatch())
        if tile is None:
            return
        canvas.saveState()
        canvas.addLiteral(operators + "\nW n")
        r, g, b, alpha = _rgba(gc.get_hatch_color())
        canvas.setStrokeColorRGB(r, g, b)
        canvas.setFillColorRGB(r, g, b)
        canvas.setStrokeAlpha(alpha)
        canvas.setFillAlpha(alpha)
        canvas.setLineWidth(gc.get_hatch_linewidth())
        canvas.setDash([])
        canvas.setLineCap(0)
        top = self.height
        parts = []
        for i in range(int(np.floor(box.x0 / _HATCH_TILE)), int(np.ceil(box.x1 / _HATCH_TILE))):
            for j in range(int(np.floor((box.y0 - top) / _HATCH_TILE)), int(np.ceil((box.y1 - top) / _HATCH_TILE))):
                at = Affine2D().scale(_HATCH_TILE).translate(i * _HATCH_TILE, top + j * _HATCH_TILE)
                parts.append(path_operators(tile, at, None, False))
        canvas.addLiteral("\n".join(parts) + "\nB")
        canvas.restoreState()

    # ------------------------------------------------------------------
    # Text and images
    # ------------------------------------------------------------------

    def draw_text(
        self,
        gc: GraphicsContextBase,
        x: float,
        y: float,
        s: str,
        prop: FontProperties,
        angle: float,
        ismath: bool | Literal["TeX"] = False,
        mtext: Any = None,
    ) -> None:
        if ismath:
            super().draw_text(gc, x, y, s, prop, angle, ismath, mtext)  # outlines, as matplotlib draws them
            return
        from matplotlib import font_manager

        r, g, b, alpha = _rgba(gc.get_rgb())
        if alpha <= 0 or not s:
            return
        canvas = self.canvas
        canvas.saveState()
        self._clip(gc)
        canvas.setFillColorRGB(r, g, b)
        canvas.setFillAlpha(alpha)
        canvas.translate(x, y)
        if angle:
            canvas.rotate(angle)
        canvas.font(str(font_manager.findfont(prop)), prop.get_size_in_points())
        canvas.drawString(0, 0, s)
        canvas.restoreState()

    def draw_image(self, gc: GraphicsContextBase, x: float, y: float, im: Any, transform: Any = None) -> None:
        h, w = im.shape[:2]
        if w == 0 or h == 0:
            return
        canvas = self.canvas
        canvas.saveState()
        self._clip(gc)
        canvas.translate(x, y)
        if transform is not None:  # the image fills the unit square of the transform
            canvas.transform(*transform.frozen().to_values())
            w, h = 1, 1
        canvas.image(np.asarray(im), w, h)
        canvas.restoreState()
