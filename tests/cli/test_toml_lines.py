"""The line of a key path in a TOML text (flyopt.cli.toml_lines), for flyopt check's FILE:LINE."""

import pytest
from conftest import PROBLEMS, ROOT
from hypothesis import given, settings
from hypothesis import strategies as st

from flyopt._toml import tomllib
from flyopt.cli.toml_lines import key_lines, line_of, set_value

TRICKY = '''\
title = "a # not a comment [x]"  # a comment = 1
[machine]
speed = "1500 rpm"
"delta" = 0.05
notes = """
x = 1
[not_a_table]
"""
literal = \'\'\'
y = [2
\'\'\'
[torque.driving]
points = [
  [0, 1],  # a row, then a comment with ] and [
  [90, 2],

  [180, "3 ]"],
]
motor = { kind = "induction", "rated power" = "7 kW", nested = { a = 1 } }
[[member]]
name = "a"
[[member]]
name = 'b'
sub.key = 3
[member.extra]
x = 1
[[power_chain.branch]]
name = "b1"
[[power_chain.branch.branch]]
name = "b11"
'''

EXPECTED = {
    "title": 1,
    "machine": 2,
    "machine.speed": 3,
    "machine.delta": 4,
    "machine.notes": 5,
    "machine.literal": 9,
    "torque.driving": 12,
    "torque.driving.points": 13,
    "torque.driving.points[0]": 14,
    "torque.driving.points[1][1]": 15,
    "torque.driving.points[2]": 17,
    "torque.driving.motor.kind": 19,
    "torque.driving.motor.rated power": 19,
    "torque.driving.motor.nested.a": 19,
    "member[0]": 20,
    "member[0].name": 21,
    "member[1]": 22,
    "member[1].name": 23,
    "member[1].sub.key": 24,
    "member[1].extra": 25,
    "member[1].extra.x": 26,
    "power_chain.branch[0].name": 28,
    "power_chain.branch[0].branch[0]": 29,
    "power_chain.branch[0].branch[0].name": 30,
}


def test_the_tricky_text_is_toml():
    tomllib.loads(TRICKY)


@pytest.mark.parametrize("path, line", EXPECTED.items())
def test_each_key_is_on_its_line(path, line):
    assert key_lines(TRICKY)[path] == line


def test_no_key_is_made_up_from_inside_a_string():
    lines = key_lines(TRICKY)
    assert "not_a_table" not in lines and "machine.x" not in lines and "machine.y" not in lines


@pytest.mark.parametrize(
    "field, line",
    [
        ("torque.driving.points[2][1]", 17),  # an element of a row: the row's line
        ("member[1].mass", 22),  # a missing key: its table's line
        ("member[5]", 20),  # an entry the file does not have: the array's first line
        ("torque.resisting.constant", 12),  # [torque.driving] made [torque]: its line
        ("sweep.vary.delta", None),
    ],
)
def test_a_field_not_written_takes_its_nearest_enclosing_line(field, line):
    assert line_of(key_lines(TRICKY), field) == line


SHIPPED = sorted([*PROBLEMS.rglob("*.toml"), *(ROOT / "tests" / "data").rglob("*.toml")])


def _keys(document, path=""):
    """Every key path of a document as tomllib reads it (arrays of tables walked)."""
    for key, value in document.items():
        here = f"{path}.{key}" if path else key
        yield here, key
        if isinstance(value, dict):
            yield from _keys(value, here)
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for k, item in enumerate(value):
                yield from _keys(item, f"{here}[{k}]")


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_key_of_a_shipped_scene_is_found_on_a_line_that_writes_it(path):
    """tomllib's keys (an independent reading) each have a line, and that line writes the key's name."""
    text = path.read_text(encoding="utf-8")
    lines = key_lines(text)
    rows = text.splitlines()
    for field, key in _keys(tomllib.loads(text)):
        assert field in lines, field
        assert key in rows[lines[field] - 1], (field, lines[field], rows[lines[field] - 1])


@pytest.mark.parametrize("text", ['a=[\\}2"2,}2.3}}b[{ \n\t. {#}\n=]\n', "a = [}", "a = {b = }}", "a = [1, }, 2]"])
def test_text_that_is_not_toml_ends_the_scan_rather_than_looping(text):
    """The app places errors on any text typed (flyopt.app.model.field_line): a stray brace once looped forever."""
    lines = key_lines(text)
    assert lines.get("a") == 1


def _written(tables, dotted):
    """A TOML text of ``tables`` ({table: {key: int}}): each table under its header, or as dotted keys."""
    lines = []
    for table, keys in tables.items():
        if dotted:
            lines += [f"{table}.{k} = {v}  # a comment" for k, v in keys.items()]
        else:
            lines.append(f"[{table}]")
            lines += [f"{k} = {v}" for k, v in keys.items()]
            lines.append("")
    return "\n".join(lines) + "\n"


_NAMES = st.sampled_from(["a", "b", "speed", "delta", "x_y"])


@settings(max_examples=150, deadline=None)
@given(
    tables=st.dictionaries(
        st.sampled_from(["machine", "design", "t"]),
        st.dictionaries(_NAMES, st.integers(0, 9), min_size=1, max_size=3),
        min_size=1,
        max_size=3,
    ),
    dotted=st.booleans(),
    table=st.sampled_from(["machine", "design", "t", "new"]),
    key=_NAMES,
    value=st.integers(10, 99),
)
def test_set_value_writes_a_text_tomllib_reads_with_the_value_and_nothing_else_moved(tables, dotted, table, key, value):
    """The app's form writes through set_value: whatever the layout (headers or dotted keys, a key written or
    not, a table written or not), the text stays TOML, holds the value, and every other value is as it was."""
    text = _written(tables, dotted)
    edited = set_value(text, f"{table}.{key}", str(value))
    data = tomllib.loads(edited)
    assert data[table][key] == value
    expected = {t: dict(keys) for t, keys in tables.items()}
    expected.setdefault(table, {})[key] = value
    assert data == expected
