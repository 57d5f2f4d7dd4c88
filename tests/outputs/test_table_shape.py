"""A table file's metadata and columns are held to their shape when read back, and when written.

``flyopt plot RESULTS`` and :func:`flyopt.read_results` used to trust what a
Parquet file's metadata or a CSV's sidecar said: objectives of one item, a
sweep's ``vary`` as a number or a list, metadata that was a JSON string each
ended in a traceback; a count of 1.5 in ``iterations`` too, and a flag column
holding "maybe" (or an empty cell) was read as true. The metadata is now
walked against the output schema's ``table`` (:func:`flyopt.io.json_shape.shape_errors`,
held here to ``jsonschema``'s verdicts), and every column against its kind.
"""

import json

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from conftest import PROBLEMS
from output_cases import VALIDATOR, delete_at, set_at

from flyopt.cli.main import main
from flyopt.io.json_shape import shape_errors
from flyopt.outputs.documents import schema
from flyopt.outputs.results import PARQUET_KEY, read_results, write_results
from flyopt.outputs.schema import metadata_errors

SHEAR = PROBLEMS / "shear-press.toml"


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    """A two-point sweep of shear-press written by `flyopt sweep`: its path, frame and metadata."""
    path = tmp_path_factory.mktemp("shape") / "s.parquet"
    assert main(["sweep", str(SHEAR), "--vary", "delta=0.02,0.05", "-o", str(path), "-q"]) == 0
    stored = json.loads(pq.read_schema(path).metadata[PARQUET_KEY])
    return path, pq.read_table(path).to_pandas(), stored


def _changed(stored, mutate):
    document = json.loads(json.dumps(stored))
    mutate(document)
    return document


def _reference_fields(document):
    """jsonschema's errors against the table definition, their paths spelled as flyopt spells fields."""
    table = {"$ref": "#/$defs/table", "$defs": schema()["$defs"]}
    fields = set()
    for error in type(VALIDATOR)(table).iter_errors(document):
        path = ""
        for part in error.absolute_path:
            path += f"[{part}]" if isinstance(part, int) else (f".{part}" if path else str(part))
        if error.validator == "required":
            key = error.message.split("'")[1]
            path = f"{path}.{key}" if path else key
        elif error.validator == "additionalProperties":
            key = error.message.split("'")[1]
            path = f"{path}.{key}" if path else key
        fields.add(path or "(top level)")
    return fields


#: Metadata changed in shape, and the field each change breaks (none of them is a conditional keyword,
#: which the walk leaves to the readers: a front's required objectives).
BROKEN = [
    ("objectives of one item", set_at(["objectives"], ["mass"]), "objectives"),
    ("objectives not led by mass", set_at(["objectives"], ["cost", "mass"]), "objectives[0]"),
    ("objectives a number", set_at(["objectives"], 3), "objectives"),
    ("vary a number", set_at(["sweep", "vary"], 5), "sweep.vary"),
    ("vary a list", set_at(["sweep", "vary"], [{"field": "delta"}]), "sweep.vary"),
    ("a varied field's unit a number", set_at(["sweep", "vary", "delta", "unit"], 3), "sweep.vary.delta.unit"),
    ("a varied field's kind unknown", set_at(["sweep", "vary", "delta", "kind"], "grid"), "sweep.vary.delta.kind"),
    ("seed a string", set_at(["sweep", "seed"], "none"), "sweep.seed"),
    ("message a number", set_at(["message"], 3), "message"),
    ("kind unknown", set_at(["kind"], "ranking"), "kind"),
    ("a column's type unknown", set_at(["columns", 0, "type"], "float"), "columns[0].type"),
    ("a digest not hexadecimal", set_at(["scene_digest"], "abc"), "scene_digest"),
    ("a unit a number", set_at(["units", "mass"], 1), "units.mass"),
    ("units a list", set_at(["units"], ["kg"]), "units"),
]


@pytest.mark.parametrize("what, mutate, field", BROKEN, ids=[case[0] for case in BROKEN])
def test_the_walk_refuses_metadata_where_jsonschema_does(sweep_file, what, mutate, field):
    _, _, stored = sweep_file
    document = _changed(stored, mutate)
    assert _reference_fields(document) == {field}  # the reference ...
    table = schema()["$defs"]["table"]
    assert {f for f, _ in shape_errors(document, table, schema())} == {field}  # ... the strict walk ...
    assert {f for f, _ in metadata_errors(document)} == {field}  # ... and the open one flyopt reads with


def test_the_written_metadata_is_sound_and_a_key_of_another_minor_version_is_no_error(sweep_file):
    _, _, stored = sweep_file
    assert _reference_fields(stored) == set() and shape_errors(stored, schema()["$defs"]["table"], schema()) == []
    other = _changed(stored, delete_at(["units"]))
    other["added_later"] = {"any": "thing"}
    assert _reference_fields(other) == {"units", "added_later"}  # the strict schema of this version ...
    assert metadata_errors(other) == []  # ... but a file of another minor version reads


def _parquet(path, frame, metadata):
    table = pa.Table.from_pandas(frame, preserve_index=False)
    if metadata is not None:
        text = metadata if isinstance(metadata, bytes) else json.dumps(metadata).encode()
        table = table.replace_schema_metadata({PARQUET_KEY: text})
    pq.write_table(table, path)


def _plot(path, tmp_path, capsys, y="mass"):
    picture = tmp_path / "p.png"
    code = main(["plot", str(path), "--what", "sweep", "--x", "delta", "--y", y, "-o", str(picture)])
    err = capsys.readouterr().err
    return code, err, picture.exists()


@pytest.mark.parametrize("what, mutate, field", BROKEN, ids=[case[0] for case in BROKEN])
def test_a_results_file_of_broken_metadata_is_one_line_naming_the_field(
    sweep_file, tmp_path, capsys, what, mutate, field
):
    _, frame, stored = sweep_file
    path = tmp_path / "t.parquet"
    _parquet(path, frame, _changed(stored, mutate))
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert f"its metadata 'flyopt': {field} " in err and not drawn, err


@pytest.mark.parametrize(
    "what, metadata, words",
    [
        ("a JSON string", b'"just a string"', "not flyopt's metadata (must be an object, got string)"),
        ("not UTF-8", b"\xff\xfenot json", "not JSON"),
        ("not JSON", b"{oops", "not JSON"),
    ],
)
def test_parquet_metadata_that_is_no_object_is_one_line(sweep_file, tmp_path, capsys, what, metadata, words):
    _, frame, _ = sweep_file
    path = tmp_path / "t.parquet"
    _parquet(path, frame, metadata)
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and words in err and not drawn, err


def test_a_sidecar_of_broken_shape_is_one_line_naming_it(sweep_file, tmp_path, capsys):
    _, frame, stored = sweep_file
    path = tmp_path / "t.csv"
    frame.to_csv(path, index=False)
    (tmp_path / "t.csv.json").write_text(json.dumps(_changed(stored, set_at(["objectives"], 3))), encoding="utf-8")
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and not drawn, err
    assert f"cannot read {tmp_path / 't.csv.json'}: objectives must be an array, got integer" in err, err


#: Columns whose values are not of their kind: (name, values, words of the refusal).
COLUMNS = [
    ("text in a quantity", "mass", ["a", "b"], "column 'mass' must hold numbers"),
    ("a fraction in a count", "iterations", [1.5, 2.0], "column 'iterations' must hold whole numbers"),
    ("a null in a count", "n_feasible", [None, 1.0], "column 'n_feasible' must hold whole numbers"),
    ("a word in a flag", "feasible", ["maybe", "True"], "column 'feasible' must hold true or false: got 'maybe'"),
    ("a null in a flag", "feasible", [True, None], "column 'feasible' must hold true or false: got None"),
    ("a 2 in a flag", "feasible", [2, 1], "column 'feasible' must hold true or false: got 2"),
    ("lists in a quantity", "delta", [[1.0], [2.0]], "column 'delta' must hold numbers"),
]


@pytest.mark.parametrize("what, column, values, words", COLUMNS, ids=[case[0] for case in COLUMNS])
def test_a_column_not_of_its_kind_is_one_line_naming_it(tmp_path, capsys, what, column, values, words):
    frame = pd.DataFrame({"delta": [0.02, 0.05], "mass": [1.0, 2.0]})
    frame[column] = pd.Series(values, dtype=object) if column != "delta" else values
    path = tmp_path / "t.parquet"
    pq.write_table(pa.Table.from_pandas(frame, preserve_index=False), path)
    with pytest.raises(ValueError, match=words.replace("(", r"\(")):
        read_results(path)
    # a diagram reads the columns it draws (a large table's others are not read): the column, drawn
    code, err, drawn = _plot(path, tmp_path, capsys, y="mass" if column == "delta" else column)
    assert code == 2 and err.count("\n") == 1 and words in err and not drawn, err


def test_a_flag_read_back_from_csv_keeps_its_values(tmp_path):
    """The strict flag is no stricter than what flyopt writes: True/False cells, 0 and 1, booleans."""
    path = tmp_path / "t.csv"
    path.write_text("delta,feasible\n0.02,True\n0.05,False\n0.08,1\n0.1,0\n", encoding="utf-8")
    read = read_results(path)
    assert read["feasible"].dtype == bool and list(read["feasible"]) == [True, False, True, False]
    path.write_text("delta,feasible\n0.02,True\n0.05,False\n", encoding="utf-8")
    assert list(read_results(path)["feasible"]) == [True, False]


def test_write_results_refuses_metadata_read_results_would_refuse_and_writes_nothing(sweep_file, tmp_path):
    _, frame, stored = sweep_file
    for suffix in ("parquet", "csv"):
        path = tmp_path / f"w.{suffix}"
        with pytest.raises(ValueError, match=r"^metadata: objectives must have exactly 2 items, got 1$"):
            write_results(frame, path, metadata=_changed(stored, set_at(["objectives"], ["mass"])))
        assert sorted(p.name for p in tmp_path.iterdir()) == []
    write_results(frame, tmp_path / "w.parquet", metadata=stored)  # sound metadata is written, and reads back
    back = read_results(tmp_path / "w.parquet")
    assert back.attrs["flyopt"] == stored and np.allclose(back["delta"], frame["delta"])


def test_a_sidecar_of_another_minor_version_reads_and_one_too_deep_is_one_line(sweep_file, tmp_path, capsys):
    """The open walk let a key of schema 3.1 pass but held schema_version to the const "3.0" (an outside review):
    any 3.x reads, another major number does not. Metadata nested 200,000 deep was a RecursionError."""
    _, frame, stored = sweep_file
    path = tmp_path / "t.csv"
    frame.to_csv(path, index=False)
    major = stored["schema_version"].split(".")[0]
    for version, readable in ((f"{major}.1", True), (f"{major}.17", True), (f"{int(major) + 1}.0", False)):
        document = {**stored, "schema_version": version, "added_in_a_later_minor": [1, 2]}
        (tmp_path / "t.csv.json").write_text(json.dumps(document), encoding="utf-8")
        code, err, _ = _plot(path, tmp_path, capsys)
        assert (code == 0) if readable else (code == 2 and "schema_version must match" in err), (version, err)
    (tmp_path / "t.csv.json").write_text("[" * 200_000 + "]" * 200_000, encoding="utf-8")
    code, err, _ = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and "nested too deeply" in err, err


def test_a_whole_number_written_as_a_float_is_an_integer_as_jsonschema_says(sweep_file):
    _, _, stored = sweep_file
    document = _changed(stored, set_at(["sweep", "points"], 2.0))
    assert _reference_fields(document) == set() and metadata_errors(document) == []
    document = _changed(stored, set_at(["sweep", "points"], 2.5))
    assert _reference_fields(document) == {"sweep.points"} == {f for f, _ in metadata_errors(document)}


def _one_word_table(path, rows, size):
    """A Parquet table of ``rows`` rows whose status is one word of ``size`` characters, stored once."""
    status = pa.DictionaryArray.from_arrays(pa.array([0] * rows, pa.int32()), pa.array(["x" * size]))
    table = pa.table(
        {"delta": pa.array(np.linspace(0.01, 0.1, rows)), "mass": pa.array([1.0] * rows), "status": status}
    )
    pq.write_table(table, path)


def test_a_small_parquet_file_that_reads_into_gigabytes_is_one_line(tmp_path, capsys, monkeypatch):
    """A word stored once in a Parquet dictionary is read once for each row: 48 kB of file held 4 GB of text
    (pyarrow's ArrowMemoryError, exit 1, after 3 GB); a table may take 1,000 bytes a row of the rows allowed."""
    from flyopt.errors import SceneError
    from flyopt.io.input_files import TABLE_ROW_BYTES

    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "1000")  # at most 1,000,000 bytes read
    limit = 1000 * TABLE_ROW_BYTES
    path = tmp_path / "t.parquet"
    _one_word_table(path, 200, 10_000)  # 2 MB of text read, from a file of some 11 kB
    assert path.stat().st_size < 20_000
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and not drawn, err
    assert f"would take 2,003,200 bytes read (allowed: at most {limit:,}" in err  # 200 x (10,000 + 8 + 8)
    assert "FLYOPT_MAX_TABLE_ROWS raises it" in err
    with pytest.raises(SceneError, match="would take"):
        read_results(path)
    _one_word_table(path, 50, 10_000)  # half a megabyte: read
    assert read_results(path)["status"].str.len().tolist() == [10_000] * 50
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 0 and drawn, err


def test_a_parquet_column_of_a_type_no_table_has_is_one_line(tmp_path, capsys):
    path = tmp_path / "t.parquet"
    when = pa.array([0, 1], pa.timestamp("s"))
    pq.write_table(pa.table({"delta": [0.02, 0.05], "mass": when}), path)
    code, err, drawn = _plot(path, tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1 and not drawn, err
    assert "column 'mass' must hold numbers: it is a timestamp[ms]" in err  # as Parquet stores seconds


def test_a_pandas_index_is_counted_with_the_columns_it_is_read_with(tmp_path, monkeypatch):
    """pandas reads a file's index with any columns: a 1 MB word as a dictionary-encoded index of 2,500 rows was
    read (2.8 GB) where the same word as a column was refused."""
    from flyopt.errors import SceneError

    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "1000")  # at most 1,000,000 bytes read
    frame = pd.DataFrame({"delta": np.linspace(0.01, 0.1, 200), "mass": 1.0})
    frame.index = pd.Index(["x" * 10_000] * 200, name="tag")
    path = tmp_path / "t.parquet"
    pq.write_table(pa.Table.from_pandas(frame, preserve_index=True), path, use_dictionary=True)
    with pytest.raises(SceneError, match=r"would take 2,003,200 bytes read \(allowed: at most 1,000,000"):
        read_results(path, columns=["delta", "mass"])


def test_plain_text_compressed_is_bounded_by_its_pages_before_it_is_read(tmp_path, monkeypatch):
    """Counting the text read it, decompressed: 300 rows of a 1 MB word (a 15 kB file, no dictionary) took 408 MB
    to count. The pages' uncompressed sizes bound it first, from the file's footer."""
    from flyopt.errors import SceneError

    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "1000")
    table = pa.table({"delta": np.linspace(0.01, 0.1, 200), "mass": [1.0] * 200, "status": ["x" * 10_000] * 200})
    path = tmp_path / "t.parquet"
    pq.write_table(table, path, use_dictionary=False, compression="zstd")
    assert path.stat().st_size < 20_000
    real = pq.ParquetFile.read

    def never(self, *args, **kwargs):
        raise AssertionError("the table was read")

    monkeypatch.setattr(pq.ParquetFile, "read", never)
    with pytest.raises(SceneError, match=r"would take 2,\d{3},\d{3} bytes read \(allowed: at most 1,000,000"):
        read_results(path)
    monkeypatch.setattr(pq.ParquetFile, "read", real)
    small = tmp_path / "s.parquet"  # the same, well within: read
    pq.write_table(table.slice(0, 50), small, use_dictionary=False, compression="zstd")
    assert read_results(small)["status"].str.len().tolist() == [10_000] * 50


def test_a_string_view_column_is_text(tmp_path):
    """Arrow's string_view is text (its read was refused as "must hold text: it is a string_view")."""
    path = tmp_path / "t.parquet"
    status = pa.array(["designed", "infeasible"]).cast(pa.string_view())
    pq.write_table(pa.table({"delta": [0.1, 0.2], "mass": [1.0, float("nan")], "status": status}), path)
    assert read_results(path)["status"].tolist() == ["designed", "infeasible"]
