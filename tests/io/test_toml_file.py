"""Large inline tables are read without tomllib, and read exactly as tomllib reads them (issue 12).

``flyopt.io.toml_file.read_toml`` cuts large ``points = [[a, b], ...]`` tables
out of the text and reads their numbers with ``float``; everything else, and
every table it is not sure of, is tomllib's. The reference here is tomllib
itself: the same numbers to the bit (the sign of zero included), and the
same error for a file tomllib refuses. A file that cannot be read, or is not
TOML, is one SceneError naming it.
"""

import math

import numpy as np
import pytest
import tomllib
from conftest import PROBLEMS
from hypothesis import given, settings
from hypothesis import strategies as st
from scene_cases import scene_text

import flyopt
from flyopt.errors import SceneError
from flyopt.io import toml_file
from flyopt.io.scene import from_dict

HEAD = """title = "t"
[machine]
speed = "300 rpm"
delta = 0.05
[torque.driving]
constant = "unknown"
[torque.resisting]
angle_unit = "deg"
unit = "N*m"
"""


def bits(array):
    """The bit patterns of an array of floats (tells -0.0 from 0.0)."""
    return np.ascontiguousarray(array, dtype=float).view(np.int64)


def table_text(angles, values, fmt=repr, sep=", ", row_sep=", ", wrap=0):
    rows = [f"[{fmt(a)}{sep}{fmt(v)}]" for a, v in zip(angles, values)]
    if wrap:
        rows = [r + ("\n" if k % wrap == wrap - 1 else "") for k, r in enumerate(rows)]
    return "points = [" + row_sep.join(rows) + "]\n"


def tomllib_scene(text):
    return from_dict(tomllib.loads(text))


def fast_scene(text):
    return from_dict(toml_file.parse_toml(text))


def large(n=400):
    angles = np.linspace(0.0, 360.0, n)
    return angles, 1000 + 400 * np.sin(np.radians(angles))


def test_a_large_table_is_read_without_tomllib_and_gives_tomllibs_floats():
    angles, values = large()
    text = HEAD + table_text(angles.tolist(), values.tolist())
    data = toml_file.parse_toml(text)
    rows = data["torque"]["resisting"]["points"]
    assert isinstance(rows, toml_file.InlineRows) and len(rows) == 400  # the fast reading took it
    expected = np.array(tomllib.loads(text)["torque"]["resisting"]["points"], dtype=float)
    assert np.array_equal(bits(rows.array), bits(expected))
    a, b = fast_scene(text), tomllib_scene(text)
    assert np.array_equal(bits(a.resisting.angles), bits(b.resisting.angles))
    assert np.array_equal(bits(a.resisting.values), bits(b.resisting.values))


@pytest.mark.parametrize(
    "sep, row_sep, end",
    [
        (", ", ", ", "]"),
        (",", ",", ",]"),
        (" , ", ",\n", ",\n]"),
        (",\t", " ,\r\n  ", "\r\n]"),
        (",\n    ", "\n  ,\n  ", "\n,\n]"),
    ],
)
def test_every_layout_of_blanks_and_commas_is_read_fast(sep, row_sep, end):
    angles, values = large()
    rows = [
        f"[{a!r}{sep}{v!r}{',' if k % 3 == 0 else ''}]"
        for k, (a, v) in enumerate(zip(angles.tolist(), values.tolist()))
    ]
    text = HEAD + "points = [" + row_sep.join(rows) + end + "\n"
    rows = toml_file.parse_toml(text)["torque"]["resisting"]["points"]
    assert isinstance(rows, toml_file.InlineRows)
    expected = np.array(tomllib.loads(text)["torque"]["resisting"]["points"], dtype=float)
    assert np.array_equal(bits(rows.array), bits(expected))


def test_a_small_table_is_left_to_tomllib():
    text = HEAD + "points = [[0, 1], [360, 1]]\n"
    assert isinstance(toml_file.parse_toml(text)["torque"]["resisting"]["points"], list)


@pytest.mark.parametrize(
    "variant",
    [
        "comment inside",
        "unit strings",
        "in a multi-line string",
        "in a literal multi-line string",
        "underscore",
        "inf",
        "leading zero",
        "bare fraction",
        "trailing dot",
        "lone carriage return",
        "three columns",
        "dotted key",
    ],
)
def test_what_the_fast_reading_is_not_sure_of_is_tomllibs(variant):
    """Each variant is read by tomllib whole: the same data, or the same error."""
    angles, values = large()
    body = table_text(angles.tolist(), values.tolist())
    text = (
        HEAD
        + {
            "comment inside": body.replace("], [", "], # a note\n [", 1),
            "unit strings": body.replace("[0.0, ", '["0 deg", ', 1),
            "in a multi-line string": 'description = """\n' + body + '"""\n',
            "in a literal multi-line string": "description = '''\n" + body + "'''\npoints = [[0, 1], [360, 1]]\n",
            "underscore": body.replace("[0.0, ", "[0.0_0, ", 1),
            "inf": body.replace("[360.0, ", "[inf, ", 1),
            "leading zero": body.replace("[0.0, ", "[00, ", 1),
            "bare fraction": body.replace("[0.0, ", "[.0, ", 1),
            "trailing dot": body.replace("[0.0, ", "[0., ", 1),
            "lone carriage return": body.replace("], [", "],\r [", 1),
            "three columns": body.replace("[0.0, ", "[0.0, 1, ", 1),
            "dotted key": body.replace("points", "resisting.points", 1).replace("[torque.resisting]", "[torque]"),
        }[variant]
    )
    data = toml_file.parse_toml(text) if _reads(text) else None
    if data is None:
        with pytest.raises(tomllib.TOMLDecodeError) as fast:
            toml_file.parse_toml(text)
        with pytest.raises(tomllib.TOMLDecodeError) as reference:
            tomllib.loads(text)
        assert str(fast.value) == str(reference.value)
    else:
        assert data == tomllib.loads(text)  # no InlineRows anywhere: tomllib's own result


def _reads(text):
    try:
        tomllib.loads(text)
        return True
    except tomllib.TOMLDecodeError:
        return False


@pytest.mark.parametrize(
    "token, expected",
    [("-0", 0.0), ("+0", 0.0), ("-0.0", -0.0), ("0", 0.0), ("-0e0", -0.0), ("1e-400", 0.0), ("-1e-400", -0.0)],
)
def test_signed_zeros_are_tomllibs(token, expected):
    angles, values = large()
    values = [token] + [repr(v) for v in values[1:].tolist()]
    text = HEAD + table_text(angles.tolist(), values, fmt=str)
    rows = toml_file.parse_toml(text)["torque"]["resisting"]["points"]
    assert isinstance(rows, toml_file.InlineRows)
    reference = float(tomllib.loads(text)["torque"]["resisting"]["points"][0][1])
    assert math.copysign(1, rows.array[0, 1]) == math.copysign(1, reference) == math.copysign(1, expected)


def test_a_number_beyond_the_floats_gets_the_error_it_got_before(tmp_path):
    angles, values = large()
    values = ["1e999"] + [repr(v) for v in values[1:].tolist()]
    path = tmp_path / "s.toml"
    path.write_text(HEAD + table_text(angles.tolist(), values, fmt=str))
    with pytest.raises(flyopt.SceneError, match=r"torque\.resisting\.points\[0\] torque: must be finite, got inf"):
        flyopt.load(path)


def test_a_decreasing_angle_in_a_large_table_names_the_point_as_before(tmp_path):
    angles, values = large()
    angles[200] = 1.0
    path = tmp_path / "s.toml"
    path.write_text(HEAD + table_text(angles.tolist(), values.tolist()))
    with pytest.raises(flyopt.SceneError, match=r"angles must not decrease: point 200 \(1 deg\) comes after"):
        flyopt.load(path)


def test_member_tables_and_two_tables_in_one_file():
    """A member's force table and a torque table, both large, in one file: each is tomllib's."""
    angles, values = large(300)
    text = (
        HEAD
        + table_text(angles.tolist(), values.tolist(), wrap=3)
        + '[[member]]\nname = "ram"\nmass = 1\nvelocity_ratio = 0.1\nangle_unit = "deg"\nunit = "N"\n'
        + table_text(angles.tolist(), (-values).tolist(), sep=",", row_sep=",\n  ").replace("points", "force")
    )
    data = toml_file.parse_toml(text)
    assert isinstance(data["member"][0]["force"], toml_file.InlineRows)
    a, b = fast_scene(text), tomllib_scene(text)
    assert np.array_equal(bits(a.resisting.values), bits(b.resisting.values))
    assert np.array_equal(bits(a.members[0].force[1]), bits(b.members[0].force[1]))


NUMBER = st.one_of(
    st.integers(-(10**6), 10**6).map(str),
    st.floats(allow_nan=False, allow_infinity=False, width=64).map(repr).filter(lambda t: "inf" not in t),
    st.floats(-1e3, 1e3).map(lambda x: f"{x:.4f}"),
    st.floats(1e-300, 1e300).map(lambda x: f"{x:.6e}"),
    st.sampled_from(["-0", "+0", "-0.0", "+1", "1E5", "1e+05", "-1e-400", "12345678901234567890123"]),
)
TOML_NOT_FAST = ("1_000", "nan", "-inf", "0x1F", '"1"')
"""TOML values the fast reading leaves to tomllib (a TOML array may mix types)."""
NOT_TOML = ["01", "1.", ".5", "1e", "--1", "1.2.3", "+.5", "1.e5", "1e400", *TOML_NOT_FAST]
BLANK = st.sampled_from(["", " ", "  ", "\t", "\n", " \n  ", "\r\n"])


#: Hypothesis' strategies of test_random_tables_read_as_tomllib_reads_them: the default run tries 30 examples, the slow run 200.
_RANDOM_TABLES = dict(
    rows=st.lists(st.tuples(NUMBER, NUMBER, BLANK, BLANK, st.booleans()), min_size=60, max_size=200),
    trailing=st.booleans(),
    bad=st.one_of(st.none(), st.tuples(st.integers(0, 599), st.sampled_from(NOT_TOML))),
)


def _random_table_case(rows, trailing, bad):
    tokens = [t for a, v, *_ in rows for t in (a, v)]
    if bad is not None:  # one number TOML does not allow
        tokens[bad[0] % len(tokens)] = bad[1]
    body = ",".join(
        f"{b1}[{tokens[2 * k]}{b2},{b1}{tokens[2 * k + 1]}{',' if comma else ''}]"
        for k, (_, _, b1, b2, comma) in enumerate(rows)
    )
    text = f"x = 1\npoints = [{body}{',' if trailing else ''}]\n"
    try:
        reference = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        with pytest.raises(tomllib.TOMLDecodeError) as fast:
            toml_file.parse_toml(text)
        assert str(fast.value) == str(err)
        return
    data = toml_file.parse_toml(text)
    points = data["points"]
    expected = np.array(reference["points"], dtype=float)
    if isinstance(points, toml_file.InlineRows):
        got = points.array
    else:  # left to tomllib: a short table, or a number beyond the floats
        assert isinstance(points, list)
        assert (
            len(text) < toml_file.FAST_TABLE_CHARACTERS + 20
            or not np.isfinite(expected).all()
            or (bad is not None and bad[1] in TOML_NOT_FAST)
        )
        got = np.array(points, dtype=float)
    assert np.array_equal(bits(got), bits(expected))
    assert data["x"] == 1


test_random_tables_read_as_tomllib_reads_them = settings(max_examples=30, deadline=None)(
    given(**_RANDOM_TABLES)(_random_table_case)
)
test_random_tables_read_as_tomllib_reads_them_many = pytest.mark.slow(
    settings(max_examples=200, deadline=None)(given(**_RANDOM_TABLES)(_random_table_case))
)


def test_toml_syntax_and_duplicate_tables(write_scene):
    with pytest.raises(SceneError, match=r"scene.toml: not valid TOML"):
        flyopt.load(write_scene("[machine\nspeed = 1"))
    dup = scene_text() + '[torque.driving]\nconstant = "10 N*m"\n'
    with pytest.raises(SceneError, match=r"not valid TOML.*torque"):
        flyopt.load(write_scene(dup))


def test_missing_file():
    with pytest.raises(SceneError, match=r"no-such.toml: cannot read the file"):
        flyopt.load("no-such.toml")


def test_a_scene_saved_with_a_byte_order_mark_reads_as_without(tmp_path, capsys):
    """Windows Notepad's "UTF-8 with BOM" made every scene "not valid TOML: Invalid statement (at line 1)"."""
    import flyopt
    from flyopt.cli.main import main
    from flyopt.cli.toml_lines import key_lines

    text = (PROBLEMS / "shear-press.toml").read_text(encoding="utf-8")
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
    with_mark, without = flyopt.load(path), flyopt.load(PROBLEMS / "shear-press.toml")
    assert with_mark.title == without.title and with_mark.delta == without.delta
    assert key_lines("\ufeff" + text) == key_lines(text)  # flyopt check's line numbers too
    path.write_bytes(b"\xef\xbb\xbfsped = 3\n" + text.encode("utf-8"))
    assert main(["check", str(path)]) == 2
    assert f"{path}:1: sped: unknown key" in capsys.readouterr().err  # said at its line, the first


@pytest.mark.parametrize("written", ["1" * 4301, "1_" * 4300 + "1", "-" + "9" * 5000])
def test_a_whole_number_longer_than_python_converts_is_placed_by_its_line(tmp_path, written):
    """tomllib's conversion of an integer of over 4,300 digits said so in Python's words ("use
    sys.set_int_max_str_digits()"), naming no line; now the line and the count of digits."""
    import sys

    text = scene_text().replace("delta = 0.05", f"delta = {written}", 1)
    assert f"delta = {written}" in text
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    line = text[: text.index(written)].count("\n") + 1
    digits = sum(c.isdigit() for c in written)
    limit = sys.get_int_max_str_digits()
    with pytest.raises(SceneError) as refusal:
        flyopt.load(path)
    assert str(refusal.value) == (
        f"{path}: not a scene: a whole number of {digits:,} digits at line {line} (allowed: at most {limit:,} digits)"
    )


def test_long_digit_runs_in_comments_and_strings_are_no_number(tmp_path):
    """The number refused is the one tomllib read: 5,000 digits in a comment and in a title before it were
    named instead ("at line 1"), and 50 comment lines of 4,300 digits took 17 s to search."""
    import time

    text = scene_text().replace("delta = 0.05", "delta = " + "7" * 4301, 1)
    head = f"# {'1' * 5000}\n" + "".join(f"# {'2' * 4300}\n" for _ in range(50))
    path = tmp_path / "scene.toml"
    path.write_text(head + text.replace('title = "t"', f'title = "{"3" * 5000}"', 1), encoding="utf-8")
    written = path.read_text(encoding="utf-8")
    line = written[: written.index("7" * 4301)].count("\n") + 1
    assert line > 52
    start = time.process_time()
    with pytest.raises(SceneError, match=rf"a whole number of 4,301 digits at line {line} \("):
        flyopt.load(path)
    assert time.process_time() - start < 5  # 17 s before; well under a second now
