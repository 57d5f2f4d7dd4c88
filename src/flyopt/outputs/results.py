"""What flyopt writes: the units of every number, the JSON documents, and the result tables.

Units
    :data:`QUANTITIES` gives the dimension of every number flyopt writes,
    :data:`INPUTS` that of a sweep's inputs (the fields of
    :data:`flyopt.io.sweep_spec.FIELDS`); :func:`unit_of` turns a name into
    its SI unit through :data:`flyopt.units.DIMENSIONS`. This is the one
    table behind the ``units`` map of ``flyopt solve --json``, the units of
    the columns of sweep, Pareto and trade-off files, and the unit labels of
    the printed tables. A name means one quantity wherever it appears
    (``mass`` is kg in ``design``, in ``parts[]`` and in a sweep's column;
    docs/nomenclature.md lists the names with their meaning).

JSON documents
    Every JSON object flyopt writes carries ``schema_version`` and ``kind``
    (``solve``, ``sweep``, ``pareto``, ``tradeoff``) and is described by the
    JSON Schema shipped with the package, ``flyopt/data/output.schema.json``
    (:func:`schema`); the version is the schema's.

Result tables
    A sweep's table has one row per point: ``point``, :data:`CORE_INPUTS`,
    the other varied fields, then :data:`RESULT_COLUMNS`; the table of a Latin
    hypercube has a ``seed`` column after ``point``. :func:`write_results` and
    :func:`read_results` round-trip it exactly, whatever the format;
    :class:`ResultWriter` writes one piece at a time (a sweep's chunks as they
    finish), so that a table larger than memory never has to be held whole.
    In Parquet the text columns are dictionary-encoded (each distinct name or
    status stored once per row group, read back by pandas as categoricals).

Missing values are nulls
    A value that does not exist (no material when nothing was designed, no
    limit that binds, no IPOPT iterations for a closed form, no cost without
    a price) is null: ``None``/NaN/``<NA>`` in pandas (:func:`normalize`),
    null in Parquet and JSON, an empty cell in CSV (pandas reads it back as
    NaN). A limit that is not set is a number, +inf (``inf`` in CSV), and
    null in JSON, which has no infinity. A file's metadata says so
    (:data:`MISSING`): in Parquet the key ``flyopt`` of the file's key-value
    metadata, for CSV a sidecar ``FILE.csv.json`` (:func:`sidecar_path`),
    with the units, the column types and the provenance (flyopt version,
    the scene and its digest, the sweep's fields and values).
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
from pathlib import Path

import numpy as np

from flyopt.errors import SceneError
from flyopt.units import DIMENSIONS

__all__ = [
    "CORE_INPUTS",
    "COUNTS",
    "INPUTS",
    "MISSING",
    "QUANTITIES",
    "RESULT_COLUMNS",
    "ResultWriter",
    "arrow_table",
    "document_units",
    "json_text",
    "normalize",
    "objective_of",
    "output_format",
    "read_results",
    "schema",
    "schema_version",
    "scene_record",
    "sidecar_path",
    "solution_document",
    "solution_json",
    "table_document",
    "table_metadata",
    "table_units",
    "unit_of",
    "write_results",
    "write_text",
]

# --------------------------------------------------------------------------
# Units
# --------------------------------------------------------------------------

#: Dimensions of outputs that no input has, with their SI unit (the others are
#: :data:`flyopt.units.DIMENSIONS`'). Money is a plain number: a material's cost is read
#: per kilogram (``"2.1 1/kg"``, dimension ``cost_per_mass``), so a wheel's cost is
#: ``dimensionless``, in the currency the scene's prices are given in.
OUTPUT_DIMENSIONS = {"time": "s", "unbalance": "kg*m"}

#: The columns of a sweep's inputs: the fields of :data:`flyopt.io.sweep_spec.FIELDS` (which
#: reads their values in these dimensions) and their dimension, None for a name. sweep_spec
#: imports this module (for :func:`output_format`), so the table cannot be read from there;
#: tests/outputs/test_results.py checks that the two agree, field by field.
INPUTS = {
    "delta": "dimensionless",
    "speed": "angular_speed",
    "inertia": "inertia",
    "torque.scale": "dimensionless",
    "design.max_outer_diameter": "length",
    "design.max_width": "length",
    "design.d_mean": "length",
    "design.hb_ratio": "dimensionless",
    "design.hb_min": "dimensionless",
    "design.hb_max": "dimensionless",
    "design.geometry": None,
    "design.objective": None,
    "material": None,
    "shaft": None,
}
#: Columns ``material.NAME.FIELD`` and ``shaft.NAME.FIELD`` of a sweep: FIELD and its dimension.
MATERIAL_INPUTS = {"density": "density", "max_rim_speed": "speed", "cost": "cost_per_mass"}
SHAFT_INPUTS = {"speed_ratio": "dimensionless"}

#: The dimension of every other number flyopt writes: the JSON of ``flyopt solve`` and the
#: columns of sweep, Pareto and trade-off tables (a name of :data:`INPUTS` that the JSON also
#: holds, ``delta`` or a part's ``inertia``, has that entry's dimension). Sections of
#: docs/flywheel-design.md.
QUANTITIES = {
    # the cycle, sections 2-5: energy indicator diagram, A_max, J_F
    "a_max": "energy",
    "delta_e": "energy",
    "work_per_cycle": "energy",
    "angle": "angle",
    "cycle_angle": "angle",
    "angle_omega_max": "angle",
    "angle_omega_min": "angle",
    "angle_delta_e_max": "angle",
    "angle_delta_e_min": "angle",
    "driving_torque": "torque",
    "resisting_torque": "torque",
    "omega": "angular_speed",
    "omega_mean": "angular_speed",
    "omega_max": "angular_speed",
    "omega_min": "angular_speed",
    "omega_target": "angular_speed",
    "j_constant": "inertia",
    "j_margin": "inertia",
    "j_required": "inertia",
    "gd2_required": "flywheel_moment",
    "achieved_delta": "dimensionless",
    "delta_allowed": "dimensionless",
    "j_error": "dimensionless",
    "tolerance": "dimensionless",
    # power and efficiency, section 11; transfer to a shaft, section 8; start-up, section 7
    "power": "power",
    "motor_power": "power",
    "efficiency": "dimensionless",
    "speed_ratio": "dimensionless",
    "best_speed_ratio": "dimensionless",
    "time": "time",
    "cycles": "dimensionless",
    "solve_time": "time",
    # the wheel, sections 9, 10 and 13
    "d_mean": "length",
    "d_outer": "length",
    "d_inner": "length",
    "h": "length",
    "b": "length",
    "outer_diameter": "length",
    "d_outer_limit": "length",
    "d_outer_needed": "length",
    "max_outer_diameter": "length",
    "max_width": "length",
    "bore": "length",
    "t_web": "length",
    "d_hub": "length",
    "l_hub": "length",
    "arm_major": "length",
    "arm_minor": "length",
    "r_inner": "length",
    "r_outer": "length",
    "thickness": "length",
    "radius": "length",
    "wall": "length",
    "hb_ratio": "dimensionless",
    "mass": "mass",
    "cost": "dimensionless",
    "density": "density",
    "j_flywheel": "inertia",
    "j_at_reference": "inertia",
    "j_max": "inertia",
    "j_required_on_shaft": "inertia",
    "rim_speed": "speed",
    "rim_speed_limit": "speed",
    "hoop_stress": "stress",
    "allowable_stress": "stress",
    "allowable": "stress",
    "strength": "stress",
    "stress": "stress",
    "max_principal": "stress",
    "von_mises": "stress",
    "hoop_max": "stress",
    "radial_max": "stress",
    "mean_hoop": "stress",
    "safety_factor": "dimensionless",
    "strength_safety": "dimensionless",
    "burst_speed": "angular_speed",
    "speed_margin": "dimensionless",
    "unbalance_permissible": "unbalance",
    # the hub's key (DIN 6885-1), section 13
    "length": "length",
    "effective_length": "length",
    "t1": "length",
    "t2": "length",
    "torque": "torque",
    "bearing_pressure": "stress",
    "shear": "stress",
    "allowable_pressure": "stress",
    "allowable_shear": "stress",
    # the drive designed with the flywheel, sections 7, 8 and 14: the motor, its ratio, its heating
    "motor_ratio": "dimensionless",
    "flywheel_ratio": "dimensionless",
    "breakdown_ratio": "dimensionless",
    "rated_power": "power",
    "rated_speed": "angular_speed",
    "synchronous_speed": "angular_speed",
    "rotor_inertia": "inertia",
    "j_delta": "inertia",
    "rms_torque": "torque",
    "mean_torque": "torque",
    "rated_torque": "torque",
    "startup_time": "time",
    "motor_mass": "mass",
    "wheel_mass": "mass",
    "total_mass": "mass",
    "price": "dimensionless",
}

#: Numbers whose unit is set by another field, so that a table or document has no single
#: unit for them where that field varies (their ``units`` entry is then null).
UNIT_SET_BY = {
    "objective": "the unit of the quantity the design's objective names "
    "(mass: kg, outer_diameter: m, cost: 1; a drive's mass is motor plus wheel)",
    "objective_bound": "the unit of the design's objective, as for objective",
    "epsilon": "the unit of the Pareto front's second objective",
    "dmass_dlimit": "kg per the unit given in the same entry's 'unit'",
    "dobjective_dlimit": "the drive objective's unit (kg for mass, 1 for cost) per the unit given in the same "
    "entry's 'unit'",
}

#: Whole numbers that count or index: no unit.
COUNTS = frozenset(
    {
        "index",
        "index_omega_max",
        "index_omega_min",
        "iterations",
        "n_arms",
        "point",
        "seed",
        "n_combinations",
        "n_feasible",
    }
)

#: The convention for values that do not exist, as each file states it.
MISSING = (
    "null where a value does not exist (nothing designed, no limit binding, no IPOPT "
    "iterations, no price); an empty cell in CSV, which pandas reads as NaN. A limit "
    "that is not set is +inf in tables (inf in CSV) and null in JSON"
)


def dimension_of(name):
    """The dimension of a numeric field, or None (text, counts, unknown names)."""
    if name in INPUTS:
        return INPUTS[name]
    parts = name.split(".")
    if len(parts) == 3 and parts[0] == "material":
        return MATERIAL_INPUTS.get(parts[2])
    if len(parts) == 3 and parts[0] == "shaft":
        return SHAFT_INPUTS.get(parts[2])
    return QUANTITIES.get(name)


def _si(dimension):
    if dimension in OUTPUT_DIMENSIONS:
        return OUTPUT_DIMENSIONS[dimension]
    return DIMENSIONS[dimension][1] or "1"


def has_unit(name):
    """Whether ``name`` is a quantity: a unit of its own, or one set by another field."""
    return name in UNIT_SET_BY or dimension_of(name) is not None


def unit_of(name, objective=None, front=None):
    """The SI unit of a field, as pint writes it ("kg", "kg*m**2", "rad/s"; "1": dimensionless).

    Parameters
    ----------
    name : str
        A JSON field or a table column: ``mass``, ``shafts``' ``omega``,
        ``design.max_width``, ``material.cast_iron.density`` ...
    objective : str, optional
        The objective the ``objective`` values are of (``mass``,
        ``outer_diameter``, ``cost``).
    front : str, optional
        The second objective of a Pareto front, the unit of ``epsilon``.

    Returns
    -------
    str or None
        None for text, counts and names that are no quantity, and for a
        field of :data:`UNIT_SET_BY` whose unit is not fixed by the arguments.
    """
    if name in ("objective", "objective_bound"):
        return unit_of(objective) if objective else None
    if name == "epsilon":
        return unit_of(front) if front else None
    dimension = dimension_of(name)
    return None if dimension is None else _si(dimension)


def table_units(columns, objective=None, front=None):
    """The ``units`` map of a table: every quantity column and its unit (null: no single unit)."""
    return {str(c): unit_of(str(c), objective, front) for c in columns if has_unit(str(c))}


def document_units(document, objective=None):
    """The ``units`` map of a JSON document: every numeric field that occurs in it, and its unit.

    A field counts where it holds a number, a list of numbers or null (a
    value that may be a number elsewhere); text, booleans, counts and
    objects do not.

    Parameters
    ----------
    document : dict
        Plain JSON data.
    objective : str, optional
        The objective the document's ``objective`` values are of.

    Returns
    -------
    dict
        Field name to unit, sorted by name.
    """
    found = set()

    def visit(key, value):
        if isinstance(value, dict):
            for k, v in value.items():
                visit(k, v)
        elif isinstance(value, list):
            if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
                found.add(key)
            for v in value:
                if isinstance(v, (dict, list)):
                    visit(key, v)
        elif value is None or (isinstance(value, (int, float)) and not isinstance(value, bool)):
            found.add(key)

    visit(None, document)
    return {name: unit_of(name, objective) for name in sorted(n for n in found if n and has_unit(n))}


# --------------------------------------------------------------------------
# JSON documents
# --------------------------------------------------------------------------

SCHEMA_FILE = "output.schema.json"


@functools.lru_cache(maxsize=1)
def schema():
    """The JSON Schema of every JSON document flyopt writes (``flyopt/data/output.schema.json``)."""
    from importlib import resources

    return json.loads(resources.files("flyopt").joinpath("data", SCHEMA_FILE).read_text(encoding="utf-8"))


def schema_version():
    """The version of flyopt's output schema, which every document and file metadata carries."""
    return schema()["$defs"]["schema_version"]["const"]


def _flyopt_version():
    import flyopt

    return flyopt.__version__


def json_safe(value):
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


def json_text(document):
    """A document as JSON text, every float as Python prints it (round-trip exact)."""
    return json.dumps(json_safe(document), indent=2, allow_nan=False)


def solution_document(solution, scene, timings=False):
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


def solution_json(solution, scene, timings=False):
    """The text ``flyopt solve --json`` prints: :func:`solution_document` as JSON."""
    return json_text(solution_document(solution, scene, timings))


def scene_record(scene, digest=None):
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
        ``scene`` (the file, or None for a scene made in Python),
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
    return {"scene": None if source is None else str(source), "scene_file_sha256": sha, "scene_digest": digest}


def table_metadata(kind, columns, *, kinds=None, scene=None, objectives=None, sweep=None, objective=None):
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

    Returns
    -------
    dict
    """
    kinds = kinds or {}
    front = objectives[1] if objectives else None
    meta = {
        "schema_version": schema_version(),
        "kind": kind,
        "flyopt_version": _flyopt_version(),
        **(scene or {"scene": None, "scene_file_sha256": None, "scene_digest": None}),
        "missing": MISSING,
        "columns": [{"name": str(c), "type": _JSON_TYPES[kinds.get(c) or _kind(c)]} for c in columns],
        "units": table_units(columns, objective, front),
    }
    if objectives is not None:
        meta["objectives"] = list(objectives)
    if sweep is not None:
        meta["sweep"] = sweep
    return json_safe(meta)


def objective_of(frame):
    """The objective every row of a table is designed for (its one ``design.objective``), or None."""
    if "design.objective" not in frame.columns:
        return None
    names = frame["design.objective"].dropna().unique()
    return str(names[0]) if len(names) == 1 else None


def table_document(frame, metadata):
    """A table as one JSON document: its metadata and ``rows``, one object per row (null: no value)."""
    records = frame.astype(object).where(frame.notna(), None).to_dict(orient="records")
    return {**metadata, "rows": json_safe(records)}


def write_text(path, text, label="-o/--output"):
    """Write ``text`` to ``path`` atomically: a temporary file beside it, moved into place.

    Nothing is left under the final name if writing fails or is interrupted.

    Raises
    ------
    SceneError
        Field ``label``: the folder of ``path`` does not exist.
    """
    path = Path(path)
    check_folder(path, label)

    def write(tmp):
        with open(tmp, "w", encoding="utf-8") as handle:
            handle.write(text)
            if text and not text.endswith("\n"):
                handle.write("\n")

    replace_atomically(path, write)


def replace_atomically(path, write, temporary_folder=None):
    """Call ``write(tmp)`` on a temporary file, then move it to ``path`` (removed on any failure)."""
    folder = path.parent if temporary_folder is None else Path(temporary_folder)
    tmp = folder / f"{path.name}.tmp-{os.getpid()}"
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


# --------------------------------------------------------------------------
# The result table's columns
# --------------------------------------------------------------------------

#: Input columns present in every result table (SI; NaN for "none").
CORE_INPUTS = (
    "delta",
    "speed",
    "inertia",
    "torque.scale",
    "design.geometry",
    "design.objective",
    "design.hb_min",
    "design.hb_max",
    "design.max_outer_diameter",
    "design.max_width",
    "design.d_mean",
)

#: Result columns, with their kind. Where a value does not exist it is null (see
#: :func:`normalize`): text None, numbers NaN, ``iterations`` <NA>.
RESULT_COLUMNS = {
    "status": "str",  # designed | not_needed | infeasible | failed
    "feasible": "bool",  # a design was found
    "method": "str",  # closed_form | ipopt | none
    "best_material": "str",
    "best_shaft": "str",
    "best_speed_ratio": "float",
    "d_mean": "float",
    "d_outer": "float",
    "d_inner": "float",
    "h": "float",
    "b": "float",
    "hb_ratio": "float",
    "mass": "float",
    "cost": "float",
    "objective": "float",
    "rim_speed": "float",
    "rim_speed_limit": "float",
    "hoop_stress": "float",
    "safety_factor": "float",
    "j_flywheel": "float",
    "j_at_reference": "float",
    "j_required_on_shaft": "float",
    "d_outer_limit": "float",
    "binding": "str",  # comma-separated names of BINDING_NAMES
    "n_combinations": "int",  # material x shaft combinations decided
    "n_feasible": "int",
    "a_max": "float",
    "j_margin": "float",
    "j_required": "float",
    "driving_torque": "float",
    "power": "float",
    "motor_power": "float",
    "solver_status": "str",
    "iterations": "int",
    "message": "str",
}

#: Whole-number columns that may have no value (IPOPT's iterations of a closed-form design):
#: pandas' nullable Int64. The sweep's evaluation marks them -1 (:func:`normalize` makes that null).
NULLABLE_INTS = frozenset({"iterations"})

#: Text columns of the trade-off table besides the names above (a material's binding limits
#: other than the inertia, and why it is infeasible).
_TEXT = frozenset({"limit", "reason"})

_JSON_TYPES = {"str": "string", "bool": "boolean", "int": "integer", "float": "number"}


def _kind(name, column=None):
    """The kind of a column: "str", "bool", "int" or "float".

    By its name; a column no table of flyopt names (a user's own) by its values."""
    kind = RESULT_COLUMNS.get(name)
    if kind is not None:
        return kind
    if (name in INPUTS and INPUTS[name] is None) or name in _TEXT:
        return "str"
    if name in COUNTS:
        return "int"
    if column is not None and not has_unit(name):
        from pandas.api import types

        if types.is_bool_dtype(column.dtype):
            return "bool"
        if not types.is_numeric_dtype(column.dtype):
            return "str"
    return "float"


def _no_minus_one(column):
    """A whole-number column of :data:`NULLABLE_INTS` as nullable Int64, its -1 (no value) null."""
    values = column.astype("Int64")
    return values.mask((values == -1).fillna(False))


def _text_dtype():
    """pandas' text dtype: ``str`` (missing: NaN) from pandas 3, object (missing: None) before."""
    import pandas as pd

    return "str" if int(pd.__version__.split(".")[0]) >= 3 else object


def normalize(frame):
    """One dtype per column and nulls for missing values, whatever the source.

    The frame of an evaluation, a CSV or a Parquet file comes out the same:
    text columns of pandas' text dtype with NaN/None where there is no
    text (an empty string is no text), numbers float64 with NaN, whole
    numbers int64 (nullable Int64 for :data:`NULLABLE_INTS`, whose -1 is
    no value), booleans bool. Modifies and returns ``frame``.
    """
    for name in frame.columns:
        column = frame[name]
        kind = _kind(name, column)
        if kind == "str":
            values = column.astype(object)  # categorical in Parquet, str or object elsewhere
            frame[name] = values.where(values.notna() & (values != ""), None).astype(_text_dtype())
        elif kind == "bool":
            frame[name] = column.astype(bool)
        elif kind == "int" and name in NULLABLE_INTS:
            frame[name] = _no_minus_one(column)
        elif kind == "int":
            frame[name] = column.astype(np.int64)
        else:
            frame[name] = column.astype(float)
    return frame


# --------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------

_SUFFIXES = {".parquet": "parquet", ".pq": "parquet", ".csv": "csv"}

#: The key of flyopt's metadata in a Parquet file's key-value metadata.
PARQUET_KEY = b"flyopt"


def output_format(path, label="output"):
    """``"parquet"`` or ``"csv"``, by the suffix of ``path``; SceneError naming ``label`` else."""
    kind = _SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError(label, f"{str(path)!r} must end in .parquet or .csv (the suffix picks the format)")
    return kind


def sidecar_path(path):
    """The sidecar of a CSV file, which holds its metadata: ``FILE.csv`` → ``FILE.csv.json``."""
    path = Path(path)
    return path.with_name(path.name + ".json")


def arrow_table(frame, metadata=None):
    """A result table as a pyarrow Table, its text columns dictionary-encoded, nulls as nulls.

    Every column gets its kind's type (string columns ``dictionary<int32,
    string>``, then int64, bool, float64) whatever the rows hold, so tables
    of different chunks share one schema. A missing value (empty text, NaN,
    ``iterations`` -1) is an Arrow null.

    Parameters
    ----------
    frame : pandas.DataFrame
    metadata : dict, optional
        flyopt's metadata (:func:`table_metadata`), stored as the schema's
        key-value metadata under ``flyopt``.

    Returns
    -------
    pyarrow.Table
    """
    import pyarrow as pa

    arrays = []
    for name in frame.columns:
        column = frame[name]
        kind = _kind(name, column)
        if kind == "str":
            arrays.append(_text(column))
        elif kind == "bool":
            arrays.append(pa.array(column.to_numpy(dtype=bool), type=pa.bool_()))
        elif kind == "int" and name in NULLABLE_INTS:
            arrays.append(pa.array(_no_minus_one(column), type=pa.int64(), from_pandas=True))
        elif kind == "int":
            arrays.append(pa.array(column.to_numpy(dtype=np.int64), type=pa.int64()))
        else:
            arrays.append(pa.array(column.to_numpy(dtype=float), type=pa.float64(), from_pandas=True))
    table = pa.Table.from_arrays(arrays, names=[str(name) for name in frame.columns])
    if metadata is not None:
        table = table.replace_schema_metadata({PARQUET_KEY: json.dumps(metadata, allow_nan=False)})
    return table


def _text(column):
    """A text column as a dictionary-encoded arrow array (null for no text)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    try:
        array = pa.array(column, from_pandas=True)
        if array.type != pa.string():
            array = array.cast(pa.string())
    except (pa.ArrowInvalid, pa.ArrowTypeError, pa.ArrowNotImplementedError):
        array = pa.array(
            [None if v is None or (isinstance(v, float) and math.isnan(v)) else str(v) for v in column.astype(object)],
            type=pa.string(),
        )
    empty = pc.equal(array, "")
    if pc.any(empty).as_py():
        array = pc.if_else(empty, pa.scalar(None, pa.string()), array)
    return array.dictionary_encode()


def _dictionary_columns(table):
    """Names of a table's dictionary-encoded (text) columns: Parquet dictionaries for these
    only (a float column's dictionary is built, found too large and dropped: time lost)."""
    import pyarrow as pa

    return [f.name for f in table.schema if pa.types.is_dictionary(f.type)]


def csv_rows(frame, handle, header):
    """Rows as CSV: a missing value is an empty cell (also a -1 of :data:`NULLABLE_INTS`)."""
    nullable = [c for c in frame.columns if c in NULLABLE_INTS]
    if nullable:
        frame = frame.copy()
        for name in nullable:
            frame[name] = _no_minus_one(frame[name])
    frame.to_csv(handle, index=False, header=header)


def _write_sidecar(path, metadata):
    """Write the sidecar of CSV ``path`` (atomically) and return its path."""
    sidecar = sidecar_path(path)
    text = json.dumps({**metadata, "csv": {"delimiter": ",", "header": True, "null": ""}}, indent=2, allow_nan=False)
    write_text(sidecar, text, label="output")
    return sidecar


class ResultWriter:
    """A result file written piece by piece, put in place only when complete.

    The pieces go to a temporary file (Parquet row groups, or CSV rows under
    one header), which :meth:`close` moves to ``path``; :meth:`abort` (or an
    exception inside a ``with`` block) removes it. So the file under its
    final name is always whole, and memory holds one piece at a time.

    Parameters
    ----------
    path : str or Path
        ``.parquet`` (or ``.pq``) or ``.csv``.
    temporary_folder : str or Path, optional
        Where the temporary file goes (on the same file system as ``path``),
        e.g. the sweep's parts folder, which a rerun cleans even after a
        kill; default: beside ``path``.
    metadata : callable, optional
        ``metadata(columns)``, flyopt's metadata of the file
        (:func:`table_metadata`): Parquet key-value metadata, or the CSV's
        sidecar (written just before the table is moved into place).

    Examples
    --------
    >>> with ResultWriter("study.parquet") as out:   # doctest: +SKIP
    ...     for frame in pieces:
    ...         out.append(frame)
    ...     out.close()
    """

    #: Rows gathered into one Parquet row group (~30 MB of a sweep's columns).
    ROW_GROUP_ROWS = 65_536

    def __init__(self, path, temporary_folder=None, metadata=None):
        self.path = Path(path)
        self.kind = output_format(self.path)
        check_folder(self.path)
        folder = self.path.parent if temporary_folder is None else Path(temporary_folder)
        self.temporary = folder / f"{self.path.name}.tmp-{os.getpid()}"
        self.rows = 0
        self._writer = self._file = None
        self._pending, self._pending_rows = [], 0
        self._columns = None
        self._metadata = metadata
        self._meta = None

    def _file_metadata(self):
        if self._meta is None and self._metadata is not None:
            self._meta = self._metadata(list(self._columns or []))
        return self._meta

    def append(self, frame):
        """Add the rows of ``frame`` (the columns of the first piece, in its order)."""
        if self._columns is None:
            self._columns = list(frame.columns)
        elif list(frame.columns) != self._columns:
            raise ValueError(f"a piece's columns differ from the file's: {list(frame.columns)} vs {self._columns}")
        if self.kind == "parquet":
            self._pending.append(arrow_table(frame, self._file_metadata()))
            self._pending_rows += len(frame)
            if self._pending_rows >= self.ROW_GROUP_ROWS:
                self._flush()
        else:
            if self._file is None:
                self._file = open(self.temporary, "w", encoding="utf-8", newline="")
            csv_rows(frame, self._file, header=self.rows == 0)
        self.rows += len(frame)

    def _flush(self):
        import pyarrow as pa
        import pyarrow.parquet as pq

        if not self._pending:
            return
        table = pa.concat_tables(self._pending) if len(self._pending) > 1 else self._pending[0]
        self._pending, self._pending_rows = [], 0
        if self._writer is None:
            self._writer = pq.ParquetWriter(self.temporary, table.schema, use_dictionary=_dictionary_columns(table))
        self._writer.write_table(table, row_group_size=max(len(table), 1))

    def close(self):
        """Finish the file and move it to its name (it then replaces any file there)."""
        sidecar = None
        try:
            if self.kind == "parquet":
                self._flush()
                if self._writer is None:  # no rows: a file with the columns alone
                    import pandas as pd
                    import pyarrow.parquet as pq

                    pq.write_table(
                        arrow_table(pd.DataFrame(columns=self._columns or []), self._file_metadata()), self.temporary
                    )
                else:
                    self._writer.close()
                    self._writer = None
            else:
                if self._file is None:
                    self._file = open(self.temporary, "w", encoding="utf-8", newline="")
                    if self._columns:
                        self._file.write(",".join(self._columns) + "\n")
                self._file.close()
                self._file = None
                if self._file_metadata() is not None:
                    sidecar = _write_sidecar(self.path, self._file_metadata())
            os.replace(self.temporary, self.path)
        except BaseException:
            if sidecar is not None:
                sidecar.unlink(missing_ok=True)
            self.abort()
            raise

    def abort(self):
        """Stop writing and remove the temporary file."""
        writer, handle = self._writer, self._file
        self._writer = self._file = None
        self._pending = []
        try:
            if writer is not None:
                writer.close()
            if handle is not None:
                handle.close()
        finally:
            self.temporary.unlink(missing_ok=True)

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        if kind is not None or self._writer is not None or self._file is not None:
            self.abort()
        return False


def write_results(frame, path, temporary_folder=None, metadata=None):
    """Write a result table to Parquet or CSV (by the suffix), atomically.

    The table is written to a temporary file and moved into place, so a
    crash never leaves a half-written file under the final name; an error
    or an interrupt while writing removes the temporary file.

    Parameters
    ----------
    frame : pandas.DataFrame
    path : str or Path
        ``.parquet`` (or ``.pq``) or ``.csv``.
    temporary_folder : str or Path, optional
        Where the temporary file goes (on the same file system as ``path``),
        e.g. the sweep's parts folder, which a rerun cleans even after a
        kill; default: beside ``path``.
    metadata : dict, optional
        flyopt's metadata (:func:`table_metadata`): Parquet key-value
        metadata, or the CSV's sidecar ``FILE.csv.json``.
    """
    path = Path(path)
    kind = output_format(path)
    check_folder(path)
    sidecar = None

    def write(tmp):
        nonlocal sidecar
        if kind == "parquet":
            import pyarrow.parquet as pq

            table = arrow_table(frame, metadata)
            pq.write_table(table, tmp, use_dictionary=_dictionary_columns(table))
        else:
            with open(tmp, "w", encoding="utf-8", newline="") as handle:
                csv_rows(frame, handle, header=True)
            if metadata is not None:
                sidecar = _write_sidecar(path, metadata)

    try:
        replace_atomically(path, write, temporary_folder)
    except BaseException:
        if sidecar is not None:
            sidecar.unlink(missing_ok=True)
        raise


def read_results(path, columns=None):
    """Read a result table written by flyopt (Parquet or CSV), dtypes and nulls restored.

    Parameters
    ----------
    path : str or Path
    columns : list of str, optional
        Read these columns only.

    Returns
    -------
    pandas.DataFrame
        Equal to the DataFrame the sweep returned. ``attrs["flyopt"]`` holds
        the file's metadata (units, provenance, a front's objectives) where
        it has any: Parquet key-value metadata, or the CSV's sidecar.
    """
    import pandas as pd

    path = Path(path)
    metadata = None
    if output_format(path) == "parquet":
        import pyarrow.parquet as pq

        frame = pd.read_parquet(path, columns=columns)
        stored = pq.read_schema(path).metadata or {}
        if PARQUET_KEY in stored:
            metadata = json.loads(stored[PARQUET_KEY])
    else:
        header = pd.read_csv(path, nrows=0).columns
        strings = [c for c in header if _kind(c) == "str"]
        numbers = [c for c in header if c not in strings]
        frame = pd.read_csv(
            path,
            dtype={c: str for c in strings},
            keep_default_na=False,
            na_values={c: ["", "NaN", "nan"] if c in numbers else [""] for c in header},
            usecols=columns,
        )
        if columns is not None:
            frame = frame[list(columns)]
        sidecar = sidecar_path(path)
        if sidecar.is_file():
            metadata = json.loads(sidecar.read_text(encoding="utf-8"))
    frame = normalize(frame)
    if metadata is not None:
        frame.attrs["flyopt"] = metadata
    return frame


def check_folder(path, label="output"):
    """The folder of an output must exist: flyopt does not create folders the user did not ask for."""
    folder = Path(path).parent
    if not folder.is_dir():
        raise SceneError(label, f"the folder {str(folder)!r} of {str(path)!r} does not exist")
