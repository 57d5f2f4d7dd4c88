"""The JSON documents flyopt writes, and what a table file says about itself.

Every JSON object flyopt writes carries ``schema_version`` and ``kind``
(``solve``, ``sweep``, ``pareto``, ``tradeoff``) and is described by the
JSON Schema shipped with the package, ``flyopt/data/output.schema.json``
(:func:`flyopt.outputs.schema.schema`, re-exported here); the version is the schema's.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.outputs.quantities import MISSING, document_units, table_units
from flyopt.outputs.results import JSON_TYPES, column_kind
from flyopt.outputs.schema import SCHEMA_FILE, schema, schema_version

if TYPE_CHECKING:
    import os

    import pandas as pd

    from flyopt.io.scene import Scene
    from flyopt.pipeline import Solution

__all__ = [
    "SCHEMA_FILE",
    "json_safe",
    "json_text",
    "objective_of",
    "schema",
    "schema_version",
    "scene_record",
    "solution_document",
    "solution_json",
    "table_document",
    "table_metadata",
]


def _flyopt_version() -> str:
    import flyopt

    return flyopt.__version__


def json_safe(value: object) -> Any:
    """Plain JSON data: NaN and ±inf (no value, no limit) become null, numpy scalars Python ones."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, np.generic):
        return json_safe(value.item())
    return value


def json_text(document: object) -> str:
    """A document as JSON text, every float as Python prints it (round-trip exact)."""
    return json.dumps(json_safe(document), indent=2, allow_nan=False)


def solution_document(solution: Solution, scene: str | os.PathLike[str], timings: bool = False) -> dict[str, Any]:
    """The JSON of ``flyopt solve``: the solution's fields, its schema version and its units.

    Parameters
    ----------
    solution : flyopt.pipeline.Solution
    scene : str
        The scene file as given on the command line.
    timings : bool
        Also the wall-clock time of each design solve (``solve_time``).

    Returns
    -------
    dict
        ``schema_version``, ``kind`` ("solve"), ``flyopt_version``,
        ``scene``, ``units`` (every numeric field of the document and its SI
        unit), then the fields of :meth:`flyopt.pipeline.Solution.to_dict`
        (docs/nomenclature.md), every number in SI, null for no value.
    """
    data = json_safe(solution.to_dict(timings=timings))
    design, drive = getattr(solution, "design", None), getattr(solution, "drive", None)
    objectives = {
        design.spec.objective if design is not None else None,
        drive.objective if drive is not None else None,
    } - {None}
    objective = objectives.pop() if len(objectives) == 1 else None
    return {
        "schema_version": schema_version(),
        "kind": "solve",
        "flyopt_version": _flyopt_version(),
        "scene": str(scene),
        "units": document_units(data, objective),
        **data,
    }


def calculation_document(
    kind: str, title: str, scene: str | os.PathLike[str], fields: Mapping[str, Any]
) -> dict[str, Any]:
    """The JSON of ``flyopt solve`` for a scene that is one calculation (kinds "operation", "position",
    "electric_drive", "power_chain"): its result's fields (``to_dict``), every number in SI, with the document's header."""
    data = json_safe({"title": title, **fields})
    return {
        "schema_version": schema_version(),
        "kind": kind,
        "flyopt_version": _flyopt_version(),
        "scene": str(scene),
        "units": document_units(data, None),
        **data,
    }


def solution_json(solution: Solution, scene: str | os.PathLike[str], timings: bool = False) -> str:
    """The text ``flyopt solve --json`` prints: :func:`solution_document` as JSON."""
    return json_text(solution_document(solution, scene, timings))


def scene_record(scene: Scene, digest: str | None = None) -> dict[str, str | None]:
    """Where a table's scene came from: its file, the file's SHA-256, flyopt's digest of it.

    Parameters
    ----------
    scene : Scene
    digest : str, optional
        :func:`flyopt.studies.payload.digest` of the scene (what a sweep's
        parts are identified by): two scenes with the same digest compute
        the same, whatever file they came from.

    Returns
    -------
    dict
        ``scene`` (the file, as :attr:`flyopt.io.scene.Scene.shown_as` names it, or None for a scene made
        in Python),
        ``scene_file_sha256`` (of the file's bytes now, None without one)
        and ``scene_digest``.
    """
    source = getattr(scene, "source", None)
    sha = None
    if source is not None:
        try:
            sha = hashlib.sha256(Path(source).read_bytes()).hexdigest()
        except OSError:
            sha = None
    shown = getattr(scene, "shown_as", None) or (None if source is None else str(source))
    return {"scene": shown, "scene_file_sha256": sha, "scene_digest": digest}


def table_metadata(
    kind: str,
    columns: Sequence[str],
    *,
    kinds: Mapping[str, str] | None = None,
    scene: Mapping[str, str | None] | None = None,
    objectives: Sequence[str] | None = None,
    sweep: Mapping[str, Any] | None = None,
    objective: str | None = None,
    message: str | None = None,
) -> dict[str, Any]:
    """What a table file says about itself: Parquet key-value metadata, the CSV sidecar.

    Parameters
    ----------
    kind : {"sweep", "pareto", "tradeoff"}
    columns : list of str
    kinds : mapping, optional
        Column name to its kind ("str", "bool", "int", "float"); by default
        each column's kind by its name.
    scene : dict, optional
        :func:`scene_record` of the scene.
    objectives : pair of str, optional
        A Pareto front's objectives, mass first: ``flyopt plot`` draws the
        second along x.
    sweep : dict, optional
        The sweep: its fields and values, samples, seed, method.
    objective : str, optional
        The objective every row's ``objective`` is of, when there is one.
    message : str, optional
        Why the table has no rows (an empty Pareto front: no flywheel needed,
        or no design anywhere on the range).

    Returns
    -------
    dict
    """
    kinds = kinds or {}
    front = objectives[1] if objectives else None
    meta: dict[str, Any] = {
        "schema_version": schema_version(),
        "kind": kind,
        "flyopt_version": _flyopt_version(),
        **(scene or {"scene": None, "scene_file_sha256": None, "scene_digest": None}),
        "missing": MISSING,
        "columns": [{"name": str(c), "type": JSON_TYPES[kinds.get(c) or column_kind(c)]} for c in columns],
        "units": table_units(columns, objective, front),
    }
    if objectives is not None:
        meta["objectives"] = list(objectives)
    if sweep is not None:
        meta["sweep"] = sweep
    if message is not None:
        meta["message"] = message
    return json_safe(meta)


def objective_of(frame: pd.DataFrame) -> str | None:
    """The objective every row of a table is designed for (its one ``design.objective``), or None."""
    if "design.objective" not in frame.columns:
        return None
    names = frame["design.objective"].dropna().unique()
    return str(names[0]) if len(names) == 1 else None


def table_document(frame: pd.DataFrame, metadata: Mapping[str, Any]) -> dict[str, Any]:
    """A table as one JSON document: its metadata and ``rows``, one object per row (null: no value)."""
    records = frame.astype(object).where(frame.notna(), None).to_dict(orient="records")
    return {**metadata, "rows": json_safe(records)}
