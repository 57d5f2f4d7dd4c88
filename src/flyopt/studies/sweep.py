"""Design sweeps: one scene varied over a grid or a Latin hypercube of its fields.

``sweep(scene, {"delta": "0.01:0.1:log20", "speed": "300,600,1200rpm",
"material": "cast_iron,cast_steel"})`` returns a pandas DataFrame with one
row per point: every input and every result (the best design, its binding
constraints, feasibility, how it was computed). The same runs from the
command line (``flyopt sweep``) and from a ``[sweep]`` table in a scene file.

Fields (``--vary FIELD=VALUES``)
--------------------------------
=================================  =====================================  ===========
field (aliases)                    what it sets                           values
=================================  =====================================  ===========
``delta``                          δ, 0 < δ < 2                           number
``speed``                          mean speed ω_m of the reference shaft  rad/s or rpm
``inertia``                        the machine's own J_c                  kg*m^2
``torque.scale``                   both torques (or the net areas) × k    k > 0
``design.max_outer_diameter``      envelope (``envelope``)                m or none
``design.max_width``               width limit B_max (``max_width``)      m or none
``design.d_mean``                  pinned mean diameter (``d_mean``)      m or none
``design.hb_ratio``                H/B, one value collapses the range     number
``design.hb_min``, ``hb_max``      one end of the H/B range               number
``design.geometry``                ``geometry``                           thin_rim, rim, disc
``design.objective``               ``objective``                          mass, cost, outer_diameter
``material``                       the one material of the point          names
``shaft``                          the one shaft of the point             names
``shaft.NAME.speed_ratio``         a shaft's ω_shaft / ω_reference        number
``material.NAME.density``          (``max_rim_speed``, ``cost`` too)      kg/m^3 ...
=================================  =====================================  ===========

Values: a list ``a,b,c``; a linear range ``a:b:n`` (n points, ends
included) or a log range ``a:b:logn``; names ``cast_iron,cast_steel``;
``none`` for an optional length. A unit after the last value applies to
every value written without one: ``300,600,1200rpm``, ``0.4:1.2:5 m``.
Plain numbers are SI. For Latin hypercube samples (``samples=N``) a range
is sampled continuously (``a:b`` or ``a:b:log``; a count is ignored) and a
list is sampled as categories, each equally often.

What is computed once, and why it is exact
------------------------------------------
The cycle is analysed once: for torques of the angle alone A_max does not
depend on δ, ω_m or J_c, and scaling both torques by k scales every ΔE, so
A_max(k) = k A_max. Each point then has J_F = k A_max / (ω_m² δ) − J_c,
the formula of the analysis itself. The designs come from
:mod:`flyopt.design.closed_form` (closed form, exact, vectorized over every point and
combination) where it covers the structure, and from
:func:`flyopt.design.optimize.design_flywheel` (IPOPT on an NLP built once per
structure and process, fed parameters) elsewhere; each row says which
(``method``). A point whose IPOPT solve fails gets ``status = "failed"``
with IPOPT's status, never a mass.

Running
-------
Points are cut into chunks. By default chunks run in parallel in worker
processes on this machine, one per CPU (serially when the sweep is estimated
to take under a second in one process, so that starting processes would cost
more than it saves: a 10,000-point closed-form sweep takes ~0.15 s), with a
progress line and an ETA on stderr. ``scheduler="tcp://host:8786"`` (or a
``dask.distributed`` Client or cluster) runs them on a Dask cluster instead.
With an ``output`` file every finished chunk is written to
``OUTPUT.parts/chunk-NNNNN.parquet`` at once, so a crash loses at most the
chunks in flight; ``resume=True`` skips the chunks already on disk. The
final file (Parquet or CSV, by its suffix) is assembled at the end and the
parts removed.
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import json
import math
import os
import re
import shutil
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

import numpy as np
import pandas as pd

from flyopt.design import closed_form as batch
from flyopt.errors import SceneError, SolverFailed
from flyopt.io.scene import NetAreas
from flyopt.machine.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.units import quantity

__all__ = [
    "FIELDS",
    "CORE_INPUTS",
    "RESULT_COLUMNS",
    "Axis",
    "SweepPlan",
    "parse_vary",
    "plan_sweep",
    "point_scene",
    "evaluate_points",
    "sweep",
    "load_sweep",
    "read_results",
    "write_results",
]

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib


# --------------------------------------------------------------------------
# Fields
# --------------------------------------------------------------------------

@dataclass(frozen=True)
class _Field:
    kind: str              # "number" | "name"
    dimension: str = "dimensionless"
    minimum: float = 0.0   # values must exceed it (or reach it when inclusive)
    inclusive: bool = False
    maximum: float | None = None
    optional: bool = False  # "none" allowed
    what: str = ""


#: The scene fields a sweep may vary (besides shaft.NAME.speed_ratio and
#: material.NAME.density|max_rim_speed|cost).
FIELDS = {
    "delta": _Field("number", what="coefficient of speed fluctuation, 0 < δ < 2", maximum=2.0),
    "speed": _Field("number", "angular_speed", what="mean speed of the reference shaft (> 0)"),
    "inertia": _Field("number", "inertia", inclusive=True,
                      what="the machine's own inertia J_c (>= 0)"),
    "torque.scale": _Field("number", what="factor on both torques (> 0)"),
    "design.max_outer_diameter": _Field("number", "length", optional=True,
                                        what="envelope on the outer diameter (> 0 or none)"),
    "design.max_width": _Field("number", "length", optional=True,
                               what="limit on the axial width (> 0 or none)"),
    "design.d_mean": _Field("number", "length", optional=True,
                            what="pinned mean diameter (> 0 or none)"),
    "design.hb_ratio": _Field("number", what="H/B, one value (> 0)"),
    "design.hb_min": _Field("number", what="lower end of the H/B range (> 0)"),
    "design.hb_max": _Field("number", what="upper end of the H/B range (> 0)"),
    "design.geometry": _Field("name", what="thin_rim, rim or disc"),
    "design.objective": _Field("name", what="mass, cost or outer_diameter"),
    "material": _Field("name", what="a material name"),
    "shaft": _Field("name", what="a shaft name"),
}

_SHAFT_FIELDS = {"speed_ratio": _Field("number", what="ω_shaft / ω_reference (> 0)")}
_MATERIAL_FIELDS = {
    "density": _Field("number", "density", what="density (> 0)"),
    "max_rim_speed": _Field("number", "speed", what="safe rim speed (> 0)"),
    "cost": _Field("number", "cost_per_mass", inclusive=True, what="cost per kg (>= 0)"),
}

_ALIASES = {
    "machine.delta": "delta", "machine.speed": "speed", "omega_mean": "speed",
    "machine.inertia": "inertia", "j_constant": "inertia",
    "envelope": "design.max_outer_diameter", "max_outer_diameter": "design.max_outer_diameter",
    "max_width": "design.max_width", "width": "design.max_width",
    "d_mean": "design.d_mean", "hb_ratio": "design.hb_ratio", "hb_min": "design.hb_min",
    "hb_max": "design.hb_max", "geometry": "design.geometry", "objective": "design.objective",
    "design.material": "material", "design.shaft": "shaft", "materials": "material",
    "shafts": "shaft", "design.materials": "material", "design.shafts": "shaft",
}

#: Input columns present in every result table (SI; NaN for "none").
CORE_INPUTS = ("delta", "speed", "inertia", "torque.scale", "design.geometry",
               "design.objective", "design.hb_min", "design.hb_max",
               "design.max_outer_diameter", "design.max_width", "design.d_mean")

#: Result columns, with their pandas dtype. Strings are "" when absent (so that
#: CSV and Parquet read back the same), numbers NaN, ``iterations`` -1.
RESULT_COLUMNS = {
    "status": "str",            # designed | not_needed | infeasible | failed
    "feasible": "bool",         # a design was found
    "method": "str",            # closed_form | ipopt | none
    "best_material": "str",
    "best_shaft": "str",
    "best_speed_ratio": "float",
    "d_mean": "float", "d_outer": "float", "d_inner": "float", "h": "float", "b": "float",
    "hb_ratio": "float", "mass": "float", "cost": "float", "objective": "float",
    "rim_speed": "float", "rim_speed_limit": "float", "hoop_stress": "float",
    "safety_factor": "float", "j_flywheel": "float", "j_at_reference": "float",
    "j_required_on_shaft": "float", "d_outer_limit": "float",
    "binding": "str",           # comma-separated names of BINDING_NAMES
    "n_combinations": "int",    # material x shaft combinations decided
    "n_feasible": "int",
    "a_max": "float", "j_margin": "float", "j_required": "float",
    "driving_torque": "float", "power": "float", "motor_power": "float",
    "solver_status": "str", "iterations": "int", "message": "str",
}

_NAME_INPUTS = {"design.geometry", "design.objective", "material", "shaft"}


def _known_fields(scene):
    names = list(FIELDS)
    names.append(f"shaft.<name>.speed_ratio (shafts: {', '.join(s.name for s in scene.shafts)})")
    names.append("material.<name>.density|max_rim_speed|cost "
                 f"(materials: {', '.join(scene.material_library())})")
    return names


def _resolve(scene, path, where):
    """Canonical field name and its description, or SceneError."""
    key = _ALIASES.get(path.strip(), path.strip())
    if key in FIELDS:
        return key, FIELDS[key]
    parts = key.split(".")
    if len(parts) == 3 and parts[0] == "shaft":
        names = [s.name for s in scene.shafts]
        if parts[1] not in names:
            raise SceneError(_where(where, path), f"unknown shaft {parts[1]!r}"
                             f"{_hint(parts[1], names)} (shafts: {', '.join(names)})")
        if parts[2] not in _SHAFT_FIELDS:
            raise SceneError(_where(where, path), f"a shaft's field is "
                             f"{', '.join(_SHAFT_FIELDS)}, not {parts[2]!r}")
        return key, _SHAFT_FIELDS[parts[2]]
    if len(parts) == 3 and parts[0] == "material":
        library = scene.material_library()
        if parts[1] not in library:
            raise SceneError(_where(where, path), f"unknown material {parts[1]!r}"
                             f"{_hint(parts[1], library)} (known: {', '.join(library)})")
        if parts[2] not in _MATERIAL_FIELDS:
            raise SceneError(_where(where, path), f"a material's field is one of "
                             f"{', '.join(_MATERIAL_FIELDS)}, not {parts[2]!r}")
        return key, _MATERIAL_FIELDS[parts[2]]
    candidates = list(FIELDS) + list(_ALIASES)
    raise SceneError(_where(where, path), f"unknown sweep field{_hint(key, candidates)}; "
                     f"allowed: {'; '.join(_known_fields(scene))}")


def _hint(name, known):
    close = difflib.get_close_matches(str(name), list(known), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _where(where, path):
    if not where:
        return path
    return f"{where} {path}" if where.startswith("--") else f"{where}.{path}"


# --------------------------------------------------------------------------
# Values: a,b,c | a:b:n | a:b:logn, with a trailing unit
# --------------------------------------------------------------------------

_NUMBER = re.compile(r"\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_COUNT = re.compile(r"^\s*(log)?\s*(\d+)?\s*(.*?)\s*$", re.IGNORECASE)


@dataclass(frozen=True)
class Axis:
    """One varied field and its values (SI floats, names, or NaN for none).

    Attributes
    ----------
    field : str
        Canonical field name (the column of the result table).
    values : tuple
        The grid values.
    kind : {"list", "range"}
    low, high : float or None
        Ends of a range (for Latin hypercube sampling).
    log : bool
        Log spacing / log-uniform sampling.
    """

    field: str
    values: tuple
    kind: str = "list"
    low: float | None = None
    high: float | None = None
    log: bool = False


def _split_unit(item):
    """'1200rpm' -> ('1200', 'rpm'); '1/20' -> ('1/20', '')."""
    m = _NUMBER.match(item)
    if m:
        rest = item[m.end():].strip()
        if rest and (rest[0].isalpha() or rest[0] in "°%"):
            return m.group().strip(), rest
    return item.strip(), ""


def _number(text, unit, spec, label):
    raw = f"{text} {unit}".strip() if unit else text
    try:
        return quantity(raw, spec.dimension, label)
    except SceneError as err:
        raise SceneError(label, err.message) from None


def _check_value(value, spec, label, text):
    if spec.optional and value is None:
        return
    low_ok = value >= spec.minimum if spec.inclusive else value > spec.minimum
    high_ok = spec.maximum is None or value < spec.maximum
    if not (low_ok and high_ok):
        raise SceneError(label, f"{text!r} is out of range: {spec.what}")


def _parse_text(scene, name, spec, text, label, sampled):
    text = text.strip()
    if not text:
        raise SceneError(label, "no values given: write a list a,b,c or a range a:b:n")
    if spec.kind == "name":
        if ":" in text:
            raise SceneError(label, f"{text!r}: a range needs numbers; give names as a list a,b,c")
        items = [t.strip() for t in text.split(",")]
        return Axis(name, tuple(_check_name(scene, name, item, label) for item in items))
    if ":" in text:
        return _parse_range(name, spec, text, label, sampled)
    items = [t.strip() for t in text.split(",")]
    if any(not t for t in items):
        raise SceneError(label, f"{text!r}: an empty value in the list")
    trailing = _split_unit(items[-1])[1]
    values = []
    for item in items:
        if spec.optional and item.lower() == "none":
            values.append(math.nan)
            continue
        number, unit = _split_unit(item)
        value = _number(number, unit or trailing, spec, label)
        _check_value(value, spec, label, item)
        values.append(value)
    return Axis(name, tuple(values))


def _parse_range(name, spec, text, label, sampled):
    parts = text.split(":")
    if len(parts) not in (2, 3):
        raise SceneError(label, f"{text!r}: a range is a:b:n (linear) or a:b:logn (log), "
                         f"with an optional unit at the end")
    if len(parts) == 3:
        m = _COUNT.match(parts[2])
        log, count, trailing = bool(m.group(1)), m.group(2), m.group(3)
        if count is None and not log:
            raise SceneError(label, f"{text!r}: the third part must be a count n or logn "
                             f"(e.g. 0.01:0.1:log20), then an optional unit")
    else:
        log, count = False, None
        trailing = _split_unit(parts[1])[1]
    if count is None and not sampled:
        raise SceneError(label, f"{text!r}: a grid range needs a count: a:b:n or a:b:logn")
    ends = []
    for part in parts[:2]:
        number, unit = _split_unit(part)
        if not number:
            raise SceneError(label, f"{text!r}: a range end is missing")
        value = _number(number, unit or trailing, spec, label)
        _check_value(value, spec, label, part.strip())
        ends.append(value)
    low, high = ends
    if log and (low <= 0 or high <= 0):
        raise SceneError(label, f"{text!r}: a log range needs positive ends")
    n = 1 if count is None else int(count)
    if n < 1:
        raise SceneError(label, f"{text!r}: the count must be at least 1")
    if log:
        values = np.geomspace(low, high, n) if n > 1 else np.array([low])
    else:
        values = np.linspace(low, high, n) if n > 1 else np.array([low])
    if n > 1:
        values[0], values[-1] = low, high
    return Axis(name, tuple(float(v) for v in values), "range", low, high, log)


def _check_name(scene, name, item, label):
    if name == "design.geometry":
        from flyopt.design.geometry import GEOMETRIES
        known = list(GEOMETRIES)
    elif name == "design.objective":
        from flyopt.design.optimize import OBJECTIVES
        known = list(OBJECTIVES)
    elif name == "material":
        known = list(scene.material_library())
    else:
        known = [s.name for s in scene.shafts]
    if item not in known:
        raise SceneError(label, f"unknown {name.split('.')[-1]} {item!r}{_hint(item, known)} "
                         f"(allowed: {', '.join(known)})")
    return item


def _parse_value(scene, name, spec, value, label, sampled):
    """A value from TOML or Python: a string (the grammar), a number, or a list."""
    if isinstance(value, str):
        return _parse_text(scene, name, spec, value, label, sampled)
    items = value if isinstance(value, (list, tuple, np.ndarray)) else [value]
    if len(items) == 0:
        raise SceneError(label, "no values given")
    values = []
    for item in items:
        if isinstance(item, str):
            values.extend(_parse_text(scene, name, spec, item, label, False).values)
        elif spec.kind == "name":
            raise SceneError(label, f"{item!r}: expected a name ({spec.what})")
        elif item is None and spec.optional:
            values.append(math.nan)
        else:
            number = _number(item, "", spec, label) if not isinstance(item, str) else None
            _check_value(number, spec, label, str(item))
            values.append(number)
    return Axis(name, tuple(values))


def parse_vary(scene, vary, *, where="--vary", samples=None):
    """Read the fields to vary and their values.

    Parameters
    ----------
    scene : Scene
        Supplies the shafts and materials that field names may refer to.
    vary : mapping or iterable of str
        ``{"delta": "0.01:0.1:log20", ...}`` or ``["delta=0.01:0.1:log20", ...]``.
        A mapping's values may also be numbers or lists (from a TOML table).
    where : str
        Where the fields come from, for messages (``--vary``, ``sweep.vary``).
    samples : int or None
        Latin hypercube sampling (ranges may then omit their count).

    Returns
    -------
    list of Axis

    Raises
    ------
    SceneError
        Bad syntax, unknown field, wrong unit or out-of-range value; the
        message names the field and what is allowed.
    """
    if isinstance(vary, Mapping):
        items = list(vary.items())
    else:
        items = []
        for text in vary:
            if not isinstance(text, str) or "=" not in text:
                raise SceneError(where, f"{text!r}: expected FIELD=VALUES, e.g. "
                                 f"delta=0.01:0.1:log20 or speed=300,600,1200rpm")
            path, values = text.split("=", 1)
            items.append((path.strip(), values))
    axes, seen = [], {}
    for path, values in items:
        if not path:
            raise SceneError(where, "a field name is missing before '='")
        name, spec = _resolve(scene, path, where)
        label = _where(where, path)
        if name in seen:
            raise SceneError(label, f"is varied twice (also as {seen[name]!r})")
        seen[name] = path
        axes.append(_parse_value(scene, name, spec, values, label, samples is not None))
    names = {a.field for a in axes}
    if "design.hb_ratio" in names and names & {"design.hb_min", "design.hb_max"}:
        raise SceneError(_where(where, "design.hb_ratio"), "vary either design.hb_ratio or "
                         "design.hb_min/design.hb_max, not both")
    return axes


# --------------------------------------------------------------------------
# Points
# --------------------------------------------------------------------------

#: Largest number of points a sweep may have.
MAX_POINTS = 20_000_000


@dataclass
class SweepPlan:
    """The points of a sweep: a DataFrame of inputs, one row per point.

    Attributes
    ----------
    axes : list of Axis
    points : pandas.DataFrame
        Column ``point`` and one column per axis (SI values, names, NaN for none).
    samples : int or None
        Latin hypercube sample count (None: full factorial grid).
    seed : int or None
    """

    axes: list
    points: pd.DataFrame
    samples: int | None = None
    seed: int | None = None


def plan_sweep(scene, vary, *, samples=None, seed=None, where="--vary"):
    """The points of a sweep: a full-factorial grid, or Latin hypercube samples.

    Parameters
    ----------
    scene : Scene
    vary : mapping or iterable of str
        See :func:`parse_vary`.
    samples : int, optional
        Number of Latin hypercube samples; without it the full grid.
    seed : int, optional
        Seed of the Latin hypercube (reproducible samples).

    Returns
    -------
    SweepPlan

    Raises
    ------
    SceneError
        Bad fields or values, too many points, or points whose design
        settings are invalid (e.g. an H/B range with min > max).
    """
    axes = parse_vary(scene, vary, where=where, samples=samples)
    if samples is not None:
        if not isinstance(samples, (int, np.integer)) or isinstance(samples, bool) or samples < 1:
            raise SceneError("samples", f"must be a positive whole number, got {samples!r}")
        if not axes:
            raise SceneError("samples", "Latin hypercube sampling needs at least one varied field")
        from scipy.stats import qmc

        unit = qmc.LatinHypercube(d=len(axes), rng=seed).random(int(samples))
        columns = {}
        for k, axis in enumerate(axes):
            u = unit[:, k]
            if axis.kind == "range":
                if axis.log:
                    lo, hi = math.log(axis.low), math.log(axis.high)
                    columns[axis.field] = np.exp(lo + u * (hi - lo))
                else:
                    columns[axis.field] = axis.low + u * (axis.high - axis.low)
            else:
                index = np.minimum((u * len(axis.values)).astype(int), len(axis.values) - 1)
                columns[axis.field] = np.asarray(axis.values, dtype=object)[index]
        n = int(samples)
    else:
        n = math.prod(len(a.values) for a in axes)
        if n > MAX_POINTS:
            raise SceneError(where, f"the grid has {n} points, more than {MAX_POINTS}; "
                             f"use fewer values or Latin hypercube samples")
        columns = {}
        if axes:
            grids = np.meshgrid(*[np.arange(len(a.values)) for a in axes], indexing="ij")
            for axis, index in zip(axes, grids):
                columns[axis.field] = np.asarray(axis.values, dtype=object)[index.ravel()]
    points = pd.DataFrame({"point": np.arange(n, dtype=np.int64)})
    for axis in axes:
        values = columns[axis.field]
        if FIELDS.get(axis.field, _Field("number")).kind == "name":
            points[axis.field] = np.asarray(values, dtype=object)
        else:
            points[axis.field] = np.asarray(values, dtype=float)
    _check_points(scene, points, where)
    return SweepPlan(axes=axes, points=points, samples=samples, seed=seed)


def _check_points(scene, points, where):
    """Reject points whose design settings are invalid, naming the field."""
    from flyopt.design.optimize import DesignSpec

    n = len(points)
    inputs = _Inputs(scene, points)
    bad = np.flatnonzero(inputs.hb_min > inputs.hb_max)
    if bad.size:
        k = int(bad[0])
        raise SceneError(_where(where, "design.hb_min"), f"H/B min {inputs.hb_min[k]:.6g} "
                         f"exceeds max {inputs.hb_max[k]:.6g} at point {k} (and "
                         f"{bad.size - 1} other points)")
    frame = pd.DataFrame({"g": inputs.geometry, "o": inputs.objective, "a": inputs.hb_min,
                          "c": inputs.hb_max, "e": inputs.envelope, "w": inputs.width,
                          "d": inputs.d_mean}).drop_duplicates()
    for row in frame.itertuples(index=False):
        try:
            DesignSpec(geometry=row.g, hb_ratio=(row.a, row.c), objective=row.o,
                       max_outer_diameter=None if math.isnan(row.e) else row.e,
                       max_width=None if math.isnan(row.w) else row.w,
                       d_mean=None if math.isnan(row.d) else row.d)
        except ValueError as err:
            raise SceneError(_where(where, "design"), str(err)) from None
    cost = inputs.objective == "cost"
    if cost.any():
        for name in inputs.material_names:
            used = cost & inputs.uses_material(name)
            if used.any() and np.isnan(inputs.material_cost[name][used]).any():
                raise SceneError(_where(where, "design.objective"), f"'cost' needs a cost per kg "
                                 f"for every material; none is given for {name}")
    if n and not inputs.material_names:
        raise SceneError("design.materials", "no material to design with")


# --------------------------------------------------------------------------
# One point as a scene
# --------------------------------------------------------------------------

def _scale_curve(curve, k):
    if curve is None:
        return None
    if isinstance(curve, PiecewiseLinear):
        return PiecewiseLinear(curve.angles, curve.values * k)
    if isinstance(curve, Constant):
        return curve if curve.unknown else Constant(curve.value * k)
    if isinstance(curve, ExpressionTorque):
        return dataclasses.replace(curve, scale=curve.scale * k)
    raise SceneError("torque.scale", f"cannot scale a torque of type {type(curve).__name__}")


def point_scene(scene, point):
    """The scene of one sweep point (for individual solves and checks).

    Parameters
    ----------
    scene : Scene
    point : mapping
        Canonical field name to value (SI, names, NaN for none), e.g. a row
        of :attr:`SweepPlan.points`.

    Returns
    -------
    Scene
    """
    from flyopt.design.materials import material_library

    changes = {}
    design = {}
    shafts = {s.name: s for s in scene.shafts}
    library = material_library(scene.materials)
    user = {m.name: m for m in scene.materials}
    for name, value in point.items():
        if name == "point":
            continue
        if name == "delta":
            changes["delta"] = float(value)
        elif name == "speed":
            changes["omega_mean"] = float(value)
        elif name == "inertia":
            changes["j_constant"] = float(value)
        elif name == "torque.scale":
            k = float(value)
            changes["driving"] = _scale_curve(scene.driving, k)
            changes["resisting"] = _scale_curve(scene.resisting, k)
            if scene.net is not None:
                changes["net"] = NetAreas(tuple(e * k for e in scene.net.energies))
        elif name == "design.hb_ratio":
            design["hb_ratio"] = (float(value), float(value))
        elif name in ("design.hb_min", "design.hb_max"):
            low, high = design.get("hb_ratio", scene.design.hb_ratio)
            design["hb_ratio"] = (float(value), high) if name.endswith("min") else (low, float(value))
        elif name in ("design.max_outer_diameter", "design.max_width", "design.d_mean"):
            design[name.split(".")[1]] = None if _is_none(value) else float(value)
        elif name in ("design.geometry", "design.objective"):
            design[name.split(".")[1]] = str(value)
        elif name == "material":
            changes["design_materials"] = (str(value),)
        elif name == "shaft":
            changes["design_shafts"] = (str(value),)
        elif name.startswith("shaft."):
            shaft_name = name.split(".")[1]
            shafts[shaft_name] = dataclasses.replace(shafts[shaft_name], speed_ratio=float(value))
        elif name.startswith("material."):
            _, material_name, prop = name.split(".")
            base = user.get(material_name, library[material_name])
            user[material_name] = dataclasses.replace(base, **{prop: float(value)})
        else:
            raise SceneError(name, "unknown sweep field")
    if design:
        changes["design"] = dataclasses.replace(scene.design, **design)
    changes["shafts"] = tuple(shafts.values())
    changes["materials"] = tuple(user.values())
    return scene.replace(**changes)


def _is_none(value):
    return value is None or (isinstance(value, float) and math.isnan(value))


# --------------------------------------------------------------------------
# Evaluation of a chunk of points
# --------------------------------------------------------------------------

def _reusable(scene):
    """Whether J_F = A_max/(ω_m² δ) − J_c with one A_max holds at every point.

    True for the energy model's scenes: a constant inertia (no members) and
    torques of the angle only. Members (a varying J_e) or speed-dependent
    torques need each point analysed by the model that is exact for it.
    """
    if scene.net is not None:
        return True
    if scene.members:
        return False
    angle_only = (PiecewiseLinear, Constant, ExpressionTorque)
    for curve in (scene.driving, scene.resisting):
        if not isinstance(curve, angle_only) or getattr(curve, "speed_dependent", False):
            return False
    return True


@dataclass(frozen=True)
class _Context:
    """What every chunk needs; picklable (the torques are left out when reusable)."""

    scene: object
    a_max: float | None
    driving_torque: float | None
    reusable: bool
    method: str = "auto"
    solver_options: dict | None = None
    axes: tuple = ()


def _context(scene, method="auto", solver_options=None, axes=()):
    from flyopt.analysis import analyse

    reusable = _reusable(scene)
    if reusable:
        analysis = analyse(scene)
        stripped = scene.replace(driving=None, resisting=None, net=None)
        return _Context(stripped, analysis.a_max, analysis.driving_torque, True, method,
                        dict(solver_options) if solver_options else None, tuple(axes))
    return _Context(scene, None, None, False, method,
                    dict(solver_options) if solver_options else None, tuple(axes))


class _Inputs:
    """Per-point input arrays of a chunk, defaults from the scene."""

    def __init__(self, scene, points):
        n = len(points)
        self.n = n
        spec = scene.design

        def col(name, default):
            if name in points:
                return points[name].to_numpy(dtype=float)
            return np.full(n, math.nan if default is None else float(default))

        def names(name, default):
            if name in points:
                return points[name].to_numpy(dtype=object)
            return np.full(n, default, dtype=object)

        self.delta = col("delta", scene.delta)
        self.speed = col("speed", scene.omega_mean)
        self.inertia = col("inertia", scene.j_constant)
        self.scale = col("torque.scale", 1.0)
        self.geometry = names("design.geometry", spec.geometry)
        self.objective = names("design.objective", spec.objective)
        if "design.hb_ratio" in points:
            self.hb_min = self.hb_max = points["design.hb_ratio"].to_numpy(dtype=float)
        else:
            self.hb_min = col("design.hb_min", spec.hb_ratio[0])
            self.hb_max = col("design.hb_max", spec.hb_ratio[1])
        self.envelope = col("design.max_outer_diameter", spec.max_outer_diameter)
        self.width = col("design.max_width", spec.max_width)
        self.d_mean = col("design.d_mean", spec.d_mean)
        library = scene.material_library()
        self.library = library
        self.material_names = list(scene.design_materials or tuple(library))
        self.material = names("material", None) if "material" in points else None
        if self.material is not None:
            self.material_names = list(dict.fromkeys(
                self.material_names + [m for m in dict.fromkeys(self.material)]))
        allowed = scene.design_shafts
        self.shaft_names = [s.name for s in scene.shafts if allowed is None or s.name in allowed]
        self.shaft = names("shaft", None) if "shaft" in points else None
        if self.shaft is not None:
            self.shaft_names = [s.name for s in scene.shafts
                                if s.name in self.shaft_names or s.name in set(self.shaft)]
        self.ratio = {s.name: col(f"shaft.{s.name}.speed_ratio", s.speed_ratio)
                      for s in scene.shafts}
        self.density, self.max_rim_speed, self.material_cost, self.allowable = {}, {}, {}, {}
        for name, m in library.items():
            self.density[name] = col(f"material.{name}.density", m.density)
            self.max_rim_speed[name] = col(f"material.{name}.max_rim_speed", m.max_rim_speed)
            self.material_cost[name] = col(f"material.{name}.cost", m.cost)
            self.allowable[name] = np.full(n, math.nan if m.allowable_stress is None
                                           else m.allowable_stress)

    def uses_material(self, name):
        if self.material is None:
            return np.full(self.n, name in self.material_names)
        return self.material == name


def _empty_results(n):
    out = {}
    for name, kind in RESULT_COLUMNS.items():
        if kind == "str":
            out[name] = np.full(n, "", dtype=object)
        elif kind == "bool":
            out[name] = np.zeros(n, dtype=bool)
        elif kind == "int":
            out[name] = np.zeros(n, dtype=np.int64)
        else:
            out[name] = np.full(n, np.nan)
    out["iterations"][:] = -1
    return out


def evaluate_points(scene_or_context, points, *, method="auto", solver_options=None):
    """Design every point of a table of sweep points.

    Parameters
    ----------
    scene_or_context : Scene
        The scene the points vary (its cycle is analysed once).
    points : pandas.DataFrame
        Rows of :attr:`SweepPlan.points`.
    method : {"auto", "closed_form", "ipopt"}
        ``auto``: the closed form of :mod:`flyopt.design.closed_form` where it is exact,
        IPOPT elsewhere; ``ipopt``: IPOPT for every point (for checks and
        benchmarks); ``closed_form``: refuse structures it does not cover.
    solver_options : mapping, optional
        CasADi/IPOPT options for the IPOPT points.

    Returns
    -------
    pandas.DataFrame
        One row per point: ``point``, :data:`CORE_INPUTS`, the other varied
        fields, then :data:`RESULT_COLUMNS`.
    """
    ctx = scene_or_context
    if not isinstance(ctx, _Context):
        ctx = _context(ctx, method, solver_options, tuple(c for c in points.columns
                                                         if c != "point"))
    return _evaluate(ctx, points)


def _evaluate(ctx, points):
    scene = ctx.scene
    inputs = _Inputs(scene, points)
    n = inputs.n
    res = _empty_results(n)
    # -- the cycle: analysed once, A_max scaled (see the module notes) ------
    if ctx.reusable:
        a_max = inputs.scale * ctx.a_max
        driving = (inputs.scale * ctx.driving_torque if ctx.driving_torque is not None
                   else np.full(n, np.nan))
        j_margin = a_max / (inputs.speed ** 2 * inputs.delta) - inputs.inertia
        inputs.omega_rim = inputs.speed * (1 + inputs.delta / 2)      # ω_max: the rim is checked there
    else:  # varying inertia or speed-dependent torques: analyse every point with its exact model
        from flyopt.analysis import analyse

        a_max, driving, j_margin = np.empty(n), np.empty(n), np.empty(n)
        inputs.omega_rim = np.empty(n)
        for k, row in enumerate(points.to_dict("records")):
            analysis = analyse(point_scene(scene, row))
            a_max[k], j_margin[k] = analysis.a_max, analysis.j_margin
            inputs.omega_rim[k] = analysis.omega_max
            driving[k] = np.nan if analysis.driving_torque is None else analysis.driving_torque
    res["a_max"], res["j_margin"] = a_max, j_margin
    res["j_required"] = np.maximum(j_margin, 0.0)
    res["driving_torque"] = driving
    res["power"] = driving * inputs.speed
    res["motor_power"] = res["power"] / scene.efficiency
    needed = j_margin > 0.0
    idle = ~needed
    res["status"][idle] = "not_needed"
    res["method"][idle] = "none"
    for k in np.flatnonzero(idle):
        res["message"][k] = (f"no flywheel needed: J_F = {j_margin[k]:.4g} kg·m² is not "
                             f"positive")
    covered = np.array([batch.covers(g, o) for g, o in zip(inputs.geometry, inputs.objective)],
                       dtype=bool) if n else np.zeros(0, dtype=bool)
    if ctx.method == "closed_form" and (needed & ~covered).any():
        k = int(np.flatnonzero(needed & ~covered)[0])
        raise SceneError("method", f"the closed form does not cover objective "
                         f"{inputs.objective[k]!r} (point {int(points['point'].iloc[k])}); "
                         f"use method 'auto' or 'ipopt'")
    use_batch = needed & covered if ctx.method != "ipopt" else np.zeros(n, dtype=bool)
    _design_closed_form(inputs, j_margin, use_batch, res)
    for k in np.flatnonzero(needed & ~use_batch):
        _design_ipopt(ctx, inputs, k, j_margin[k], res)
    return _table(inputs, points, ctx.axes, res)


def _design_closed_form(inputs, j_margin, mask, res):
    """Fill the rows of ``mask`` from the vectorized closed form."""
    if not mask.any():
        return
    geometries = list(dict.fromkeys(inputs.geometry[mask]))
    m_names, s_names = inputs.material_names, inputs.shaft_names
    m_code = (np.array([m_names.index(m) for m in inputs.material]) if inputs.material is not None
              else np.full(inputs.n, -1))
    s_code = (np.array([s_names.index(s) for s in inputs.shaft]) if inputs.shaft is not None
              else np.full(inputs.n, -1))
    for geo in geometries:
        in_geo = mask & (inputs.geometry == geo)
        keys = np.stack([m_code[in_geo], s_code[in_geo]], axis=1)
        groups, inverse = np.unique(keys, axis=0, return_inverse=True)
        points_geo = np.flatnonzero(in_geo)
        for g, (mc, sc) in enumerate(groups):
            pts = points_geo[inverse.ravel() == g]
            mats = m_names if mc < 0 else [m_names[mc]]
            shafts = s_names if sc < 0 else [s_names[sc]]
            _design_group(inputs, geo, pts, mats, shafts, j_margin, res)


def _design_group(inputs, geo, pts, mats, shafts, j_margin, res):
    """One geometry, one material list and one shaft list, for points ``pts``."""
    n_m, n_s = len(mats), len(shafts)
    per = n_m * n_s
    p = np.repeat(pts, per)
    mi = np.tile(np.repeat(np.arange(n_m), n_s), len(pts))
    si = np.tile(np.tile(np.arange(n_s), n_m), len(pts))
    order = mi * n_s + si

    def table(values, names, index):
        return np.stack([values[name] for name in names])[index, p]

    density = table(inputs.density, mats, mi)
    v_max = table(inputs.max_rim_speed, mats, mi)
    cost_per_kg = table(inputs.material_cost, mats, mi)
    allowable = table(inputs.allowable, mats, mi)
    ratio = table(inputs.ratio, shafts, si)
    out = batch.design_combinations(
        geo, j_margin[p], inputs.omega_rim[p], ratio, density, v_max, inputs.hb_min[p],
        inputs.hb_max[p], np.where(np.isnan(inputs.envelope[p]), np.inf, inputs.envelope[p]),
        np.where(np.isnan(inputs.width[p]), np.inf, inputs.width[p]), inputs.d_mean[p])
    mass = out.mass
    cost = mass * cost_per_kg
    objective = np.where(inputs.objective[p] == "cost", cost, mass)
    feasible = out.feasible
    res["n_combinations"][pts] = per
    counts = np.bincount(p[feasible], minlength=inputs.n)
    res["n_feasible"][pts] = counts[pts]
    res["method"][pts] = batch.METHOD
    # winner per point: lowest objective, then mass, then input order (as optimize),
    # objectives within TIE_RTOL of the lowest counting as equal (see TIE_RTOL)
    f = np.flatnonzero(feasible)
    if f.size:
        ranked = f[np.lexsort((order[f], mass[f], objective[f], p[f]))]
        _, first = np.unique(p[ranked], return_index=True)
        lowest = np.full(inputs.n, np.nan)
        lowest[p[ranked[first]]] = objective[ranked[first]]
        tied = f[objective[f] <= lowest[p[f]] * (1.0 + TIE_RTOL)]
        ranked = tied[np.lexsort((order[tied], p[tied]))]
        _, first = np.unique(p[ranked], return_index=True)
        w = ranked[first]
        q = p[w]
        res["status"][q] = "designed"
        res["feasible"][q] = True
        res["best_material"][q] = np.asarray(mats, dtype=object)[mi[w]]
        res["best_shaft"][q] = np.asarray(shafts, dtype=object)[si[w]]
        res["best_speed_ratio"][q] = ratio[w]
        for name in ("d_mean", "d_outer", "d_inner", "h", "b", "hb_ratio", "mass",
                     "rim_speed", "hoop_stress", "j_flywheel", "j_at_reference"):
            res[name][q] = out[name][w]
        res["j_required_on_shaft"][q] = out.j_shaft[w]
        res["d_outer_limit"][q] = out.cap[w]
        res["rim_speed_limit"][q] = v_max[w]
        res["cost"][q] = cost[w]
        res["objective"][q] = objective[w]
        res["safety_factor"][q] = allowable[w] / out.hoop_stress[w]
        res["binding"][q] = [",".join(batch.binding_names(b)) for b in out.binding[w]]
    none = pts[counts[pts] == 0]
    if none.size:
        # the combination that comes closest: largest J_max / J' (for the message)
        closeness = out.j_max / out.j_shaft
        lost = np.isin(p, none)
        idx = np.flatnonzero(lost)
        ranked = idx[np.lexsort((order[idx], -closeness[idx], p[idx]))]
        _, first = np.unique(p[ranked], return_index=True)
        for c in ranked[first]:
            k = p[c]
            res["status"][k] = "infeasible"
            res["message"][k] = (
                f"no material and shaft can give the inertia; the closest, "
                f"{mats[mi[c]]} on the {shafts[si[c]]} shaft, can give at most "
                f"{out.j_max[c]:.4g} of the {out.j_shaft[c]:.4g} kg·m² it needs there")


#: Designs whose objectives differ by less than this (relative) are ranked as equal,
#: and the first in input order (materials, then shafts) wins. Such ties are exact
#: in the mathematics (e.g. a disc at the envelope weighs 8 J / D^2 whatever its
#: density), so without it round-off would pick the winner.
TIE_RTOL = 1e-9

_IPOPT_LOCK = threading.Lock()


def _design_ipopt(ctx, inputs, k, j_required, res):
    """One point by optimize.design_flywheel (IPOPT, NLP cached per structure)."""
    from flyopt.design.optimize import DesignSpec, MountShaft, design_flywheel
    from flyopt.design.materials import Material

    mats = [inputs.material[k]] if inputs.material is not None else inputs.material_names
    shafts = [inputs.shaft[k]] if inputs.shaft is not None else inputs.shaft_names
    materials = []
    for name in mats:
        base = inputs.library[name]
        cost = inputs.material_cost[name][k]
        materials.append(Material(name, inputs.density[name][k], inputs.max_rim_speed[name][k],
                                  base.allowable_stress, None if math.isnan(cost) else cost,
                                  base.source))
    mounts = [MountShaft(name, inputs.ratio[name][k]) for name in shafts]

    def opt(x):
        return None if math.isnan(x) else float(x)

    spec = DesignSpec(geometry=inputs.geometry[k], hb_ratio=(inputs.hb_min[k], inputs.hb_max[k]),
                      max_outer_diameter=opt(inputs.envelope[k]), max_width=opt(inputs.width[k]),
                      d_mean=opt(inputs.d_mean[k]), objective=inputs.objective[k])
    res["method"][k] = "ipopt"
    res["n_combinations"][k] = len(materials) * len(mounts)
    try:
        with _IPOPT_LOCK:  # a CasADi Function is not to be called from two threads at once
            result = design_flywheel(float(j_required), float(inputs.omega_rim[k]), mounts,
                                     materials, spec, solver_options=ctx.solver_options,
                                     method="ipopt")
    except SolverFailed as err:
        res["status"][k] = "failed"
        res["solver_status"][k] = str(getattr(err, "status", "") or "error")
        res["message"][k] = str(err)
        return
    res["n_feasible"][k] = sum(c.feasible for c in result.candidates)
    best = result.best
    if best is None:
        res["status"][k] = "infeasible"
        res["message"][k] = result.message
        return
    res["status"][k] = "designed"
    res["feasible"][k] = True
    res["best_material"][k] = best.material
    res["best_shaft"][k] = best.shaft
    res["best_speed_ratio"][k] = best.speed_ratio
    for name in ("d_mean", "d_outer", "d_inner", "h", "b", "hb_ratio", "mass", "rim_speed",
                 "hoop_stress", "j_flywheel", "j_at_reference", "j_required_on_shaft",
                 "d_outer_limit", "rim_speed_limit", "objective"):
        res[name][k] = getattr(best, name)
    res["cost"][k] = math.nan if best.cost is None else best.cost
    res["safety_factor"][k] = math.nan if best.safety_factor is None else best.safety_factor
    res["binding"][k] = ",".join(best.binding)
    res["solver_status"][k] = best.solver_status
    res["iterations"][k] = best.iterations


def _table(inputs, points, axes, res):
    n = inputs.n
    data = {"point": points["point"].to_numpy(dtype=np.int64)}
    core = {"delta": inputs.delta, "speed": inputs.speed, "inertia": inputs.inertia,
            "torque.scale": inputs.scale, "design.geometry": inputs.geometry,
            "design.objective": inputs.objective, "design.hb_min": inputs.hb_min,
            "design.hb_max": inputs.hb_max, "design.max_outer_diameter": inputs.envelope,
            "design.max_width": inputs.width, "design.d_mean": inputs.d_mean}
    data.update(core)
    for name in axes:
        if name not in data:
            data[name] = points[name].to_numpy()
    data.update(res)
    return pd.DataFrame(data, index=pd.RangeIndex(n), copy=False)


def _normalize(frame):
    """One dtype per column, whatever the source (evaluation, CSV or Parquet)."""
    for name in frame.columns:
        kind = RESULT_COLUMNS.get(name)
        if kind is None:
            kind = "str" if name in _NAME_INPUTS else ("int" if name == "point" else "float")
        if kind == "str":
            frame[name] = frame[name].fillna("").astype(str)
        elif kind == "bool":
            frame[name] = frame[name].astype(bool)
        elif kind == "int":
            frame[name] = frame[name].astype(np.int64)
        else:
            frame[name] = frame[name].astype(float)
    return frame


# --------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------

_SUFFIXES = {".parquet": "parquet", ".pq": "parquet", ".csv": "csv"}


def _format(path):
    kind = _SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise SceneError("output", f"{str(path)!r} must end in .parquet or .csv "
                         f"(the suffix picks the format)")
    return kind


def write_results(frame, path):
    """Write a result table to Parquet or CSV (by the suffix), atomically.

    The file is written beside its final name and moved into place, so a
    crash never leaves a half-written file under that name.
    """
    path = Path(path)
    kind = _format(path)
    _check_folder(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    if kind == "parquet":
        frame.to_parquet(tmp, index=False)
    else:
        frame.to_csv(tmp, index=False)
    os.replace(tmp, path)


def read_results(path):
    """Read a result table written by a sweep (Parquet or CSV), dtypes restored.

    Returns
    -------
    pandas.DataFrame
        Equal to the DataFrame the sweep returned.
    """
    path = Path(path)
    if _format(path) == "parquet":
        frame = pd.read_parquet(path)
    else:
        header = pd.read_csv(path, nrows=0).columns
        strings = [c for c in header
                   if RESULT_COLUMNS.get(c) == "str" or c in _NAME_INPUTS]
        numbers = [c for c in header if c not in strings]
        frame = pd.read_csv(path, dtype={c: str for c in strings}, keep_default_na=False,
                            na_values={c: ["", "NaN", "nan"] for c in numbers})
    return _normalize(frame)


# --------------------------------------------------------------------------
# Running: serial, processes, Dask; parts on disk; resume
# --------------------------------------------------------------------------

#: Points per chunk when every point is closed form, and when some need IPOPT.
CHUNK_CLOSED_FORM = 2500
CHUNK_IPOPT = 50
#: Under workers="auto" a sweep estimated to take less than this in one process
#: runs serially: starting worker processes (0.05 s forked, ~2 s from a fresh
#: forkserver) and shipping the chunks would cost more than it saves.
SERIAL_SECONDS = 1.0
#: Estimated cost of one combination [s]: closed form (measured ~1 µs) and IPOPT
#: (measured ~2 ms per NLP, benchmarks/results/design.md).
SECONDS_CLOSED_FORM = 2e-6
SECONDS_IPOPT = 2.5e-3


def _estimated_seconds(inputs, method):
    per_point = len(inputs.material_names) * len(inputs.shaft_names)
    if inputs.material is not None:
        per_point //= max(len(inputs.material_names), 1)
    if inputs.shaft is not None:
        per_point //= max(len(inputs.shaft_names), 1)
    covered = np.array([batch.covers(g, o) for g, o in zip(inputs.geometry, inputs.objective)],
                       dtype=bool) if method != "ipopt" else np.zeros(inputs.n, dtype=bool)
    closed = int(covered.sum())
    return per_point * (closed * SECONDS_CLOSED_FORM + (inputs.n - closed) * SECONDS_IPOPT)


class _Progress:
    """A progress line with rate and ETA on stderr (a bar on a terminal)."""

    def __init__(self, total_points, total_chunks, enabled, stream=None, done_points=0):
        self.total, self.chunks = total_points, total_chunks
        self.enabled = enabled
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.perf_counter()
        self.points, self.skipped, self.designs, self.done_chunks = 0, done_points, 0, 0
        self.last = 0.0

    def update(self, points, designs):
        self.points += points
        self.designs += designs
        self.done_chunks += 1
        now = time.perf_counter()
        final = self.skipped + self.points >= self.total
        if self.enabled and (final or now - self.last > (0.2 if self.tty else 5.0)):
            self.last = now
            self._write(final)

    def close(self):
        """End the line on a terminal when the run stopped before the last chunk."""
        if self.enabled and self.tty and self.skipped + self.points < self.total:
            self._write(False)
            self.stream.write("\n")
            self.stream.flush()

    def _write(self, final):
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        done = self.skipped + self.points
        rate = self.points / elapsed
        left = self.total - done
        eta = left / rate if rate > 0 else math.inf
        fraction = done / self.total if self.total else 1.0
        bar = "#" * int(24 * fraction) + "-" * (24 - int(24 * fraction))
        text = (f"sweep [{bar}] {done}/{self.total} points ({100 * fraction:.0f}%), "
                f"{self.designs / elapsed:,.0f} designs/s, "
                f"{'done in ' + _clock(elapsed) if final else 'ETA ' + _clock(eta)}")
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + text + end)
        self.stream.flush()


def _clock(seconds):
    if not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def _run_chunk(ctx, index, points):
    return index, _evaluate(ctx, points)


_WORKER_CONTEXT = None


def _init_worker(ctx):
    global _WORKER_CONTEXT
    _WORKER_CONTEXT = ctx


def _run_chunk_in_worker(index, points):
    return index, _evaluate(_WORKER_CONTEXT, points)


def _cpu_count():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _mp_context():
    import multiprocessing as mp

    methods = mp.get_all_start_methods()
    # fork is fast and safe while this process runs a single thread; otherwise
    # (e.g. a Dask client's threads) a fresh forkserver
    if "fork" in methods and threading.active_count() == 1:
        return mp.get_context("fork")
    if "forkserver" in methods:
        context = mp.get_context("forkserver")
        # the server imports flyopt (numpy, pandas, CasADi) once; workers fork from it
        context.set_forkserver_preload(["flyopt.studies.sweep"])
        return context
    return mp.get_context("spawn")  # pragma: no cover - Windows


def _fingerprint(ctx, points, chunk_size):
    scene = ctx.scene.replace(source=None)
    text = repr((repr(scene), ctx.a_max, ctx.driving_torque, ctx.reusable, ctx.method,
                 sorted((ctx.solver_options or {}).items()), ctx.axes, chunk_size))
    digest = hashlib.sha256(text.encode())
    digest.update(pd.util.hash_pandas_object(points, index=False).to_numpy().tobytes())
    return digest.hexdigest()


def _parts_dir(output):
    output = Path(output)
    return output.with_name(output.name + ".parts")


def _part_path(parts, index):
    return parts / f"chunk-{index:05d}.parquet"


def sweep(scene, vary=None, *, samples=None, seed=None, output=None, workers="auto",
          chunk_size=None, scheduler=None, resume=False, max_chunks=None, progress=False,
          method="auto", solver_options=None, keep_parts=False):
    """Sweep a scene over a grid (or Latin hypercube) of its fields.

    Parameters
    ----------
    scene : Scene
    vary : mapping or iterable of str
        Fields and their values, ``{"delta": "0.01:0.1:log20"}`` or
        ``["delta=0.01:0.1:log20"]``; see the module notes for the grammar.
    samples : int, optional
        Latin hypercube samples instead of the full grid.
    seed : int, optional
        Seed of the Latin hypercube.
    output : str or Path, optional
        File to write, ``.parquet`` or ``.csv``. Chunks are streamed to
        ``OUTPUT.parts/`` as they finish.
    workers : int or "auto"
        Worker processes on this machine (1: serial, in this process).
        ``auto``: one per available CPU, or serial when the sweep is
        estimated to take under :data:`SERIAL_SECONDS` in one process.
    chunk_size : int, optional
        Points per chunk (default 2500 closed form, 50 when IPOPT runs).
    scheduler : str or dask.distributed Client or cluster, optional
        Run the chunks on a Dask cluster (``"tcp://host:8786"``).
    resume : bool
        Continue an interrupted sweep: chunks whose part file exists are
        read, not rerun. The parts must come from the same sweep.
    max_chunks : int, optional
        Run at most this many chunks in this call and stop (the rest is left
        for ``resume``); the returned table then holds the finished chunks.
    progress : bool
        Progress line with rate and ETA on stderr.
    method : {"auto", "closed_form", "ipopt"}
        See :func:`evaluate_points`.
    solver_options : mapping, optional
        CasADi/IPOPT options for points solved by IPOPT.
    keep_parts : bool
        Keep ``OUTPUT.parts/`` after the final file is written.

    Returns
    -------
    pandas.DataFrame
        One row per point (see :func:`evaluate_points`), in point order.
        ``frame.attrs["sweep"]`` tells how it ran: chunks run and reused,
        workers, seconds, whether it is complete.

    Raises
    ------
    SceneError
        Bad fields, values or options (named), or parts of another sweep.
    NonPeriodicCycle
        The scene's cycle does not balance.
    """
    if method not in ("auto", "closed_form", "ipopt"):
        raise SceneError("method", f"{method!r} is not known (allowed: auto, closed_form, ipopt)")
    plan = plan_sweep(scene, vary or {}, samples=samples, seed=seed)
    points = plan.points
    ctx = _context(scene, method, solver_options, tuple(a.field for a in plan.axes))
    n = len(points)
    inputs = _Inputs(ctx.scene, points)
    all_closed = method != "ipopt" and all(
        batch.covers(g, o) for g, o in set(zip(inputs.geometry, inputs.objective)))
    if chunk_size is None:
        chunk_size = CHUNK_CLOSED_FORM if all_closed else CHUNK_IPOPT
    if not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise SceneError("chunk_size", f"must be a positive whole number, got {chunk_size!r}")
    n_chunks = max(1, math.ceil(n / chunk_size))
    chunks = [(i, points.iloc[i * chunk_size:(i + 1) * chunk_size]) for i in range(n_chunks)]
    if output is not None:
        _format(output)
    if resume and output is None:
        raise SceneError("resume", "needs an output file (its parts hold the finished chunks)")
    # -- parts already on disk ---------------------------------------------
    done = {}
    parts = _parts_dir(output) if output is not None else None
    fingerprint = _fingerprint(ctx, points, chunk_size)
    if parts is not None:
        manifest = parts / "sweep.json"
        if parts.exists():
            if not resume:
                raise SceneError("output", f"{str(parts)!r} holds the chunks of an earlier, "
                                 f"unfinished sweep: resume it (--resume) or delete the folder")
            try:
                old = json.loads(manifest.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                old = {}
            if old.get("fingerprint") != fingerprint:
                raise SceneError("resume", f"the parts in {str(parts)!r} come from a different "
                                 f"sweep (scene, fields, values or chunk size differ); delete "
                                 f"the folder to start over")
            for i, _ in chunks:
                part = _part_path(parts, i)
                if part.exists():
                    done[i] = read_results(part)
        else:
            _check_folder(parts)
            parts.mkdir()
            manifest.write_text(json.dumps({"fingerprint": fingerprint, "points": n,
                                            "chunk_size": int(chunk_size),
                                            "chunks": n_chunks}), encoding="utf-8")
    pending = [(i, chunk) for i, chunk in chunks if i not in done]
    if max_chunks is not None:
        if not isinstance(max_chunks, (int, np.integer)) or max_chunks < 0:
            raise SceneError("max_chunks", f"must be a whole number >= 0, got {max_chunks!r}")
        pending = pending[:max_chunks]
    # -- how to run ----------------------------------------------------------
    if scheduler is not None:
        mode, n_workers = "dask", None
    else:
        if workers == "auto":
            small = _estimated_seconds(inputs, method) < SERIAL_SECONDS
            n_workers = 1 if small else min(_cpu_count(), len(pending))
        else:
            if not isinstance(workers, (int, np.integer)) or workers < 1:
                raise SceneError("workers", f"must be a positive whole number or 'auto', "
                                 f"got {workers!r}")
            n_workers = min(int(workers), max(len(pending), 1))
        # a scene whose torques must travel to the workers may not pickle
        mode = "serial" if n_workers <= 1 or not ctx.reusable else "processes"
    meter = _Progress(n, n_chunks, progress, done_points=sum(len(d) for d in done.values()))
    results = dict(done)
    ran = []
    start = time.perf_counter()

    def finished(i, frame):
        if parts is not None:
            write_results(frame, _part_path(parts, i))
        results[i] = frame
        ran.append(i)
        meter.update(len(frame), int(frame["n_combinations"].sum()))

    if pending:
        if mode == "serial":
            for i, chunk in pending:
                finished(*_run_chunk(ctx, i, chunk))
        elif mode == "processes":
            _run_processes(ctx, pending, n_workers, finished)
        else:
            _run_dask(scheduler, ctx, pending, finished)
    meter.close()
    elapsed = time.perf_counter() - start
    complete = len(results) == n_chunks
    frames = [results[i] for i in sorted(results)]
    frame = (pd.concat(frames, ignore_index=True) if frames
             else evaluate_points(ctx, points.iloc[:0]))
    if complete and output is not None:
        write_results(frame, output)
        if not keep_parts:
            shutil.rmtree(parts, ignore_errors=True)
    frame.attrs["sweep"] = {
        "points": n, "chunks": n_chunks, "chunk_size": int(chunk_size),
        "chunks_run": sorted(ran), "chunks_reused": sorted(done), "complete": complete,
        "mode": mode, "workers": n_workers, "seconds": elapsed,
        "designs": int(sum(results[i]["n_combinations"].sum() for i in ran)),
        "output": None if output is None else str(output),
    }
    return frame


def _run_processes(ctx, pending, n_workers, finished):
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=n_workers, mp_context=_mp_context(),
                             initializer=_init_worker, initargs=(ctx,)) as pool:
        futures = [pool.submit(_run_chunk_in_worker, i, chunk) for i, chunk in pending]
        try:
            for future in as_completed(futures):
                finished(*future.result())
        except BaseException:
            for future in futures:
                future.cancel()
            raise


def _run_dask(scheduler, ctx, pending, finished):
    try:
        from dask.distributed import Client, as_completed
    except ImportError as err:  # pragma: no cover - dask is in the test extras
        raise SceneError("scheduler", "running on a Dask cluster needs dask[distributed] "
                         "(pip install 'flyopt[cluster]')") from err
    own = not isinstance(scheduler, Client)
    if own:
        address = scheduler if isinstance(scheduler, str) else scheduler
        try:
            client = Client(address)
        except (OSError, TimeoutError, ValueError) as err:
            raise SceneError("scheduler", f"cannot connect to the Dask scheduler "
                             f"{scheduler!r}: {err}") from err
    else:
        client = scheduler
    try:
        context = client.scatter(ctx, broadcast=True)
        futures = [client.submit(_run_chunk, context, i, chunk, pure=False)
                   for i, chunk in pending]
        for future in as_completed(futures):
            finished(*future.result())
    finally:
        if own:
            client.close()


# --------------------------------------------------------------------------
# [sweep] tables in scene files
# --------------------------------------------------------------------------

_SWEEP_KEYS = {"vary", "samples", "seed", "output", "chunk_size", "method", "workers",
               "description"}


def _flatten(table, prefix=""):
    out = {}
    for key, value in table.items():
        name = f"{prefix}.{key}" if prefix else key
        if isinstance(value, dict):
            out.update(_flatten(value, name))
        else:
            out[name] = value
    return out


def _check_folder(path):
    """The folder of an output must exist: flyopt does not create folders the user did not ask for."""
    folder = Path(path).parent
    if not folder.is_dir():
        raise SceneError("output", f"the folder {str(folder)!r} of {str(path)!r} does not exist")


def load_sweep(path):
    """Read a scene file that may hold a ``[sweep]`` table.

    ::

        [sweep]
        samples = 500          # Latin hypercube (omit for the full grid)
        seed = 1
        output = "study.parquet"
        [sweep.vary]
        delta = "0.01:0.1:log20"
        speed = "300,600,1200rpm"
        material = ["cast_iron", "cast_steel"]
        "shaft.motor.speed_ratio" = "2:8:4"   # or [sweep.vary.shaft.motor]

    A relative ``output`` is relative to the scene file's folder (``flyopt
    sweep`` applies it; ``-o`` on the command line wins).

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    scene : Scene
        The scene without its ``[sweep]`` table.
    options : dict
        ``vary`` (flattened to dotted field names) and the other keys.

    Raises
    ------
    SceneError
        Bad file, scene or ``[sweep]`` key (named, with the file).
    """
    from flyopt.io.scene import from_dict

    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError("", f"cannot read the file: {err}", str(path)) from None
    except tomllib.TOMLDecodeError as err:
        raise SceneError("", f"not valid TOML: {err}", str(path)) from None
    table = data.pop("sweep", {})
    try:
        scene = from_dict(data, source=str(path))
        if not isinstance(table, dict):
            raise SceneError("sweep", "must be a table")
        unknown = sorted(set(table) - _SWEEP_KEYS)
        if unknown:
            raise SceneError(f"sweep.{unknown[0]}", f"unknown key{_hint(unknown[0], _SWEEP_KEYS)} "
                             f"(allowed here: {', '.join(sorted(_SWEEP_KEYS))})")
        options = {k: v for k, v in table.items() if k != "description"}
        for key in ("seed", "samples", "chunk_size"):
            value = options.get(key)
            if value is not None and (isinstance(value, bool) or not isinstance(value, int) or
                                      (key != "seed" and value < 1) or value < 0):
                raise SceneError(f"sweep.{key}", f"must be a whole number{' >= 1' if key != 'seed' else ' >= 0'}, "
                                 f"got {value!r}")
        if "output" in options and not isinstance(options["output"], str):
            raise SceneError("sweep.output", f"must be a file name (.csv or .parquet), got {options['output']!r}")
        vary = options.pop("vary", {})
        if not isinstance(vary, dict):
            raise SceneError("sweep.vary", "must be a table of FIELD = VALUES")
        options["vary"] = _flatten(vary)
    except SceneError as err:
        raise err.with_source(str(path)) from None
    return scene, options
