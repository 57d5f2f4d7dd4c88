"""Two-column CSV tables named by a scene field (``points_file``, a member's ``force_file``, ...).

Every wrong line is reported by its number, with what is allowed.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.errors import SceneError, clip
from flyopt.io.compiled_reader import compiled_numbers, compiled_reader_reads
from flyopt.io.input_files import check_rows, inside_scene, quote_from_file, read_input

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path


def csv_table(
    raw: object, where: str, files: Path, columns: Sequence[str], units: Sequence[str]
) -> tuple[npt.NDArray[np.float64], Sequence[int], str]:
    """The rows of a two-column CSV file named by a scene field (see :func:`read_csv`).

    Parameters
    ----------
    raw : object
        The field's value: a path, relative to the scene file's folder ``files``.
    where : str
        The field, for messages.
    files : Path
        The scene file's folder: the file must be inside it (see :func:`~flyopt.io.input_files.inside_scene`).
    columns, units : tuple of str
        What the two columns hold and their units as written (for messages).

    Returns
    -------
    numbers : ndarray, shape (n, 2)
    lines : sequence of int
        Line number of each row.
    name : str
        The file as messages name it.
    """
    path = inside_scene(raw, where, files, "CSV file")
    name = clip(str(path))
    text = read_input(path, where, name, encoding="utf-8-sig")
    # the lines bound the rows before they are read (one may be the header; a last line break ends a line);
    # the rows read are counted after ("\n" + 1 refused a header and 1,999,999 rows as over 2,000,000)
    check_rows(text.count("\n") + (0 if text.endswith("\n") else 1) - 1, where, name)
    numbers, lines = read_csv(text, where, name, columns, units)
    check_rows(len(numbers), where, name)
    return numbers, lines, name


def read_csv(
    text: str, where: str, name: str, columns: Sequence[str], units: Sequence[str]
) -> tuple[npt.NDArray[np.float64], Sequence[int]]:
    """The numbers of a two-column CSV table, and the line of each row.

    A header line (the first line with text, when it has a letter and none
    of its fields is a number), blank lines and lines starting with ``#``
    are skipped; lines end at
    ``\\n`` (a ``\\r`` before it is a blank). A clean file (a header at most,
    then one row ``angle,value`` per line) is read in one pass over its
    fields (by pyarrow's compiled reader when it is large, see
    :mod:`flyopt.io.compiled_reader`, else by ``float``); anything else, or a
    field either refuses, line by line, which names the first wrong line.
    Each gives the same rows: Python's ``float`` decides what is a number,
    and the compiled reader accepts only what it accepts, to the same double.

    Returns
    -------
    numbers : ndarray, shape (n, 2)
        Rows of the two columns (angle and value, speed and torque) in the file's units, n >= 2.
    lines : sequence of int
        Line number (from 1) of each row.
    """
    first = text.find("\n")
    header = _is_header(text if first < 0 else text[:first])
    offset = 2 if header else 1
    numbers = _compiled_rows(text, (first + 1 if first >= 0 else len(text)) if header else 0)
    if numbers is not None and np.isfinite(numbers).all():
        return numbers, range(offset, offset + len(numbers))
    if numbers is not None:  # each field a number, as float reads it: a NaN or infinity, named below
        return read_csv_lines(text.split("\n"), where, name, columns, units)
    body = (text[first + 1 :] if first >= 0 else "") if header else text
    body = body.rstrip()
    codes = np.frombuffer(body.encode("utf-8"), dtype=np.uint8)
    ends, commas = np.flatnonzero(codes == 10), np.flatnonzero(codes == 44)
    if len(commas) == len(ends) + 1 >= 2 and np.all(commas[:-1] < ends) and np.all(commas[1:] > ends):
        try:  # one comma on each line: rows of two fields
            numbers = np.array(body.replace("\n", ",").split(","), dtype=float)
        except ValueError:
            numbers = None
        if numbers is not None and np.isfinite(numbers).all():
            return numbers.reshape(-1, 2), range(offset, offset + len(commas))
    return read_csv_lines(text.split("\n"), where, name, columns, units)


def read_csv_lines(
    rows: Sequence[str], where: str, name: str, columns: Sequence[str], units: Sequence[str]
) -> tuple[npt.NDArray[np.float64], Sequence[int]]:
    """:func:`read_csv` line by line: the first wrong line, named, or the same numbers."""
    numbers, lines = [], []
    allowed = {k: f"a plain number, the {columns[k]} in {units[k]}" for k in (0, 1)}
    header = True  # the first line with text may name the columns
    for number, line in enumerate(rows, 1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if header:
            header = False
            if _is_header(line):
                continue
        fields = line.split(",")
        if len(fields) != 2:
            raise SceneError(
                where,
                f"{name} line {number}: expected 2 columns, {columns[0]} and {columns[1]} separated by "
                f"a comma, got {len(fields)}: {quote_from_file(stripped)}",
            )
        row = []
        for k, text in enumerate(fields):
            try:
                value = float(text)
            except ValueError:
                raise SceneError(
                    where,
                    f"{name} line {number}, column {k + 1}: {quote_from_file(text.strip())} is not a "
                    f"number (allowed: {allowed[k]})",
                ) from None
            if not math.isfinite(value):
                raise SceneError(
                    where,
                    f"{name} line {number}, column {k + 1}: {quote_from_file(text.strip())} is not "
                    f"finite (allowed: {allowed[k]})",
                )
            row.append(value)
        numbers.append(row)
        lines.append(number)
    if len(numbers) < 2:
        found = f"only line {lines[0]} holds one" if numbers else "there is none"
        first = "at angle 0, the last at the cycle angle" if columns[0] == "angle" else "at rest"
        raise SceneError(
            where, f"{name}: a table needs at least two rows of {columns[0]},{columns[1]} (the first {first}); {found}"
        )
    return np.array(numbers), lines


def _compiled_rows(text, start):
    """The rows of ``text[start:]`` (blanks at its end left out) by the compiled reader, or None.

    None for a table the compiled reader does not read (:func:`~flyopt.io.compiled_reader.compiled_reader_reads`),
    one not in ASCII, one with a carriage return not before a newline (pyarrow
    would end a line there, Python's ``split`` does not), one ending in 64
    blanks, and one whose lines are not each two fields the compiled reader
    takes for numbers: all these are read by ``float``.
    """
    if not compiled_reader_reads(len(text)) or not text.isascii():
        return None
    if "\r" in text and text.count("\r") != text.count("\r\n"):
        return None
    tail = text[-64:]
    kept = len(tail.rstrip())  # str.rstrip's blanks, as the body's rstrip
    if kept == 0:
        return None
    data = memoryview(text.encode("ascii"))[start : len(text) - len(tail) + kept]
    numbers = compiled_numbers(data, None, 2)  # each line a row: a line of other than two fields is refused
    return numbers if numbers is not None and len(numbers) >= 2 else None  # fewer: said by the exact reader


def _has_letter(line):
    """Whether ``line`` holds a letter (``str.isalpha``). An ASCII line has one exactly where its upper and lower
    cases differ: two passes in C, where a test of each character took 9 s of a hostile 50 MB first line (and
    `flyopt check` near its 10 s limit in tools/hostile.py); other text is tested character by character."""
    if line.isascii():
        return line.upper() != line.lower()
    return any(map(str.isalpha, line))


def _is_header(line):
    """A first line naming the columns: it has a letter, and none of its comma-separated fields is a number."""
    if line.lstrip().startswith("#") or not _has_letter(line):
        return False
    for text in line.split(","):
        try:
            float(text)
            return False
        except ValueError:
            pass
    return True
