"""Castability: the sections a foundry can pour (or a shop can machine), per process.

The rules are data (``flyopt/data/castability.toml``, each number with its
source): per process the thinnest wall by the size of the piece, and the
largest ratio of two adjoining sections. This module reads them, says which
process makes a material (the scene may name another, or override the
numbers), and writes each rule as arithmetic on a wheel's dimensions that
works on floats and on CasADi symbols alike, so that the whole-wheel NLP
(:func:`flyopt.design.wheel_nlp.formulate`), the check of a rounded wheel
(:mod:`flyopt.design.rounding`, through the same rows) and the report's record
(:func:`record`) use one arithmetic::

    every wall w of a part >= min_wall(D)          (piecewise linear in the outer diameter D)
    1/r <= t_eq(a) / t_eq(b) <= r                  at each junction (a, b) of the wheel

with t_eq = 2 V/A the equivalent thickness (twice the casting modulus):
t for a plate (the web), H B / (H + B) for a rectangular section (the rim,
the hub's wall by its length), 2 A / P for the arms' ellipse.

The same file holds what the drawing and the FE check need of the process
(:func:`finishing`): the fillet at a re-entrant junction (:func:`fillet_radius`,
one rule for the FE's section and the drawing's), the draft of the cast
faces, the chamfers of the machined edges (:func:`chamfer_size`) and the
machined faces' surface texture.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, section 23.
.. [2] N. Chvorinov, Giesserei 27 (1940) 177-186 (freezing time ~ (V/A)^2).
"""

from __future__ import annotations

import fnmatch
import functools
import math
from collections.abc import Callable, Mapping
from importlib import resources
from typing import Any, NamedTuple

from flyopt._toml import tomllib
from flyopt.design.wheel import has_hub
from flyopt.names import Geometry

__all__ = [
    "NONE",
    "Rules",
    "Overrides",
    "Process",
    "processes",
    "process_of",
    "rules_for",
    "min_wall_at",
    "wall_asked",
    "walls",
    "sections",
    "junctions",
    "record",
    "thinnest_wall",
    "too_thin",
    "too_thin_to_cast",
    "who_asks",
    "ARM_THICKNESS",
    "Finishing",
    "finishing",
    "process_of_design",
    "fillet_radius",
    "chamfer_size",
]

_DATA_FILE = "castability.toml"

#: The scene's word for "no castability rules" ([design] process = "none").
NONE = "none"

#: Bounds on a scene's overrides: a wall [m] and a section ratio [-].
WALL_RANGE = (1e-5, 0.5)
WALL_WHY = f"a wall from {WALL_RANGE[0] * 1e3:g} mm to {WALL_RANGE[1] * 1e3:g} mm"
RATIO_RANGE = (1.0, 10.0)


class Rules(NamedTuple):
    """The castability rules one wheel is designed to (hashable: part of the NLP's structure).

    ``min_wall``: rows (size D [m], wall [m]) in increasing size (empty: no minimum); ``section_ratio``: the thicker of
    two adjoining sections at most this times the thinner [-], ``math.inf`` for no such rule.
    """

    process: str
    min_wall: tuple[tuple[float, float], ...]
    section_ratio: float = math.inf


class Overrides(NamedTuple):
    """A scene's castability: the process for every material, and numbers replacing the process's."""

    process: str | None = None
    min_wall: tuple[tuple[float, float], ...] | None = None
    section_ratio: float | None = None


class Process(NamedTuple):
    """A process of the data file: its rules, what it is, and where its numbers come from."""

    rules: Rules
    description: str
    source: str


def _table(rows: Any, where: str) -> tuple[tuple[float, float], ...]:
    """A min_wall table checked: [[size, wall], ...], sizes increasing, walls positive and not decreasing."""
    if not isinstance(rows, list) or not rows:
        raise ValueError(f"{where}: min_wall must be a list of [size, wall] rows")
    out = []
    for row in rows:
        if (
            not isinstance(row, list)
            or len(row) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in row)
        ):
            raise ValueError(f"{where}: a min_wall row must be [size, wall] in metres, got {row!r}")
        out.append((float(row[0]), float(row[1])))
    for (s0, w0), (s1, w1) in zip(out, out[1:]):
        if s1 <= s0 or w1 < w0:
            raise ValueError(f"{where}: min_wall rows must have increasing sizes and walls that do not decrease")
    if any(s < 0 or w <= 0 for s, w in out):
        raise ValueError(f"{where}: min_wall sizes must be >= 0 and walls > 0")
    return tuple(out)


@functools.lru_cache(maxsize=1)
def _load() -> tuple[dict[str, Process], dict[str, str], tuple[tuple[str, str], ...]]:
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    origin = f"flyopt/data/{_DATA_FILE}"
    found = {}
    for name, table in data.get("process", {}).items():
        where = f"{origin}: process {name!r}"
        source = table.get("source", "")
        if not isinstance(source, str) or not source.strip():
            raise ValueError(f"{where} cites no source")
        ratio = table.get("section_ratio", math.inf)
        if not isinstance(ratio, (int, float)) or not ratio >= 1.0:
            raise ValueError(f"{where}: section_ratio must be a number >= 1")
        rules = Rules(name, _table(table.get("min_wall"), where), float(ratio))
        found[name] = Process(rules, str(table.get("description", "")), source)
    materials = dict(data.get("materials", {}))
    patterns = tuple((p["match"], p["process"]) for p in data.get("pattern", []))
    for process in (*materials.values(), *(p for _, p in patterns)):
        if process not in found:
            raise ValueError(f"{origin}: unknown process {process!r}")
    return found, materials, patterns


def processes() -> dict[str, Process]:
    """The processes of the data file, by name."""
    return dict(_load()[0])


def process_of(material: str) -> str | None:
    """The process that makes a material by default (by its key), or None where the data file names none."""
    _, materials, patterns = _load()
    if material in materials:
        return materials[material]
    for pattern, process in patterns:
        if fnmatch.fnmatch(material.lower(), pattern.lower()):
            return process
    return None


def rules_for(material: str, overrides: Overrides | None = None) -> Rules | None:
    """The rules a wheel of a material is designed to: its process's (or the scene's), the scene's numbers
    over them; None where no process applies (none named, or ``process = "none"``).

    Remembered by its arguments (a material's key and the scene's overrides, their rows made tuples; the rules
    are an immutable tuple): a ranking asks it for every candidate, a sweep for every point."""
    if overrides is not None and overrides.min_wall is not None:
        overrides = overrides._replace(min_wall=tuple((float(s), float(w)) for s, w in overrides.min_wall))
    return _rules_for(material, overrides)


@functools.lru_cache(maxsize=256)
def _rules_for(material: str, overrides: Overrides | None) -> Rules | None:
    over = overrides or Overrides()
    name = over.process or process_of(material)
    if name == NONE:
        return None
    if name is None:
        if over.min_wall is None and over.section_ratio is None:
            return None
        base = Rules("scene", over.min_wall or (), math.inf)  # the scene's numbers alone
    else:
        base = processes()[name].rules
    return Rules(
        base.process if name is not None else "scene",
        over.min_wall if over.min_wall is not None else base.min_wall,
        over.section_ratio if over.section_ratio is not None else base.section_ratio,
    )


def _fmin(a: Any, b: Any) -> Any:
    return min(a, b)


def _fmax(a: Any, b: Any) -> Any:
    return max(a, b)


def min_wall_at(
    rules: Rules, size: Any, fmin: Callable[[Any, Any], Any] = _fmin, fmax: Callable[[Any, Any], Any] = _fmax
) -> Any:
    """The process's thinnest wall at a size [m]: linear between the table's rows, the end row's beyond them.

    ``size`` a float, or a CasADi symbol with ``fmin``/``fmax`` = ``casadi.fmin``/``casadi.fmax``.
    """
    rows = rules.min_wall
    if not rows:
        return 0.0
    wall = rows[0][1]
    for (s0, w0), (s1, w1) in zip(rows, rows[1:]):
        wall = wall + (w1 - w0) / (s1 - s0) * (fmin(fmax(size, s0), s1) - s0)
    return wall


def wall_asked(rules: Rules | None, floor: float, size: float) -> float:
    """The thinnest wall a wheel of outer diameter ``size`` [m] may have [m]: the larger of ``floor`` (the
    scene's or the material's ``min_wall``) and the process's table at that size (``rules`` None: ``floor``
    alone). The one rule of the wall used: the designed wheel's bound (``wheel_design.min_wall_at``), its
    record (:func:`record`) and a bare wheel's check (:func:`too_thin`)."""
    return max(floor, float(min_wall_at(rules, size))) if rules is not None else floor


def _rect(a: Any, b: Any) -> Any:
    """2 V/A of a long bar of section a x b cooled all round [m]: a b / (a + b)."""
    return a * b / (a + b)


def _arm_thickness() -> float:
    """2 A / P of the arms' elliptical section per unit major axis [-] (axes 1 and wheel.ARM_MINOR_RATIO;
    Ramanujan's perimeter)."""
    from flyopt.design.wheel import ARM_MINOR_RATIO

    a, b = 0.5, 0.5 * ARM_MINOR_RATIO  # semi-axes
    area = math.pi * a * b
    perimeter = math.pi * (3.0 * (a + b) - math.sqrt((3.0 * a + b) * (a + 3.0 * b)))
    return 2.0 * area / perimeter


#: The arms' equivalent thickness per metre of major axis [-].
ARM_THICKNESS = _arm_thickness()


def walls(geometry: str, dims: Any) -> tuple[tuple[str, Any], ...]:
    """(part, wall) of every section the minimum wall bounds [m]: the rim's H and B, the web, the arms'
    minor axis, the hub's radial wall, a disc's width (floats or symbols)."""
    from flyopt.design.wheel import ARM_MINOR_RATIO

    if geometry == Geometry.DISC:
        disc: tuple[tuple[str, Any], ...] = (("disc", dims.b),)
        return disc + ((("hub", (dims.d_hub - dims.bore) / 2.0),) if has_hub(dims) else ())
    out: list[tuple[str, Any]] = [("rim", dims.h), ("rim", dims.b)]
    if geometry == Geometry.RIM_WEB:
        out.append(("web", dims.t_web))
    elif geometry == Geometry.RIM_ARMS:
        out.append(("arms", ARM_MINOR_RATIO * dims.arm_major))
    if has_hub(dims):
        out.append(("hub", (dims.d_hub - dims.bore) / 2.0))
    return tuple(out)


def sections(geometry: str, dims: Any) -> dict[str, Any]:
    """Each part's equivalent thickness 2 V/A [m] (twice its casting modulus): the web's t, the rim's
    H B/(H + B), the hub's wall by its length, the arms' 2 A/P (floats or symbols)."""
    out = {"disc": dims.b} if geometry == Geometry.DISC else {"rim": _rect(dims.h, dims.b)}
    if geometry == Geometry.RIM_WEB:
        out["web"] = dims.t_web
    elif geometry == Geometry.RIM_ARMS:
        out["arms"] = ARM_THICKNESS * dims.arm_major
    if has_hub(dims):
        out["hub"] = _rect((dims.d_hub - dims.bore) / 2.0, dims.l_hub)
    return out


def junctions(geometry: str, hub: bool) -> tuple[tuple[str, str], ...]:
    """The adjoining parts of a wheel, rim side first: rim-web and web-hub, rim-arms and arms-hub, or a
    bored disc's disc-hub."""
    if geometry == Geometry.DISC:
        return (("disc", "hub"),) if hub else ()
    if geometry == Geometry.RIM_WEB:
        middle = "web"
    elif geometry == Geometry.RIM_ARMS:
        middle = "arms"
    else:
        return ()
    return (("rim", middle), (middle, "hub")) if hub else (("rim", middle),)


def record(rules: Rules | None, floor: float, geometry: str, dims: Any) -> dict[str, Any] | None:
    """What castability asks of a designed wheel and what it has, for the report and the JSON.

    ``floor``: the scene's (or the material's) min_wall [m]. Returns ``process``, ``casting_size`` (D [m]),
    ``process_min_wall`` (the table at D [m], 0 where the rules give none), ``min_wall`` (the larger of it
    and ``floor``: the wall used [m]), ``thinnest_wall`` [m] and ``thinnest_part``, ``section_ratio``
    (None: no rule) and ``junctions``: each junction's ``junction`` ("rim-web") and ``ratio``, the
    thicker over the thinner equivalent thickness [-]; None without rules.
    """
    if rules is None:
        return None
    size = float(dims.d_outer)
    process_wall = float(min_wall_at(rules, size))
    part, thinnest = thinnest_wall(geometry, dims)
    t_eq = {p: float(v) for p, v in sections(geometry, dims).items()}
    return {
        "process": rules.process,
        "casting_size": size,
        "process_min_wall": process_wall,
        "min_wall": wall_asked(rules, floor, size),
        "thinnest_wall": thinnest,
        "thinnest_part": part,
        "section_ratio": rules.section_ratio if math.isfinite(rules.section_ratio) else None,
        "junctions": [
            {"junction": f"{a}-{b}", "ratio": max(t_eq[a], t_eq[b]) / min(t_eq[a], t_eq[b])}
            for a, b in junctions(geometry, "hub" in t_eq)
        ],
    }


def thinnest_wall(geometry: str, dims: Any) -> tuple[str, float]:
    """(part, wall [m]) of a wheel's thinnest section among :func:`walls` (the rim's H or B, a disc's width,
    the web, the arms' minor axis, the hub's wall)."""
    (part, first), *others = walls(geometry, dims)
    thinnest = float(first)
    for name, wall in others:  # the first of equal walls, as min() gives it
        if float(wall) < thinnest:
            part, thinnest = name, float(wall)
    return part, thinnest


@functools.lru_cache(maxsize=64)
def _thickest(rules: Rules | None) -> float:
    """The process's largest minimum wall at any size [m] (0: no rules, or no table)."""
    return max((wall for _, wall in rules.min_wall), default=0.0) if rules is not None else 0.0


def too_thin(rules: Rules | None, floor: float, geometry: str, dims: Any) -> dict[str, Any] | None:
    """A wheel's thinnest section where it is thinner than the wall asked of it; None where it is not.

    For a wheel not designed to the rules (a textbook bare rim or disc, whose books size the section by its
    inertia and rim speed alone; a whole wheel keeps them as rows of its NLP). The wall asked is the one
    :func:`record` names the wall used: the larger of the process's minimum at the wheel's outer diameter
    (``rules``; None: no process) and ``floor``, the scene's (or the material's) ``min_wall`` [m].

    Returns ``process`` (None: none), ``thinnest_part``, ``thinnest_wall`` [m], ``min_wall`` (the wall
    asked [m]), ``process_min_wall`` (the process's at the size [m], 0: none), ``casting_size`` (the outer
    diameter [m]), ``set_by`` ("process" or "min_wall": which one asks the most) and ``cast`` (whether the
    process casts the piece: it has a draft, :func:`finishing`), the fields of the JSON's ``thin_wall``.
    """
    most = max(floor, _thickest(rules))  # the most asked at any size
    if most <= 0.0:
        return None
    part, thinnest = thinnest_wall(geometry, dims)
    if thinnest >= most:
        return None
    size = float(dims.d_outer)
    process_wall = float(min_wall_at(rules, size)) if rules is not None else 0.0
    asked = wall_asked(rules, floor, size)
    if not thinnest < asked:
        return None
    process = rules.process if rules is not None else None
    return {
        "process": process,
        "thinnest_part": part,
        "thinnest_wall": thinnest,
        "min_wall": asked,
        "process_min_wall": process_wall,
        "casting_size": size,
        "set_by": "process" if process_wall >= floor else "min_wall",
        "cast": process is not None and finishing(process).draft is not None,
    }


def who_asks(thin: Mapping[str, Any]) -> str:
    """Who asks the wall a :func:`too_thin` wheel falls short of, in words ("the cast steel process makes",
    "asked of it (design.min_wall, ...)"): the one phrase of its note and its answer, which add the size."""
    if thin["set_by"] == "min_wall":
        return "asked of it (design.min_wall, or its material's min_wall)"
    if thin["process"] == "scene":
        return "the scene's castability asks (design.castability.min_wall)"
    return f"the {thin['process'].replace('_', ' ')} process makes"


def too_thin_to_cast(thin: Mapping[str, Any]) -> bool:
    """Whether a :func:`too_thin` wheel is too thin to cast (its process casts the piece and asks the wall), not
    only to make (a machined piece, a wall asked by design.min_wall)."""
    return bool(thin["cast"]) and thin["set_by"] == "process"


# ------------------------------------------------------------------ finishing: fillets, draft, chamfers, texture


class Finishing(NamedTuple):
    """What the drawing and the FE check take of a process (flyopt/data/castability.toml).

    ``process``: the process's name, None where none is known; ``fillet_ratio``: the fillet at a
    re-entrant junction over the thinner part's thickness [-]; ``min_fillet``: the process's smallest
    fillet [m] (0: none known); ``draft``: the draft of the unmachined faces parallel to the axis [deg],
    None where the piece is not cast (or the process is not known); ``machined_ra``, ``bore_ra``: the
    surface texture Ra of the machined faces and of the bore [m]; ``source``: where the numbers come from.
    """

    process: str | None
    fillet_ratio: float
    min_fillet: float
    draft: float | None
    machined_ra: float
    bore_ra: float
    source: str


@functools.lru_cache(maxsize=1)
def _finishing_data() -> dict[str, Any]:
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    origin = f"flyopt/data/{_DATA_FILE}"
    out: dict[str, Any] = {}
    for table, keys in (
        ("fillet", ("ratio",)),
        ("chamfer", ("table", "face_fraction")),
        ("finish", ("machined_ra", "bore_ra")),
    ):
        if (
            table not in data
            or any(k not in data[table] for k in keys)
            or not str(data[table].get("source", "")).strip()
        ):
            raise ValueError(f"{origin}: [{table}] needs {', '.join(keys)} and a source")
        out[table] = data[table]
    ratio = out["fillet"]["ratio"]
    if not isinstance(ratio, (int, float)) or not 0.0 < ratio <= 2.0:
        raise ValueError(f"{origin}: [fillet] ratio must be a number in (0, 2]")
    rows = out["chamfer"]["table"]
    if any(d1 <= d0 or c1 < c0 for (d0, c0), (d1, c1) in zip(rows, rows[1:])) or any(c <= 0 for _, c in rows):
        raise ValueError(f"{origin}: [chamfer] table rows must be [diameter, chamfer] with both increasing")
    out["process"] = {}
    for name, table in data.get("process", {}).items():
        where = f"{origin}: process {name!r}"
        if ("min_fillet" in table or "draft" in table) and not str(table.get("finishing_source", "")).strip():
            raise ValueError(f"{where}: min_fillet and draft need a finishing_source")
        draft = table.get("draft")
        if draft is not None and not (isinstance(draft, (int, float)) and 0.0 < draft < 10.0):
            raise ValueError(f"{where}: draft must be an angle in degrees in (0, 10)")
        out["process"][name] = table
    return out


#: The fillet at a re-entrant junction over the thinner part's thickness [-] (castability.toml, [fillet]).
FILLET_RATIO = float(_finishing_data()["fillet"]["ratio"])


@functools.lru_cache(maxsize=32)
def finishing(process: str | None) -> Finishing:
    """The finishing rules of a process (None or a name the file does not know: the common rules alone,
    no minimum fillet and no draft)."""
    data = _finishing_data()
    table = data["process"].get(process or "", {})
    sources = [data["fillet"]["source"], data["finish"]["source"]]
    if table.get("finishing_source"):
        sources.insert(0, table["finishing_source"])
    return Finishing(
        process if table else None,
        FILLET_RATIO,
        float(table.get("min_fillet", 0.0)),
        float(table["draft"]) if "draft" in table else None,
        float(data["finish"]["machined_ra"]),
        float(data["finish"]["bore_ra"]),
        " ".join(sources),
    )


def process_of_design(design: Any) -> str | None:
    """The process a designed wheel is made by: the one its castability record names (the rules it was
    designed to), else its material's (:func:`process_of`); None where neither is known."""
    record = getattr(getattr(design, "limits", None), "castability", None)
    if record and record.get("process") in processes():
        return str(record["process"])
    return process_of(design.material)


#: Two parts whose thicknesses differ by less than this, relatively, are one section: no corner, no fillet
#: (an NLP's equal-thickness web and rim differ in the eighth digit).
SAME_THICKNESS = 1e-6


def fillet_radius(finish: Finishing, t_a: float, t_b: float, length: float, cast_wall: bool = True) -> float:
    """The fillet [m] where parts of thicknesses ``t_a`` and ``t_b`` meet, the one rule of the FE check
    (:func:`flyopt.design.fem.section`) and the drawing (:func:`flyopt.outputs.drawing.finish_of`).

    Parameters
    ----------
    finish : Finishing
    t_a, t_b : float
        The two parts' (full) thicknesses at the junction [m].
    length : float
        The thinner part's free length from this junction to its other end [m] (its fillet there shares it).
    cast_wall : bool
        False for a model's section that is no wall of the casting (the FE's equivalent web of the arms):
        the ratio applies, the process's minimum does not.

    Returns
    -------
    float
        r = max(ratio x thinner, min_fillet), at most half of ``length`` and half the step on one side
        (|t_a - t_b| / 4); 0 where the parts are as thick (to :data:`SAME_THICKNESS`).

    Notes
    -----
    The ratio and the minimum are data (castability.toml, ``[fillet]`` and each process's ``min_fillet``),
    with their sources.
    """
    if math.isclose(t_a, t_b, rel_tol=SAME_THICKNESS):
        return 0.0
    radius = finish.fillet_ratio * min(t_a, t_b)
    if cast_wall:
        radius = max(radius, finish.min_fillet)
    return min(radius, 0.5 * length, 0.5 * abs(t_a - t_b) / 2.0)


def chamfer_size(diameter: float, face: float) -> float:
    """The chamfer C [m] (45 deg) of a machined edge on a circle of ``diameter`` [m] joining faces the
    shorter of which is ``face`` [m] long: castability.toml's [chamfer] table by the diameter, at most
    ``face_fraction`` x ``face``, rounded down to a row of the table (the table's smallest at least)."""
    data = _finishing_data()["chamfer"]
    rows = [(float(d), float(c)) for d, c in data["table"]]
    by_size = next((c for d, c in rows if diameter <= d), rows[-1][1])
    cap = float(data["face_fraction"]) * face
    allowed = [c for _, c in rows if c <= min(by_size, cap) * (1.0 + 1e-9)]
    return allowed[-1] if allowed else rows[0][1]
