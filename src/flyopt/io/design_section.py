"""The [design] section: geometry, H/B range, envelope, objective, and the materials and shafts to choose from."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SAFETY_RANGE, SAFETY_WHY, Table, check_count, check_magnitude
from flyopt.names import Geometry, hint, unknown
from flyopt.units import MAGNITUDES, quantity

if TYPE_CHECKING:
    from collections.abc import Sequence

    from flyopt.design.materials import Material
    from flyopt.design.spec import DesignSpec
    from flyopt.machine.transmission import Shaft

LENGTH_RANGE = MAGNITUDES["length"][:2]
LENGTH_WHY = MAGNITUDES["length"][2]
"""Allowed lengths of the [design] envelope and walls [m], every length's (:data:`flyopt.units.MAGNITUDES`);
beyond them the wheel's powers of length overflow."""


def read_design(
    raw: object, shafts: Sequence[Shaft], materials: Sequence[Material]
) -> tuple[DesignSpec, tuple[str, ...] | None, tuple[str, ...] | None]:
    """The [design] section: the spec, and the names of the materials and shafts it may use (None: all)."""
    from flyopt.design.geometry import GEOMETRIES
    from flyopt.design.materials import material_library
    from flyopt.design.spec import CRITERIA, OBJECTIVES, DesignSpec

    table = Table(
        raw,
        "design",
        {
            "geometry",
            "materials",
            "shafts",
            "hb_ratio",
            "max_outer_diameter",
            "max_width",
            "d_mean",
            "objective",
            "description",
            "criterion",
            "safety_factor",
            "bore",
            "arms",
            "min_wall",
            "rim_share",
            "rim_speed",
            "radius_of_gyration",
            "round_to",
            "diameter_series",
            "prune",
            "fem_check",
            "disc_hub",
            "process",
            "castability",
        },
    )
    library = material_library(materials)
    names = _name_list(table, "materials", library, "material")
    shaft_names = _name_list(table, "shafts", {s.name: s for s in shafts}, "shaft")
    options = {}
    for key in ("geometry", "objective", "criterion"):
        if table.has(key):
            value = table.get(key)
            vocabulary: Any = {"geometry": GEOMETRIES, "objective": OBJECTIVES, "criterion": CRITERIA}[key]
            allowed = tuple(vocabulary)
            if value not in allowed:
                raise SceneError(f"design.{key}", unknown(value, allowed))
            options[key] = value
    if table.has("hb_ratio"):
        hb = table.get("hb_ratio")
        pair = hb if isinstance(hb, list) else [hb, hb]
        if len(pair) != 2:
            raise SceneError("design.hb_ratio", f"must be one number or a range [min, max], got {shorten(hb)}")
        low, high = (quantity(v, "dimensionless", "design.hb_ratio") for v in pair)
        if not 0 < low <= high:
            raise SceneError("design.hb_ratio", f"must be a range 0 < min <= max, got {shorten(hb)}")
        for value in (low, high):
            check_magnitude(
                value,
                "design.hb_ratio",
                hb,
                *HB_RANGE,
                "",
                HB_WHY,
            )
        options["hb_ratio"] = (low, high)
    if table.has("round_to") and isinstance(table.get("round_to"), bool):
        if table.get("round_to"):
            raise SceneError(
                "design.round_to", 'is a manufacturing step (e.g. "1 mm") or false (not rounded), not true'
            )
        options["round_to"] = 0.0  # the continuous optimum, asked for
    for key in ("max_outer_diameter", "max_width", "d_mean", "min_wall", "round_to"):
        if table.has(key) and key not in options:
            value = table.quantity(key, "length", required=True, own_range=True)
            if value <= 0:
                raise SceneError(f"design.{key}", f"must be positive, got {shorten(table.raw(key))}")
            check_magnitude(value, f"design.{key}", table.raw(key), *LENGTH_RANGE, "m", LENGTH_WHY)
            options[key] = value
    if options.get("round_to", 0.0) > MAX_ROUND_TO:
        raise SceneError(
            "design.round_to",
            f"{shorten(table.raw('round_to'))} is no manufacturing step (allowed: up to {MAX_ROUND_TO * 1e3:g} mm; "
            'e.g. "1 mm" for whole millimetres)',
        )
    if table.has("diameter_series"):
        from flyopt.design.preferred import SERIES

        value = table.get("diameter_series")
        if value not in SERIES:
            raise SceneError("design.diameter_series", unknown(value, SERIES))
        options["diameter_series"] = value
    if table.has("bore"):
        value = table.quantity("bore", "length", required=True)
        if value < 0:
            raise SceneError("design.bore", f"must be >= 0 (0: no bore), got {shorten(table.raw('bore'))}")
        envelope = options.get("max_outer_diameter", math.inf)
        if value >= envelope:
            raise SceneError(
                "design.bore",
                f"{shorten(table.raw('bore'))} does not fit inside "
                f"max_outer_diameter {shorten(table.raw('max_outer_diameter'))}",
            )
        options["bore"] = value
    if table.has("safety_factor"):
        value = table.quantity("safety_factor", "dimensionless", required=True, own_range=True)
        if value < 1:
            raise SceneError(
                "design.safety_factor",
                f"must be >= 1 (the allowable stress is the strength "
                f"over it), got {shorten(table.raw('safety_factor'))}",
            )
        check_magnitude(value, "design.safety_factor", table.raw("safety_factor"), *SAFETY_RANGE, "", SAFETY_WHY)
        options["safety_factor"] = value
    if table.has("rim_speed"):
        value = table.quantity("rim_speed", "speed", required=True, own_range=True)
        if value <= 0:
            raise SceneError("design.rim_speed", f"must be positive, got {shorten(table.raw('rim_speed'))}")
        check_magnitude(value, "design.rim_speed", table.raw("rim_speed"), *RIM_SPEED_RANGE, "m/s", RIM_SPEED_WHY)
        options["rim_speed"] = value
    if table.has("radius_of_gyration"):
        options["d_mean"] = 2.0 * _radius_of_gyration(table, options)
    if table.has("rim_share"):
        share = table.quantity("rim_share", "dimensionless", required=True, own_range=True)
        if not MIN_RIM_SHARE <= share <= 1:
            raise SceneError(
                "design.rim_share",
                f'must lie in [{MIN_RIM_SHARE:g}, 1] (the share of the inertia the rim gives, e.g. 0.9 or "95 %"), '
                f"got {shorten(table.raw('rim_share'))}",
            )
        options["rim_share"] = share
    if table.has("arms"):
        arms = table.get("arms")
        arms = arms if isinstance(arms, list) else [arms]
        check_count(arms, "design.arms", MAX_ARM_COUNTS, "arm counts", "(each is a design)")
        if (
            not arms
            or any(isinstance(n, bool) or not isinstance(n, int) or n < 3 for n in arms)
            or len(set(arms)) != len(arms)
        ):
            raise SceneError(
                "design.arms",
                f"must be whole arm counts >= 3, each once (e.g. [4, 6, 8]), got {shorten(table.raw('arms'))}",
            )
        options["arms"] = tuple(arms)
    if table.has("prune"):
        value = table.get("prune")
        if not isinstance(value, bool):
            raise SceneError("design.prune", f"must be true or false, got {shorten(table.raw('prune'))}")
        options["prune"] = value
    if table.has("fem_check"):
        value = table.get("fem_check")
        if not isinstance(value, bool):
            raise SceneError("design.fem_check", f"must be true or false, got {shorten(table.raw('fem_check'))}")
        options["fem_check"] = value
    if table.has("disc_hub"):
        value = table.get("disc_hub")
        if not isinstance(value, bool):
            raise SceneError("design.disc_hub", f"must be true or false, got {shorten(table.raw('disc_hub'))}")
        if value and options.get("geometry") != Geometry.DISC:
            raise SceneError("design.disc_hub", 'is for geometry = "disc" (web and arms wheels have a hub)')
        options["disc_hub"] = value
    if table.has("process") or table.has("castability"):
        options["castability"] = _castability(table)
    if options.get("objective") == "cost":
        from flyopt.design.materials import design_material_names

        chosen = design_material_names(library, names)
        missing = [n for n in chosen if library[n].cost is None]
        if missing:
            raise SceneError(
                "design.objective",
                f"'cost' needs a cost per kg for every material; none is given for {', '.join(missing)}",
            )
    try:
        spec = DesignSpec(**options)
    except ValueError as err:
        raise SceneError("design", str(err)) from None
    if spec.min_wall is not None:
        _check_min_wall(spec, table)
    return spec, names, shaft_names


MAX_ARM_COUNTS = 16
"""Most arm counts ``design.arms`` may list: a wheel is designed with each."""

#: Allowed H/B [-]: beyond it a rim's other section runs to kilometres or to nothing.
HB_RANGE = (1e-3, 1e3)
HB_WHY = "from a plate 1000 times wider than thick to a ring 1000 times thicker"

#: Smallest design.rim_share [-]: a rim that gives less is no flywheel's rim (the books' shares are 85-95 %).
MIN_RIM_SHARE = 0.01

#: Largest design.round_to [m]: a coarser step is no manufacturing step for a flywheel.
MAX_ROUND_TO = 0.1

#: Allowed design.rim_speed [m/s]: a walking pace to beyond any rotor's burst speed.
RIM_SPEED_RANGE = (1e-3, 1e4)
RIM_SPEED_WHY = "a millimetre a second to 10 km/s, beyond any flywheel's burst speed"


def _castability(table: Table) -> Any:
    """design.process and [design.castability] (min_wall, section_ratio): the scene's castability, every number
    bounded (docs/flywheel-design.md, section 23)."""
    from flyopt.design import castability

    process = None
    if table.has("process"):
        process = table.get("process")
        allowed = (*castability.processes(), castability.NONE)
        if not isinstance(process, str) or process not in allowed:
            raise SceneError("design.process", unknown(process, allowed))
    raw = table.get("castability")
    if raw is None:
        return castability.Overrides(process)
    cast = Table(raw, "design.castability", {"min_wall", "section_ratio"})
    rows = None
    low, high = castability.WALL_RANGE
    why = castability.WALL_WHY
    if cast.has("min_wall"):
        given = cast.get("min_wall")
        if isinstance(given, list):
            if not given or len(given) > MAX_WALL_ROWS:
                raise SceneError(
                    "design.castability.min_wall",
                    f'must be 1 to {MAX_WALL_ROWS} rows [size, wall] (e.g. [["0.25 m", "5 mm"], '
                    f'["1 m", "7 mm"]]) or one wall, got {shorten(given)}',
                )
            rows = []
            for k, row in enumerate(given):
                where = f"design.castability.min_wall[{k}]"
                if not isinstance(row, list) or len(row) != 2:
                    raise SceneError(where, f"must be a row [size, wall] of two lengths, got {shorten(row)}")
                size, wall = (quantity(v, "length", where) for v in row)
                if not 0 <= size <= LENGTH_RANGE[1]:
                    raise SceneError(where, f"size {shorten(row[0])} is out of range (allowed: 0 to 1000 m)")
                check_magnitude(wall, where, row[1], low, high, "m", why)
                rows.append((size, wall))
            if any(s1 <= s0 or w1 < w0 for (s0, w0), (s1, w1) in zip(rows, rows[1:])):
                raise SceneError(
                    "design.castability.min_wall",
                    "rows must go up in size, and their walls must not go down (a larger casting's thinnest wall is "
                    f"no thinner), got {shorten(given)}",
                )
        else:
            wall = cast.quantity("min_wall", "length", required=True, own_range=True)
            check_magnitude(wall, "design.castability.min_wall", given, low, high, "m", why)
            rows = [(0.0, wall)]
    ratio = None
    if cast.has("section_ratio"):
        ratio = cast.quantity("section_ratio", "dimensionless", required=True, own_range=True)
        r_low, r_high = castability.RATIO_RANGE
        if not r_low <= ratio <= r_high:
            raise SceneError(
                "design.castability.section_ratio",
                f"{shorten(cast.raw('section_ratio'))} is out of range (allowed: {r_low:g} to {r_high:g}: the thicker "
                "of two adjoining sections over the thinner)",
            )
    return castability.Overrides(process, tuple(rows) if rows is not None else None, ratio)


#: Most rows of a scene's design.castability.min_wall table.
MAX_WALL_ROWS = 20


def _radius_of_gyration(table: Table, options: dict[str, Any]) -> float:
    """design.radius_of_gyration k [m], for a thin rim only (J = m k², so D_m = 2k): the books' "k = 0.5 m"."""
    k = table.quantity("radius_of_gyration", "length", required=True, own_range=True)
    raw = table.raw("radius_of_gyration")
    if k <= 0:
        raise SceneError("design.radius_of_gyration", f"must be positive, got {shorten(raw)}")
    check_magnitude(k, "design.radius_of_gyration", raw, LENGTH_RANGE[0] / 2, LENGTH_RANGE[1] / 2, "m", "up to 500 m")
    if options.get("geometry") != "thin_rim":
        raise SceneError(
            "design.radius_of_gyration",
            'is a thin rim\'s (J = m k², D_m = 2k): give geometry = "thin_rim" with it '
            "(another wheel's k follows from its shape)",
        )
    for other in ("d_mean", "rim_speed"):
        if table.has(other):
            raise SceneError(
                "design.radius_of_gyration", f"and design.{other} both set the mean diameter: give one of them"
            )
    return k


def _check_min_wall(spec, table):
    """Refuse a ``min_wall`` that does not fit in the envelope (the design would start from negative walls).

    Every section is at least ``min_wall`` thick: the rim's width must fit in
    ``max_width``, and across the radius, from the bore to the outer
    diameter, lie one wall (a disc, a rim) or two (the rim and the hub of a
    rim_web or rim_arms wheel).
    """
    wall, raw = spec.min_wall, shorten(table.raw("min_wall"))
    if wall >= spec.max_width:
        raise SceneError(
            "design.min_wall",
            f"{raw} does not fit in max_width {shorten(table.raw('max_width'))} "
            "(allowed: a wall thinner than the wheel's widest width)",
        )
    walls = 2 if spec.geometry in (Geometry.RIM_WEB, Geometry.RIM_ARMS) else 1
    room = (spec.max_outer_diameter - (spec.bore or 0.0)) / 2
    if walls * wall >= room:
        across = "the radius" if not spec.bore else "the radius outside the bore"
        raise SceneError(
            "design.min_wall",
            f"{raw} does not fit in max_outer_diameter {shorten(table.raw('max_outer_diameter'))}: "
            f"{'the rim and the hub, each' if walls == 2 else 'a section'} at least min_wall thick, "
            f"must lie across {across}, {room:.6g} m (allowed: below {room / walls:.6g} m)",
        )


def _name_list(table, key, known, what):
    if not table.has(key):
        return None
    raw = table.get(key)
    if not isinstance(raw, list) or not raw or not all(isinstance(n, str) for n in raw):
        raise SceneError(f"design.{key}", f"must be a non-empty list of {what} names")
    for k, name in enumerate(raw):
        if name not in known:
            raise SceneError(
                f"design.{key}[{k}]", f"unknown {what} {shorten(name)}{hint(name, known)} (known: {', '.join(known)})"
            )
    if len(set(raw)) != len(raw):
        raise SceneError(f"design.{key}", f"a {what} is named twice")
    return tuple(raw)
