"""The sweep grammar: the scene fields a sweep may vary, their values, and ``[sweep]`` tables.

``parse_vary(scene, {"delta": "0.01:0.1:log20", "speed": "300,600,1200rpm"})``
reads the fields to vary into :class:`Axis` objects (SI values or names);
:func:`load_sweep` reads a scene file's ``[sweep]`` table. The points are made
from the axes by :func:`flyopt.studies.plan.plan_sweep`.

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

"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt.errors import SceneError, clip, shorten
from flyopt.units import quantity, unit_value

if TYPE_CHECKING:
    import os

    from flyopt.io.scene import Scene

__all__ = [
    "FIELDS",
    "METHODS",
    "Axis",
    "parse_vary",
    "vary_from_texts",
    "check_options",
    "option_label",
    "whole_number",
    "load_sweep",
]

from flyopt.io.design_section import HB_RANGE, HB_WHY, LENGTH_RANGE, LENGTH_WHY
from flyopt.io.fields import DELTA_RANGE, SPEED_RANGE, SPEED_WHY, check_magnitude, check_scale
from flyopt.io.input_files import inside_scene
from flyopt.io.material_section import MATERIAL_MAGNITUDES
from flyopt.io.shaft_section import RATIO_RANGE, RATIO_WHY
from flyopt.io.toml_file import read_toml
from flyopt.names import closest

# --------------------------------------------------------------------------


@dataclass(frozen=True)
class SweepField:
    kind: str  # "number" | "name"
    dimension: str = "dimensionless"
    minimum: float = 0.0  # values must exceed it (or reach it when inclusive)
    inclusive: bool = False
    maximum: float | None = None
    optional: bool = False  # "none" allowed
    what: str = ""
    # the loader's (low, high, unit, why): one range for a field; None: its dimension's (flyopt.units.MAGNITUDES)
    bounds: tuple[float, float, str, str] | None = None


_LENGTHS = (*LENGTH_RANGE, "m", LENGTH_WHY)
_HB = (*HB_RANGE, "", HB_WHY)

#: The scene fields a sweep may vary (besides shaft.NAME.speed_ratio and
#: material.NAME.density|max_rim_speed|cost); a value is checked as the loader checks the field (``bounds``:
#: its range), so that no point is a scene the loader refuses.
FIELDS = {
    "delta": SweepField(
        "number",
        what="coefficient of speed fluctuation, 0 < δ < 2",
        maximum=2.0,
        bounds=(DELTA_RANGE[0], math.nextafter(DELTA_RANGE[1], 0.0), "", "as machine.delta"),
    ),
    "speed": SweepField(
        "number",
        "angular_speed",
        what="mean speed of the reference shaft (> 0)",
        bounds=(*SPEED_RANGE, "rad/s", SPEED_WHY),
    ),
    "inertia": SweepField(
        "number",
        "inertia",
        inclusive=True,
        what="the constant inertia J_c at the reference shaft, the shafts' own inertia included (>= 0)",
    ),
    "torque.scale": SweepField("number", what="factor on both torques (> 0)"),
    "design.max_outer_diameter": SweepField(
        "number", "length", optional=True, what="envelope on the outer diameter (> 0 or none)", bounds=_LENGTHS
    ),
    "design.max_width": SweepField(
        "number", "length", optional=True, what="limit on the axial width (> 0 or none)", bounds=_LENGTHS
    ),
    "design.d_mean": SweepField(
        "number", "length", optional=True, what="pinned mean diameter (> 0 or none)", bounds=_LENGTHS
    ),
    "design.hb_ratio": SweepField("number", what="H/B, one value (> 0)", bounds=_HB),
    "design.hb_min": SweepField("number", what="lower end of the H/B range (> 0)", bounds=_HB),
    "design.hb_max": SweepField("number", what="upper end of the H/B range (> 0)", bounds=_HB),
    "design.geometry": SweepField("name", what="thin_rim, rim or disc"),
    "design.objective": SweepField("name", what="mass, cost or outer_diameter"),
    "material": SweepField("name", what="a material name"),
    "shaft": SweepField("name", what="a shaft name"),
}

_SHAFT_FIELDS = {
    "speed_ratio": SweepField("number", what="ω_shaft / ω_reference (> 0)", bounds=(*RATIO_RANGE, "", RATIO_WHY))
}
_MATERIAL_FIELDS = {
    "density": SweepField("number", "density", what="density (> 0)", bounds=MATERIAL_MAGNITUDES["density"]),
    "max_rim_speed": SweepField(
        "number", "speed", what="safe rim speed (> 0)", bounds=MATERIAL_MAGNITUDES["max_rim_speed"]
    ),
    "cost": SweepField("number", "cost_per_mass", inclusive=True, what="cost per kg (>= 0)"),
}

_ALIASES = {
    "machine.delta": "delta",
    "machine.speed": "speed",
    "omega_mean": "speed",
    "machine.inertia": "inertia",
    "j_constant": "inertia",
    "envelope": "design.max_outer_diameter",
    "max_outer_diameter": "design.max_outer_diameter",
    "max_width": "design.max_width",
    "width": "design.max_width",
    "d_mean": "design.d_mean",
    "hb_ratio": "design.hb_ratio",
    "hb_min": "design.hb_min",
    "hb_max": "design.hb_max",
    "geometry": "design.geometry",
    "objective": "design.objective",
    "design.material": "material",
    "design.shaft": "shaft",
    "materials": "material",
    "shafts": "shaft",
    "design.materials": "material",
    "design.shafts": "shaft",
}


def _known_fields(scene):
    names = list(FIELDS)
    names.append(f"shaft.<name>.speed_ratio (shafts: {', '.join(s.name for s in scene.shafts)})")
    names.append(f"material.<name>.density|max_rim_speed|cost (materials: {', '.join(scene.material_library())})")
    return names


def resolve_field(scene: Scene, path: str, where: str) -> tuple[str, SweepField]:
    """Canonical field name and its description, or SceneError."""
    key = _ALIASES.get(path.strip(), path.strip())
    if key in FIELDS:
        return key, FIELDS[key]
    parts = key.split(".")
    if len(parts) == 3 and parts[0] == "shaft":
        names = [s.name for s in scene.shafts]
        if parts[1] not in names:
            raise SceneError(
                field_path(where, path),
                f"unknown shaft {parts[1]!r}{_hint(parts[1], names)} (shafts: {', '.join(names)})",
            )
        if parts[2] not in _SHAFT_FIELDS:
            raise SceneError(
                field_path(where, path), f"a shaft's field is {', '.join(_SHAFT_FIELDS)}, not {parts[2]!r}"
            )
        carried = _carried(scene, parts[1])
        if carried:
            raise SceneError(
                field_path(where, path),
                f"shaft {parts[1]!r} carries {carried}: the machine's physics would change with the "
                "ratio, where a sweep's shaft ratio moves only the flywheel; vary the ratio of a shaft that carries "
                "none of these, or make a scene per ratio"
                + (" (or compare ratios by [drive] ratios)" if "motor" in carried else ""),
            )
        return key, _SHAFT_FIELDS[parts[2]]
    if len(parts) == 3 and parts[0] == "material":
        library = scene.material_library()
        if parts[1] not in library:
            raise SceneError(
                field_path(where, path),
                f"unknown material {parts[1]!r}{_hint(parts[1], library)} (known: {', '.join(library)})",
            )
        if parts[2] not in _MATERIAL_FIELDS:
            raise SceneError(
                field_path(where, path), f"a material's field is one of {', '.join(_MATERIAL_FIELDS)}, not {parts[2]!r}"
            )
        return key, _MATERIAL_FIELDS[parts[2]]
    candidates = list(FIELDS) + list(_ALIASES)
    raise SceneError(
        field_path(where, path),
        f"unknown sweep field{_hint(key, candidates)}; allowed: {'; '.join(_known_fields(scene))}",
    )


def _carried(scene: Scene, name: str) -> str:
    """What shaft ``name`` carries whose reduction to the reference shaft its speed ratio enters, in words ("" for
    nothing): inertia (J i²), the motor (M(i ω) i η). The scene holds them reduced at the ratio it gives, so a
    sweep that moved the ratio would analyse the old machine (a motor shaft's ratio swept on motor-press reported
    designs its scene does not give). (A wheel that exists is no study's: :func:`flyopt.design.design_inputs`.)"""
    from flyopt.cycle.torque import MotorTorque

    shaft = next(s for s in scene.shafts if s.name == name)
    found = ["inertia (J i²)"] if getattr(shaft, "inertia", 0.0) else []
    if any(isinstance(c, MotorTorque) and c.shaft == name for c in (scene.driving, scene.resisting)):
        found.append("the motor (its torque M(i ω) i η)")
    return " and ".join(found)


def _hint(name, known):
    close = closest(name, known)
    return f" (did you mean {close!r}?)" if close else ""


def field_path(where: str, path: str) -> str:
    """The field ``path`` as messages name it under ``where`` (``--vary delta``, ``sweep.vary.delta``)."""
    if not where:
        return path
    return f"{where} {path}" if where.startswith("--") else f"{where}.{path}"


# --------------------------------------------------------------------------
# The other options of a sweep: one rule each, for [sweep] tables, the
# command line and the Python API alike
# --------------------------------------------------------------------------

#: How the points are designed (see :func:`flyopt.studies.evaluate.evaluate_points`).
METHODS = ("auto", "closed_form", "ipopt")


class TooManyPoints(SceneError):
    """A range whose values would make a grid of more points than allowed (``points``), refused before they are made."""

    def __init__(self, points: int, field: str, message: str, source: str | None = None) -> None:
        self.points = points
        super().__init__(field, message, source)


def option_label(where: str, key: str) -> str:
    """The name of option ``key`` as the user wrote it.

    Parameters
    ----------
    where : str
        Where the options come from: ``"--"`` or ``"--vary"`` (the command
        line), ``"sweep"`` or ``"sweep.vary"`` (a ``[sweep]`` table, maybe
        after a file name), ``""`` (Python keywords).
    key : str
        The keyword of :func:`flyopt.studies.sweep.sweep`, e.g. ``chunk_size``.

    Returns
    -------
    str
        ``--chunk-size``, ``sweep.chunk_size`` or ``chunk_size``.
    """
    base = where[: -len("vary")] if where.endswith("vary") else where
    if base.startswith("--"):
        return "--" + key.replace("_", "-")
    base = base.rstrip(".")
    return f"{base}.{key}" if base else key


def whole_number(value: object, label: str, minimum: int, maximum: int | None = None) -> int:
    """``value`` as an int, or SceneError naming ``label`` and the values allowed."""
    if (
        isinstance(value, (int, np.integer))
        and not isinstance(value, bool)
        and value >= minimum
        and (maximum is None or value <= maximum)
    ):
        return int(value)
    allowed = f">= {minimum}" if maximum is None else f"from {minimum} to {maximum}"
    raise SceneError(label, f"must be a whole number {allowed}, got {clip(repr(value))}")


#: The least value of each whole-number option of a sweep (0 chunks: a sweep that does nothing); a resumed
#: sweep's manifest is held to them too (flyopt.studies.sweep).
OPTION_MINIMUMS = {"samples": 1, "seed": 0, "chunk_size": 1, "max_chunks": 1}
#: The largest value of a whole-number option where there is one: a seed is written in the sweep's file as a
#: 64-bit signed integer (its ``seed`` column and manifest).
OPTION_MAXIMUMS = {"seed": 2**63 - 1}
#: Most worker processes a sweep starts on this machine: each holds numpy, pandas and CasADi (some 150 MB), and
#: ``--workers 100000 --chunk-size 1`` would have started one for each chunk.
MAX_WORKERS = 256


def check_options(options: Mapping[str, Any], where: str = "sweep") -> None:
    """Check the options of a sweep other than ``vary`` (their values, not the scene's).

    Parameters
    ----------
    options : mapping
        Keywords of :func:`flyopt.studies.sweep.sweep`: ``samples``, ``seed``,
        ``output``, ``chunk_size``, ``max_chunks``, ``method``, ``workers``,
        ``resume``, ``keep_parts``; absent or None means the default.
    where : str
        Where they come from, for messages (see :func:`option_label`).

    Raises
    ------
    SceneError
        The first bad option, named as the user wrote it, with what is allowed.
    """
    from flyopt.outputs.results import output_format

    for key, lowest in OPTION_MINIMUMS.items():
        if options.get(key) is not None:
            whole_number(options[key], option_label(where, key), lowest, OPTION_MAXIMUMS.get(key))
    method = options.get("method")
    if method is not None and method not in METHODS:
        raise SceneError(option_label(where, "method"), f"{method!r} is not known (allowed: {', '.join(METHODS)})")
    workers = options.get("workers")
    if workers is not None and workers != "auto":
        try:
            whole_number(workers, option_label(where, "workers"), 1, MAX_WORKERS)
        except SceneError as err:
            raise SceneError(
                err.field, f"must be 'auto' or a whole number from 1 to {MAX_WORKERS}, got {clip(repr(workers))}"
            ) from None
    output = options.get("output")
    if output is not None:
        if not isinstance(output, (str, Path)):
            raise SceneError(option_label(where, "output"), f"must be a file name (.csv or .parquet), got {output!r}")
        output_format(output, option_label(where, "output"))
    if options.get("resume") and output is None:
        raise SceneError(option_label(where, "resume"), "needs an output file (its parts hold the finished chunks)")
    if options.get("keep_parts") and output is None:  # there would be no parts to keep
        raise SceneError(option_label(where, "keep_parts"), "needs an output file (its parts are OUTPUT.parts/)")


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
    unit : str or None
        The unit the values were written in (``"rpm"`` of ``300,600,1200rpm``), where they share one;
        None for plain (SI) numbers, names, or values written in different units. Recorded in a
        sweep file's metadata, so that :func:`flyopt.read_results` gives the column back in it.
    """

    field: str
    values: tuple[float | str, ...]
    kind: str = "list"
    low: float | None = None
    high: float | None = None
    log: bool = False
    unit: str | None = None

    def ends(self) -> tuple[float, float]:
        """(low, high) of a range axis; ValueError for a list."""
        if self.low is None or self.high is None:
            raise ValueError(f"{self.field} is a list of values, not a range")
        return self.low, self.high


def split_unit(item: str) -> tuple[str, str]:
    """'1200rpm' -> ('1200', 'rpm'); '1/20' -> ('1/20', '')."""
    m = _NUMBER.match(item)
    if m:
        rest = item[m.end() :].strip()
        if rest and (rest[0].isalpha() or rest[0] in "°%"):
            return m.group().strip(), rest
    return item.strip(), ""


def _given_unit(units: Iterable[str]) -> str | None:
    """The one unit a field's values were written in ('' for a plain number); None if none or several."""
    distinct = set(units)
    return distinct.pop() if len(distinct) == 1 and "" not in distinct else None


def _number(text, unit, spec, label):
    raw = f"{text} {unit}".strip() if unit else text
    try:
        value = quantity(raw, spec.dimension, label)
        if unit:  # a unit alone: "60rpm*2" was 120 rpm, and "rpm*2" the file's unit, which it then refused to read
            unit_value(unit, spec.dimension, label)
        return value
    except SceneError as err:
        raise SceneError(label, err.message) from None


def _check_value(value, spec, label, text):
    if spec.optional and value is None:
        return
    low_ok = value >= spec.minimum if spec.inclusive else value > spec.minimum
    high_ok = spec.maximum is None or value < spec.maximum
    if not (low_ok and high_ok):
        raise SceneError(label, f"{shorten(text)} is out of range: {spec.what}")
    if spec.bounds is not None:
        check_magnitude(value, label, text, *spec.bounds)
    else:  # no range of its own: its dimension's sizes, as the loader holds every field (flyopt.units.MAGNITUDES)
        check_scale(value, spec.dimension, label, text)


def _parse_text(scene, name, spec, text, label, sampled, cap=None):
    text = text.strip()
    if not text:
        raise SceneError(label, "no values given: write a list a,b,c or a range a:b:n")
    if spec.kind == "name":
        if ":" in text:
            raise SceneError(label, f"{text!r}: a range needs numbers; give names as a list a,b,c")
        items = [t.strip() for t in text.split(",")]
        return Axis(name, tuple(_check_name(scene, name, item, label) for item in items))
    if ":" in text:
        return _parse_range(name, spec, text, label, sampled, cap)
    items = [t.strip() for t in text.split(",")]
    if any(not t for t in items):
        raise SceneError(label, f"{text!r}: an empty value in the list")
    trailing = split_unit(items[-1])[1]
    values, units = [], []
    for item in items:
        if spec.optional and item.lower() == "none":
            values.append(math.nan)
            continue
        number, unit = split_unit(item)
        value = _number(number, unit or trailing, spec, label)
        _check_value(value, spec, label, item)
        values.append(value)
        units.append(unit or trailing)
    return Axis(name, tuple(values), unit=_given_unit(units))


def _parse_range(name, spec, text, label, sampled, cap=None):
    parts = text.split(":")
    if len(parts) not in (2, 3):
        raise SceneError(
            label, f"{shorten(text)}: a range is a:b:n (linear) or a:b:logn (log), with an optional unit at the end"
        )
    if len(parts) == 3:
        m = _COUNT.match(parts[2])
        if m is None:  # every part of the pattern is optional: it matches any text
            raise SceneError(label, f"{shorten(text)}: the third part of a range is a count")
        log, count, trailing = bool(m.group(1)), m.group(2), m.group(3)
        if count is not None and re.match(r"[.,\d]|[eE][+-]?\d", trailing):  # 3.2 is not 3 points in a unit ".2"
            raise SceneError(
                label,
                f"{shorten(text)}: the count of a range is a whole number of values, got {shorten(parts[2].strip())}",
            )
        if count is None and not log:
            raise SceneError(
                label,
                f"{text!r}: the third part must be a count n or logn (e.g. 0.01:0.1:log20), then an optional unit",
            )
    else:
        log, count = False, None
        trailing = split_unit(parts[1])[1]
    if count is None and not sampled:
        raise SceneError(label, f"{text!r}: a grid range needs a count: a:b:n or a:b:logn")
    ends, units = [], []
    for part in parts[:2]:
        number, unit = split_unit(part)
        if not number:
            raise SceneError(label, f"{text!r}: a range end is missing")
        value = _number(number, unit or trailing, spec, label)
        _check_value(value, spec, label, part.strip())
        ends.append(value)
        units.append(unit or trailing)
    low, high = ends
    if log and (low <= 0 or high <= 0):
        raise SceneError(label, f"{text!r}: a log range needs positive ends")
    n = 1 if count is None else int(count)
    if n < 1:
        raise SceneError(label, f"{text!r}: the count must be at least 1")
    if cap is not None and n * cap[0] > cap[1]:  # (points of the fields before, most points)
        raise TooManyPoints(
            n * cap[0],
            label,
            f"{text!r}: {n} values make a grid of {n * cap[0]} points, "
            f"more than the {cap[1]} a sweep may have; use fewer values or "
            f"Latin hypercube samples",
        )
    if log:
        values = np.geomspace(low, high, n) if n > 1 else np.array([low])
    else:
        values = np.linspace(low, high, n) if n > 1 else np.array([low])
    if n > 1:
        values[0], values[-1] = low, high
    return Axis(name, tuple(float(v) for v in values), "range", low, high, log, _given_unit(units))


def _check_name(scene, name, item, label):
    if name == "design.geometry":
        from flyopt.design.geometry import GEOMETRIES

        known = list(GEOMETRIES)
    elif name == "design.objective":
        from flyopt.design.spec import OBJECTIVES

        known = list(OBJECTIVES)
    elif name == "material":
        known = list(scene.material_library())
    else:
        known = [s.name for s in scene.shafts]
    if item not in known:
        raise SceneError(
            label, f"unknown {name.split('.')[-1]} {item!r}{_hint(item, known)} (allowed: {', '.join(known)})"
        )
    return item


def _parse_value(scene, name, spec, value, label, sampled, cap=None):
    """A value from TOML or Python: a string (the grammar), a number, or a list."""
    if isinstance(value, str):
        return _parse_text(scene, name, spec, value, label, sampled, cap)
    items = value if isinstance(value, (list, tuple, np.ndarray)) else [value]
    if len(items) == 0:
        raise SceneError(label, "no values given")
    values = []
    units: list[str] = []
    for item in items:
        if isinstance(item, str):
            axis = _parse_text(scene, name, spec, item, label, False)
            values.extend(axis.values)
            units.append(axis.unit or "")
        elif spec.kind == "name":
            raise SceneError(label, f"{item!r}: expected a name ({spec.what})")
        elif item is None and spec.optional:
            values.append(math.nan)
        else:
            number = _number(item, "", spec, label) if not isinstance(item, str) else None
            _check_value(number, spec, label, str(item))
            values.append(number)
            units.append("")
    return Axis(name, tuple(values), unit=None if spec.kind == "name" else _given_unit(units))


def _text_items(texts, where):
    """``["FIELD=VALUES", ...]`` as (field, values) pairs."""
    if isinstance(texts, str):
        texts = [texts]
    items = []
    for text in texts:
        if not isinstance(text, str) or "=" not in text:
            raise SceneError(
                where, f"{text!r}: expected FIELD=VALUES, e.g. delta=0.01:0.1:log20 or speed=300,600,1200rpm"
            )
        path, values = text.split("=", 1)
        if not path.strip():
            raise SceneError(where, "a field name is missing before '='")
        items.append((path.strip(), values))
    return items


def _check_once(scene, items, where):
    """Refuse a field given twice, under its name or an alias (the first would be lost)."""
    seen: dict[str, str] = {}
    for path, _ in items:
        name = resolve_field(scene, path, where)[0]
        if name in seen:
            raise SceneError(
                field_path(where, path),
                f"is varied twice (also as {seen[name]!r}); give each field once, with all its values",
            )
        seen[name] = path


def vary_from_texts(scene: Scene, texts: Iterable[str], where: str = "--vary") -> dict[str, str]:
    """The fields to vary, from ``FIELD=VALUES`` texts (e.g. repeated ``--vary`` options).

    Parameters
    ----------
    scene : Scene
        Supplies the shafts and materials that field names may refer to.
    texts : iterable of str
        ``["delta=0.01:0.1:log20", "speed=300,600,1200rpm"]``.
    where : str
        Where the texts come from, for messages.

    Returns
    -------
    dict
        Field as written to its values text, in the order given (the
        ``vary`` mapping of :func:`parse_vary`).

    Raises
    ------
    SceneError
        A text without ``=``, an unknown field, or a field given twice (also
        under an alias, e.g. ``envelope`` and ``design.max_outer_diameter``).
    """
    items = _text_items(texts, where)
    _check_once(scene, items, where)
    return dict(items)


def parse_vary(
    scene: Scene,
    vary: Mapping[str, Any] | Iterable[str],
    *,
    where: str = "--vary",
    samples: int | None = None,
    max_points: int | None = None,
) -> list[Axis]:
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
    max_points : int, optional
        Most points the grid may have: a range that would make more is
        refused before its values are made.

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
        if any(not str(path).strip() for path, _ in items):
            raise SceneError(where, "a field name is missing")
    else:
        items = _text_items(vary, where)
    _check_once(scene, items, where)
    axes, points = [], 1
    for path, values in items:
        name, spec = resolve_field(scene, path, where)
        cap = None if max_points is None else (points, max_points)
        axes.append(_parse_value(scene, name, spec, values, field_path(where, path), samples is not None, cap))
        if samples is None:
            points *= len(axes[-1].values)
    names = {a.field for a in axes}
    if "design.hb_ratio" in names and names & {"design.hb_min", "design.hb_max"}:
        raise SceneError(
            field_path(where, "design.hb_ratio"), "vary either design.hb_ratio or design.hb_min/design.hb_max, not both"
        )
    return axes


# --------------------------------------------------------------------------
# [sweep] tables in scene files
# --------------------------------------------------------------------------

_SWEEP_KEYS = {"vary", "samples", "seed", "output", "chunk_size", "method", "workers", "description"}


def _flatten(table, prefix=""):
    out = {}
    for key, value in table.items():
        name = f"{prefix}.{key}" if prefix else key
        if isinstance(value, dict):
            out.update(_flatten(value, name))
        else:
            out[name] = value
    return out


def load_sweep(path: str | os.PathLike[str]) -> tuple[Scene, dict[str, Any]]:
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

    A relative ``output`` is relative to the scene file's folder: ``options["output"]``
    is that path (the folder joined with it; ``-o`` on the command line wins).

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
        Bad file, scene, ``[sweep]`` key or option value (named, with the
        file). The fields and values of ``vary`` and the points they make are
        checked by :func:`flyopt.studies.sweep.check_sweep`, which also runs
        these checks (``flyopt check`` and ``flyopt sweep`` share it).
    """
    from flyopt.io.scene import from_dict

    path = Path(path)
    data = read_toml(path)  # the reading of flyopt.io.scene.load: regular files within the caps only
    table = data.pop("sweep", {})
    try:
        scene = from_dict(data, source=str(path))
        if not isinstance(table, dict):
            raise SceneError("sweep", "must be a table")
        unknown = sorted(set(table) - _SWEEP_KEYS)
        if unknown:
            raise SceneError(
                f"sweep.{unknown[0]}",
                f"unknown key{_hint(unknown[0], _SWEEP_KEYS)} (allowed here: {', '.join(sorted(_SWEEP_KEYS))})",
            )
        options = {k: v for k, v in table.items() if k != "description"}
        check_options(options, "sweep")
        if options.get("output") is not None:  # written where the scene's author says: inside its folder
            raw = options["output"]
            from flyopt.outputs.files import check_file_name

            check_file_name(str(raw), "sweep.output")  # "x.csv/" was written as x.csv
            options["output"] = str(inside_scene(raw, "sweep.output", path.parent, "output file"))
            # and so are the files the sweep writes beside it: a CSV's sidecar, the folder of its finished chunks
            from flyopt.outputs.results import parts_folder, table_files

            for beside in (*table_files(raw)[1:], parts_folder(raw)):
                inside_scene(str(beside), "sweep.output", path.parent, "output file")
        vary = options.pop("vary", {})
        if not isinstance(vary, dict):
            raise SceneError("sweep.vary", "must be a table of FIELD = VALUES")
        options["vary"] = _flatten(vary)
    except SceneError as err:
        raise err.with_source(str(path)) from None
    return scene, options
