"""Output files written atomically: a temporary file beside the target, moved into place.

Nothing is left under the final name if writing fails or is interrupted, and
flyopt never creates a folder the user did not ask for (:func:`check_folder`).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from flyopt.errors import SceneError

__all__ = ["check_folder", "replace_atomically", "write_text"]


def write_text(path: str | os.PathLike[str], text: str, label: str = "-o/--output") -> None:
    """Write ``text`` to ``path`` atomically: a temporary file beside it, moved into place.

    Nothing is left under the final name if writing fails or is interrupted.

    Raises
    ------
    SceneError
        Field ``label``: the folder of ``path`` does not exist.
    """
    path = Path(path)
    check_folder(path, label)

    def write(tmp: Path) -> None:
        with open(tmp, "w", encoding="utf-8") as handle:
            handle.write(text)
            if text and not text.endswith("\n"):
                handle.write("\n")

    replace_atomically(path, write)


def replace_atomically(
    path: Path, write: Callable[[Path], object], temporary_folder: str | os.PathLike[str] | None = None
) -> None:
    """Call ``write(tmp)`` on a temporary file, then move it to ``path`` (removed on any failure)."""
    folder = path.parent if temporary_folder is None else Path(temporary_folder)
    tmp = folder / f"{path.name}.tmp-{os.getpid()}"
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def check_folder(path: str | os.PathLike[str], label: str = "output") -> None:
    """The folder of an output must exist: flyopt does not create folders the user did not ask for."""
    folder = Path(path).parent
    if not folder.is_dir():
        raise SceneError(label, f"the folder {str(folder)!r} of {str(path)!r} does not exist")
