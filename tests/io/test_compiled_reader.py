"""Large tables read by pyarrow's compiled reader give the exact reader's floats and refusals (issue 26).

The compiled reader (:mod:`flyopt.io.compiled_reader`) is a fast path only:
a CSV table is held to the line-by-line reader (:func:`csv_table.read_csv_lines`,
Python's ``float``), an inline TOML table to ``tomllib`` and to ``float`` of
each written number; bit for bit (the sign of zero included), with the same
line numbers, and each refusal the same message naming the same line,
column or point. Small tables are read by the compiled reader here by
lowering its threshold, so that awkward numbers cost no large file.
"""

import contextlib
import sys
from unittest import mock

import numpy as np
import pytest
import tomllib
from hypothesis import given, settings
from hypothesis import strategies as st

import flyopt
from flyopt.errors import SceneError
from flyopt.io import compiled_reader, csv_table, toml_file

COLUMNS, UNITS = ("angle", "torque"), ("deg", "N*m")

SCENE = """title = "t"
[machine]
speed = "300 rpm"
delta = 0.05
[torque.driving]
constant = "unknown"
[torque.resisting]
angle_unit = "deg"
unit = "N*m"
{table}
"""


def bits(array):
    """The bit patterns of an array of floats (tells -0.0 from 0.0)."""
    return np.ascontiguousarray(array, dtype=float).view(np.int64)


@contextlib.contextmanager
def compiled_always():
    """Every table goes to the compiled reader, whatever its size; yields the list of what it returned."""
    returned = []

    def spy(*args, **kwargs):
        result = compiled_reader.compiled_numbers(*args, **kwargs)
        returned.append(result)
        return result

    with (
        mock.patch.object(compiled_reader, "COMPILED_READER_BYTES", 0),
        mock.patch.object(csv_table, "compiled_numbers", spy),
        mock.patch.object(toml_file, "compiled_numbers", spy),
    ):
        yield returned


def exact_csv(text):
    """The line-by-line reading: (numbers, lines), or the message of its refusal."""
    try:
        numbers, lines = csv_table.read_csv_lines(text.split("\n"), "f", "t.csv", COLUMNS, UNITS)
    except SceneError as err:
        return str(err)
    return numbers, list(lines)


def fast_csv(text):
    try:
        numbers, lines = csv_table.read_csv(text, "f", "t.csv", COLUMNS, UNITS)
    except SceneError as err:
        return str(err)
    return numbers, list(lines)


def assert_same(got, expected):
    if isinstance(expected, str):
        assert got == expected
    else:
        assert not isinstance(got, str), got
        assert np.array_equal(bits(got[0]), bits(expected[0])) and got[1] == expected[1]


def large_rows(n, seed=3, wild=True):
    """``n`` rows of a torque table; ``wild``: every seventh value's exponent far from 1 (the readers' test), else
    every value within the torques a scene may give (flyopt.units.MAGNITUDES: a scene that loads)."""
    rng = np.random.default_rng(seed)
    angles = np.linspace(0.0, 360.0, n)
    values = 1000 + 300 * np.sin(np.radians(angles) * 3) + rng.normal(0, 20, n)
    values[::7] *= 10.0 ** rng.integers(-300, 300, len(values[::7])) if wild else 10.0 ** rng.integers(-6, 9)
    values[::11] *= -1
    return angles, values


# -- awkward numbers, each read by both readers -----------------------------------------

AWKWARD = [
    "1.5", "+1.5", "-1.5", "-0", "+0", "-0.0", "0", "1.", ".5", "+.5e-3", "-.5E+3", "1e5", "1E+05", "1e-05",
    "00012", "9007199254740993", "123456789012345678901234567890123456789",
    "0.1000000000000000055511151231257827021181583404541015625", "4.9e-324", "2.4703282292062328e-324",
    "1e-400", "-1e-400", "1.7976931348623157e308", "1.7976931348623158e308", " 7", "7 ", "\t7\t", "  -2.5e3  ",
]  # fmt: skip
"""Numbers Python's float reads, written as people and programs write them."""

ODD = [
    "1_000", "\x0b7", "7\x0c", "\u00a07", "\uff17", "1e999", "-inf", "nan", "Infinity", "", " ", "1e", "e5", ".", "-",
    "1,5", "1 5", "0x10", "1d3", '"7"', "'7'", "7\x00", "--1", "1..2", "seven", "7 N*m", "#7",
]  # fmt: skip
"""Fields only float reads (underscores, a vertical tab, a no-break space, a full-width digit), or nothing reads."""

FIELD = st.one_of(st.sampled_from(AWKWARD), st.floats(allow_nan=False, allow_infinity=False).map(repr))
LINE_END = st.sampled_from(["\n", "\r\n"])


@settings(max_examples=150, deadline=None)
@given(
    rows=st.lists(st.tuples(FIELD, FIELD, LINE_END), min_size=2, max_size=40),
    header=st.sampled_from(["", "angle,torque\n", "angle [deg],torque [N*m]\r\n", "\ufeffangle,torque\n"]),
    odd=st.one_of(st.none(), st.tuples(st.integers(0, 79), st.sampled_from(ODD))),
    extra=st.one_of(
        st.none(),
        st.tuples(st.integers(0, 40), st.sampled_from(["\n", "\r\n", "# a note\n", "  \n", "1,2,3\n", "7\n", "\r"])),
    ),
)
def test_the_compiled_reader_gives_the_exact_readers_rows_or_refusal(rows, header, odd, extra):
    """Any CSV text: the same numbers to the bit and the same lines, or the same one-line refusal."""
    fields = [f for a, b, _ in rows for f in (a, b)]
    if odd is not None:
        fields[odd[0] % len(fields)] = odd[1]
    lines = [f"{fields[2 * k]},{fields[2 * k + 1]}{end}" for k, (_, _, end) in enumerate(rows)]
    if extra is not None:  # a comment, a blank line, a wrong line, a lone carriage return
        lines.insert(extra[0] % (len(lines) + 1), extra[1])
    text = (header + "".join(lines)).removeprefix("\ufeff")  # read_input's utf-8-sig takes the mark
    expected = exact_csv(text)
    with compiled_always() as returned:
        got = fast_csv(text)
    assert_same(got, expected)
    if odd is None and extra is None and text.isascii():  # a clean file: the compiled reader read it
        assert returned and returned[0] is not None


def test_awkward_numbers_are_read_by_the_compiled_reader_to_floats_doubles():
    rows = [(a, b) for a in AWKWARD for b in AWKWARD[:5]]
    for end in ("\n", "\r\n"):
        text = "angle,torque" + end + "".join(f"{a},{b}{end}" for a, b in rows)
        with compiled_always() as returned:
            got = fast_csv(text)
        assert returned[0] is not None  # read by the compiled reader
        expected = np.array([[float(a), float(b)] for a, b in rows])
        assert np.array_equal(bits(got[0]), bits(expected))
        assert got[1] == list(range(2, 2 + len(rows)))
        assert_same(got, exact_csv(text))


# -- a table of a million rows --------------------------------------------------------------


@pytest.fixture(scope="module")
def million():
    """A 10⁶-row table (angle in deg, torque in N*m) as its CSV text: exponents, signs and a header."""
    angles, values = large_rows(1_000_000)
    text = "angle,torque\n" + "".join(f"{a!r},{v!r}\n" for a, v in zip(angles.tolist(), values.tolist()))
    return text


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
def test_a_million_row_csv_reads_to_the_exact_readers_floats(million):
    assert len(million) >= compiled_reader.COMPILED_READER_BYTES  # the compiled reader's size, not a patched one
    with mock.patch.object(csv_table, "compiled_numbers", wraps=compiled_reader.compiled_numbers) as spy:
        numbers, lines = csv_table.read_csv(million, "f", "t.csv", COLUMNS, UNITS)
    assert spy.call_count == 1 and isinstance(lines, range)
    reference, reference_lines = csv_table.read_csv_lines(million.split("\n"), "f", "t.csv", COLUMNS, UNITS)
    assert np.array_equal(bits(numbers), bits(reference))
    assert list(lines) == reference_lines == list(range(2, 1_000_002))


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
def test_a_million_row_inline_table_reads_to_floats_of_its_numbers(million):
    """The inline table of the same numbers: each as float of its TOML text (tomllib's value, which
    tests/io/test_toml_file.py holds the float reading to); a scene refuses the first of its torques above
    the largest a torque may have (flyopt.units.MAGNITUDES: its exponents run to ±300), naming the point."""
    body = million.split("\n", 1)[1].rstrip("\n").replace("\n", "], [")
    table = f"points = [[{body}]]"
    with mock.patch.object(toml_file, "compiled_numbers", wraps=compiled_reader.compiled_numbers) as spy:
        data = toml_file.parse_toml(SCENE.format(table=table))
    rows = data["torque"]["resisting"]["points"]
    assert spy.call_count == 1 and isinstance(rows, toml_file.InlineRows) and len(rows) == 1_000_000
    expected = np.array(body.replace("], [", ",").split(","), dtype=float).reshape(-1, 2)  # float of each text
    assert np.array_equal(bits(rows.array), bits(expected))
    first = int(np.argmax(np.abs(expected[:, 1]) > 1e15))
    with pytest.raises(SceneError, match=rf"torque\.resisting\.points\[{first}\] torque: .* is out of range"):
        flyopt.from_dict(data)


# -- refusals in large tables name the same line -------------------------------------------


def large_csv(bad_line=None, replacement=None, n=40_000, wild=True):
    """A table over the compiled reader's threshold, line ``bad_line`` (from 1, the header is line 1) replaced
    (``wild``: :func:`large_rows`)."""
    angles, values = large_rows(n, wild=wild)
    lines = ["angle,torque"] + [f"{a!r},{v!r}" for a, v in zip(angles.tolist(), values.tolist())]
    if bad_line is not None:
        lines[bad_line - 1] = replacement
    text = "\n".join(lines) + "\n"
    assert len(text) > compiled_reader.COMPILED_READER_BYTES
    return text


@pytest.mark.parametrize(
    "replacement, match",
    [
        ("180,1e999", r"t\.csv line 20001, column 2: '1e999' is not finite \(allowed: a plain number, the torque"),
        ("180,nan", r"t\.csv line 20001, column 2: 'nan' is not finite"),
        ("-inf,1", r"t\.csv line 20001, column 1: '-inf' is not finite \(allowed: a plain number, the angle in deg"),
        ("180,1.6 kN*m", r"t\.csv line 20001, column 2: '1\.6 kN\*m' is not a number"),
        ("180,", r"t\.csv line 20001, column 2: '' is not a number"),
        ('"180",1', r"t\.csv line 20001, column 1: '\"180\"' is not a number"),
        ("180,1,2", r"t\.csv line 20001: expected 2 columns, angle and torque separated by a comma, got 3"),
        ("180", r"t\.csv line 20001: expected 2 columns, angle and torque separated by a comma, got 1: '180'"),
        ("180;1", r"t\.csv line 20001: expected 2 columns"),
    ],
)
def test_a_wrong_line_of_a_large_csv_is_named_as_the_exact_reader_names_it(replacement, match):
    text = large_csv(20001, replacement)
    with pytest.raises(SceneError, match=match) as err:
        csv_table.read_csv(text, "f", "t.csv", COLUMNS, UNITS)
    assert str(err.value) == exact_csv(text)


@pytest.mark.parametrize("replacement", ["", "   ", "# a note", "\r"])
def test_a_blank_or_comment_line_in_a_large_csv_keeps_the_line_numbers(replacement):
    text = large_csv(20001, replacement)
    got = fast_csv(text)
    assert_same(got, exact_csv(text))
    assert got[1][19998:20000] == [20000, 20002]  # line 20001 skipped


@pytest.mark.slow  # 3 s: a large CSV read twice; the reader's refusals are tested by default
def test_underscores_and_unusual_blanks_in_a_large_csv_are_floats(tmp_path):
    """What only Python's float reads (refused by the compiled reader), or a lone carriage return
    (which pyarrow takes for the end of a line), is read as before."""
    for replacement in ("180,1_000", "180,\x0b1000", "180,\u00a01000", "180\r,1000"):
        text = large_csv(20001, replacement)
        got = fast_csv(text)
        assert got[0][19999, 1] == 1000.0
        assert_same(got, exact_csv(text))


def test_a_large_csv_scene_names_its_file_line_and_what_is_allowed(tmp_path):
    """Through flyopt.load: the field, the file, the line (the decreasing angle after the compiled reading)."""
    text = large_csv(30001, "1.0,1000.0")
    (tmp_path / "torque.csv").write_text(text)
    path = tmp_path / "s.toml"
    path.write_text(SCENE.format(table='points_file = "torque.csv"'))
    with pytest.raises(SceneError) as err:
        flyopt.load(path)
    message = str(err.value)
    assert "\n" not in message
    assert "torque.resisting.points_file" in message
    assert message.endswith(
        "torque.csv line 30001: angles must not decrease: 1 deg comes after 269.989 deg on line 30000"
    )


def test_the_row_cap_holds_before_the_compiled_reader(tmp_path, monkeypatch):
    (tmp_path / "torque.csv").write_text(large_csv(wild=False))
    path = tmp_path / "s.toml"
    path.write_text(SCENE.format(table='points_file = "torque.csv"'))
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "39999")
    with mock.patch.object(csv_table, "compiled_numbers") as spy:
        with pytest.raises(SceneError, match=r"has over 39999 rows \(allowed: at most 39999"):
            flyopt.load(path)
    assert spy.call_count == 0  # refused before reading
    # a table of exactly the cap, after its header (its lines counted with the header's: refused before)
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "40000")
    assert len(flyopt.load(path).resisting.values) == 40_000
    headless = tmp_path / "torque.csv"  # without a header, the same rows are counted once read
    headless.write_text(headless.read_text().split("\n", 1)[1])
    monkeypatch.setenv("FLYOPT_MAX_TABLE_ROWS", "39999")
    with pytest.raises(SceneError, match=r"has over 39999 rows \(allowed: at most 39999"):
        flyopt.load(path)


# -- inline TOML tables by the compiled reader -------------------------------------------

TOML_NUMBER = st.one_of(
    st.integers(-(10**6), 10**6).map(str),
    st.floats(allow_nan=False, allow_infinity=False, width=64).map(repr).filter(lambda t: "inf" not in t),
    st.floats(1e-300, 1e300).map(lambda x: f"{x:.6e}"),
    st.sampled_from(["-0", "+0", "-0.0", "+1", "1E5", "1e+05", "-1e-400", "12345678901234567890123", "1e400"]),
)
NOT_TOML = ["01", "1.", ".5", "1e", "1_000", "nan", "-inf", '"1"']
BLANK = st.sampled_from(["", " ", "\t", "\n", " \n  ", "\r\n"])


#: Hypothesis' strategies of test_inline_tables_by_the_compiled_reader_are_tomllibs: the default run tries 30 examples, the slow run 200.
_INLINE_TABLES = dict(
    rows=st.lists(st.tuples(TOML_NUMBER, TOML_NUMBER, BLANK), min_size=60, max_size=150),
    bad=st.one_of(st.none(), st.tuples(st.integers(0, 299), st.sampled_from(NOT_TOML))),
)


def _inline_table_case(rows, bad):
    tokens = [t for a, v, _ in rows for t in (a, v)]
    if bad is not None:
        tokens[bad[0] % len(tokens)] = bad[1]
    body = ",".join(f"{b}[{tokens[2 * k]}, {tokens[2 * k + 1]}]" for k, (_, _, b) in enumerate(rows))
    text = f"x = 1\npoints = [{body}]\n"
    try:
        reference = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        with compiled_always(), pytest.raises(tomllib.TOMLDecodeError) as fast:
            toml_file.parse_toml(text)
        assert str(fast.value) == str(err)
        return
    with compiled_always():
        data = toml_file.parse_toml(text)
    points = data["points"]
    got = points.array if isinstance(points, toml_file.InlineRows) else np.array(points, dtype=float)
    assert np.array_equal(bits(got), bits(np.array(reference["points"], dtype=float)))


test_inline_tables_by_the_compiled_reader_are_tomllibs = settings(max_examples=30, deadline=None)(
    given(**_INLINE_TABLES)(_inline_table_case)
)
test_inline_tables_by_the_compiled_reader_are_tomllibs_many = pytest.mark.slow(
    settings(max_examples=200, deadline=None)(given(**_INLINE_TABLES)(_inline_table_case))
)


def test_a_large_inline_table_by_the_compiled_reader_names_the_point(tmp_path):
    angles, values = large_rows(40_000)
    angles[20000] = 1.0
    table = "points = [" + ", ".join(f"[{a!r}, {v!r}]" for a, v in zip(angles.tolist(), values.tolist())) + "]"
    assert len(table) > compiled_reader.COMPILED_READER_BYTES
    path = tmp_path / "s.toml"
    path.write_text(SCENE.format(table=table))
    with pytest.raises(SceneError, match=r"torque\.resisting\.points: angles must not decrease: point 20000 \(1 deg\)"):
        flyopt.load(path)


@pytest.mark.parametrize(
    "text",
    [
        "a" * 1_100_000 + ",b\n0,1\n",  # a header over the threshold, one row: too few rows
        "a" * 1_100_000 + ",b\n",  # a header alone
        large_csv() + " \n" * 100,  # blank lines at the end, more than the tail looked at
        large_csv() + "\r\n\r\n",
        large_csv().replace("\n", "\r\n"),
        large_csv().replace("\n", "\r\n", 1000),  # CRLF and LF mixed
        large_csv().replace("\n", "\n\n", 1),  # a blank line after the header
    ],
)
def test_edges_of_a_large_csv_are_the_exact_readers(text):
    assert_same(fast_csv(text), exact_csv(text))


# -- the size from which the compiled reader reads, with pyarrow imported or not -----------------


def _tables(rows):
    """(csv text, inline scene text, the numbers) of a table of ``rows`` rows."""
    angles, values = large_rows(rows)
    pairs = list(zip(angles.tolist(), values.tolist()))
    text = "angle,torque\n" + "".join(f"{a!r},{v!r}\n" for a, v in pairs)
    inline = SCENE.format(table="points = [" + ", ".join(f"[{a!r}, {v!r}]" for a, v in pairs) + "]")
    return text, inline, np.column_stack([angles, values])


@pytest.mark.parametrize("imported", [True, False])
def test_a_table_of_tens_of_kilobytes_is_read_by_pyarrow_where_it_is_imported_already(imported, monkeypatch):
    """From LOADED_READER_BYTES in a process that has imported pyarrow (pandas, a sweep, the app), where only
    the reader's own start is left to pay; in one that has not, below COMPILED_READER_BYTES, by float, and
    pyarrow is not imported for it. The same floats either way, bit for bit."""
    import pyarrow  # noqa: F401 (as pandas imports it)

    text, inline, numbers = _tables(1200)
    assert compiled_reader.LOADED_READER_BYTES <= len(text) < compiled_reader.COMPILED_READER_BYTES
    if not imported:  # the one key the decision reads, as a process that has not imported it sees it
        monkeypatch.delitem(sys.modules, "pyarrow")
    with (
        mock.patch.object(csv_table, "compiled_numbers", wraps=compiled_reader.compiled_numbers) as csv_spy,
        mock.patch.object(toml_file, "compiled_numbers", wraps=compiled_reader.compiled_numbers) as toml_spy,
    ):
        read, lines = csv_table.read_csv(text, "f", "t.csv", COLUMNS, UNITS)
        rows = toml_file.parse_toml(inline)["torque"]["resisting"]["points"]
    left_unimported = "pyarrow" not in sys.modules
    assert (csv_spy.call_count, toml_spy.call_count) == ((1, 1) if imported else (0, 0))
    if not imported:
        assert left_unimported  # the decision never imports pyarrow
    assert np.array_equal(bits(read), bits(numbers)) and list(lines) == list(range(2, 1202))
    assert isinstance(rows, toml_file.InlineRows) and np.array_equal(bits(rows.array), bits(numbers))


def test_a_table_below_the_loaded_size_is_read_by_float_with_pyarrow_imported():
    import pyarrow  # noqa: F401

    text, inline, numbers = _tables(300)
    assert len(text) < compiled_reader.LOADED_READER_BYTES
    with (
        mock.patch.object(csv_table, "compiled_numbers") as csv_spy,
        mock.patch.object(toml_file, "compiled_numbers") as toml_spy,
    ):
        read, _ = csv_table.read_csv(text, "f", "t.csv", COLUMNS, UNITS)
        rows = toml_file.parse_toml(inline)["torque"]["resisting"]["points"]
    assert (csv_spy.call_count, toml_spy.call_count) == (0, 0)
    assert np.array_equal(bits(read), bits(numbers)) and np.array_equal(bits(rows.array), bits(numbers))


@pytest.mark.parametrize("size", [40_000, 1_100_000])
def test_a_process_that_blocks_pyarrow_reads_every_table_by_float(size, monkeypatch):
    """sys.modules["pyarrow"] = None (how a missing library is simulated, or an import that failed) is not an
    imported pyarrow: a table below 1 MB is read by float, and one above it, whose compiled reading cannot
    import pyarrow, goes to the exact reader instead of raising ImportError."""
    text, _, numbers = _tables(size // 30)
    assert (len(text) >= compiled_reader.COMPILED_READER_BYTES) == (size > 10**6)
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    assert compiled_reader.compiled_reader_reads(len(text)) == (size > 10**6)
    read, lines = csv_table.read_csv(text, "f", "t.csv", COLUMNS, UNITS)
    assert np.array_equal(bits(read), bits(numbers)) and list(lines) == list(range(2, len(numbers) + 2))
