"""ISO 286 tolerances of a flywheel's seat: the H7 bore of its hub and the JS9 width of its keyway.

The standard tolerance grades IT7 and IT9 by nominal size live in the
package data file ``flyopt/data/iso286.toml`` with their sources (sizes in
mm, tolerances in µm, as the standard prints them); this module converts
them to SI on loading. Every argument and result here is SI (m).

References
----------
.. [1] ISO 286-1:2010, Table 1: standard tolerance grades by nominal size.
.. [2] ISO 286-2:2010: a hole H has EI = 0, ES = +IT; a hole JS has ES = +IT/2, EI = -IT/2.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

from flyopt._toml import tomllib
from flyopt.validate import positive

__all__ = ["Tolerance", "hole_tolerance", "it_grade"]

_DATA_FILE = "iso286.toml"
_ORIGIN = f"flyopt/data/{_DATA_FILE}"
_COLUMNS = ["d_over", "d_up_to", "IT7", "IT9"]
#: The tolerance classes of a hole this module gives: the fundamental deviation and the grade.
_CLASSES = {"H7": ("H", "IT7"), "JS9": ("JS", "IT9")}


@dataclass(frozen=True)
class Tolerance:
    """A toleranced size of a hole, SI.

    Attributes
    ----------
    nominal : float
        The nominal size [m].
    fit : str
        The ISO 286 tolerance class, e.g. ``"H7"``.
    upper, lower : float
        The upper and lower limit deviations ES and EI [m] (the size lies in
        ``nominal + lower`` ... ``nominal + upper``).
    """

    nominal: float
    fit: str
    upper: float
    lower: float


@functools.lru_cache(maxsize=1)
def _load():
    """The rows of ``iso286.toml``: ((d_over, d_up_to, {grade: tolerance}), ...) in metres, checked."""
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    table = tomllib.loads(text)["it_grades"]
    if table.get("size_unit") != "mm" or table.get("tolerance_unit") != "um" or table.get("columns") != _COLUMNS:
        raise ValueError(f"{_ORIGIN}: it_grades must give size_unit 'mm', tolerance_unit 'um', columns {_COLUMNS}")
    rows: list[tuple[float, float, dict[str, float]]] = []
    for index, row in enumerate(table["rows"]):
        values = dict(zip(_COLUMNS, (float(v) for v in row)))
        if len(row) != len(_COLUMNS) or not 0 <= values["d_over"] < values["d_up_to"]:
            raise ValueError(f"{_ORIGIN}: it_grades.rows[{index}] = {row!r} is not (d_over < d_up_to, IT7, IT9)")
        if rows and values["d_over"] * 1e-3 != rows[-1][1]:
            raise ValueError(f"{_ORIGIN}: it_grades.rows[{index}] does not start where the row before ends")
        rows.append((values["d_over"] * 1e-3, values["d_up_to"] * 1e-3, {g: values[g] * 1e-6 for g in ("IT7", "IT9")}))
    return tuple(rows)


def it_grade(size: float, grade: str) -> float:
    """The ISO 286-1 standard tolerance of ``grade`` ("IT7" or "IT9") for a nominal size [m]; [m].

    Raises
    ------
    ValueError
        The size is not positive, or beyond the table (500 mm), or the grade is not in it.
    """
    size = positive(size, "nominal size [m]")
    for d_over, d_up_to, grades in _load():
        if d_over < size <= d_up_to:
            if grade not in grades:
                raise ValueError(f"{_ORIGIN} gives no {grade!r} (it gives {', '.join(grades)})")
            return grades[grade]
    raise ValueError(f"a nominal size of {size * 1e3:g} mm is beyond the ISO 286 table of {_ORIGIN} (up to 500 mm)")


def hole_tolerance(size: float, fit: str = "H7") -> Tolerance:
    """The limit deviations of a hole of nominal ``size`` [m] in tolerance class ``fit`` ("H7" or "JS9").

    Examples
    --------
    A 55 mm bore H7: IT7 = 30 µm over 50 up to 80 mm, so 55.000 ... 55.030 mm.
    """
    if fit not in _CLASSES:
        raise ValueError(f"tolerance class {fit!r} is not one flyopt gives (it gives {', '.join(_CLASSES)})")
    deviation, grade = _CLASSES[fit]
    it = it_grade(size, grade)
    upper, lower = (it, 0.0) if deviation == "H" else (it / 2.0, -it / 2.0)
    return Tolerance(nominal=float(size), fit=fit, upper=upper, lower=lower)
