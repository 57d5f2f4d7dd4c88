"""Large tables of numbers read by a compiled reader: pyarrow's CSV reader, imported only for them (or
smaller ones in a process that has imported pyarrow already: :func:`compiled_reader_reads`).

A table of 10⁶ rows takes Python's ``float`` (one call per number, however
it is driven: ``np.array`` of the strings, ``np.loadtxt``, ``np.fromstring``)
about a second; pyarrow's CSV reader, already a dependency of flyopt for the
studies' Parquet files, reads it in about 0.1 s. It is only a fast path: what
it accepts, Python's ``float`` accepts too and reads to the same double (both
round a decimal correctly; ``tests/io/test_compiled_reader.py`` holds them
to it), and whatever it refuses goes to the exact reader of its caller,
which decides what is allowed and says what is wrong. The rules of a table
are not here.
"""

from __future__ import annotations

import sys

import numpy as np
import numpy.typing as npt

COMPILED_READER_BYTES = 1_000_000
"""Tables of at least this many bytes (about 25,000 rows) are read by pyarrow: below it, importing
pyarrow (about 35-60 ms in a fresh process) costs more than the compiled reader saves.

The reader runs in the calling thread: on a 2-core host shared with a sweep's
workers, pyarrow's thread pool took as much CPU and more wall-clock time."""

LOADED_READER_BYTES = 30_000
"""Tables of at least this many bytes are read by pyarrow where it is already imported (pandas imports it,
and so do a sweep's Parquet files and the app): what is left is ``pyarrow.csv`` (about 1 ms, once) and the
reader's own start, about 0.4 ms a table. Measured on 2026-11-30, ``float`` took 0.41 ms for a table of
12 kB (300 rows of 17-digit numbers: the compiled reader 0.47 ms) and 0.68 ms for one of 16 kB (1,000 rows
of one decimal: 0.55 ms); at 40-50 kB the compiled reader took 0.45-0.55 of float's time, at 120 kB 0.3."""


def compiled_reader_reads(size: int) -> bool:
    """Whether a table of ``size`` bytes (or characters) is read by the compiled reader (the one rule of its
    callers): from :data:`COMPILED_READER_BYTES`, or from :data:`LOADED_READER_BYTES` in a process that has
    imported pyarrow already (not one that blocks it, ``sys.modules["pyarrow"] = None``). The answer never
    imports it."""
    return size >= COMPILED_READER_BYTES or (size >= LOADED_READER_BYTES and sys.modules.get("pyarrow") is not None)


def compiled_numbers(
    data: bytes | memoryview, rows: int | None, columns: int, skip_empty: bool = False
) -> npt.NDArray[np.float64] | None:
    """The ``rows`` × ``columns`` numbers of ``data``, or None where the compiled reader refuses a field.

    Parameters
    ----------
    data : bytes or memoryview
        ASCII text of ``rows`` lines of ``columns`` comma-separated numbers,
        lines ending at ``\\n`` or ``\\r\\n`` (pyarrow also ends a line at a
        lone ``\\r``: the caller refuses one). A quote is a character like
        any other (not a number); a line of another number of fields, or an
        empty line unless ``skip_empty``, is refused.
    rows : int or None
        The lines the caller counted (None: any number): another count read is a refusal.
    columns : int
        The fields of each line: a line of another number of fields is a refusal.
    skip_empty : bool
        Skip empty lines instead of refusing them.

    Returns
    -------
    ndarray, shape (rows, columns), or None
        The doubles of the fields (infinities and NaNs as written: the caller
        refuses them), or None if a field is not a number to the compiled
        reader, or the shape differs: the caller's exact reader then reads the
        text and says what is wrong, or accepts what only it accepts
        (``1_000``, a vertical tab around a number); None too where pyarrow cannot be imported.
    """
    try:
        import pyarrow as pa
        import pyarrow.csv as pa_csv
    except ImportError:  # blocked or broken: the exact reader reads every table
        return None

    names = [f"c{k}" for k in range(columns)]
    try:
        table = pa_csv.read_csv(
            pa.py_buffer(data),
            read_options=pa_csv.ReadOptions(column_names=names, use_threads=False),
            parse_options=pa_csv.ParseOptions(
                delimiter=",",
                quote_char=False,
                escape_char=False,
                newlines_in_values=False,
                ignore_empty_lines=skip_empty,
            ),
            convert_options=pa_csv.ConvertOptions(
                column_types=dict.fromkeys(names, pa.float64()),
                null_values=[],
                strings_can_be_null=False,
                quoted_strings_can_be_null=False,
            ),
        )
    except (pa.ArrowInvalid, pa.ArrowTypeError):
        return None
    if (rows is not None and table.num_rows != rows) or table.num_columns != columns:
        return None
    numbers = np.empty((table.num_rows, columns))
    for k in range(columns):
        column = table.column(k)
        if column.null_count:
            return None
        numbers[:, k] = column.to_numpy()
    return numbers
