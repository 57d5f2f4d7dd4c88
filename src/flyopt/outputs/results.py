"""The result tables: their columns, nulls for missing values, and their Parquet and CSV files.

Result tables
    A sweep's table has one row per point: ``point``, :data:`CORE_INPUTS`,
    the other varied fields, then :data:`RESULT_COLUMNS`; the table of a Latin
    hypercube has a ``seed`` column after ``point``. :func:`write_results` and
    :func:`read_results` round-trip it exactly, whatever the format;
    :class:`ResultWriter` writes one piece at a time (a sweep's chunks as they
    finish), so that a table larger than memory never has to be held whole.
    In Parquet the text columns are dictionary-encoded (each distinct name or
    status stored once per row group, read back by pandas as categoricals).

Missing values are nulls
    A value that does not exist (no material when nothing was designed, no
    limit that binds, no IPOPT iterations for a closed form, no cost without
    a price) is null: ``None``/NaN/``<NA>`` in pandas (:func:`normalize`),
    null in Parquet and JSON, an empty cell in CSV (pandas reads it back as
    NaN). A limit that is not set is a number, +inf (``inf`` in CSV), and
    null in JSON, which has no infinity. A file's metadata says so
    (:data:`~flyopt.outputs.quantities.MISSING`): in Parquet the key ``flyopt`` of the file's key-value
    metadata, for CSV a sidecar ``FILE.csv.json`` (:func:`sidecar_path`),
    with the units, the column types and the provenance (flyopt version,
    the scene and its digest, the sweep's fields and values).
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Any, Literal, TextIO

import numpy as np

from flyopt.errors import SceneError, shorten
from flyopt.outputs.files import (
    Temporary,
    check_folder,
    check_not_a_link,
    check_not_scene,
    output_error,
)
from flyopt.outputs.quantities import COUNTS, INPUTS, has_unit

if TYPE_CHECKING:
    import pandas as pd
    import pyarrow as pa

    from flyopt.io.scene import Scene

__all__ = [
    "CORE_INPUTS",
    "JSON_TYPES",
    "NULLABLE_INTS",
    "PARQUET_KEY",
    "RESULT_COLUMNS",
    "ResultWriter",
    "arrow_table",
    "check_table_output",
    "column_kind",
    "csv_rows",
    "normalize",
    "output_format",
    "parts_folder",
    "read_results",
    "sidecar_path",
    "table_files",
    "write_results",
]


# --------------------------------------------------------------------------
# The result table's columns
# --------------------------------------------------------------------------

#: Input columns present in every result table (SI; NaN for "none").
CORE_INPUTS = (
    "delta",
    "speed",
    "inertia",
    "torque.scale",
    "design.geometry",
    "design.objective",
    "design.hb_min",
    "design.hb_max",
    "design.max_outer_diameter",
    "design.max_width",
    "design.d_mean",
)

#: Result columns, with their kind. Where a value does not exist it is null (see
#: :func:`normalize`): text None, numbers NaN, ``iterations`` <NA>.
RESULT_COLUMNS = {
    "status": "str",  # designed | not_needed | infeasible | failed
    "feasible": "bool",  # a design was found
    "method": "str",  # closed_form | ipopt | none
    "best_material": "str",
    "best_shaft": "str",
    "best_speed_ratio": "float",
    "d_mean": "float",
    "d_outer": "float",
    "d_inner": "float",
    "h": "float",
    "b": "float",
    "hb_ratio": "float",
    "mass": "float",
    "cost": "float",
    "objective": "float",
    "rim_speed": "float",
    "rim_speed_limit": "float",
    "hoop_stress": "float",
    "safety_factor": "float",
    "j_flywheel": "float",
    "j_at_reference": "float",
    "j_required_on_shaft": "float",
    "d_outer_limit": "float",
    "binding": "str",  # comma-separated names of BINDING_NAMES
    "n_combinations": "int",  # material x shaft combinations decided
    "n_feasible": "int",
    "a_max": "float",
    "j_margin": "float",
    "j_required": "float",
    "driving_torque": "float",
    "power": "float",
    "motor_power": "float",
    "solver_status": "str",
    "iterations": "int",
    "message": "str",
}

#: Whole-number columns that may have no value (IPOPT's iterations of a closed-form design):
#: pandas' nullable Int64. The sweep's evaluation marks them -1 (:func:`normalize` makes that null).
NULLABLE_INTS = frozenset({"iterations"})

#: Text columns of the trade-off table and the drive's Pareto front besides the names above (a
#: material's binding limits other than the inertia, why it is infeasible; the motor's name).
_TEXT = frozenset({"limit", "reason", "motor"})

JSON_TYPES = {"str": "string", "bool": "boolean", "int": "integer", "float": "number"}


def column_kind(name: str, column: pd.Series | None = None) -> str:
    """The kind of a column: "str", "bool", "int" or "float".

    By its name; a column no table of flyopt names (a user's own) by its values."""
    return _kind(name, None if column is None else column.dtype)


def _kind(name: str, dtype: Any) -> str:
    """:func:`column_kind` of a column of ``dtype`` (None: not known)."""
    kind = RESULT_COLUMNS.get(name)
    if kind is not None:
        return kind
    if (name in INPUTS and INPUTS[name] is None) or name in _TEXT:
        return "str"
    if name in COUNTS:
        return "int"
    if dtype is not None and not has_unit(name):
        from pandas.api import types

        if types.is_bool_dtype(dtype):
            return "bool"
        if not types.is_numeric_dtype(dtype):
            return "str"
    return "float"


def no_minus_one(column: pd.Series) -> pd.Series:
    """A whole-number column of :data:`NULLABLE_INTS` as nullable Int64, its -1 (no value) null."""
    values = column.astype("Int64")
    return values.mask((values == -1).fillna(False))


def _text_dtype():
    """pandas' text dtype: ``str`` (missing: NaN) from pandas 3, object (missing: None) before."""
    import pandas as pd

    return "str" if int(pd.__version__.split(".")[0]) >= 3 else object


def normalize(frame: pd.DataFrame) -> pd.DataFrame:
    """One dtype per column and nulls for missing values, whatever the source.

    The frame of an evaluation, a CSV or a Parquet file comes out the same:
    text columns of pandas' text dtype with NaN/None where there is no
    text (an empty string is no text), numbers float64 with NaN, whole
    numbers int64 (nullable Int64 for :data:`NULLABLE_INTS`, whose -1 is
    no value), booleans bool. Modifies and returns ``frame``.

    Raises
    ------
    ValueError
        A column whose values are not of its kind (text in a number's column,
        a fraction or a null in a count's, anything but true and false in a flag's),
        naming the column.
    """
    for position, (name, dtype) in enumerate(frame.dtypes.items()):
        kind = _kind(name, dtype)
        if _is_of_kind(frame, position, dtype, kind, name):
            continue  # as a sweep's chunks come from its workers: a conversion costs ~0.3 ms a column
        try:
            frame[name] = _of_kind(frame[name], kind, name)
        except (TypeError, ValueError) as err:
            raise ValueError(f"column {shorten(name)} must hold {_KIND_WORDS[kind]}: {err}") from None
    return frame


def _is_of_kind(frame: pd.DataFrame, position: int, dtype: Any, kind: str, name: str) -> bool:
    """Whether :func:`_of_kind` would give the column at ``position`` of ``frame`` back as it is: its kind's
    dtype already and, for text, pandas 3's ``str`` (missing values NaN: ``object`` may hold None or NaN) with
    no empty string."""
    if kind == "float":
        return bool(dtype == np.float64)
    if kind == "bool":
        return bool(dtype == np.bool_)
    if kind == "int":
        return name not in NULLABLE_INTS and bool(dtype == np.int64)
    if _text_dtype() != "str" or dtype != "str" or getattr(dtype, "storage", None) != "pyarrow":
        return False  # (the conversion gives pandas' default storage, Arrow's: a "python" one is converted)
    import pyarrow as pa
    import pyarrow.compute as pc

    # pandas' text array hands Arrow its values without a copy (__arrow_array__): some 50 µs against pandas'
    # own comparison's 250 µs; any() of no values, or of nulls only, is null
    values = pa.array(frame.iloc[:, position].array)
    return pc.any(pc.equal(values, "")).as_py() is not True


_KIND_WORDS = {"str": "text", "bool": "true or false", "int": "whole numbers", "float": "numbers"}


def _of_kind(column: pd.Series, kind: str, name: str) -> pd.Series:
    if kind == "str":
        values = column.astype(object)  # categorical in Parquet, str or object elsewhere
        return values.where(values.notna() & (values != ""), None).astype(_text_dtype())
    if kind == "bool":
        from pandas.api import types

        if not types.is_bool_dtype(column.dtype):  # astype(bool) would read "no", NaN and 2 as true
            flags = column.map(_flag)
            if flags.isna().any():
                bad = column[flags.isna()].iloc[0]
                raise ValueError(f"got {shorten(bad.item() if isinstance(bad, np.generic) else bad)}")
            column = flags
        return column.astype(bool)
    if kind == "int" and name in NULLABLE_INTS:
        return no_minus_one(column)
    if kind == "int":
        return column.astype(np.int64)
    return column.astype(float)


#: What a flag's column may hold: booleans (equal to 0 and 1), 0 and 1, and the words a CSV writes.
_FLAGS: dict[object, bool] = {
    0: False,
    1: True,
    "0": False,
    "1": True,
    "False": False,
    "True": True,
    "false": False,
    "true": True,
}


def _flag(value: object) -> bool | None:
    try:
        return _FLAGS.get(value)
    except TypeError:  # a list or a mapping in a cell
        return None


# --------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------

_SUFFIXES = {".parquet": "parquet", ".pq": "parquet", ".csv": "csv"}

#: The key of flyopt's metadata in a Parquet file's key-value metadata.
PARQUET_KEY = b"flyopt"


def output_format(path: str | os.PathLike[str], label: str = "output") -> str:
    """``"parquet"`` or ``"csv"``, by the suffix of ``path``; SceneError naming ``label`` else."""
    kind = _SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError(label, f"{str(path)!r} must end in .parquet or .csv (the suffix picks the format)")
    return kind


def sidecar_path(path: str | os.PathLike[str]) -> Path:
    """The sidecar of a CSV file, which holds its metadata: ``FILE.csv`` → ``FILE.csv.json``."""
    path = Path(path)
    return path.with_name(path.name + SIDECAR_SUFFIX)


PARTS_SUFFIX, SIDECAR_SUFFIX = ".parts", ".json"
SWEEP_BESIDE = (SIDECAR_SUFFIX, PARTS_SUFFIX)
"""What a sweep writes beside its table ``FILE``: a CSV's sidecar ``FILE.json``, the folder ``FILE.parts``."""


def parts_folder(path: str | os.PathLike[str]) -> Path:
    """The folder of a sweep's finished chunks beside its table (:class:`flyopt.studies.parts.Parts`):
    ``FILE`` → ``FILE.parts``."""
    path = Path(path)
    return path.with_name(path.name + PARTS_SUFFIX)


def table_files(path: str | os.PathLike[str]) -> tuple[Path, ...]:
    """The files writing a table to ``path`` makes: the table and, for CSV, its sidecar (:func:`sidecar_path`)."""
    path = Path(path)
    return (path, sidecar_path(path)) if _SUFFIXES.get(path.suffix.lower()) == "csv" else (path,)


def check_table_output(path: str | os.PathLike[str], scene: Scene, what: str, label: str = "-o/--output") -> None:
    """Refuse a table's output that would replace a file the scene read (the scene file or a data file:
    :func:`flyopt.outputs.files.check_not_scene`): any of :func:`table_files`."""
    files = table_files(path)
    for file in files:
        check_not_scene(file, scene, what, label)
    for file in files[1:]:  # the sidecar: a name flyopt makes, never written through a link
        check_not_a_link(file, label)


def arrow_table(frame: pd.DataFrame, metadata: Mapping[str, Any] | None = None) -> pa.Table:
    """A result table as a pyarrow Table, its text columns dictionary-encoded, nulls as nulls.

    Every column gets its kind's type (string columns ``dictionary<int32,
    string>``, then int64, bool, float64) whatever the rows hold, so tables
    of different chunks share one schema. A missing value (empty text, NaN,
    ``iterations`` -1) is an Arrow null.

    Parameters
    ----------
    frame : pandas.DataFrame
    metadata : dict, optional
        flyopt's metadata (:func:`table_metadata`), stored as the schema's
        key-value metadata under ``flyopt``.

    Returns
    -------
    pyarrow.Table
    """
    import pyarrow as pa

    arrays = []
    for name in frame.columns:
        column = frame[name]
        kind = column_kind(name, column)
        if kind == "str":
            arrays.append(_text(column))
        elif kind == "bool":
            arrays.append(pa.array(column.to_numpy(dtype=bool), type=pa.bool_()))
        elif kind == "int" and name in NULLABLE_INTS:
            arrays.append(pa.array(no_minus_one(column), type=pa.int64(), from_pandas=True))
        elif kind == "int":
            arrays.append(pa.array(column.to_numpy(dtype=np.int64), type=pa.int64()))
        else:
            arrays.append(pa.array(column.to_numpy(dtype=float), type=pa.float64(), from_pandas=True))
    table = pa.Table.from_arrays(arrays, names=[str(name) for name in frame.columns])
    if metadata is not None:
        table = table.replace_schema_metadata({PARQUET_KEY: json.dumps(metadata, allow_nan=False)})
    return table


def _text(column):
    """A text column as a dictionary-encoded arrow array (null for no text)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    try:
        array = pa.array(column, from_pandas=True)
        if array.type != pa.string():
            array = array.cast(pa.string())
    except (pa.ArrowInvalid, pa.ArrowTypeError, pa.ArrowNotImplementedError):
        array = pa.array(
            [None if v is None or (isinstance(v, float) and math.isnan(v)) else str(v) for v in column.astype(object)],
            type=pa.string(),
        )
    empty = pc.equal(array, "")
    if pc.any(empty).as_py():
        array = pc.if_else(empty, pa.scalar(None, pa.string()), array)
    return array.dictionary_encode()


def _dictionary_columns(table):
    """Names of a table's dictionary-encoded (text) columns: Parquet dictionaries for these
    only (a float column's dictionary is built, found too large and dropped: time lost)."""
    import pyarrow as pa

    return [f.name for f in table.schema if pa.types.is_dictionary(f.type)]


def csv_rows(frame: pd.DataFrame, handle: TextIO, header: bool) -> None:
    """Rows as CSV: a missing value is an empty cell (also a -1 of :data:`NULLABLE_INTS`)."""
    nullable = [c for c in frame.columns if c in NULLABLE_INTS]
    if nullable:
        frame = frame.copy()
        for name in nullable:
            frame[name] = no_minus_one(frame[name])
    frame.to_csv(handle, index=False, header=header)


def _sidecar_text(metadata: Mapping[str, Any]) -> bytes:
    """The sidecar of a CSV file: its metadata and how the CSV is written."""
    text = json.dumps({**metadata, "csv": {"delimiter": ",", "header": True, "null": ""}}, indent=2, allow_nan=False)
    return (text + "\n").encode("utf-8")


def _finish(
    table: Temporary,
    path: Path,
    sidecar_of: Mapping[str, Any] | None,
    folder: str | os.PathLike[str] | None,
    label: str,
) -> None:
    """Move the finished temporary ``table`` to ``path``, with the CSV's sidecar when ``sidecar_of`` is given.

    Both files are written to temporaries first, and both names are checked (a folder, a
    device) before either is renamed: a refusal or a failure leaves the earlier pair as it
    was. Only a rename of the table failing after its sidecar's removes the new sidecar
    (it describes a table that is not there). The temporaries are removed on any failure.
    """
    if sidecar_of is None:
        table.finish(label)
        return
    sidecar = sidecar_path(path)
    try:
        side = Temporary(sidecar, folder, own_name=True)  # a name flyopt makes: never through a link
    except BaseException:
        table.discard()
        raise
    try:
        side.write(_sidecar_text(sidecar_of))
        check_folder(path, label)
        check_not_a_link(sidecar, label)
        check_folder(sidecar, label)
        written = sidecar
        side.finish(label)
    except BaseException:
        side.discard()
        table.discard()
        raise
    try:
        table.finish(label)
    except BaseException:
        written.unlink(missing_ok=True)
        raise


class ResultWriter:
    """A result file written piece by piece, put in place only when complete.

    The pieces go to a temporary file (Parquet row groups, or CSV rows under
    one header), which :meth:`close` moves to ``path``; :meth:`abort` (or an
    exception inside a ``with`` block) removes it. So the file under its
    final name is always whole, and memory holds one piece at a time.

    Parameters
    ----------
    path : str or Path
        ``.parquet`` (or ``.pq``) or ``.csv``.
    temporary_folder : str or Path, optional
        Where the temporary file goes (on the same file system as ``path``),
        e.g. the sweep's parts folder, which a rerun cleans even after a
        kill; default: beside ``path``.
    metadata : callable, optional
        ``metadata(columns)``, flyopt's metadata of the file
        (:func:`table_metadata`): Parquet key-value metadata, or the CSV's
        sidecar (written just before the table is moved into place).

    Examples
    --------
    >>> with ResultWriter("study.parquet") as out:   # doctest: +SKIP
    ...     for frame in pieces:
    ...         out.append(frame)
    ...     out.close()
    """

    #: Rows gathered into one Parquet row group (~30 MB of a sweep's columns).
    ROW_GROUP_ROWS = 65_536

    def __init__(
        self,
        path: str | os.PathLike[str],
        temporary_folder: str | os.PathLike[str] | None = None,
        metadata: Callable[[list[str]], Mapping[str, Any]] | None = None,
    ) -> None:
        self.path = Path(path)
        self.kind = output_format(self.path)
        check_folder(self.path)
        self._folder = temporary_folder
        self._temporary: Temporary | None = None  # made on the first write (Temporary: a new file)
        self.rows = 0
        self._writer: Any = None  # a pyarrow.parquet.ParquetWriter
        self._file: TextIO | None = None
        self._pending: list[pa.Table] = []
        self._pending_rows = 0
        self._columns: list[str] | None = None
        self._metadata = metadata
        self._meta: Mapping[str, Any] | None = None

    @property
    def temporary(self) -> Path | None:
        """The temporary file the rows go to (``None`` before the first is written)."""
        return None if self._temporary is None else self._temporary.path

    def _new_file(self) -> Temporary:
        if self._temporary is None:
            self._temporary = Temporary(self.path, self._folder)
        return self._temporary

    def _text_file(self) -> TextIO:
        return io.TextIOWrapper(self._new_file().handle, encoding="utf-8", newline="")

    def _file_metadata(self) -> Mapping[str, Any] | None:
        if self._meta is None and self._metadata is not None:
            self._meta = self._metadata(list(self._columns or []))
        return self._meta

    def append(self, frame: pd.DataFrame) -> None:
        """Add the rows of ``frame`` (the columns of the first piece, in its order)."""
        if self._columns is None:
            self._columns = list(frame.columns)
        elif list(frame.columns) != self._columns:
            raise ValueError(f"a piece's columns differ from the file's: {list(frame.columns)} vs {self._columns}")
        if self.kind == "parquet":
            self._pending.append(arrow_table(frame, self._file_metadata()))
            self._pending_rows += len(frame)
            if self._pending_rows >= self.ROW_GROUP_ROWS:
                self._flush()
        else:
            if self._file is None:
                self._file = self._text_file()
            csv_rows(frame, self._file, header=self.rows == 0)
        self.rows += len(frame)

    def _flush(self):
        import pyarrow as pa
        import pyarrow.parquet as pq

        if not self._pending:
            return
        table = pa.concat_tables(self._pending) if len(self._pending) > 1 else self._pending[0]
        self._pending, self._pending_rows = [], 0
        if self._writer is None:
            self._writer = pq.ParquetWriter(
                self._new_file().handle, table.schema, use_dictionary=_dictionary_columns(table)
            )
        self._writer.write_table(table, row_group_size=max(len(table), 1))

    def close(self) -> None:
        """Finish the file and move it to its name (it then replaces any file there).

        A CSV file's sidecar is written beside it first, and the pair moved into place
        only when both are written (:func:`_finish`)."""
        try:
            if self.kind == "parquet":
                self._flush()
                if self._writer is None:  # no rows: a file with the columns alone
                    import pandas as pd
                    import pyarrow.parquet as pq

                    pq.write_table(
                        arrow_table(pd.DataFrame(columns=self._columns or []), self._file_metadata()),
                        self._new_file().handle,
                    )
                else:
                    self._writer.close()
                    self._writer = None
            else:
                if self._file is None:
                    self._file = self._text_file()
                    if self._columns:
                        self._file.write(",".join(self._columns) + "\n")
                self._file.close()
                self._file = None
            sidecar_of = self._file_metadata() if self.kind == "csv" else None
            table, self._temporary = self._new_file(), None
        except BaseException:
            self.abort()
            raise
        _finish(table, self.path, sidecar_of, self._folder, "output")

    def abort(self) -> None:
        """Stop writing and remove the temporary file."""
        writer, handle = self._writer, self._file
        self._writer = self._file = None
        self._pending = []
        try:
            if writer is not None:
                writer.close()
            if handle is not None:
                handle.close()
        finally:
            temporary, self._temporary = self._temporary, None
            if temporary is not None:
                temporary.discard()

    def __enter__(self) -> ResultWriter:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, value: BaseException | None, traceback: TracebackType | None
    ) -> Literal[False]:
        if kind is not None or self._writer is not None or self._file is not None:
            self.abort()
        return False


def write_results(
    frame: pd.DataFrame,
    path: str | os.PathLike[str],
    temporary_folder: str | os.PathLike[str] | None = None,
    metadata: Mapping[str, Any] | None = None,
) -> None:
    """Write a result table to Parquet or CSV (by the suffix), atomically.

    The table is written to a temporary file and moved into place, so a
    crash never leaves a half-written file under the final name; an error
    or an interrupt while writing removes the temporary file.

    Parameters
    ----------
    frame : pandas.DataFrame
    path : str or Path
        ``.parquet`` (or ``.pq``) or ``.csv``.
    temporary_folder : str or Path, optional
        Where the temporary file goes (on the same file system as ``path``),
        e.g. the sweep's parts folder, which a rerun cleans even after a
        kill; default: beside ``path``.
    metadata : dict, optional
        flyopt's metadata (:func:`table_metadata`): Parquet key-value
        metadata, or the CSV's sidecar ``FILE.csv.json``.
    """
    path = Path(path)
    kind = output_format(path)
    from flyopt.outputs.schema import metadata_errors

    errors = metadata_errors(metadata) if metadata is not None else []
    if errors:  # what read_results would refuse is not written
        field, message = errors[0]
        raise ValueError(f"metadata: {field} {message}")
    wrong = _wrong_unit(metadata) if metadata is not None else ""
    if wrong:
        raise ValueError(f"metadata: {wrong}")
    check_folder(path)
    table = Temporary(path, temporary_folder)
    try:
        try:
            if kind == "parquet":
                import pyarrow.parquet as pq

                arrow = arrow_table(frame, metadata)
                pq.write_table(arrow, table.handle, use_dictionary=_dictionary_columns(arrow))
            else:
                handle = io.TextIOWrapper(table.handle, encoding="utf-8", newline="")
                csv_rows(frame, handle, header=True)
                handle.close()
            table.close()
        except OSError as err:
            raise output_error(err, path) from err
    except BaseException:
        table.discard()
        raise
    _finish(table, path, metadata if kind == "csv" else None, temporary_folder, "-o/--output")


def _metadata(text: str | bytes, where: str) -> dict[str, Any]:
    """A table's metadata from its JSON text, its shape checked (:func:`metadata_errors`); SceneError else,
    its message led by ``where``."""
    try:
        metadata = json.loads(text)
    except ValueError as err:  # UnicodeDecodeError too
        raise SceneError("", f"{where}: not JSON ({err})") from None
    except RecursionError:  # arrays nested a hundred thousand deep
        raise SceneError("", f"{where}: not flyopt's metadata (nested too deeply to read)") from None
    from flyopt.io.input_files import MAX_TABLE_COLUMNS

    columns = metadata.get("columns") if isinstance(metadata, dict) else None
    if isinstance(columns, list) and len(columns) > MAX_TABLE_COLUMNS:  # before the walk and pandas' copies
        # check_columns' rule, in words that keep the whole path of the file named
        raise SceneError("", f"{where}: columns has {len(columns)} entries (allowed: at most {MAX_TABLE_COLUMNS})")
    from flyopt.outputs.schema import metadata_errors

    errors = metadata_errors(metadata)
    if errors:
        field, message = errors[0]
        raise SceneError(
            "",
            f"{where}: not flyopt's metadata ({message})" if field == "(top level)" else f"{where}: {field} {message}",
        )
    wrong = _wrong_unit(metadata)
    if wrong:
        raise SceneError("", f"{where}: {wrong}")
    return metadata


def _wrong_unit(metadata: Mapping[str, Any]) -> str:
    """What is wrong with the first unit the metadata gives a quantity ("" if none is): each of ``units`` and
    each varied field's ``unit`` must be a unit of the field's dimension. A sidecar's mass in "furlong" was
    read without a word, and a varied δ "in furlong" failed only when read back in the input's units, naming
    no file."""
    from flyopt.outputs.quantities import OUTPUT_DIMENSIONS, dimension_of
    from flyopt.units import registry, unit_value

    given = [(f"units.{name}", name, unit) for name, unit in (metadata.get("units") or {}).items()]
    vary = (metadata.get("sweep") or {}).get("vary") or {}
    given += [(f"sweep.vary.{name}.unit", name, entry.get("unit")) for name, entry in vary.items()]
    for field, name, unit in given:
        dimension = dimension_of(name)
        if not isinstance(unit, str) or dimension is None:
            continue
        try:
            if dimension in OUTPUT_DIMENSIONS:  # a dimension only results have (an unbalance in kg*m): by pint
                ureg = registry()
                measures = (  # a unit alone (pint's Unit refuses a factor: "kg*m*0")
                    ureg.Unit(unit).dimensionality == ureg.Unit(OUTPUT_DIMENSIONS[dimension]).dimensionality
                )
            else:  # as the scene's fields read it (rpm, %)
                if unit != "1":  # "1": a plain number
                    unit_value(unit, dimension, field)
                measures = True
        except Exception:  # noqa: BLE001 - pint's errors of a unit it cannot read: not this quantity's
            measures = False
        if not measures:
            words = "a plain number" if dimension == "dimensionless" else dimension.replace("_", " ")
            return f"{field} {shorten(unit)} does not measure {words}"
    return ""


def results_columns(path: str | os.PathLike[str]) -> tuple[list[str], dict[str, Any] | None]:
    """The columns of a result table written by flyopt (Parquet or CSV), in the file's order, and its metadata
    (``attrs["flyopt"]`` of :func:`read_results`, or None), checked as :func:`read_results` checks the file,
    without reading its rows: a reader that needs a few columns of a large table names them to
    :func:`read_results`.
    """
    path, kind, name = Path(path), output_format(path), str(path)
    from flyopt.io.input_files import check_columns, check_input, check_rows, read_input

    check_input(path, "", name)  # a regular file within the size cap, as every input
    if kind == "parquet":
        import pyarrow.parquet as pq

        parquet = pq.ParquetFile(path)
        check_rows(parquet.metadata.num_rows, "", name)  # a small file may hold a billion rows
        check_columns(parquet.metadata.num_columns, "", name)
        schema = parquet.schema_arrow
        columns = [str(c) for c in schema.empty_table().to_pandas().columns]  # as pandas names them (an index)
        stored = schema.metadata or {}
        if PARQUET_KEY not in stored:
            return columns, None
        return columns, _metadata(stored[PARQUET_KEY], f"its metadata {PARQUET_KEY.decode()!r}")
    import pandas as pd

    with open(path, encoding="utf-8", newline="") as handle:  # pandas took 2.5 s over 20,000 names
        first = handle.readline(2**20)  # at least the first 1,000 names, unless over a kilobyte each
    check_columns(len(next(csv.reader([first]), [])), "", name)
    columns = [str(c) for c in pd.read_csv(path, nrows=0).columns]
    sidecar = sidecar_path(path)
    if not os.path.lexists(sidecar):
        return columns, None
    return columns, _metadata(read_input(sidecar, "", str(sidecar)), f"cannot read {sidecar}")


def _check_parquet_size(path: Path, columns: Sequence[str], name: str) -> None:
    """Refuse a Parquet table whose ``columns`` (and its pandas index, which pandas reads with them) would take more
    than :func:`flyopt.io.input_files.check_read_bytes` allows read: numbers their width; text its characters,
    bounded first by the pages' uncompressed sizes (what reading them decompresses), then counted from the text
    read dictionary-encoded (a word stored once in a dictionary is read once for every row that names it).

    Raises
    ------
    SceneError
        Naming the file: the bytes it would take and what is allowed.
    ValueError
        A column of a type no results table has (a list, a date), named as :func:`normalize` names a column
        not of its kind.
    """
    import pyarrow as pa
    import pyarrow.compute as pc
    import pyarrow.parquet as pq

    from flyopt.io.input_files import check_read_bytes

    stored = pq.ParquetFile(path)
    schema, meta = stored.schema_arrow, stored.metadata
    index = [c for c in (schema.pandas_metadata or {}).get("index_columns", []) if isinstance(c, str)]
    wanted, rows, texts, fixed = {*columns, *index}, meta.num_rows, [], 0
    is_view = getattr(pa.types, "is_string_view", lambda kind: False)
    for field in schema:
        if field.name not in wanted:
            continue
        kind = field.type.value_type if pa.types.is_dictionary(field.type) else field.type
        if pa.types.is_string(kind) or pa.types.is_large_string(kind) or is_view(kind):
            texts.append(field.name)
        elif pa.types.is_integer(kind) or pa.types.is_floating(kind) or pa.types.is_boolean(kind):
            fixed += rows * max(kind.bit_width // 8, 1)
        elif not pa.types.is_null(kind):
            column = str(field.name)
            raise ValueError(f"column {shorten(column)} must hold {_KIND_WORDS[_kind(column, None)]}: it is a {kind}")
    places = [j for j in range(meta.num_columns) if meta.schema.column(j).path in texts]
    pages = sum(meta.row_group(g).column(j).total_uncompressed_size for g in range(meta.num_row_groups) for j in places)
    check_read_bytes(fixed + pages, "", name)  # what reading the text decompresses, before any of it is read
    total = fixed
    if texts:  # the text as a dictionary and indices: a word's length counted for each index to it
        for column in pq.ParquetFile(path, read_dictionary=texts).read(columns=texts).columns:
            for chunk in column.chunks:
                if not pa.types.is_dictionary(chunk.type):  # (a view type pyarrow reads as it is)
                    total += int(pc.sum(pc.binary_length(chunk)).as_py() or 0)
                    continue
                lengths = pc.binary_length(chunk.dictionary).fill_null(0).to_numpy(zero_copy_only=False)
                indices = chunk.indices.drop_null().to_numpy(zero_copy_only=False)
                total += int(np.bincount(indices, minlength=len(lengths)).astype(np.int64) @ lengths)
    check_read_bytes(total, "", name)


def read_results(path: str | os.PathLike[str], columns: Sequence[str] | None = None) -> pd.DataFrame:
    """Read a result table written by flyopt (Parquet or CSV), dtypes and nulls restored.

    Parameters
    ----------
    path : str or Path
    columns : list of str, optional
        Read these columns only (in the file's order: :func:`results_columns` names them).

    Returns
    -------
    pandas.DataFrame
        Equal to the DataFrame the sweep returned. ``attrs["flyopt"]`` holds
        the file's metadata (units, provenance, a front's objectives) where
        it has any: Parquet key-value metadata, or the CSV's sidecar.
    """
    import pandas as pd

    path = Path(path)
    header, metadata = results_columns(path)
    if output_format(path) == "parquet":
        _check_parquet_size(path, header if columns is None else columns, str(path))
        frame = pd.read_parquet(path, columns=columns)
    else:
        strings = [c for c in header if column_kind(c) == "str"]
        numbers = [c for c in header if c not in strings]
        frame = pd.read_csv(
            path,
            dtype={c: str for c in strings},
            keep_default_na=False,
            na_values={c: ["", "NaN", "nan"] if c in numbers else [""] for c in header},
            usecols=columns,
        )
        if columns is not None:
            frame = frame[list(columns)]
    try:
        frame = normalize(frame)
    except ValueError as err:
        raise SceneError("", str(err)) from None
    if metadata is not None:
        frame.attrs["flyopt"] = metadata
    return frame
