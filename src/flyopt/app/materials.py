"""The app's "Compare materials" tab without a browser: the library, the trade-off, the Pareto front.

Every number comes from the command line's own paths, so that the tab cannot
disagree with it:

- the library is ``flyopt materials``' rows (:func:`flyopt.cli.materials.library_rows`'s
  fields, one per material) of the scene's library, the built-in materials
  extended or replaced by the scene's own ``[[material]]`` tables
  (:meth:`flyopt.io.scene.Scene.material_library`);
- ticking materials runs ``flyopt tradeoff`` on the scene with those materials
  (:func:`flyopt.studies.tradeoff.material_tradeoff` of the scene whose
  ``[design] materials`` are the ticked ones: the same as writing them into
  the scene and running the command);
- the Pareto front is ``flyopt pareto``'s (:func:`flyopt.studies.pareto.pareto`,
  its columns ordered as the command orders them), drawn by the report's
  :func:`flyopt.report.plots.plot_pareto`; each point carries a link
  ``#pick-N`` (N its row) that the page turns into "show this design".

Numbers are shown in the user's unit system by :mod:`flyopt.report.display`
(one unit per column, chosen from its values, four significant figures), and
materials by their display names. docs/flywheel-design.md §8 (the design
problem) and §9 (studies) say what the tables mean.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from flyopt.report import display

if TYPE_CHECKING:
    import pandas as pd

    from flyopt.io.scene import Scene

#: The trade-off's columns the tab shows (``flyopt tradeoff``'s printed columns), in order.
TRADEOFF_SHOWN = (
    "material",
    "status",
    "shaft",
    "d_outer",
    "b",
    "h",
    "rim_speed",
    "rim_speed_limit",
    "mass",
    "cost",
    "limit",
)

#: What the chart beside the trade-off draws per material: its columns, each titled in its words
#: (:func:`flyopt.report.display.column_words`).
CHART = ("mass", "d_outer", "cost")

#: The Pareto fronts the tab offers (``flyopt pareto --objectives``) and its number of ε values.
OBJECTIVES = ("mass,outer_diameter", "mass,cost", "mass,delta")
PARETO_POINTS = 15


def library(scene: Scene | None) -> pd.DataFrame:
    """The material library of ``scene`` (the built-in one without a scene): ``flyopt materials``' fields.

    One row per material, values in SI: ``name``, ``display_name``,
    ``density``, ``tensile_strength``, ``yield_strength``, ``rim_speed_limit``,
    ``ductile``, ``default``, ``source`` (as ``flyopt materials --json``), and
    ``origin``: "scene" for a material of the scene's ``[[material]]`` tables
    (which may replace a built-in one of the same name), else "built-in".
    """
    import pandas as pd

    from flyopt.cli.materials import material_row
    from flyopt.design.materials import builtin_materials, material_library

    defaults = builtin_materials(default_only=True)
    own = {m.name for m in scene.materials} if scene is not None else set()
    materials = scene.material_library() if scene is not None else material_library(())
    rows = []
    for material in materials.values():
        row = material_row(material, material.name in defaults and material.name not in own)
        row["origin"] = "scene" if material.name in own else "built-in"
        rows.append(row)
    return pd.DataFrame(rows)


def design_materials(scene: Scene) -> list[str]:
    """The materials the scene's design uses (its ``[design] materials``, else the defaults): ticked at first."""
    from flyopt.design.materials import design_material_names

    return list(design_material_names(scene.material_library(), scene.design_materials))


def with_materials(scene: Scene, names: Sequence[str]) -> Scene:
    """The scene whose design may use the materials ``names`` only (``[design] materials = [...]``).

    SceneError for a name the scene's library does not hold (the loader's words).
    """
    from flyopt.errors import SceneError

    known = scene.material_library()
    unknown = [n for n in names if n not in known]
    if unknown:
        raise SceneError("design.materials", f"unknown material {unknown[0]!r} (known: {', '.join(known)})")
    if not names:
        raise SceneError("design.materials", "tick at least one material")
    return dataclasses.replace(scene, design_materials=tuple(names))


def tradeoff(scene: Scene, names: Sequence[str], method: str = "auto") -> pd.DataFrame:
    """``flyopt tradeoff`` of the scene with the materials ``names``: each one's lightest design, ranked (SI)."""
    from flyopt.studies.tradeoff import material_tradeoff

    return material_tradeoff(with_materials(scene, names), method=method)  # type: ignore[arg-type]


def pareto_front(scene: Scene, names: Sequence[str], objectives: str, points: int = PARETO_POINTS) -> pd.DataFrame:
    """``flyopt pareto --objectives OBJECTIVES --points POINTS`` of the scene with the materials ``names``.

    Its columns as the command writes them: mass, the other objective, then the rest. An empty front
    carries the study's ``message`` in ``attrs`` (no flywheel needed, or no design).
    """
    from flyopt.studies.pareto import objective_pair, pareto

    pair, other = objective_pair(objectives)
    front = pareto(with_materials(scene, names), pair, points=points)
    if front.empty:
        return front
    ordered = front[["mass", other, *(c for c in front.columns if c not in ("mass", other))]]
    ordered.attrs = dict(front.attrs)
    return ordered


def display_names(scene: Scene | None) -> dict[str, str]:
    """Each material's display name (``gjs_keyed`` -> its ``display_name``), for the tables."""
    from flyopt.design.materials import material_library

    materials = scene.material_library() if scene is not None else material_library(())
    return {name: m.display_name for name, m in materials.items()}


def shown(
    frame: pd.DataFrame,
    columns: Sequence[str],
    units: str,
    names: dict[str, str] | None = None,
    digits: int | None = None,
) -> pd.DataFrame:
    """``frame``'s ``columns`` as people read them: numbers in the unit system (one unit per column, chosen from
    its values by :func:`flyopt.report.display.column`, in its heading) rounded to ``digits`` significant
    figures but kept numbers (so that the table sorts and filters them), materials by display name.

    A column that is not a quantity keeps its values (text as is: the page escapes it).
    """
    import pandas as pd
    from pandas.api.types import is_bool_dtype, is_integer_dtype, is_numeric_dtype

    from flyopt.outputs import quantities

    digits = display.DEFAULT_DIGITS if digits is None else digits
    words = display.for_people(frame[[c for c in columns if c in frame.columns]].copy(), names or {})
    out: dict[str, Any] = {}
    for c in columns:
        if c not in frame.columns:
            continue
        values = words[c]
        if c in ("material", "best_material", "binding", "limit"):  # in words (display.for_people)
            out[c] = list(values)
            continue
        dimension = quantities.dimension_of(c)
        if not is_numeric_dtype(values) or is_bool_dtype(values) or (dimension is None and is_integer_dtype(values)):
            out[c] = list(values)
            continue
        numbers = [None if v is None or v != v else float(v) for v in values]
        if dimension is None:
            scale = display.largest(numbers)
            out[c] = [_number(display.number(v, digits, scale)) for v in numbers]
            continue
        unit, texts = display.column(numbers, c, units, digits)
        heading = c if unit == "-" else f"{c} [{unit}]"
        out[heading] = [_number(t) for t in texts]
    return pd.DataFrame(out)


def _number(text: str) -> float | None:
    """A number as :func:`flyopt.report.display.number` wrote it, back as a float (None for "-")."""
    if text == "-":
        return None
    try:
        return float(text.replace(",", ""))
    except ValueError:
        return math.nan


def library_shown(table: pd.DataFrame, units: str, digits: int | None = None) -> pd.DataFrame:
    """The library as the tab shows it: ``flyopt materials``' columns (:data:`flyopt.cli.materials.COLUMNS`:
    their headings and dimensions), numbers in the unit system (one unit per column, from its values), the
    display name first, then the origin (built-in or the scene's) and the full source."""
    import pandas as pd

    from flyopt.cli.materials import COLUMNS

    digits = display.DEFAULT_DIGITS if digits is None else digits
    out: dict[str, Any] = {"material": list(table["display_name"]), "name": list(table["name"])}
    for key, heading, dimension in COLUMNS:
        if dimension is None or key not in table.columns:
            continue
        values = [None if v is None or v != v else float(v) for v in table[key]]
        unit, factor = display.unit(dimension, units, display.largest(values), digits)
        scale = display.largest(values) / factor
        out[f"{heading} [{unit}]"] = [
            None if v is None else _number(display.number(v / factor, digits, scale)) for v in values
        ]
    out["ductile"] = ["-" if v is None else ("yes" if v else "no") for v in table["ductile"]]
    out["origin"] = list(table["origin"])
    out["source"] = list(table["source"])
    return pd.DataFrame(out)


def chart_svg(table: pd.DataFrame, units: str, names: dict[str, str] | None = None) -> str:
    """A chart of mass, outer diameter D and cost per material of a trade-off table, as inline SVG ("" for no
    designed material): one bar chart each, in the unit system, the lightest material first."""
    from flyopt.report.plots import standard

    designed = table[table["status"] == "designed"]
    if designed.empty:
        return ""
    with standard.LOCK:  # drawn in the tab's worker thread: one draw at a time (matplotlib is not thread-safe)
        return _chart_svg(designed, units, names)


def _chart_svg(designed: pd.DataFrame, units: str, names: dict[str, str] | None) -> str:
    from flyopt.app.model import page_svg
    from flyopt.report.plots import standard

    # drawable: tick labels are made from these at the layout, after make_drawable has seen the figure's texts
    labels = [standard.drawable((names or {}).get(m, m)) for m in designed["material"]]
    figure = standard.figure_class()(figsize=(9, 2.8))
    axes = figure.subplots(1, len(CHART))
    for ax, column in zip(axes, CHART):
        title = display.column_words(column)
        values = [float(v) for v in designed[column]]
        if all(v != v for v in values):  # no prices: the scene's materials carry no cost
            ax.set_title(f"{title}: no prices", fontsize=9)
            ax.text(
                0.5,
                0.5,
                "the materials have no cost per kg\n([[material]] cost = ...)",
                ha="center",
                va="center",
                fontsize=8,
                transform=ax.transAxes,
                color="gray",
            )
            ax.set_axis_off()
            continue
        if column == "cost":
            ax.set_title("cost [currency of the prices]", fontsize=9)
            shown_values = values
        else:
            unit, factor = display.unit(display.dimension_of(column), units, display.largest(values))
            shown_values = [v / factor for v in values]
            ax.set_title(f"{title} [{unit}]", fontsize=9)
        bars = ax.barh(range(len(labels)), [0 if v != v else v for v in shown_values], color=standard.DEFICIT)
        ax.bar_label(bars, labels=[display.number(v) if v == v else "-" for v in shown_values], fontsize=8, padding=2)
        ax.set_yticks(range(len(labels)), labels=labels if ax is axes[0] else [], fontsize=8)
        ax.invert_yaxis()
        ax.margins(x=0.25)
        ax.tick_params(axis="x", labelsize=8)
        ax.grid(True, axis="x", alpha=0.3)
    figure.tight_layout()
    return page_svg(standard.make_drawable(figure), "tradeoff")


#: The link each Pareto point carries in the SVG: ``#pick-N``, N the point's row in the front.
PICK = "#pick-{}"


def pareto_svg(front: pd.DataFrame, units: str, names: dict[str, str] | None = None) -> tuple[str, str]:
    """The front drawn by the report's :func:`~flyopt.report.plots.plot_pareto` (mass against the other
    objective), each designed point made a link ``#pick-N`` (an unseen dot over it) for the page to load; and the
    read-outs of its points (:func:`flyopt.app.model.readout_json`: material by ``names``, the two objectives)."""
    from flyopt.report import plots
    from flyopt.report.plots import standard

    other = str(front.columns[1])
    with standard.LOCK:  # drawn in the tab's worker thread: one draw at a time (matplotlib is not thread-safe)
        ax = plots.plot_pareto(front, other, "mass", units=units, names=names)
        return _pareto_svg(front, ax, other, units)


def _pareto_svg(front: pd.DataFrame, ax: Any, other: str, units: str) -> tuple[str, str]:
    import numpy as np

    from flyopt.app.model import page_svg, readout_json
    from flyopt.report.plots import standard
    from flyopt.studies.pareto import PARETO_OBJECTIVES

    dimension = PARETO_OBJECTIVES.get(other)
    xs = front[other].to_numpy(dtype=float)
    xs = xs if dimension is None else np.asarray(display.show(xs, dimension, units))
    ys = np.asarray(display.show(front["mass"].to_numpy(dtype=float), "mass", units))
    rows = [i for i in range(len(front)) if np.isfinite(xs[i]) and np.isfinite(ys[i])]
    dots = ax.scatter(xs[rows], ys[rows], s=140, color="white", alpha=0.01, zorder=5, gid="pick")  # filled: clickable
    dots.set_urls([PICK.format(i) for i in rows])
    ax.set_title(ax.get_title() + " (click a point for its design)")
    figure = standard.figure_of(ax)
    try:
        return page_svg(figure, "pareto"), readout_json(figure)
    finally:
        standard.close(figure)


#: The point's design as the panel lists it: (label, column).
POINT_ROWS = (
    ("material", "best_material"),
    ("shaft", "best_shaft"),
    (display.column_words("d_outer"), "d_outer"),
    (display.column_words("b"), "b"),
    (display.column_words("h"), "h"),
    (display.column_words("mass"), "mass"),
    (display.column_words("cost"), "cost"),
    ("ε (the constraint of this point)", "epsilon"),
    ("limits that bind", "binding"),
    ("method", "method"),
)


def point_rows(
    front: pd.DataFrame, index: int, units: str, names: dict[str, str] | None = None
) -> list[tuple[str, str]]:
    """The design of the front's point ``index`` as (label, value) lines, values in the unit system.

    IndexError for a row the front does not have (a stale click).
    """
    from flyopt.studies.pareto import PARETO_OBJECTIVES

    row = front.iloc[index]
    words = display.for_people(front.iloc[[index]].copy(), names or {}).iloc[0]  # materials, limits in words
    other = str(front.columns[1])
    lines = []
    for label, column in POINT_ROWS:
        if column not in front.columns:
            continue
        value = row[column]
        if value is None or (isinstance(value, float) and math.isnan(value)):
            text = "-"
        elif column in ("best_material", "binding"):
            text = str(words[column]) or "-"
        elif isinstance(value, str):
            text = value or "-"
        elif column == "epsilon":
            dimension = PARETO_OBJECTIVES.get(other)
            text = (
                display.number(float(value))
                if dimension is None
                else display.quantity_text(float(value), dimension, units)
            )
        elif column == "cost":
            text = display.number(float(value))
        else:
            text = display.field_text(float(value), column, units)
        lines.append((label, text))
    return lines


def point_changes(scene: Scene, front: pd.DataFrame, index: int) -> list[tuple[str, str]]:
    """What the scene's TOML must say for its design to be the front's point ``index``: (key path, TOML value).

    The point's material and shaft (``[design] materials`` and, where the scene has several, ``shafts``), and
    the constraint that made the point where it is not the scene's own: the objective (the front's first point
    is the smallest wheel: ``objective = "outer_diameter"``), the envelope ε (``max_outer_diameter``, in mm to
    ten significant figures: the wheel's D is ε where it binds) or δ. The point's row is the sweep's
    (:func:`flyopt.studies.points.point_scene` made its scene from the same fields). IndexError for a row the
    front does not have (a stale click); ValueError for a point with no design (nothing to load).
    """
    from flyopt.app.form import literal

    row = front.iloc[index]
    material = row.get("best_material")
    if not isinstance(material, str) or row.get("status") != "designed":
        raise ValueError(f"point {index} of the front has no design to load")
    changes = [("design.materials", f"[{_quoted(material)}]")]
    shaft = row.get("best_shaft")
    if isinstance(shaft, str) and len(scene.shafts) > 1:
        changes.append(("design.shafts", f"[{_quoted(shaft)}]"))
    spec = scene.design
    objective = row.get("design.objective")
    if isinstance(objective, str) and spec is not None and objective != spec.objective:
        changes.append(("design.objective", _quoted(objective)))
    envelope = _finite(row.get("design.max_outer_diameter"))
    if envelope is not None and spec is not None and not math.isclose(envelope, spec.max_outer_diameter, rel_tol=1e-12):
        changes.append(("design.max_outer_diameter", _quoted(f"{envelope * 1000:.10g} mm")))
    delta = _finite(row.get("delta"))
    if delta is not None and not math.isclose(delta, scene.allowed_delta, rel_tol=1e-12):
        changes.append(("machine.delta", literal(f"{delta:.10g}")))
    return changes


def point_text(text: str, scene: Scene, front: pd.DataFrame, index: int) -> str:
    """``text`` (the scene the front was drawn of) made the scene whose design is the front's point ``index``:
    :func:`point_changes` written by the form's one editing path (:func:`flyopt.cli.toml_lines.set_value`:
    comments and layout kept, a key not written added to its table)."""
    from flyopt.cli.toml_lines import set_value

    for path, value in point_changes(scene, front, index):
        text = set_value(text, path, value)
    return text


def _quoted(text: str) -> str:
    """A TOML basic string (the form's own quoting)."""
    from flyopt.app.form import toml_string

    return toml_string(text)


def _finite(value: Any) -> float | None:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def rows_html(title: str, lines: Sequence[tuple[str, str]]) -> str:
    """(label, value) lines as the card's small table, every string escaped."""
    from html import escape

    body = "".join(f"<tr><th>{escape(label)}</th><td>{escape(value)}</td></tr>" for label, value in lines)
    return f'<div class="card"><div class="status"><b>{escape(title)}</b></div><table>{body}</table></div>'
