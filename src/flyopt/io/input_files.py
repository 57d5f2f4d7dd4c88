"""The files a scene reads: where they may be, what they may be, and how large.

A file named inside a scene (``points_file``, ``pressure_file``, a member's
``force_file``, ``[sweep] output``, ...) is relative to the scene file's
folder and must stay inside it once symbolic links are resolved: a scene
from elsewhere cannot read ``/etc/shadow`` nor write over ``../../x``. A path
given on the command line is the user's own and may go anywhere.

Every input (the scene file itself and each file it names) must be a regular
file (not a folder, FIFO or device such as ``/dev/zero``) of at most
:func:`max_file_bytes` bytes, checked before a byte is read; a table holds at
most :func:`max_table_rows` rows and :data:`MAX_TABLE_COLUMNS` columns. The first two limits are raised by an environment
variable (``FLYOPT_MAX_FILE_BYTES``, ``FLYOPT_MAX_TABLE_ROWS``), read here only.
"""

from __future__ import annotations

import os
import stat
import sys
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, clip, shorten

if TYPE_CHECKING:
    from collections.abc import Callable, Iterator

MAX_FILE_BYTES = 100_000_000
"""Default largest input file [bytes] (100 MB); ``FLYOPT_MAX_FILE_BYTES`` raises it."""

MAX_TABLE_ROWS = 2_000_000
"""Default largest table [rows], inline or in a CSV file; ``FLYOPT_MAX_TABLE_ROWS`` raises it."""

MAX_TABLE_COLUMNS = 1_000
"""Largest table [columns]: a result file of flyopt's has about 50 (one more per field a sweep varies); a CSV
of 20,000 columns took 22 s to refuse for want of its ``mass``, a sidecar naming a million columns 108 s."""

TABLE_ROW_BYTES = 1_000
"""Most bytes a table's rows take read, on average [bytes a row]: :func:`max_table_rows` of them is the most a
table read may take (a number 8 bytes, a text its characters; a row of a flyopt sweep's table takes some 400). A
Parquet file of 48 kB held 3,000 rows of one dictionary-encoded word of a megabyte: 4 GB read."""

FILE_BYTES_VARIABLE = "FLYOPT_MAX_FILE_BYTES"
TABLE_ROWS_VARIABLE = "FLYOPT_MAX_TABLE_ROWS"

QUOTE_FROM_FILE = 40
"""Longest quotation of a data file's text (a cell, a line) in a message [characters]."""


_READ: ContextVar[list[tuple[str, str]] | None] = ContextVar("flyopt_inputs_read", default=None)
"""The files :func:`read_input` has read inside :func:`recording_inputs`, or None outside it."""


@contextmanager
def recording_inputs() -> Iterator[list[tuple[str, str]]]:
    """Record each file :func:`read_input` reads within the block, as (the field that names it, its absolute path).

    The scene's loader records the data files a scene reads (:attr:`flyopt.io.scene.Scene.inputs`), so that
    no output replaces one of them (:func:`flyopt.outputs.files.check_not_scene`). The path is made absolute when
    read, so that it names the same file after the working folder changes (a notebook's ``os.chdir``).
    """
    read: list[tuple[str, str]] = []
    token = _READ.set(read)
    try:
        yield read
    finally:
        _READ.reset(token)


def max_file_bytes() -> int:
    """The largest input file [bytes]: ``FLYOPT_MAX_FILE_BYTES``, or :data:`MAX_FILE_BYTES`."""
    return _limit(FILE_BYTES_VARIABLE, MAX_FILE_BYTES)


def max_table_rows() -> int:
    """The largest table [rows]: ``FLYOPT_MAX_TABLE_ROWS``, or :data:`MAX_TABLE_ROWS`."""
    return _limit(TABLE_ROWS_VARIABLE, MAX_TABLE_ROWS)


def _limit(variable: str, default: int) -> int:
    text = os.environ.get(variable, "").strip()
    if not text:
        return default
    try:
        value = int(text.replace("_", ""))
    except ValueError:
        value = 0
    if value < 1:
        raise SceneError(
            "", f"the environment variable {variable} must be a whole number of at least 1, got {shorten(text)}"
        )
    return min(value, sys.maxsize - 1)  # beyond every file and table there is; a larger one overflows a size


def quote_from_file(text: str) -> str:
    """A piece of a data file (a cell, a line) as a message may quote it: at most 40 characters."""
    return shorten(text, QUOTE_FROM_FILE)


def inside_scene(raw: object, where: str, folder: Path, what: str = "file") -> Path:
    """The path a scene field names, relative to the scene's ``folder`` and kept inside it.

    Parameters
    ----------
    raw : object
        The field's value as written (a relative path).
    where : str
        The field, for messages (``torque.resisting.points_file``).
    folder : Path
        The folder of the scene file.
    what : str
        What the field names, for messages ("CSV file", "output file").

    Returns
    -------
    Path
        ``folder / raw``, as written (not resolved), for reading or writing.

    Raises
    ------
    SceneError
        Not a non-empty string, a NUL in it, an absolute path, or a path
        that leaves ``folder`` once ``..`` and symbolic links are resolved.
    """
    if not isinstance(raw, str) or not raw.strip():
        raise SceneError(where, f"must be the name of a {what} (a string), got {shorten(raw)}")
    allowed = "allowed: a path relative to the scene file's folder that stays inside it"
    if "\0" in raw:
        raise SceneError(where, f"{shorten(raw)} holds a NUL character ({allowed})")
    if os.path.isabs(raw) or raw.startswith("~"):
        raise SceneError(where, f"{shorten(raw)} is not relative to the scene file's folder ({allowed})")
    path = folder / raw
    try:
        root = folder.resolve()
        target = path.resolve()
    except (OSError, RuntimeError) as err:  # a loop of symbolic links
        raise SceneError(where, f"cannot resolve {shorten(raw)}: {getattr(err, 'strerror', None) or err}") from None
    if not target.is_relative_to(root):
        raise SceneError(where, f"{shorten(raw)} leads outside the scene file's folder ({allowed})")
    return path


def check_input(path: str | os.PathLike[str], where: str, name: str) -> int:
    """The size [bytes] of an input another reader will open (pandas, pyarrow), refused as :func:`read_input`
    refuses one: not a regular file (a FIFO would block that reader, ``/dev/zero`` fill its memory), or over the
    size cap. Checked on a descriptor opened without blocking."""
    descriptor, size = _open_input(path, lambda reason: SceneError(where, f"cannot read {name}: {reason}"))
    os.close(descriptor)
    return size


def _open_input(path: str | os.PathLike[str], refuse: Callable[[str], SceneError]) -> tuple[int, int]:
    """(an open descriptor, the size [bytes]) of an input: opened without blocking (a FIFO returns at once) and
    checked on that descriptor to be a regular file within :func:`max_file_bytes`; else ``refuse(reason)`` is
    raised, the descriptor closed. The caller closes the descriptor it gets."""
    limit = max_file_bytes()
    try:
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    except ValueError:  # a NUL in the path
        raise refuse("not a file name (it holds a NUL character)") from None
    except OSError as err:
        raise refuse(err.strerror or type(err).__name__) from None
    try:
        info = os.fstat(descriptor)
        if not stat.S_ISREG(info.st_mode):
            raise refuse(f"{_kind(info.st_mode)} (allowed: a regular file)")
        if info.st_size > limit:
            raise refuse(f"{info.st_size} bytes, over the limit of {limit} ({_raise_it(FILE_BYTES_VARIABLE)})")
    except OSError as err:
        os.close(descriptor)
        raise refuse(err.strerror or type(err).__name__) from None
    except SceneError:
        os.close(descriptor)
        raise
    return descriptor, info.st_size


def read_input(path: Path, where: str, name: str, encoding: str = "utf-8", source: str | None = None) -> str:
    """The text of an input file, refused before reading unless it is a regular file within the size cap.

    The file is opened without blocking (a FIFO returns at once) and checked
    on its open descriptor: a regular file of at most :func:`max_file_bytes`
    bytes; then at most that many bytes are read (a file growing meanwhile is
    refused too). Inside :func:`recording_inputs` the file read is recorded.

    Parameters
    ----------
    path : Path
    where : str
        The field that names the file ("" for the scene file itself).
    name : str
        The file as messages name it ("the file" for the scene file).
    encoding : str
    source : str, optional
        The scene file, for the message.

    Returns
    -------
    str

    Raises
    ------
    SceneError
        ``cannot read NAME: REASON``: it cannot be opened, is not a regular
        file, is over the size cap, or is not text in ``encoding``.
    """

    def refuse(reason: str) -> SceneError:
        return SceneError(where, f"cannot read {name}: {reason}", source)

    limit = max_file_bytes()
    descriptor, size = _open_input(path, refuse)
    try:
        with os.fdopen(descriptor, "rb", closefd=False) as handle:
            # the size it has, and a byte to see it grew: a read of the cap itself would reserve the cap
            data = handle.read(min(size, limit) + 1)
            while size < len(data) <= limit:  # it grew while read: on, a block at a time, to one byte over the cap
                more = handle.read(min(1 << 20, limit + 1 - len(data)))
                if not more:
                    break
                data += more
    except OSError as err:
        raise refuse(err.strerror or type(err).__name__) from None
    finally:
        os.close(descriptor)
    if len(data) > limit:
        raise refuse(f"over the limit of {limit} bytes ({_raise_it(FILE_BYTES_VARIABLE)})")
    read = _READ.get()
    if read is not None:
        read.append((where, os.path.abspath(path)))
    try:
        return data.decode(encoding)
    except UnicodeDecodeError:
        raise refuse("not UTF-8 text" if encoding.lower().startswith("utf") else f"not {encoding} text") from None


def check_rows(count: int, where: str, name: str = "the table") -> None:
    """Refuse a table of more than :func:`max_table_rows` rows (``count`` counted, or bounded, before parsing)."""
    limit = max_table_rows()
    if count > limit:
        raise SceneError(
            where, f"{clip(name)} has over {limit} rows (allowed: at most {limit}; {_raise_it(TABLE_ROWS_VARIABLE)})"
        )


def check_columns(count: int, where: str, name: str = "the table") -> None:
    """Refuse a table of more than :data:`MAX_TABLE_COLUMNS` columns (``count`` counted before its rows are read)."""
    if count > MAX_TABLE_COLUMNS:
        raise SceneError(where, f"{clip(name)} has {count} columns (allowed: at most {MAX_TABLE_COLUMNS})")


def check_read_bytes(count: int, where: str, name: str = "the table") -> None:
    """Refuse a table that would take more than :data:`TABLE_ROW_BYTES` a row of :func:`max_table_rows` read
    (``count`` bytes, counted before it is read)."""
    rows = max_table_rows()
    limit = rows * TABLE_ROW_BYTES
    if count > limit:
        raise SceneError(
            where,
            f"{clip(name)} would take {count:,} bytes read (allowed: at most {limit:,}, {TABLE_ROW_BYTES:,} a "
            f"row of the {rows:,} rows a table may have; {_raise_it(TABLE_ROWS_VARIABLE)})",
        )


def _raise_it(variable: str) -> str:
    return f"the environment variable {variable} raises it"


def _kind(mode: int) -> str:
    """What a file that is not a regular file is, as a refusal says it."""
    if stat.S_ISDIR(mode):
        return "Is a directory"  # the words of the system's own error for a folder
    kinds = ((stat.S_ISFIFO, "FIFO"), (stat.S_ISCHR, "device"), (stat.S_ISBLK, "device"), (stat.S_ISSOCK, "socket"))
    kind = next((name for test, name in kinds if test(mode)), "special file")
    return f"not a regular file but a {kind}"
