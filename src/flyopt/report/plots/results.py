"""Diagrams of results tables: a sweep against a varied field, a Pareto front of two objectives."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.errors import clip
from flyopt.report import display
from flyopt.report.plots import readout, standard
from flyopt.said import counted

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    import pandas as pd
    from matplotlib.axes import Axes

RESULT_PLOTS = {
    "sweep": "a result of a sweep against a varied field, one line per group (--by) and per other varied field",
    "pareto": "a Pareto front: the non-dominated designs of two objectives",
}

#: Most lines a sweep diagram draws (one per group of the other varied fields).
MAX_LINES = 12


def _dimension(column, frame=None):
    """The dimension of a results column (flyopt.outputs.results' table), or None (text, counts, unknown)."""
    metadata = (frame.attrs.get("flyopt", {}) if frame is not None else {}) or {}
    if column == "objective":
        column = metadata.get("objective") or _objective_of(frame)
        if column is None:
            return None
    if column == "epsilon":
        objectives = metadata.get("objectives") or (pareto_objectives(frame) if frame is not None else None)
        if not objectives:
            return None
        column = objectives[1]
    try:
        return display.dimension_of(column)
    except ValueError:
        return None


def _objective_of(frame):
    if frame is None or "design.objective" not in frame.columns:
        return None
    names = frame["design.objective"].dropna().unique()
    return str(names[0]) if len(names) == 1 else None


def _scale(frame, column, units=display.DEFAULT, digits=standard.DIGITS):
    """The unit a column is drawn in (its dimension from flyopt.outputs.results, the one table of units): chosen
    from the whole column's largest value (:func:`~flyopt.report.plots.standard.scale`, a power in kW or W as
    the text writes it), one for the axis and the legend alike; None for a column without a dimension."""
    dimension = _dimension(column, frame)
    if dimension is None:
        return None
    values = frame[column].to_numpy(dtype=float) if _is_number(frame[column]) else ()
    return standard.scale(dimension, units, [values], digits)


def _label(column, units=display.DEFAULT, frame=None, digits=standard.DIGITS):
    """A column's axis label in words (:func:`flyopt.report.display.column_words`) with its unit in the system."""
    if column == "cost":
        return "cost [currency of the prices]"
    scale = _scale(frame, column, units, digits)
    words = display.column_words(column)
    return words if scale is None else scale.axis_label(words)


def _column(frame, name):
    """The column a user names: itself, or the result of that name (``material`` is ``best_material``)."""
    return _column_named(list(frame.columns), name)


def _column_named(columns, name):
    """:func:`_column` among the names ``columns`` (a table's, in its order)."""
    for column in (name, f"best_{name}"):
        if column in columns:
            return column
    raise ValueError(f"the results have no column {name!r} (columns: {', '.join(columns)})")


def plotted_columns(
    columns: Sequence[str], metadata: Mapping[str, Any] | None, what: str, x: str, y: str, by: str | None = None
) -> list[str]:
    """The columns of a results table that :func:`plot_sweep` (``what`` "sweep") or :func:`plot_pareto`
    ("pareto") of ``x``, ``y`` (and ``by``) reads, in the table's order: a large table is read for these only (a
    sweep of 2 million points read whole, 47 columns, took 11.5 s and 1.6 GB to plot).

    ``columns`` are the table's names in its order and ``metadata`` its flyopt metadata
    (:func:`flyopt.outputs.results.results_columns`). Beside the named columns, those the diagram reads of its own
    accord: the status; a sweep's varied fields (those its metadata records, else every input column, of which
    :func:`varied_fields` keeps those that vary); a front's material and the fields of the machine's physics;
    the objective's name for an ``objective`` column; a front's first two columns for an ``epsilon``. The
    diagram of these columns is the diagram of the whole table.

    Raises
    ------
    ValueError
        A named column the table does not have, as the diagram says it.
    """
    from flyopt.outputs.quantities import INPUTS
    from flyopt.studies.points import PHYSICS_FIELDS

    names = list(columns)
    named = {_column_named(names, x), _column_named(names, y), *([_column_named(names, by)] if by else [])}
    wanted = named | {"status"}
    if "objective" in named:
        wanted.add("design.objective")
    if "epsilon" in named:
        wanted.update(names[:2])
    if what == "pareto":
        wanted.update(PHYSICS_FIELDS, ("best_material", "material"))
    else:
        recorded = ((metadata or {}).get("sweep") or {}).get("vary")
        wanted.update(recorded or (c for c in names if c in INPUTS or c.startswith(("material.", "shaft."))))
    return [c for c in names if c in wanted]


MAX_DRAWN = 1e150
"""Largest size of a value a results diagram draws: a mass of 1e308 in a hand-edited CSV overflowed
matplotlib's transforms ("arange: cannot compute length"); no result of flyopt's comes near it."""


def _is_number(column):
    """Whether a table's column holds numbers (flags among them), not text."""
    from pandas.api.types import is_numeric_dtype

    return bool(is_numeric_dtype(column.dtype))


def _drawable(frame, column, by=None):
    """``column``, checked to hold numbers (``by``: the option that draws a line per value of a text column
    instead) finite and at most :data:`MAX_DRAWN` in size (NaN is no value)."""
    if not _is_number(frame[column]):
        instead = f" (one line per {column}: {by} {column})" if by else ""
        raise ValueError(f"the column {column!r} holds text, and an axis draws numbers{instead}")
    values = frame[column].to_numpy(dtype=float)
    wild = values[~np.isnan(values) & ~(np.abs(values) <= MAX_DRAWN)]
    if wild.size:
        raise ValueError(
            f"the column {column!r} holds {wild[0]:g} (allowed: numbers of size at most {MAX_DRAWN:g}, or "
            "none): it cannot be drawn"
        )
    return column


#: Most markers one set of points of a results diagram draws each as itself. Over it, of points closer than
#: 1/:data:`MARK_CELLS` of the data's span on both axes (half a point of a diagram's axis, a tenth of a marker)
#: one is marked, and a set still over it is drawn as an image in a vector file: 2 million points marked one by
#: one made a 214 MB SVG in 83 s.
MAX_MARKERS = 2000

#: Cells across each axis' span that :data:`MAX_MARKERS` marks one point in.
MARK_CELLS = 800


def _marked(line, xs, ys, log_x=False):
    """Mark at most one of ``line``'s points (``xs``, ``ys``, as drawn) in each cell of
    :data:`MARK_CELLS` × :data:`MARK_CELLS` over their span (in the x axis' scale, log where ``log_x``) where
    there are over :data:`MAX_MARKERS`: the line and its data (what the app reads out) are every point, and a
    marker stands where a point is, within a tenth of its size of all the points it stands for."""
    if len(xs) <= MAX_MARKERS:
        return
    key = np.zeros(len(xs), dtype=np.int64)
    for values, log in ((xs, log_x), (ys, False)):
        values = np.asarray(values, dtype=float)
        if log:
            with np.errstate(divide="ignore", invalid="ignore"):
                values = np.log10(values)
        finite = values[np.isfinite(values)]
        low, span = (finite.min(), np.ptp(finite)) if finite.size else (0.0, 0.0)
        cell = np.floor((values - low) / span * MARK_CELLS) if span > 0 else np.zeros_like(values)
        # cells 0 to MARK_CELLS; a point without a value (not drawn) in one cell of its own kind
        key = key * (MARK_CELLS + 2) + np.where(np.isfinite(cell), cell + 1, 0).astype(np.int64)
    first = np.sort(np.unique(key, return_index=True)[1])
    line.set_markevery(first.tolist())
    if len(first) > MAX_MARKERS:
        line.set_rasterized(True)


def _values(part, column, scale):
    """A column's numbers (of ``part``, rows of the frame) in its axis' unit (``scale`` of :func:`_scale`)."""
    values = part[column].to_numpy(dtype=float)
    return values if scale is None else scale.show(values)


def _value_text(value, column, units, frame=None, digits=standard.DIGITS, name=None):
    """A varied field's value as a legend writes it: "speed = 600 rpm", "material = cast_iron" (``name`` for the
    column's own name on the left)."""
    name = column if name is None else name
    if isinstance(value, (float, int, np.floating, np.integer)) and not isinstance(value, bool):
        scale = _scale(frame, column, units, digits) if frame is not None else None
        return _number_text(float(value), name, scale, digits)
    return f"{name} = {clip(str(value))}"  # a text of 100,000 characters took 19 s to lay out in the legend


def _number_text(value, name, scale, digits):
    """A number as :func:`_value_text` writes it, in ``scale`` (:func:`_scale`; None: a number without a unit)."""
    return f"{name} = {display.number(value, digits)}" if scale is None else f"{name} = {scale.q(value)}"


def _point_rows(frame, rows, columns, units, digits, names):
    """The read-out of each of the frame's ``rows`` (positions): its material, then its ``columns``' values
    (each column's unit chosen once: a front of 20,000 designs took 11 s choosing it for every value)."""
    material = next((c for c in ("best_material", "material") if c in frame.columns), None)
    shown = [
        (display.column_words(c), _scale(frame, c, units, digits), frame[c].to_numpy(dtype=float)[rows])
        for c in columns
    ]
    materials = frame[material].to_numpy(dtype=object)[rows] if material is not None else None
    out = []
    for i in range(len(rows)):  # each objective named as its axis names it
        texts = [_number_text(float(values[i]), words, scale, digits) for words, scale, values in shown]
        if materials is not None and isinstance(materials[i], str):
            texts.insert(0, f"material = {clip((names or {}).get(materials[i], materials[i]))}")
        out.append(texts)
    return out


def pareto_objectives(frame: pd.DataFrame | Sequence[str]) -> tuple[str, str] | None:
    """The two objectives of a front written by ``flyopt pareto`` (a table, or its columns' names in
    order), or None.

    A front has an ``epsilon`` column (the constraint value of each point)
    and its two objectives as its first two columns, mass first.

    Returns
    -------
    tuple of str or None
        ``("mass", "outer_diameter")`` and so on; None for other results (a sweep).
    """
    columns = [str(c) for c in getattr(frame, "columns", frame)]
    if "epsilon" not in columns or len(columns) < 3 or columns[0] != "mass":
        return None
    return str(columns[0]), str(columns[1])


def varied_fields(frame: pd.DataFrame) -> list[str]:
    """The inputs a sweep varied: its recorded sweep specification, else the input columns that take
    more than one value (flyopt.outputs.results.INPUTS and the material and shaft fields)."""
    from flyopt.outputs.quantities import INPUTS

    recorded = ((frame.attrs.get("flyopt") or {}).get("sweep") or {}).get("vary")
    if recorded:
        return [name for name in recorded if name in frame.columns]
    names = [c for c in frame.columns if c in INPUTS or c.startswith(("material.", "shaft."))]
    return [c for c in names if frame[c].nunique(dropna=True) > 1]


def axis_fields(frame: pd.DataFrame) -> list[str]:
    """The varied fields (:func:`varied_fields`) a sweep diagram may draw along x: those of numbers (a field of
    names, the material, is drawn as one line per value instead)."""
    return [f for f in varied_fields(frame) if _is_number(frame[f])]


_NOT_DESIGNED = {
    "infeasible": ("x", "infeasible: no material and shaft can give J_F"),
    "failed": ("X", "failed: the solver did not converge"),
    "not_needed": ("o", "no flywheel needed"),
}


def plot_sweep(
    frame: pd.DataFrame,
    x: str,
    y: str = "mass",
    by: str | None = None,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
) -> Axes:
    """A sweep's result ``y`` against a varied field ``x``: one line per value of ``by`` and of every
    other varied field, so that a line never joins points that differ in anything but ``x``.

    Points that are not designed (infeasible, failed, not needed) have no
    ``y``: each is marked at its ``x`` along the bottom of the plot, by kind,
    and counted in the legend. Values are shown in the system's units, the
    legends' too (``speed = 600 rpm``), each axis in one unit chosen from its column's largest value (a
    power in W or kW as the text writes it), ``digits`` significant figures. A field spanning more than a decade is
    drawn on a log axis. A name that is not a column may name a result:
    ``material`` and ``shaft`` are the winner's, ``best_material`` and
    ``best_shaft``, when the sweep did not vary them.

    Raises
    ------
    ValueError
        A column that does not exist or holds a number beyond :data:`MAX_DRAWN`, or more than
        :data:`MAX_LINES` lines.
    """
    from matplotlib.transforms import blended_transform_factory

    display.check_system(units)
    x, y = _drawable(frame, _column(frame, x), by="--by"), _drawable(frame, _column(frame, y))
    by = _column(frame, by) if by else None
    others = [f for f in varied_fields(frame) if f not in (x, by)]
    keys = ([by] if by else []) + others
    grouped = frame.groupby(keys, sort=True, dropna=False) if keys else None
    lines = grouped.ngroups if grouped is not None else 1  # counted before any group is made (50,000 took 43 s)
    if lines > MAX_LINES:
        raise ValueError(
            f"the sweep varies {', '.join(keys)} besides {x}: {lines} lines would be drawn "
            f"(at most {MAX_LINES}); sweep fewer fields at once, or plot one of them along x"
        )
    groups = list(grouped) if grouped is not None else [((), frame)]
    ax, own = standard.axes(ax)
    x_scale, y_scale = _scale(frame, x, units, digits), _scale(frame, y, units, digits)
    status = frame["status"] if "status" in frame.columns else None
    bottom = blended_transform_factory(ax.transData, ax.transAxes)
    values = _values(frame, x, x_scale)
    positive = values[np.isfinite(values) & (values > 0)]
    log_x = bool(positive.size and positive.max() / positive.min() > 10)  # a field spanning over a decade
    counts: dict[Any, int] = {}
    for key, part in groups:
        part = part.sort_values(x)
        key = key if isinstance(key, tuple) else (key,)
        words = ", ".join(_value_text(v, k, units, frame, digits) for k, v in zip(keys, key)) or y
        ok = (part["status"] == "designed").to_numpy() if status is not None else np.ones(len(part), bool)
        xs, ys = _values(part, x, x_scale), _values(part, y, y_scale)
        (line,) = ax.plot(xs[ok], ys[ok], "o-", ms=3.5, lw=1.3, label=words)
        _marked(line, xs[ok], ys[ok], log_x)
        if y_scale is not None:
            readout.curve(line, f"{y} ({words})" if keys else y, y_scale)
        for kind, (marker, _w) in _NOT_DESIGNED.items():
            miss = (part["status"] == kind).to_numpy() if status is not None else np.zeros(len(part), bool)
            if miss.any():
                (marks,) = ax.plot(
                    xs[miss],
                    np.full(miss.sum(), 0.03),
                    marker,
                    transform=bottom,
                    color=line.get_color(),
                    ms=6,
                    mfc="none" if marker == "o" else line.get_color(),
                    clip_on=False,
                    gid=kind,
                )
                _marked(marks, xs[miss], np.zeros(miss.sum()), log_x)
                counts[kind] = counts.get(kind, 0) + int(miss.sum())
    for kind, n in counts.items():
        marker, words = _NOT_DESIGNED[kind]
        ax.plot(
            [],
            [],
            marker,
            color="gray",
            mfc="none" if marker == "o" else "gray",
            label=f"{words} ({counted(n, 'point')}), marked at the bottom",
        )
    if log_x:
        ax.set_xscale("log")
    ax.set(xlabel=_label(x, units, frame, digits), ylabel=_label(y, units, frame, digits))
    if x_scale is not None:
        readout.abscissa(ax, x, x_scale)
    ax.grid(True, alpha=0.3)
    standard.title(
        ax,
        own,
        f"sweep: {display.column_words(y)} against {display.column_words(x)}"
        + (f", one line per {', '.join(display.column_words(k) for k in keys)}" if keys else ""),
    )
    standard.legend(ax, own, ncol=3)
    return ax


def plot_pareto(
    frame: pd.DataFrame,
    x: str,
    y: str,
    ax: Axes | None = None,
    units: str = display.DEFAULT,
    digits: int = display.DEFAULT_DIGITS,
    names: Mapping[str, str] | None = None,
) -> Axes:
    """The Pareto front of two objectives (both minimized), non-dominated points joined.

    A front compares designs of one machine: the points must share the
    fields that set the machine's physics (``delta``, ``speed``, ``inertia``,
    ``torque.scale``: flyopt.studies.points.PHYSICS_FIELDS), unless the
    field is an objective itself (``flyopt pareto --objectives mass,delta``).
    Points without a design are left out and counted in the legend. Each design drawn is named for the app's
    read-outs (:func:`~flyopt.report.plots.readout.points`): its material (by ``names``, a material's display
    name, where given) and its two objectives, as the legends write values.

    Raises
    ------
    ValueError
        A column that does not exist or holds a number beyond :data:`MAX_DRAWN`, points of different
        physics, or no design with both values.
    """
    from flyopt.studies.points import PHYSICS_FIELDS

    display.check_system(units)
    x, y = _drawable(frame, _column(frame, x)), _drawable(frame, _column(frame, y))
    mixed = [f for f in PHYSICS_FIELDS if f in frame.columns and f not in (x, y) and frame[f].nunique(dropna=True) > 1]
    if mixed:
        spans = "; ".join(
            f"{f} from {_value_text(frame[f].min(), f, units, frame, digits).split(' = ')[1]} to "
            f"{_value_text(frame[f].max(), f, units, frame, digits).split(' = ')[1]}"
            for f in mixed
        )
        hint = ", or make δ an objective (flyopt pareto --objectives mass,delta)" if mixed == ["delta"] else ""
        raise ValueError(
            f"the points differ in {' and '.join(mixed)} ({spans}), and a Pareto front compares "
            f"designs of one machine: plot the points of one {' and '.join(mixed)} at a time{hint}"
        )
    usable = frame[[x, y]].notna().all(axis=1).to_numpy()
    if "status" in frame.columns:
        usable = usable & frame["status"].isin(["designed", "not_needed"]).to_numpy()
    if not usable.any():  # (an empty front ended in an IndexError)
        raise ValueError(f"no design has both {x} and {y}: there is no front to draw")
    ax, own = standard.axes(ax)
    data = np.column_stack(
        [_values(frame, x, _scale(frame, x, units, digits)), _values(frame, y, _scale(frame, y, units, digits))]
    )[usable]
    order = np.lexsort((data[:, 1], data[:, 0]))
    data = data[order]
    front = data[np.concatenate(([True], data[1:, 1] < np.minimum.accumulate(data[:, 1])[:-1]))]
    dropped = int((~usable).sum())
    (designs,) = ax.plot(
        data[:, 0],
        data[:, 1],
        "o",
        color="lightgray",
        ms=4,
        label=f"designs ({len(data)})" + (f"; {dropped} without a design left out" if dropped else ""),
    )
    _marked(designs, data[:, 0], data[:, 1])
    readout.points(designs, _point_rows(frame, np.flatnonzero(usable)[order], (x, y), units, digits, names))
    ax.step(front[:, 0], front[:, 1], where="post", color=standard.DEFICIT, lw=1.2)
    (marks,) = ax.plot(
        front[:, 0],
        front[:, 1],
        "o",
        color=standard.DEFICIT,
        ms=5,
        label=f"Pareto front ({counted(len(front), 'point')})",
        gid="front",
    )
    _marked(marks, front[:, 0], front[:, 1])
    ax.set(xlabel=_label(x, units, frame, digits), ylabel=_label(y, units, frame, digits))
    ax.grid(True, alpha=0.3)
    standard.title(
        ax, own, f"Pareto front: {display.column_words(y)} against {display.column_words(x)}, both minimized"
    )
    standard.legend(ax, own)
    return ax
