"""Writing a diagram to a file: the formats, the check of the output path before anything is computed, the atomic save."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, cast

from flyopt.errors import SceneError
from flyopt.report.plots import standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.backend_bases import RendererBase
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    from matplotlib.figure import Figure

#: Image formats :func:`save` writes, by the suffix of the file.
FORMATS = ("png", "svg", "pdf")


def check_output(path: str | os.PathLike[str]) -> None:
    """Check the file a diagram will go to, before anything is computed (that it is none the diagram is drawn
    from is checked where that is read: :func:`flyopt.outputs.files.check_not_scene`).

    Parameters
    ----------
    path : str or Path
        The output file; its suffix picks the format (:data:`FORMATS`).

    Raises
    ------
    SceneError
        Field ``-o/--output``: an unsupported suffix, or a folder that does
        not exist (flyopt does not create folders the user did not ask for).
    """
    from flyopt.outputs.files import check_folder

    path = Path(path)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise SceneError("-o/--output", f"{str(path)!r} must end in .png, .svg or .pdf (the suffix picks the format)")
    check_folder(path, "-o/--output")


def save(ax: Axes, path: str | os.PathLike[str], dpi: float = 150, own_name: bool = False) -> Path:
    """Write the Axes' figure to ``path`` (png, svg or pdf by suffix), atomically (``own_name``: a name flyopt made
    in the folder the user gave, never written through a link: :func:`flyopt.outputs.files.check_not_a_link`).

    Raises
    ------
    SceneError
        See :func:`check_output`.
    OSError
        The folder cannot be written; the error names ``path``.
    """
    check_output(path)
    from flyopt.outputs.files import write_atomically

    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    fig = standard.figure_of(ax)
    try:
        # into the handle of the file made for it (never reopened by its name); drawable: figure_class
        write_atomically(path, lambda handle: fig.savefig(handle, format=suffix, dpi=dpi), own_name=own_name)
    finally:
        standard.close(fig)
    return path


#: Resolution a vector renderer draws a figure at: one pixel a point, as matplotlib's PDF and SVG backends.
VECTOR_DPI = 72.0


def draw_vector(figure: Figure, make_renderer: Callable[[], RendererBase | MixedModeRenderer]) -> None:
    """Draw ``figure`` once with the vector renderer ``make_renderer()`` (sized in points), at :data:`VECTOR_DPI`.

    The renderer is made once the figure is at :data:`VECTOR_DPI` (matplotlib's
    mixed-mode renderer takes the figure's dpi as the one to return to after a
    rasterised artist). The figure's layout engine (constrained layout) runs
    within this one draw and measures the texts with that renderer, as
    ``savefig`` lays a figure out with the renderer of its format; but
    ``savefig`` lays it out in a draw of its own first and then draws it again,
    with a second renderer, so every text is measured twice. The figure's dpi
    and canvas are its own again afterwards; its texts are made drawable by its
    class (:func:`~flyopt.report.plots.standard.figure_class`).
    """
    from matplotlib.backend_bases import FigureCanvasBase

    class Measuring(FigureCanvasBase):
        """The canvas the layout engine asks for a renderer while the figure is drawn."""

        renderer: RendererBase | MixedModeRenderer | None = None

        def get_renderer(self) -> RendererBase | MixedModeRenderer | None:
            return self.renderer

    canvas, dpi = figure.canvas, figure.dpi
    measuring = Measuring(figure)  # the figure's canvas until the finally
    try:
        figure.dpi = VECTOR_DPI
        measuring.renderer = make_renderer()
        figure.draw(cast("RendererBase", measuring.renderer))  # a MixedModeRenderer passes each call on
    finally:
        figure.dpi = dpi
        figure.set_canvas(canvas)
