"""Output files written atomically: a temporary file beside the target, moved into place.

Nothing is left under the final name if writing fails or is interrupted, and
flyopt never creates a folder the user did not ask for (:func:`check_folder`).
An output replaces only a regular file: a folder, a device, a FIFO or a socket
at its path is refused (before anything is computed, and again at the rename),
and a symbolic link is followed, its target written atomically (the link stays).
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable
from pathlib import Path

from flyopt.errors import FlyoptError, OutputError, SceneError

__all__ = ["check_folder", "move_into_place", "output_target", "replace_atomically", "write_text"]


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

    replace_atomically(path, write, label=label)


def replace_atomically(
    path: Path,
    write: Callable[[Path], object],
    temporary_folder: str | os.PathLike[str] | None = None,
    label: str = "-o/--output",
) -> None:
    """Call ``write(tmp)`` on a temporary file, then move it to ``path`` (removed on any failure).

    A symbolic link at ``path`` is followed (:func:`output_target`); the file at the end is replaced
    only if it is a regular file, checked again just before the rename.
    """
    target = output_target(path)
    folder = target.parent if temporary_folder is None else Path(temporary_folder)
    tmp = folder / f"{target.name}.tmp-{os.getpid()}"
    try:
        try:
            write(tmp)
        except OSError as err:
            raise _output_error(err, path) from err
        move_into_place(tmp, path, label)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def move_into_place(tmp: Path, path: str | os.PathLike[str], label: str = "-o/--output") -> None:
    """The last step of every output: the finished temporary file ``tmp`` renamed to ``path`` (or to the
    target of a link there), which must be absent or a regular file (checked again now: a device or a
    folder put there meanwhile is not renamed over). A failure is an :class:`OutputError` naming ``path``."""
    target = output_target(path)
    _check_replaceable(target, path, label)
    try:
        os.replace(tmp, target)
    except OSError as err:
        raise _output_error(err, path) from err


def _output_error(err: OSError, path: str | os.PathLike[str]) -> OSError:
    """The error of an output that could not be written, naming the file the user named (not the
    temporary one): ``out.json: cannot be written: No space left on device``."""
    if isinstance(err, FlyoptError):
        return err
    return OutputError(err.errno, f"cannot be written: {err.strerror or err}", str(path))


def output_target(path: str | os.PathLike[str]) -> Path:
    """The file an output at ``path`` goes to: the end of a chain of symbolic links, else ``path`` itself."""
    path = Path(path)
    return Path(os.path.realpath(path)) if path.is_symlink() else path


def check_folder(path: str | os.PathLike[str], label: str = "output") -> None:
    """Check where an output goes, before anything is computed.

    Its folder must exist (flyopt does not create folders the user did not ask
    for), and whatever is at its path must be a regular file that it may
    replace: a folder, a device, a FIFO or a socket is refused. A symbolic
    link is followed to its target.
    """
    target = output_target(path)
    folder = target.parent
    if not folder.is_dir():
        raise SceneError(label, f"the folder {str(folder)!r} of {str(path)!r} does not exist")
    _check_replaceable(target, path, label)


def _check_replaceable(target: Path, path: str | os.PathLike[str], label: str) -> None:
    """A SceneError unless ``target`` is absent or a regular file."""
    try:
        mode = os.lstat(target).st_mode
    except FileNotFoundError:
        return
    if stat.S_ISREG(mode):
        return
    kind = (
        "folder"
        if stat.S_ISDIR(mode)
        else "device"
        if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
        else "FIFO"
        if stat.S_ISFIFO(mode)
        else "socket"
        if stat.S_ISSOCK(mode)
        else "special file"
    )
    raise SceneError(label, f"{str(path)!r} is a {kind}: an output is a new file or replaces a regular file")
