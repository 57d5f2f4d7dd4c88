"""Results in a notebook: the answer card, the ranking as a DataFrame, and tables in the user's units.

What a result looks like in Jupyter is decided here, on the report's floor,
and registered in :mod:`flyopt.views`, which the result classes consult
(they stand on lower floors and may not import this module):

- a :class:`~flyopt.pipeline.Solution` shows its answer card
  (``_repr_html_``), the card the app shows (:mod:`flyopt.report.card`: the
  report's answer section as a small table under the scene's title, every
  string escaped), and an :class:`~flyopt.analysis.Analysis` (``flyopt.analyse``)
  the same card of the cycle alone;
- a :class:`~flyopt.design.result.DesignResult` gives its ranking as a
  DataFrame (``to_frame``: every material × shaft combination, the JSON's
  ``design.candidates`` fields, SI, each column's unit in
  ``attrs["flyopt"]["units"]``) and shows it as a table in the reader's units.

:func:`to_units` puts a table's quantities into a unit system of
:mod:`flyopt.report.display` (or, for a sweep, into the units its fields were
given in), keeping each column's unit in the metadata; :func:`read_results`
reads a sweep, Pareto or trade-off file back (in SI, or in those units).
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from html import escape
from typing import TYPE_CHECKING, Any

from flyopt.design.check import binding_label
from flyopt.outputs.quantities import dimension_of, table_units
from flyopt.report import display
from flyopt.views import register

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.analysis import Analysis
    from flyopt.design.result import DesignResult
    from flyopt.pipeline import Solution

__all__ = [
    "INPUT",
    "RANKING_COLUMNS",
    "analysis_card",
    "answer_card",
    "ranking_frame",
    "ranking_html",
    "read_results",
    "to_units",
]

#: ``units=INPUT``: a sweep's varied fields in the units they were given in (``300,600rpm``: rpm).
INPUT = display.INPUT_UNITS

#: The columns of a ranking shown in a notebook (:func:`ranking_html`); ``to_frame`` has them all.
RANKING_COLUMNS = ("material", "shaft", "feasible", "mass", "d_outer", "b", "h", "rim_speed", "cost", "binding")


# --------------------------------------------------------------------------
# The answer card
# --------------------------------------------------------------------------


def answer_card(solution: Solution, units: str = display.DEFAULT, digits: int = display.DEFAULT_DIGITS) -> str:
    """The answer card of a solution as HTML: the app's card (:func:`flyopt.report.card.solution_card`, the
    report's answer section: the verdict, then the model, speeds, δ, A_max, J_F, the wheel with its limits and
    the verified δ), every string escaped.

    Parameters
    ----------
    solution : flyopt.pipeline.Solution
    units : str
        The unit system (:data:`flyopt.report.display.SYSTEMS`).
    digits : int
        Significant figures (:func:`flyopt.report.display.check_digits`).

    Returns
    -------
    str
        ``<div class="card flyopt-answer ...">...</div>``.
    """
    from flyopt.report.card import card_html, solution_card

    return card_html(solution_card(solution, units, digits))


def analysis_card(analysis: Analysis, units: str = display.DEFAULT, digits: int = display.DEFAULT_DIGITS) -> str:
    """The answer card of a cycle's analysis (``flyopt.analyse``) as HTML, by the same card
    (:func:`flyopt.report.card.analysis_card`)."""
    from flyopt.report.card import analysis_card as card_of_analysis
    from flyopt.report.card import card_html

    return card_html(card_of_analysis(analysis, units, digits))


# --------------------------------------------------------------------------
# The ranking
# --------------------------------------------------------------------------


def ranking_frame(design: DesignResult, units: str | None = None) -> pd.DataFrame:
    """Every combination a design decided, best first, one row each (``DesignResult.to_frame``).

    The columns are the scalar fields of the JSON's ``design.candidates``
    (:meth:`~flyopt.design.result.Candidate.to_dict`), in their order:
    ``material`` (its key), ``shaft``, ``feasible``, ``mass``, ``d_outer`` ...;
    ``binding`` and ``notes`` are joined (``"inertia,rim_speed"``, as in a
    sweep's table); records (parts, stresses, the key, sensitivities) are
    left to the JSON. A value that does not exist is null (NaN, None).

    Parameters
    ----------
    design : flyopt.design.result.DesignResult
    units : str, optional
        None: SI. A unit system of :data:`flyopt.report.display.SYSTEMS`
        converts the quantities (:func:`to_units`).

    Returns
    -------
    pandas.DataFrame
        ``attrs["flyopt"]["units"]``: each quantity column's unit.
    """
    import pandas as pd

    records = [candidate.to_dict() for candidate in design.candidates]
    columns = [name for name in (records[0] if records else ()) if _column(name, [r[name] for r in records])]
    rows = [
        {name: _JOINED[name].join(record[name] or ()) if name in _JOINED else record[name] for name in columns}
        for record in records
    ]
    frame = pd.DataFrame(rows, columns=columns)
    for name in columns:  # numbers with None where none exists: float columns with NaN
        if dimension_of(name) is not None:
            frame[name] = frame[name].astype(float)
    frame.attrs["flyopt"] = {"kind": "ranking", "units": table_units(columns, design.spec.objective)}
    return frame if units is None else to_units(frame, units)


#: List fields of a candidate joined into one text cell, and their separator.
_JOINED = {"binding": ",", "notes": "; "}


def _column(name: str, values: list[Any]) -> bool:
    """Whether a candidate's field is a column: a list to join, or a number, a text or a flag in every row (a
    record, such as the key, is not; nor a field without a unit that no row has, such as a bare rim's key)."""
    if name in _JOINED:
        return True
    scalar = all(v is None or isinstance(v, (str, bool, int, float)) for v in values)
    return scalar and (dimension_of(name) is not None or any(v is not None for v in values))


def ranking_html(design: DesignResult, units: str = display.DEFAULT) -> str:
    """The ranking of :func:`ranking_frame` as an HTML table in ``units``: :data:`RANKING_COLUMNS`, each
    number to four significant figures by the text's formatter (:func:`flyopt.report.display.number`), the
    materials by their names for people, the binding limits in words
    (:func:`flyopt.design.check.binding_label`), and for a combination without a design its reason; where the
    first row is the rounded wheel, the text's note under it (:func:`flyopt.report.display.rounded_rank_note`)."""
    frame = ranking_frame(design)
    shown = to_units(frame[[c for c in RANKING_COLUMNS if c in frame.columns]], units, labels=True)
    shown["material"] = [design.material_name(key) for key in frame["material"]]
    shown = shown.rename(columns={"binding": "binding, or why not"})
    shown["binding, or why not"] = [  # what binds a design, why a combination has none (its reason)
        ", ".join(binding_label(b) for b in binding.split(",") if b) if feasible else reason
        for binding, feasible, reason in zip(frame["binding"], frame["feasible"], frame["reason"])
    ]
    formatters = {
        name: _number_cell for name in shown.columns if shown[name].dtype.kind == "f"
    }  # floats only: a flag or a name as it is
    table = str(shown.to_html(index=False, na_rep="-", formatters=formatters, classes="flyopt-ranking"))
    if design.best is not None and design.continuous is not None:
        mass = display.quantity_text(design.continuous.mass, "mass", units)
        table += f'<p class="flyopt-ranking-note">{escape(display.rounded_rank_note(mass))}</p>'
    return table


def _number_cell(value: float) -> str:
    return "-" if value is None or math.isnan(value) else display.number(value, 4)


# --------------------------------------------------------------------------
# Tables in the user's units
# --------------------------------------------------------------------------


def to_units(frame: pd.DataFrame, units: str, *, labels: bool = False) -> pd.DataFrame:
    """A table of flyopt (SI) with its quantities in ``units``, each column's new unit in its metadata.

    A column's dimension is flyopt's one table of output fields
    (:func:`flyopt.outputs.quantities.dimension_of`); text, flags, counts and
    columns whose unit another field sets (``objective``) are left as they are.

    Parameters
    ----------
    frame : pandas.DataFrame
        A table in SI: a sweep, a Pareto front, a trade-off, a ranking
        (``to_frame()``), or one read by :func:`read_results`.
    units : str
        ``"input"``: a sweep's varied fields in the units they were given in
        (``--vary speed=750:3000:10rpm``: rpm), from the table's metadata
        (``attrs["flyopt"]["sweep"]["vary"]``); every other column stays SI.
        Or a unit system of :mod:`flyopt.report.display` (``engineering``:
        mm, rpm, kN·m, MPa; ``si``; ``imperial``).
    labels : bool
        Put each quantity's unit in its column's name (``"d_outer [mm]"``), for reading.

    Returns
    -------
    pandas.DataFrame
        A copy. ``attrs["flyopt"]`` is the table's metadata with ``units``
        now the unit of each quantity column as shown, ``si_units`` the SI
        ones, and ``shown_in`` the ``units`` asked for.

    Raises
    ------
    ValueError
        An unknown ``units``, a table that is already converted (convert the SI table), or
        ``"input"`` for a table that is no sweep's.
    """
    import numpy as np
    import pandas as pd

    if units != INPUT and units not in display.SYSTEMS:
        raise ValueError(f"units {units!r} is not known (allowed: {', '.join((INPUT, *display.SYSTEMS))})")
    meta = dict(frame.attrs.get("flyopt") or {})
    if "shown_in" in meta:
        raise ValueError(f"this table is already in {meta['shown_in']!r} units: convert the SI table")
    si_units = dict(meta.get("units") or table_units(frame.columns))
    vary = (meta.get("sweep") or {}).get("vary")
    if units == INPUT and vary is None:
        raise ValueError(
            "units 'input' needs a sweep's table (its metadata records the units its fields were given in)"
        )
    given = {name: entry.get("unit") for name, entry in (vary or {}).items() if entry}
    shown = frame.copy()
    shown_units = dict(si_units)
    names = {}
    for name in frame.columns:
        target = _unit_of_column(str(name), frame[name], units, given)
        if target is None:
            continue
        label, factor = target
        # the data in the unit shown without the round-off of converting it: 1500 rpm, not 1500.0000000000002;
        # a result equal to what was written (a diameter at its envelope) equal to it shown; the column's own
        # dtype kept (a nullable Float64's missing values stay <NA>). A factor of 1 converts nothing: the column
        # as it is, the SI table's own figures.
        if factor != 1.0:
            converted = frame[name] / factor
            cleaned = display.without_conversion_noise(converted.to_numpy(dtype=float, na_value=np.nan))
            shown[name] = pd.Series(cleaned, index=frame.index, name=name).astype(converted.dtype)
        shown_units[str(name)] = label
        if labels and label not in ("-", "1"):
            names[name] = f"{name} [{label}]"
    shown.attrs = {**frame.attrs, "flyopt": {**meta, "units": shown_units, "si_units": si_units, "shown_in": units}}
    return shown.rename(columns=names) if names else shown


def _unit_of_column(name: str, column: pd.Series, units: str, given: dict[str, str | None]) -> tuple[str, float] | None:
    """(label, SI value of one shown unit) of a column in ``units``; None to leave it as it is."""
    from pandas.api import types

    dimension = dimension_of(name)
    if dimension is None or types.is_bool_dtype(column.dtype) or not types.is_numeric_dtype(column.dtype):
        return None
    if units == INPUT:
        written = given.get(name)
        if not written:
            return None
        from flyopt.units import unit_value

        return written, unit_value(written, dimension, name)  # the factor the sweep read it with
    if dimension not in display.UNITS:
        return None
    return display.unit(dimension, units)


def read_results(
    path: str | os.PathLike[str], columns: Sequence[str] | None = None, units: str | None = None
) -> pd.DataFrame:
    """Read a table flyopt wrote (a sweep, a Pareto front, a trade-off; Parquet or CSV), with its units.

    Parameters
    ----------
    path : str or Path
    columns : list of str, optional
        Read these columns only.
    units : str, optional
        None: SI, as written. ``"input"``: a sweep's varied fields in the
        units they were given in (``speed`` in rpm for
        ``--vary speed=750:3000:10rpm``), or a unit system of
        :mod:`flyopt.report.display` for every quantity (:func:`to_units`).

    Returns
    -------
    pandas.DataFrame
        Dtypes and nulls restored (:func:`flyopt.outputs.results.read_results`);
        ``attrs["flyopt"]`` the file's metadata (provenance, the sweep), its
        ``units`` each quantity column's unit.
    """
    from flyopt.outputs import results

    if units is not None and units != INPUT and units not in display.SYSTEMS:
        raise ValueError(f"units {units!r} is not known (allowed: {', '.join((INPUT, *display.SYSTEMS))})")
    frame = results.read_results(path, columns)
    return frame if units is None else to_units(frame, units)


register("solution", "html", answer_card)
register("analysis", "html", analysis_card)
register("design", "frame", ranking_frame)
register("design", "html", ranking_html)
