"""Writing a diagram to a file: the formats, the check of the output path before anything is computed, the atomic save."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from flyopt.errors import SceneError
from flyopt.report.plots import standard

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: Image formats :func:`save` writes, by the suffix of the file.
FORMATS = ("png", "svg", "pdf")


def check_output(path: str | os.PathLike[str]) -> None:
    """Check the file a diagram will go to, before anything is computed.

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


def save(ax: Axes, path: str | os.PathLike[str], dpi: float = 150) -> Path:
    """Write the Axes' figure to ``path`` (png, svg or pdf by suffix), atomically.

    Raises
    ------
    SceneError
        See :func:`check_output`.
    OSError
        The folder cannot be written; the error names ``path``.
    """
    check_output(path)
    from flyopt.outputs.files import replace_atomically

    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    fig = standard.figure_of(ax)
    try:
        replace_atomically(path, lambda tmp: fig.savefig(tmp, format=suffix, dpi=dpi))  # drawable: figure_class
    finally:
        standard.pyplot().close(fig)
    return path
