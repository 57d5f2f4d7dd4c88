"""Output files written atomically: a temporary file beside the target, moved into place.

Nothing is left under the final name if writing fails or is interrupted, and
flyopt never creates a folder the user did not ask for (:func:`check_folder`).
An output replaces only a regular file: a folder, a device, a FIFO or a socket
at its path is refused (before anything is computed, and again at the rename),
and a symbolic link is followed, its target written atomically (the link stays).

Every temporary file is new (:class:`Temporary`): created by this process
alone (``O_CREAT | O_EXCL``, under a name no other run predicts), so a link or
a file planted where a temporary goes is neither followed nor overwritten, and
what is renamed into place is checked to be the file that was created.
"""

from __future__ import annotations

import errno
import os
import secrets
import stat
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, BinaryIO

from flyopt.errors import FlyoptError, OutputError, SceneError, shorten

if TYPE_CHECKING:
    from flyopt.io.scene import Scene

__all__ = [
    "Temporary",
    "check_folder",
    "check_not_scene",
    "move_into_place",
    "output_error",
    "output_target",
    "replace_atomically",
    "write_atomically",
    "write_text",
]

#: The flags of a new temporary file: created here or not at all, never through a link.
_NEW_FILE = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)

#: The longest name of a file (bytes; POSIX's NAME_MAX on the file systems flyopt writes to).
_NAME_MAX = 255


class Temporary:
    """A new file for the output at ``path``, in ``folder`` (default: beside the file it becomes).

    Created exclusively (``O_CREAT | O_EXCL | O_NOFOLLOW``) under the name
    ``NAME.tmp-PID-RANDOM``: whatever already has a name tried (a planted link,
    a file) is left alone and another name is tried. :attr:`handle` writes to the
    file that was created; :meth:`finish` renames that same file into place (a
    file swapped in under its name meanwhile is refused), :meth:`discard` removes it.

    Raises
    ------
    OutputError
        The file cannot be created (no permission, a full disk), naming ``path``.
    """

    #: Names tried before giving up (each a fresh random one).
    ATTEMPTS = 100

    def __init__(
        self, path: str | os.PathLike[str], folder: str | os.PathLike[str] | None = None, own_name: bool = False
    ) -> None:
        self.own_name = own_name  # a name flyopt made (check_not_a_link): never through a link, at no time
        self.target = Path(path) if own_name else output_target(path)
        self.named = Path(path)
        place = self.target.parent if folder is None else Path(folder)
        for _ in range(self.ATTEMPTS):
            candidate = place / _temporary_name(self.target.name)
            try:
                fd = os.open(candidate, _NEW_FILE, 0o666)
            except FileExistsError:
                continue
            except OSError as err:
                if err.errno == errno.ELOOP:  # a link at the name (O_NOFOLLOW): try another
                    continue
                raise output_error(err, path) from err
            break
        else:
            raise OutputError(errno.EEXIST, "cannot be written: no new temporary file could be created", str(path))
        self.path = candidate
        self._identity = _identity(os.fstat(fd))
        self.handle: BinaryIO = os.fdopen(fd, "wb")

    def write(self, data: bytes) -> None:
        """Write ``data`` to the file (an ``OSError`` is an :class:`OutputError` naming the output)."""
        try:
            self.handle.write(data)
        except OSError as err:
            raise output_error(err, self.named) from err

    def close(self) -> None:
        """Close :attr:`handle` (for a writer that opens the file by its name)."""
        if not self.handle.closed:
            self.handle.close()

    def finish(self, label: str = "-o/--output") -> None:
        """Close the file and rename it to the output (:func:`move_into_place`); removed on any failure."""
        try:
            try:
                self.close()
                now = os.lstat(self.path)
            except OSError as err:
                raise output_error(err, self.named) from err
            if not stat.S_ISREG(now.st_mode) or _identity(now) != self._identity:
                raise OutputError(
                    errno.EEXIST,
                    f"cannot be written: its temporary file {self.path.name!r} was replaced by another while writing",
                    str(self.named),
                )
            move_into_place(self.path, self.named, label, self.own_name)
        except BaseException:
            self.discard()
            raise

    def discard(self) -> None:
        """Close and remove the file (nothing else: an unlink never follows a link)."""
        try:
            self.close()
        except OSError:
            pass
        finally:
            self.path.unlink(missing_ok=True)


def _temporary_name(name: str) -> str:
    """``NAME.tmp-PID-RANDOM``, ``NAME`` cut so that the whole stays within a file name's length."""
    tail = f".tmp-{os.getpid()}-{secrets.token_hex(6)}"
    room = _NAME_MAX - len(os.fsencode(tail))
    while name and len(os.fsencode(name)) > room:
        name = name[:-1]
    return name + tail


def _identity(status: os.stat_result) -> tuple[int, int]:
    return status.st_dev, status.st_ino


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
    data = text.encode("utf-8")  # before any file is made: a text that cannot be written leaves none
    if text and not text.endswith("\n"):
        data += b"\n"
    write_atomically(path, lambda handle: handle.write(data), label=label)


def write_atomically(
    path: str | os.PathLike[str],
    write: Callable[[BinaryIO], object],
    temporary_folder: str | os.PathLike[str] | None = None,
    label: str = "-o/--output",
    own_name: bool = False,
) -> None:
    """Call ``write(handle)`` on a new temporary file (:class:`Temporary`, binary), then move it to ``path``.

    The temporary file is removed on any failure; an ``OSError`` while writing is an
    :class:`OutputError` naming ``path``. ``own_name``: a name flyopt made, never written through a link
    (:func:`check_not_a_link`).
    """
    temporary = Temporary(path, temporary_folder, own_name)
    try:
        try:
            write(temporary.handle)
            temporary.close()  # a full disk may only show when the last bytes are flushed
        except OSError as err:
            raise output_error(err, path) from err
    except BaseException:
        temporary.discard()
        raise
    temporary.finish(label)


def replace_atomically(
    path: Path,
    write: Callable[[Path], object],
    temporary_folder: str | os.PathLike[str] | None = None,
    label: str = "-o/--output",
) -> None:
    """Call ``write(tmp)`` on a new temporary file, then move it to ``path`` (removed on any failure).

    For a writer that opens a file by its name: ``tmp`` was created empty by this process
    (:class:`Temporary`) and is renamed only if it is still that file. A symbolic link at
    ``path`` is followed (:func:`output_target`); the file at the end is replaced only if it
    is a regular file, checked again just before the rename.
    """
    temporary = Temporary(path, temporary_folder)
    try:
        temporary.close()
        try:
            write(temporary.path)
        except OSError as err:
            raise output_error(err, path) from err
    except BaseException:
        temporary.discard()
        raise
    temporary.finish(label)


def move_into_place(
    tmp: Path, path: str | os.PathLike[str], label: str = "-o/--output", own_name: bool = False
) -> None:
    """The last step of every output: the finished temporary file ``tmp`` renamed to ``path`` (or to the
    target of a link there), which must be absent or a regular file (checked again now: a device or a
    folder put there meanwhile is not renamed over). A failure is an :class:`OutputError` naming ``path``.
    ``own_name``: a name flyopt made, where a link is refused (:func:`check_not_a_link`, again now) and the
    rename never follows one (a link put there after the check is replaced, in its folder)."""
    if own_name:
        check_not_a_link(path, label)
    target = Path(path) if own_name else output_target(path)
    _check_replaceable(target, path, label)
    try:
        os.replace(tmp, target)
    except OSError as err:
        raise output_error(err, path) from err


def output_error(err: OSError, path: str | os.PathLike[str]) -> OSError:
    """The error of an output that could not be written, naming the file the user named (not the
    temporary one): ``out.json: cannot be written: No space left on device``."""
    if isinstance(err, FlyoptError):
        return err
    return OutputError(err.errno, f"cannot be written: {err.strerror or err}", str(path))


def output_target(path: str | os.PathLike[str]) -> Path:
    """The file an output at ``path`` goes to: the end of a chain of symbolic links, else ``path`` itself."""
    path = Path(path)
    return Path(os.path.realpath(path)) if path.is_symlink() else path


def check_not_a_link(path: str | os.PathLike[str], label: str = "-o/--output") -> None:
    """Refuse a symbolic link at a file flyopt names itself (a diagram of ``--what all`` in the folder given, a
    CSV's sidecar ``FILE.csv.json``): the user named the folder or the table, not this file, so where a link there
    leads is no place they pointed at (a diagram was written through a planted link out of the folder).

    Raises
    ------
    SceneError
        Field ``label``: the link, and what to do.
    """
    if os.path.islink(path):
        raise SceneError(
            label,
            f"{str(path)!r} is a symbolic link: flyopt writes the files it names itself beside the output given, "
            "never through a link; remove it",
        )


def check_file_name(text: str, label: str) -> None:
    """Refuse an output's name that names no file: ``-`` (stdout to many tools), one ending in a separator (a
    folder's: it was written as the file without it) or one holding a control character (SceneError naming
    ``label``). :func:`check_folder` of the command line's outputs, and a scene's ``[sweep] output`` before it
    is resolved in the scene's folder."""
    if text == "-":  # many tools read it as stdout; here it would be a file named "-"
        raise SceneError(label, "'-' is no file's name: leave the option out to print to stdout, or name a file")
    if text.endswith(("/", os.sep)):
        raise SceneError(label, f"{text!r} names a folder (it ends in {text[-1]!r}): give a file's name")
    control = next((c for c in text if _acting(c)), None)
    if control is not None:  # a line break in a name splits every line that quotes it; NUL ends it
        raise SceneError(label, f"{shorten(text)} holds the control character {ascii(control)}: give a printable name")


def check_folder(path: str | os.PathLike[str], label: str = "output", beside: tuple[str, ...] = ()) -> None:
    """Check where an output goes, before anything is computed.

    Its folder must exist (flyopt does not create folders the user did not ask
    for), and whatever is at its path must be a regular file that it may
    replace: a folder, a device, a FIFO or a socket is refused. A symbolic
    link is followed to its target. A name that ends in a separator ("out/") names a folder, not a file:
    refused, not written as the file ``out``. A name is printable (no control character, line or paragraph
    separator, nor a byte 0x80-0x9f of a name that is no UTF-8) and fits the file system's length, with the
    longest of the suffixes ``beside`` it that flyopt writes next to it (a sweep's ``.parts`` folder).
    """
    text = os.fspath(path)
    check_file_name(text, label)
    name = os.path.basename(text)
    suffix = max(beside, key=len, default="")
    size, limit = len(os.fsencode(name + suffix)), _name_max(os.path.dirname(text) or ".")
    if size > limit:  # before the path is resolved, which the system refuses in its own words
        with_suffix = f" with the {suffix!r} flyopt writes beside it" if suffix else ""
        raise SceneError(
            label,
            f"the file name {name[:40]!r}... is {size} bytes long{with_suffix}: the file system takes at most {limit}",
        )
    target = output_target(path)
    folder = target.parent
    if not folder.is_dir():
        raise SceneError(label, f"the folder {str(folder)!r} of {str(path)!r} does not exist")
    _check_replaceable(target, path, label)


def _acting(c: str) -> bool:
    """Whether a character of a file's name acts instead of showing: a C0 or C1 control, DEL, a line or paragraph
    separator, or a byte 0x80-0x9f of a name that is no UTF-8 (Python's surrogate escape of it: a C1 control to
    an 8-bit terminal)."""
    return c < " " or "\x7f" <= c <= "\x9f" or c in "\u2028\u2029" or "\udc80" <= c <= "\udc9f"


def _name_max(folder: str) -> int:
    """The longest file name [bytes] the file system of ``folder`` takes (POSIX's 255 where it does not say)."""
    try:
        return int(os.pathconf(folder, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return 255


def check_not_scene(
    path: str | os.PathLike[str], scene: str | os.PathLike[str] | Scene, what: str, label: str = "-o/--output"
) -> None:
    """Refuse an output that would replace an input: the scene file, or, given the loaded :class:`Scene`, a data
    file it read too (:attr:`~flyopt.io.scene.Scene.inputs`: a ``points_file``, a ``force_file``, ...), whose
    field the message names. ``what`` the output would be ("the report") goes in the message, which asks for
    another file. The same file by another path counts as it: a symbolic link to it, a hard link, another case of
    its name on a file system that ignores case."""
    inputs: tuple[tuple[str, str], ...] = ()
    source: str | os.PathLike[str] | None = None
    if isinstance(scene, (str, os.PathLike)):
        source = scene
    else:
        source, inputs = scene.source, scene.inputs
    if source is not None and _same_file(path, source):
        raise SceneError(label, f"{str(path)!r} is the scene file itself: name another file for {what}")
    for field, read in inputs:
        if _same_file(path, read):
            raise SceneError(
                label, f"{str(path)!r} is the file the scene's {field} names, an input: name another file for {what}"
            )


def _same_file(path: str | os.PathLike[str], other: str | os.PathLike[str]) -> bool:
    """Whether ``path`` names the file ``other`` names: the same real path, or, both existing, the same file
    (device and inode: a hard link, or a name in another case where the file system ignores case)."""
    if os.path.realpath(path) == os.path.realpath(other):
        return True
    try:
        return os.path.samefile(path, other)
    except (OSError, ValueError):  # either is absent (an output yet to be made), or a NUL in a name
        return False


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
