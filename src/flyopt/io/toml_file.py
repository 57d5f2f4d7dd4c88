"""Reading a scene file's TOML: ``tomllib``, with large inline tables of plain numbers read by string handling.

A table ``points = [[0, 150], [5, 152.5], ...]`` of 10,000 rows takes
``tomllib`` 60 ms; :func:`parse_toml` cuts such tables out and reads them
with ``float``, or a large one with pyarrow's compiled reader (the same
floats), leaving everything else to ``tomllib``.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from flyopt._toml import tomllib
from flyopt.errors import SceneError, clip
from flyopt.io.compiled_reader import compiled_numbers, compiled_reader_reads
from flyopt.io.input_files import read_input

if TYPE_CHECKING:
    import os


def read_toml(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The contents of a TOML scene file, as ``tomllib`` reads them.

    Large tables of plain numbers (``points = [[0, 150], [5, 152.5], ...]``,
    a member's ``force = [[...]]``, ...) are read by string handling and
    ``float`` instead of ``tomllib``, which takes 60 ms for 10,000 rows; such a
    table comes back as an :class:`InlineRows` that :func:`flyopt.io.scene.from_dict` reads as
    the list it stands for (see :func:`parse_toml`).

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    dict

    Raises
    ------
    SceneError
        The file cannot be read (not a regular file, over the size cap of
        :func:`~flyopt.io.input_files.max_file_bytes`) or is not TOML (the
        message names the file).
    """
    path = Path(path)
    # a byte-order mark (Windows Notepad's "UTF-8 with BOM") is no TOML statement: "Invalid statement at line 1"
    text = read_input(path, "", "the file", source=str(path)).removeprefix("\ufeff")
    try:
        data = parse_toml(text)
    except SceneError as err:
        raise err.with_source(str(path)) from None
    except tomllib.TOMLDecodeError as err:
        raise SceneError("", f"not valid TOML: {err}", str(path)) from None
    except ValueError as err:  # an integer of over 4300 digits
        raise SceneError("", f"not a scene: {_too_long_integer(text) or clip(str(err))}", str(path)) from None
    except (RecursionError, MemoryError):
        raise SceneError(
            "",
            f"not a scene: arrays or tables nested too deeply (or too large) to read ({len(text)} characters)",
            str(path),
        ) from None
    too_deep = _too_deep(data)
    if too_deep is not None:
        raise SceneError(too_deep, f"nests tables or arrays more than {MAX_DEPTH} deep: not a scene", str(path))
    return data


def _too_long_integer(text: str) -> str:
    """Where the text holds a whole number longer than Python converts (4,300 digits), in words; "" if nowhere:
    the message of the conversion named neither the field nor the line. Each long line is searched once, its
    strings and comment left out (a digit run there is no number), by patterns that cannot backtrack: one that
    could took 17 s over 50 comment lines of 4,300 digits."""
    limit = sys.get_int_max_str_digits()
    for number, line in enumerate(text.split("\n"), 1):
        if len(line) <= limit:
            continue
        for run in _DIGIT_RUN.finditer(_NOT_A_NUMBER.sub(" ", line)):
            digits = len(run.group()) - run.group().count("_")
            if digits > limit:
                return f"a whole number of {digits:,} digits at line {number} (allowed: at most {limit:,} digits)"
    return ""


#: A run of digits, underscores between them (TOML's 1_000).
_DIGIT_RUN = re.compile(r"[0-9][0-9_]*")
#: What on a TOML line holds no number: a quoted string, or the comment.
_NOT_A_NUMBER = re.compile(r'"(?:[^"\\]|\\.)*"|\'[^\']*\'|#.*')


MAX_DEPTH = 32
"""The deepest a scene's tables and arrays nest (its deepest, a shaft's train or a mechanism's member, is
under 8): deeper, every reader of the scene that walks it (its error messages, the sweep's keys) would recurse
hundreds of levels, and ``tomllib`` takes seconds and gigabytes for a dotted key thousands of keys long."""

#: A bare or quoted key of a dotted key or table header ("a", 'b', "c d").
_KEY_PART = r"""(?:[A-Za-z0-9_-]++|"[^"\n]*+"|'[^'\n]*+')"""
#: A dotted key of more than MAX_DEPTH parts, at a line's start (``a.b.c = ``, ``[a.b.c]``, ``[[a.b.c]]``) or
#: in an inline table (``{a.b.c = ``): no scene's text has one elsewhere but in a string of such a form.
_DEEP_KEY = re.compile(
    rf"(?:^[ \t]*+\[?+\[?+|[{{,])[ \t]*+{_KEY_PART}(?:[ \t]*+\.[ \t]*+{_KEY_PART}){{{MAX_DEPTH},}}+",
    re.MULTILINE,
)


def _key_of(dotted: str, parts: int = 4) -> str:
    """The first ``parts`` keys of a dotted key as the field to name ("machine.speed.a.a…")."""
    keys = [key.strip().strip("\"'") for key in dotted.lstrip(" \t[{,").split(".")]
    return ".".join(keys[:parts]) + "…"


def _too_deep(data: dict[str, Any]) -> str | None:
    """The path of the first value nested more than :data:`MAX_DEPTH` tables or arrays deep (its first four
    keys or indices), or None (a walk of its own stack: no recursion)."""
    stack: list[tuple[Any, tuple[str, ...]]] = [(data, ())]
    while stack:
        value, where = stack.pop()
        if len(where) > MAX_DEPTH:
            shown = "".join(part if part.startswith("[") else f".{part}" for part in where[:4]).lstrip(".")
            return shown + "…"
        if isinstance(value, dict):
            stack.extend((item, (*where, str(key))) for key, item in value.items())
        elif isinstance(value, list):
            stack.extend((item, (*where, f"[{k}]")) for k, item in enumerate(value))
    return None


FAST_TABLE_CHARACTERS = 2000
"""Inline tables at least this long [characters] are read without ``tomllib`` (shorter ones: no gain)."""

#: A TOML number of the forms tables use: an integer without leading zeros, a fraction, an
#: exponent (no "_", "inf", "nan", hex: those go to tomllib). Possessive: no backtracking.
_TOML_NUMBER = r"[+-]?+(?:0|[1-9][0-9]*+)(?:\.[0-9]++)?+(?:[eE][+-]?+[0-9]++)?+"
_TOML_BLANK = r"[ \t\r\n]*+"
_TOML_PAIR = (
    rf"\[{_TOML_BLANK}{_TOML_NUMBER}{_TOML_BLANK},{_TOML_BLANK}{_TOML_NUMBER}{_TOML_BLANK}(?:,{_TOML_BLANK})?+\]"
)
_TOML_PAIRS = re.compile(
    rf"\[{_TOML_BLANK}{_TOML_PAIR}(?:{_TOML_BLANK},{_TOML_BLANK}{_TOML_PAIR})*+{_TOML_BLANK}"
    rf"(?:,{_TOML_BLANK})?+\]"
)
_TABLE_KEY = re.compile(r"^[ \t]*(?:points|force|torque|velocity_ratio|angular_ratio)[ \t]*=[ \t]*(?=\[)", re.MULTILINE)
_BRACKETS = str.maketrans("[],", "   ")
_ONE_A_LINE = bytes.maketrans(b"[],", b"\n\n\n")


class InlineRows:
    """A large inline table ``[[a, b], ...]`` of plain numbers, read without ``tomllib``.

    Stands for the list of pairs ``tomllib`` would have given: :func:`flyopt.io.angle_tables.angle_curve`
    and the [[member]] tables of :mod:`flyopt.io.member_section` read it as that list (the same floats: TOML
    and Python's ``float`` round a decimal the same way).

    Attributes
    ----------
    array : ndarray, shape (n, 2)
        The numbers, as ``float`` of each TOML number (an integer ``-0`` is 0.0, as ``float(0)``).
    """

    __slots__ = ("array",)

    def __init__(self, array: npt.NDArray[np.float64]) -> None:
        self.array = array

    def __len__(self) -> int:
        return len(self.array)

    def __repr__(self) -> str:
        return f"a table of {len(self.array)} rows"


def parse_toml(text: str) -> dict[str, Any]:
    """``tomllib.loads(text)``, with every large table of plain-number pairs read by :func:`_fast_rows`.

    Each such table (``KEY = [[number, number], ...]`` at the start of a
    line, KEY one of points, force, torque, velocity_ratio, angular_ratio,
    blanks and newlines only between its items, at least
    ``FAST_TABLE_CHARACTERS`` long) is cut out of the text and replaced by a
    unique string; ``tomllib`` reads the rest, and each string, found exactly
    once as a value, becomes the :class:`InlineRows` of its table. Anything
    else (a comment inside the table, a unit string, a text in which a
    replacement is not found as one value, e.g. inside a multi-line string)
    is left to ``tomllib`` whole, so what is read, and every error, is
    ``tomllib``'s.
    """
    tables: dict[str, Any] = {}
    pieces: list[str] = []
    end = 0
    nonce = None
    key = _TABLE_KEY.search(text)
    while key is not None:
        match = _TOML_PAIRS.match(text, key.end())
        rows = None
        if match is not None and match.end() - match.start() >= FAST_TABLE_CHARACTERS:
            rows = _fast_rows(match.group())
        if match is not None and rows is not None:
            if nonce is None:
                nonce = _nonce(text)
            marker = f"flyopt-table-{nonce}-{len(tables)}"
            tables[marker] = rows
            pieces += [text[end : match.start()], f'"{marker}"']
            end = match.end()
        key = _TABLE_KEY.search(text, match.end() if match is not None and rows is not None else key.end())
    if not tables:
        return _loads(text)
    try:
        data = _loads("".join(pieces) + text[end:])
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return _loads(text)
    expected = len(tables)
    if _put_rows(data, tables) != expected:
        return _loads(text)
    return data


def _loads(text: str) -> dict[str, Any]:
    """``tomllib.loads(text)``, a dotted key of more than :data:`MAX_DEPTH` parts refused first (SceneError, no
    file named): ``tomllib``'s time and memory grow with the square of its length (37 s and 2.4 GB for
    20,000 parts). Run on what ``tomllib`` reads: the large tables :func:`parse_toml` cuts out are not
    searched (a search of 40 MB takes some 2 s)."""
    deep = _DEEP_KEY.search(text)
    if deep is not None:
        raise SceneError("", f"not a scene: the key {_key_of(deep.group())} nests tables more than {MAX_DEPTH} deep")
    return tomllib.loads(text)


def _fast_rows(table):
    """The :class:`InlineRows` of a matched ``[[a, b], ...]`` text, or None to leave it to tomllib.

    None for a carriage return not followed by a newline (not TOML), and for
    a number beyond the floats (tomllib and the field's checks say what is wrong).
    A table the compiled reader reads (a large one, or a smaller one where pyarrow is imported already:
    :func:`flyopt.io.compiled_reader.compiled_reader_reads`) is read by pyarrow: the pattern has already decided that
    each number is a TOML number, which that reader and ``float`` read to
    the same double; a table holding a zero with a minus sign is read by
    ``float``, which keeps the written text to tell ``-0`` from ``-0.0``.
    """
    if "\r" in table and table.count("\r") != table.count("\r\n"):
        return None
    if compiled_reader_reads(len(table)):  # ASCII (the pattern), one number a line for the compiled reader
        numbers = compiled_numbers(
            table.encode("ascii").translate(_ONE_A_LINE, b" \t\r"), 2 * table.count("[") - 2, 1, skip_empty=True
        )
        if numbers is not None and not np.isfinite(numbers).all():
            return None  # the compiled reader's doubles are float's
        if numbers is not None and not np.signbit(numbers[numbers == 0]).any():
            return InlineRows(numbers.reshape(-1, 2))  # a -0 (integer or not?) is told below
    tokens = table.translate(_BRACKETS).split()
    numbers = np.array(tokens, dtype=float)
    if not np.isfinite(numbers).all():
        return None
    for k in np.flatnonzero((numbers == 0) & np.signbit(numbers)):
        if tokens[k].lstrip("+-").isdigit():  # the integer -0 is 0 in TOML, and float(0) is 0.0
            numbers[k] = 0.0
    return InlineRows(numbers.reshape(-1, 2))


def _nonce(text):
    """A string that does not occur in ``text`` (for the markers of :func:`parse_toml`)."""
    k = 0
    while f"flyopt-table-{k}x" in text:
        k += 1
    return f"{k}x"


def _put_rows(data, tables):
    """Replace each marker string of ``tables`` in the parsed ``data`` by its rows; the count replaced."""
    found = 0
    items = data.items() if isinstance(data, dict) else enumerate(data)
    for key, value in items:
        if isinstance(value, str):
            if value in tables:
                data[key] = tables.pop(value)
                found += 1
        elif isinstance(value, (dict, list)):
            found += _put_rows(value, tables)
    return found
