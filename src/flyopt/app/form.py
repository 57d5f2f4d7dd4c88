"""The app's form beside the TOML: the common fields and the scene's tables, written into the text as if typed.

The editor's text stays the one truth. The form shows what the text says (read
by ``tomllib`` after each valid edit) and a change in the form rewrites only
that value in the text (:func:`flyopt.cli.toml_lines.set_value`: comments and
layout kept), which is then checked and solved like any edit, by flyopt's own
loader: the form adds no rule of its own about what a field may hold.

Tables (a torque's, a force's or a pressure's ``points``) are shown as a grid;
rows pasted from a spreadsheet (tab, semicolon or comma separated) or uploaded
as a CSV file are read by the loader's own CSV reader
(:func:`flyopt.io.csv_table.read_csv`, with its refusals and its row limit) and
written inline as plain numbers with the table's ``angle_unit`` and ``unit``,
so that the scene stays one file (the Scene download holds the table).
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from flyopt._toml import tomllib
from flyopt.cli.toml_lines import set_value
from flyopt.design.spec import DesignSpec
from flyopt.io.scene import Scene
from flyopt.names import Geometry

__all__ = [
    "FIELDS",
    "SHAFT_COLUMNS",
    "Field",
    "parse",
    "pasted_rows",
    "rows_of",
    "set_field",
    "set_rows",
    "set_shafts",
    "shaft_rows",
    "set_table_numbers",
    "shown_values",
    "tables",
]


@dataclass(frozen=True)
class Field:
    """One common field of the form: its key path, its label and how it is entered.

    ``kind``: "quantity" (a number, or a string with its unit: "1500 rpm"), "choice" (one of
    ``choices``), "materials" (names of the scene's material library).
    """

    path: str
    label: str
    kind: str = "quantity"
    choices: tuple[str, ...] = ()


# what a field the text does not write is taken to be, as the loader takes it (its one default), said in the label
_EFFICIENCY = Scene.__dataclass_fields__["efficiency"].default
_HB_LOW, _HB_HIGH = DesignSpec().hb_ratio

#: The common fields (issue 29: speed, δ, efficiency, the envelope, the geometry and the materials).
FIELDS: tuple[Field, ...] = (
    Field("machine.speed", "mean speed (e.g. 1500 rpm)"),
    Field("machine.delta", "allowed δ (e.g. 0.05 or 5 %)"),
    Field("machine.efficiency", f"efficiency (e.g. 0.85; {_EFFICIENCY:g} if not given)"),
    Field("design.geometry", "geometry", "choice", tuple(g.value for g in Geometry)),
    Field("design.max_outer_diameter", "largest outer diameter (e.g. 600 mm)"),
    Field("design.max_width", "largest width (e.g. 250 mm)"),
    Field("design.hb_ratio", f"rim H/B (e.g. 1.5, or 1.5, 2 for a range; {_HB_LOW:g} to {_HB_HIGH:g} if not given)"),
    Field("design.materials", "materials", "materials"),
)

#: What the first column of a table holds, and the second's name by the table's kind.
_COLUMNS = {"torque": ("angle", "torque"), "force": ("angle", "force"), "pressure": ("angle", "pressure")}


def parse(text: str) -> dict[str, Any] | None:
    """The text as TOML data, or None where it is not TOML (the editor says why)."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return None


def _get(data: Mapping[str, Any], path: str) -> Any:
    current: Any = data
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", path):
        if part.startswith("["):
            index = int(part[1:-1])
            if not isinstance(current, list) or index >= len(current):
                return None
            current = current[index]
        elif isinstance(current, Mapping) and part in current:
            current = current[part]
        else:
            return None
    return current


def shown_values(data: Mapping[str, Any]) -> dict[str, Any]:
    """Each common field's value as the form shows it ("" where the text does not write it)."""
    shown: dict[str, Any] = {}
    for field in FIELDS:
        value = _get(data, field.path)
        if field.kind == "materials":
            shown[field.path] = [str(v) for v in value] if isinstance(value, list) else []
        elif value is None or isinstance(value, (dict, list)) and field.kind != "quantity":
            shown[field.path] = ""
        elif isinstance(value, list):
            shown[field.path] = ", ".join(_cell(v) for v in value)
        else:
            shown[field.path] = _cell(value)
    return shown


def _cell(value: Any) -> str:
    """A TOML value as typed in a cell: a number as written, a string's content."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return repr(value)
    return str(value)


def literal(shown: str) -> str:
    """The TOML value of what is typed in a field or cell: a number where TOML reads it as one (a finite
    integer or float, as typed), else a string (its control characters escaped)."""
    text = shown.strip()
    try:
        value = tomllib.loads(f"v = {text}")["v"] if text and "\n" not in text and "#" not in text else None
    except tomllib.TOMLDecodeError:
        value = None
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        return text
    return toml_string(text)


def toml_string(text: str) -> str:
    """``text`` as a TOML basic string: JSON's escapes, and DEL and the C1 controls (which TOML refuses raw)."""
    quoted = json.dumps(text, ensure_ascii=False)  # a JSON string is a TOML basic string but for these
    return re.sub(r"[\x7f-\x9f]", lambda m: f"\\u{ord(m.group()):04x}", quoted)


def set_field(text: str, field: Field, shown: Any) -> str:
    """``text`` with the common ``field`` set to what the form shows (a list of names for the materials).

    An empty quantity leaves the text as it is (a field is removed in the editor, where its comment is).
    A range typed "1.2, 1.8" (H/B, efficiencies of stages) is written as an array.
    """
    if field.kind == "materials":
        names = [str(name) for name in shown]
        return set_value(text, field.path, "[" + ", ".join(toml_string(n) for n in names) + "]")
    typed = str(shown).strip()
    if not typed:
        return text
    if field.kind == "quantity" and "," in typed:
        return set_value(text, field.path, "[" + ", ".join(literal(p) for p in typed.split(",")) + "]")
    return set_value(text, field.path, literal(typed))


def tables(data: Mapping[str, Any]) -> list[str]:
    """The key paths of the scene's tables written inline: every ``points`` array of rows of two."""
    return sorted(_tables(data, ""))


def _tables(value: Any, path: str) -> Iterator[str]:
    if isinstance(value, Mapping):
        for key, inner in value.items():
            here = f"{path}.{key}" if path else str(key)
            if (
                key == "points"
                and isinstance(inner, list)
                and inner
                and all(isinstance(row, list) and len(row) == 2 for row in inner)
            ):
                yield here
            else:
                yield from _tables(inner, here)
    elif isinstance(value, list) and value and all(isinstance(v, Mapping) for v in value):
        for index, inner in enumerate(value):
            yield from _tables(inner, f"{path}[{index}]")


def columns_of(path: str) -> tuple[str, str]:
    """The two columns' names of a table, by the kind its path names (angle and torque by default)."""
    for kind, names in _COLUMNS.items():
        if kind in path:
            return names
    return ("angle", "value")


def rows_of(data: Mapping[str, Any], path: str) -> list[list[str]]:
    """The table at ``path`` as cells (its numbers as written, its strings' contents)."""
    rows = _get(data, path)
    return [[_cell(a), _cell(b)] for a, b in rows] if isinstance(rows, list) else []


def _rows_literal(rows: Sequence[Sequence[str]]) -> str:
    cells = ["[" + ", ".join(literal(str(c)) for c in row) + "]" for row in rows]
    if len(cells) <= 4:
        return "[" + ", ".join(cells) + "]"
    return "[\n" + "".join(f"    {c},\n" for c in cells) + "]"


def set_rows(text: str, path: str, rows: Sequence[Sequence[str]]) -> str:
    """``text`` with the table at ``path`` holding ``rows`` (cells as typed: a number, or a value with its unit)."""
    kept = [[str(c).strip() for c in row] for row in rows if any(str(c).strip() for c in row)]
    return set_value(text, path, _rows_literal(kept))


def pasted_rows(pasted: str, path: str, units: tuple[str, str], source: str = "the pasted rows") -> list[list[float]]:
    """Rows pasted from a spreadsheet or a CSV file (``source`` names them in a message: the file's name), read by
    the loader's CSV reader (its refusals, its limit).

    Tabs and semicolons separate columns as commas do; a first line naming the columns is skipped.

    Raises
    ------
    SceneError
        The rows are not a table of two columns of numbers (the line named), or too many.
    """
    from flyopt.io.csv_table import read_csv
    from flyopt.io.input_files import check_rows

    text = pasted.replace("\r\n", "\n").replace("\t", ",").replace(";", ",")
    text = "\n".join(re.sub(r"\s*,\s*", ",", line.strip()) for line in text.split("\n"))
    check_rows(text.count("\n") + 1, path, source)
    numbers, _lines = read_csv(text, path, source, columns_of(path), units)
    return [[float(a), float(b)] for a, b in numbers]


def set_table_numbers(text: str, path: str, numbers: Sequence[Sequence[float]], units: tuple[str, str]) -> str:
    """``text`` with the table at ``path`` holding plain ``numbers`` in ``units`` (angle_unit and unit set)."""
    table = path.rpartition(".")[0]
    rows = [[repr(float(a)), repr(float(b))] for a, b in numbers]
    text = set_value(text, path, _rows_literal(rows))
    text = set_value(text, f"{table}.angle_unit", json.dumps(units[0]))
    return set_value(text, f"{table}.unit", json.dumps(units[1]))


#: The columns of the form's shafts grid: each ``[[shaft]]`` the text writes, by its name and speed ratio (the
#: issue's common fields; a shaft described as a part, its layout and its train, is edited in the TOML).
SHAFT_COLUMNS = ("name", "speed_ratio")


def shaft_rows(data: Mapping[str, Any]) -> list[list[str]]:
    """The text's ``[[shaft]]`` entries as cells (name, speed ratio; "" where an entry does not write one)."""
    shafts = data.get("shaft")
    if not isinstance(shafts, list):
        return []
    return [[_cell(entry.get(c, "")) if isinstance(entry, Mapping) else "" for c in SHAFT_COLUMNS] for entry in shafts]


def set_shafts(text: str, rows: Sequence[Sequence[str]]) -> str:
    """``text`` with its ``[[shaft]]`` entries' names and speed ratios as the grid shows them: each cell written
    where it differs from the text (a name as a string, a ratio as typed), the rest of the text kept.

    Raises
    ------
    KeyError
        A row for an entry the text does not write (a shaft is added in the TOML).
    """
    data = parse(text) or {}
    written = shaft_rows(data)
    for index, row in enumerate(rows):
        if index >= len(written):
            raise KeyError(f"shaft[{index}]: add a [[shaft]] in the TOML; the form edits the shafts it writes")
        for column, typed, was in zip(SHAFT_COLUMNS, row, written[index]):
            typed = str(typed).strip()
            if not typed or typed == was:
                continue
            value = toml_string(typed) if column == "name" else literal(typed)
            try:
                text = set_value(text, f"shaft[{index}].{column}", value)
            except KeyError:  # the entry is there, but not as a [[shaft]] table of its own lines
                raise KeyError(
                    "the shafts are written inline (shaft = [...]): edit them in the TOML, or write each as [[shaft]]"
                ) from None
    return text
