"""Writing a diagram to a file: the formats, the check of the output path before anything is computed, the atomic save."""

from __future__ import annotations

import os
import tempfile
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
    path = Path(path)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise SceneError("-o/--output", f"{str(path)!r} must end in .png, .svg or .pdf (the suffix picks the format)")
    folder = path.parent
    if not folder.is_dir():
        raise SceneError("-o/--output", f"the folder {str(folder)!r} does not exist")


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
    path = Path(path)
    suffix = path.suffix.lower().lstrip(".")
    fig = standard.figure_of(ax)
    try:
        handle, tmp = tempfile.mkstemp(suffix=path.suffix, dir=path.parent)
    except OSError as err:
        standard.pyplot().close(fig)
        raise OSError(err.errno, err.strerror, str(path)) from err
    os.close(handle)
    try:
        standard.make_drawable(fig).savefig(tmp, format=suffix, dpi=dpi)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
        standard.pyplot().close(fig)
    return path
