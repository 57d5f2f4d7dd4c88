"""Flywheel materials: density, elastic constants, strength, safe rim speed and cost.

The built-in materials live in the package data file
``flyopt/data/materials.toml``, each with its source; nothing numeric about a
material is written in this module. Users extend or override them with their
own materials (:func:`make_material`, :func:`material_library`).

A material states how strong it is in one of three ways, and
:meth:`Material.allowable` turns each into an allowable stress [Pa]:

1. an explicit ``allowable_stress``;
2. strengths: the tensile strength R_m and the yield (0.2 % proof) strength
   R_p0.2, possibly by section thickness (castings lose strength in thick
   walls, quenched-and-tempered steels in large ruling sections). A ductile
   material is checked by von Mises against R_p0.2, a brittle one by its
   largest principal stress against R_m; the allowable stress is that
   strength over a safety factor;
3. only a safe rim speed v_max (the textbook limits). A rotating thin ring
   carries the hoop stress

       sigma ~ rho v^2,

   with v the peripheral speed at the outer diameter, so the speed limit
   implies the allowable hoop stress rho v_max^2, and conversely an allowable
   stress gives v_max = sqrt(sigma_allow / rho).

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, section 10 (rim speed
   limits: cast iron 36 m/s, cast steel 50 m/s).
.. [2] EN 1561 (grey cast iron) and EN 1563 (spheroidal graphite cast iron):
   strength by "relevant wall thickness" of each part of a casting.
.. [3] EN 10083-1/-3 (steels for quenching and tempering): strength by the
   ruling section of the heat-treated piece.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, fields
from importlib import resources
from typing import Any, NamedTuple, cast

from flyopt._toml import tomllib
from flyopt.design.castability import WALL_RANGE, WALL_WHY
from flyopt.errors import BrokenInvariant, shorten
from flyopt.names import closest
from flyopt.validate import number

__all__ = [
    "Material",
    "StrengthRow",
    "ThicknessOutOfRange",
    "THICKNESS_RULES",
    "builtin_materials",
    "default_materials",
    "make_material",
    "material_library",
    "get_material",
    "rim_speed_from_stress",
]

_DATA_FILE = "materials.toml"

THICKNESS_RULES = ("part", "wheel")
"""Which section thickness selects a row of a strength table.

``"part"``: each part of a casting by its own wall (EN 1561/EN 1563 "relevant
wall thickness"); ``"wheel"``: one ruling section for the whole heat-treated
piece (EN 10083-1/-3)."""


class ThicknessOutOfRange(ValueError):
    """A section is thicker than the material's strength table covers."""


class StrengthRow(NamedTuple):
    """One row of a strength-by-thickness table.

    Attributes
    ----------
    max_thickness : float
        Upper bound of the row's section thickness [m]; the row holds for
        thicknesses above the previous row's bound up to and including this.
    tensile_strength : float
        Tensile strength R_m [Pa].
    yield_strength : float or None
        Yield (0.2 % proof) strength R_p0.2 [Pa]; None where the source gives
        none (brittle grey iron).
    """

    max_thickness: float
    tensile_strength: float
    yield_strength: float | None = None


def _number(value, what, name, *, minimum=0.0, strict=True, below=None, allow_none=False):
    """``value`` as a finite float in the allowed range, else ValueError naming material and field.

    ``minimum`` is exclusive when ``strict`` (``> minimum``), inclusive otherwise;
    ``below`` is an exclusive upper bound.
    """
    if value is None and allow_none:
        return None
    if (  # a plain float in range (every call of a design's check): no message made
        type(value) is float
        and (value > minimum if strict else value >= minimum)
        and (below is None or value < below)
        and value < math.inf
    ):
        return value
    return number(value, f"material {shorten(name)}: {what}", minimum=minimum, strict=strict, below=below)


def _positive_finite(value, what, name):
    """Return ``value`` as a float, raising ValueError unless finite and > 0."""
    return _number(value, what, name)


def _rows(table, name):
    """A strength table as a tuple of StrengthRow, checked; ValueError naming the row.

    None or an empty sequence is no table (strength independent of thickness).
    """
    what = "strength_by_thickness"
    if table is None:
        return ()
    if isinstance(table, (str, bytes, Mapping)) or not isinstance(table, Iterable):
        raise ValueError(
            f"material {shorten(name)}: {what} must be a list of rows "
            f"(max_thickness [m], tensile_strength [Pa], yield_strength [Pa] or none), "
            f"got {shorten(table)}"
        )
    rows: list[StrengthRow] = []
    for k, row in enumerate(table):
        where = f"{what}[{k}]"
        if isinstance(row, Mapping):
            unknown = set(row) - set(StrengthRow._fields)
            if unknown:
                raise ValueError(
                    f"material {shorten(name)}: {where} has unknown keys "
                    f"{sorted(unknown)}; allowed are {list(StrengthRow._fields)}"
                )
            row = (row.get("max_thickness"), row.get("tensile_strength"), row.get("yield_strength"))
        if isinstance(row, (str, bytes)) or not isinstance(row, Iterable):
            raise ValueError(
                f"material {shorten(name)}: {where} must be (max_thickness [m], "
                f"tensile_strength [Pa]) or (..., yield_strength [Pa]), got {shorten(row)}"
            )
        row = tuple(row)
        if len(row) not in (2, 3):
            raise ValueError(
                f"material {shorten(name)}: {where} must have 2 or 3 numbers "
                f"(max_thickness [m], tensile_strength [Pa], yield_strength [Pa]), "
                f"got {len(row)}"
            )
        thickness = _number(row[0], f"{where}.max_thickness [m]", name)
        tensile = _number(row[1], f"{where}.tensile_strength [Pa]", name)
        yield_ = _number(row[2] if len(row) == 3 else None, f"{where}.yield_strength [Pa]", name, allow_none=True)
        if yield_ is not None and yield_ > tensile:
            raise ValueError(
                f"material {shorten(name)}: {where}.yield_strength {yield_:g} Pa exceeds "
                f"its tensile_strength {tensile:g} Pa; yield must be <= tensile"
            )
        if rows and thickness <= rows[-1].max_thickness:
            raise ValueError(
                f"material {shorten(name)}: {where}.max_thickness {thickness:g} m must be "
                f"larger than the previous row's {rows[-1].max_thickness:g} m "
                f"(rows in increasing thickness)"
            )
        rows.append(StrengthRow(thickness, tensile, yield_))
    return tuple(rows)


def _weakest(rows):
    """(R_m, R_p0.2) that hold for every row: the smallest of each (R_p0.2 None if a row lacks one)."""
    tensile = min(row.tensile_strength for row in rows)
    yields = [row.yield_strength for row in rows]
    return tensile, (None if any(y is None for y in yields) else min(yields))


@dataclass(frozen=True)
class Material:
    """A flywheel material.

    Parameters
    ----------
    name : str
        Name used in scenes and reports, e.g. ``"cast_iron"``.
    density : float
        Density rho [kg/m^3].
    max_rim_speed : float or None
        Safe peripheral speed at the outer diameter v_max [m/s], the limit of
        the textbook rim-speed criterion. When None it is derived:
        sqrt(allowable_stress / rho) from an explicit allowable stress, else
        sqrt(allowable() / rho) from the strengths when a safety factor is
        known; a material given by strengths without a safety factor keeps
        None (its limit then needs the design's factor:
        :meth:`rim_speed_limit`).
    allowable_stress : float or None
        Explicit allowable hoop stress [Pa]; when known the design reports a
        safety factor sigma_allow / (rho v^2), and it overrides strengths.
    cost : float or None
        Cost per kilogram [currency/kg], needed for the ``cost`` objective.
    source : str
        Where the numbers come from.
    elastic_modulus : float or None
        Young's modulus E [Pa].
    poisson_ratio : float or None
        Poisson's ratio nu [-], 0 <= nu < 0.5.
    tensile_strength : float or None
        Tensile strength R_m [Pa], thickness-independent. With a
        ``strength_by_thickness`` table it is the table's weakest row (filled
        in when left out).
    yield_strength : float or None
        Yield (0.2 % proof) strength R_p0.2 [Pa], <= R_m; as R_m for tables.
    ductile : bool or None
        True: the material is checked by von Mises against R_p0.2; False
        (brittle): by its largest principal stress against R_m. Required when
        strengths are given.
    safety_factor : float or None
        Default factor of practice on strength (> 1); a design's own factor
        wins over it (:meth:`allowable`).
    strength_by_thickness : sequence of StrengthRow
        Strength by section thickness: rows (max_thickness [m], R_m [Pa],
        R_p0.2 [Pa] or None) in increasing thickness; empty when the strength
        does not depend on thickness.
    thickness_rule : {"part", "wheel"} or None
        Which thickness selects a row (:data:`THICKNESS_RULES`); required with
        a table, refused without one.
    min_wall : float or None
        Thinnest section the process makes [m].
    bearing_pressure : float or None
        Allowable surface pressure of a keyed hub of this material [Pa] (the
        DIN 6885 key check).
    hub_rule : str or None
        Which hub proportions of ``flyopt/data/keys.toml`` a keyed hub of
        this material follows (``"cast_iron"``, ``"steel"``, ...); None: by
        ductility (:attr:`hub_kind`).
    display : str or None
        The name for people (a grade's designation, ``"EN-GJS-400-18"``); None: the name with spaces
        (:attr:`display_name`).

    Raises
    ------
    ValueError
        If a value is out of its range; the message names the material, the
        field and what is allowed.

    Notes
    -----
    Without a thickness, :meth:`strength` gives the weakest row of a table:
    a strength that holds for every section the table covers. Above the last
    row the table gives no strength and :meth:`strength` refuses
    (:class:`ThicknessOutOfRange`) rather than extrapolate; below the first
    row's bound the first row holds (strength does not fall as walls get
    thinner), and ``min_wall`` is the lower limit a design must respect.
    """

    name: str
    density: float
    max_rim_speed: float | None = None
    allowable_stress: float | None = None
    cost: float | None = None
    source: str = ""
    elastic_modulus: float | None = None
    poisson_ratio: float | None = None
    tensile_strength: float | None = None
    yield_strength: float | None = None
    ductile: bool | None = None
    safety_factor: float | None = None
    strength_by_thickness: tuple[StrengthRow, ...] = ()
    thickness_rule: str | None = None
    min_wall: float | None = None
    bearing_pressure: float | None = None
    hub_rule: str | None = None
    display: str | None = None

    @property
    def display_name(self) -> str:
        """The material's name for people, the one the text, the report and the drawing use: a grade's
        designation from the data (``EN-GJS-400-18``), else the name with spaces (``gjs keyed``)."""
        return self.display or self.name.replace("_", " ")

    def __post_init__(self) -> None:
        name = self.name
        if not isinstance(name, str) or not name.strip():
            raise ValueError(f"material name must be a non-empty string, got {shorten(name)}")
        set_ = functools.partial(object.__setattr__, self)
        set_("density", _positive_finite(self.density, "density [kg/m^3]", name))
        set_("max_rim_speed", _number(self.max_rim_speed, "max_rim_speed [m/s]", name, allow_none=True))
        set_("allowable_stress", _number(self.allowable_stress, "allowable_stress [Pa]", name, allow_none=True))
        set_("cost", _number(self.cost, "cost [1/kg]", name, strict=False, allow_none=True))
        if not isinstance(self.source, str):
            raise ValueError(f"material {shorten(name)}: source must be a string, got {shorten(self.source)}")
        set_("elastic_modulus", _number(self.elastic_modulus, "elastic_modulus [Pa]", name, allow_none=True))
        set_(
            "poisson_ratio",
            _number(self.poisson_ratio, "poisson_ratio [-]", name, strict=False, below=0.5, allow_none=True),
        )
        set_("min_wall", _number(self.min_wall, "min_wall [m]", name, allow_none=True))
        if self.min_wall is not None and not WALL_RANGE[0] <= self.min_wall <= WALL_RANGE[1]:
            raise ValueError(
                f"material {shorten(name)}: min_wall {self.min_wall:g} m is out of range (allowed: "
                f"{WALL_RANGE[0]:g} to {WALL_RANGE[1]:g} m; {WALL_WHY})"
            )
        set_("bearing_pressure", _number(self.bearing_pressure, "bearing_pressure [Pa]", name, allow_none=True))
        set_("safety_factor", _number(self.safety_factor, "safety_factor [-]", name, minimum=1.0, allow_none=True))
        if self.display is not None and (not isinstance(self.display, str) or not self.display.strip()):
            raise ValueError(f"material {shorten(name)}: display must be a non-empty name, got {shorten(self.display)}")
        if self.hub_rule is not None and (not isinstance(self.hub_rule, str) or not self.hub_rule.strip()):
            raise ValueError(
                f"material {shorten(name)}: hub_rule must be the name of a hub rule, got {shorten(self.hub_rule)}"
            )
        self._check_strengths(set_)
        if self.max_rim_speed is None:
            set_("max_rim_speed", self._derived_rim_speed())

    def _check_strengths(self, set_):
        name = self.name
        tensile = _number(self.tensile_strength, "tensile_strength [Pa]", name, allow_none=True)
        yield_ = _number(self.yield_strength, "yield_strength [Pa]", name, allow_none=True)
        rows = _rows(self.strength_by_thickness, name)
        set_("strength_by_thickness", rows)
        if rows:
            weakest = _weakest(rows)
            for field, given, row_value in (
                ("tensile_strength", tensile, weakest[0]),
                ("yield_strength", yield_, weakest[1]),
            ):
                if given is not None and given != row_value:
                    raise ValueError(
                        f"material {shorten(name)}: {field} {given:g} Pa differs from the weakest row "
                        f"of strength_by_thickness ({row_value!r} Pa); with a table leave {field} out "
                        f"(it is then the weakest row)"
                    )
            tensile, yield_ = weakest
        if tensile is not None and yield_ is not None and yield_ > tensile:
            raise ValueError(
                f"material {shorten(name)}: yield_strength {yield_:g} Pa exceeds "
                f"tensile_strength {tensile:g} Pa; yield must be <= tensile"
            )
        set_("tensile_strength", tensile)
        set_("yield_strength", yield_)
        if self.ductile is not None and not isinstance(self.ductile, bool):
            raise ValueError(f"material {shorten(name)}: ductile must be true or false, got {shorten(self.ductile)}")
        has_strength = tensile is not None or yield_ is not None
        if has_strength and self.ductile is None:
            raise ValueError(
                f"material {shorten(name)}: ductile must be given (true: von Mises against "
                f"yield_strength; false: largest principal stress against tensile_strength) "
                f"when strengths are"
            )
        if self.ductile is True and has_strength and yield_ is None:
            raise ValueError(
                f"material {shorten(name)}: a ductile material is checked against "
                f"yield_strength [Pa]; give it (in every row of strength_by_thickness)"
            )
        if self.ductile is False and has_strength and tensile is None:
            raise ValueError(
                f"material {shorten(name)}: a brittle material is checked against tensile_strength [Pa]; give it"
            )
        if self.safety_factor is not None and not has_strength:
            raise ValueError(
                f"material {shorten(name)}: safety_factor applies to tensile_strength or "
                f"yield_strength, and none is given"
            )
        rule = self.thickness_rule
        if rows and rule not in THICKNESS_RULES:
            raise ValueError(
                f"material {shorten(name)}: thickness_rule must be one of "
                f"{list(THICKNESS_RULES)} with a strength_by_thickness table "
                f"(part: each part's own wall, EN 1561/1563; wheel: the ruling section "
                f"of the whole piece, EN 10083-3), got {shorten(rule)}"
            )
        if not rows and rule is not None:
            raise ValueError(
                f"material {shorten(name)}: thickness_rule {shorten(rule)} needs a "
                f"strength_by_thickness table, and none is given"
            )
        if rows and self.min_wall is not None and self.min_wall > rows[-1].max_thickness:
            raise ValueError(
                f"material {shorten(name)}: min_wall {self.min_wall:g} m is above the "
                f"thickest row of strength_by_thickness ({rows[-1].max_thickness:g} m)"
            )

    def _derived_rim_speed(self):
        """v_max from the allowable stress or the strengths, None if strengths lack a factor."""
        if self.allowable_stress is not None:
            return rim_speed_from_stress(self.allowable_stress, self.density)
        if self.is_strength_based:
            if self.safety_factor is None:
                return None
            return rim_speed_from_stress(self.allowable(), self.density)
        raise ValueError(
            f"material {shorten(self.name)}: give max_rim_speed [m/s] or allowable_stress [Pa] "
            f"(the rim speed then follows from sigma = rho v^2), or tensile_strength/yield_strength "
            f"[Pa] with ductile; neither was given"
        )

    @property
    def is_strength_based(self) -> bool:
        """True when the allowable stress comes from strengths (no explicit allowable_stress)."""
        return self.allowable_stress is None and (self.tensile_strength is not None or self.yield_strength is not None)

    @property
    def failure_criterion(self) -> str | None:
        """``"von_mises"`` (ductile, against R_p0.2), ``"max_principal"`` (brittle, against R_m) or None."""
        if self.ductile is None:
            return None
        return "von_mises" if self.ductile else "max_principal"

    @property
    def hub_kind(self) -> str:
        """The hub proportions a keyed hub of this material follows (a ``hub_proportions`` row of keys.toml).

        ``hub_rule`` when the material names one; otherwise ``"steel"`` for a
        ductile material and ``"cast_iron"`` for a brittle one or one whose
        ductility is not given (the larger hub, D/d 1.8-2: the safe side).
        """
        if self.hub_rule is not None:
            return self.hub_rule
        return "steel" if self.ductile else "cast_iron"

    def strength(self, thickness: float | None = None) -> tuple[float | None, float | None]:
        """Tensile and yield strength at a section thickness.

        Parameters
        ----------
        thickness : float, optional
            Section thickness [m] chosen by :attr:`thickness_rule` (a part's
            relevant wall, or the ruling section of the whole piece). Omitted:
            the weakest row of the table, which holds for every section it
            covers.

        Returns
        -------
        tuple of (float or None, float or None)
            (R_m, R_p0.2) [Pa]; (None, None) for a material without strengths.

        Raises
        ------
        ThicknessOutOfRange
            If ``thickness`` is above the table's last row: the source gives
            no strength there and none is extrapolated.
        ValueError
            If ``thickness`` is not a positive finite number.
        """
        if thickness is None:
            return self.tensile_strength, self.yield_strength
        thickness = _number(thickness, "thickness [m]", self.name)
        for row in self.strength_by_thickness:
            if thickness <= row.max_thickness:
                return row.tensile_strength, row.yield_strength
        if self.strength_by_thickness:
            last = self.strength_by_thickness[-1].max_thickness
            raise ThicknessOutOfRange(
                f"material {shorten(self.name)}: section thickness {thickness * 1e3:g} mm is above its "
                f"strength table, which ends at {last * 1e3:g} mm ({self.thickness_rule} rule); "
                f"no strength is extrapolated: choose a thinner section or another material"
            )
        return self.tensile_strength, self.yield_strength

    def allowable(self, thickness: float | None = None, safety_factor: float | None = None) -> float:
        """Allowable stress [Pa] of the material at a section thickness.

        Parameters
        ----------
        thickness : float, optional
            Section thickness [m] for a strength table (:meth:`strength`).
        safety_factor : float, optional
            The design's factor on strength (> 1); it wins over the
            material's :attr:`safety_factor`.

        Returns
        -------
        float
            In this order: the explicit :attr:`allowable_stress`; else
            R_p0.2 / S for a ductile material or R_m / S for a brittle one
            (S the design's factor, else the material's); else, for a
            material known only by its rim speed (the textbook limits), the
            thin-ring hoop stress that speed implies, rho v_max^2.

        Raises
        ------
        ValueError
            If the material is given by strengths and neither the design nor
            the material gives a safety factor, or a value is out of range.
        ThicknessOutOfRange
            If ``thickness`` is above the strength table.

        Notes
        -----
        Thin rotating ring: sigma = rho v^2 [1]_, so v_max gives
        sigma_allow = rho v_max^2. Neither the thickness nor the safety factor
        changes an explicit allowable stress or a textbook rim-speed limit.
        """
        if safety_factor is not None:
            safety_factor = _number(safety_factor, "safety_factor [-] of the design", self.name, minimum=1.0)
        if thickness is not None:
            _number(thickness, "thickness [m]", self.name)
        if self.allowable_stress is not None:
            return self.allowable_stress
        if self.is_strength_based:
            factor = safety_factor if safety_factor is not None else self.safety_factor
            if factor is None:
                raise ValueError(
                    f"material {shorten(self.name)}: no safety factor to divide its strength "
                    f"by; give the design's safety_factor (> 1) or the material's"
                )
            tensile, yield_ = self.strength(thickness)
            governing = yield_ if self.ductile else tensile
            # __post_init__ refuses a ductile material without yield_strength and a brittle one without tensile_strength
            if governing is None:
                raise RuntimeError(
                    f"material {shorten(self.name)}: no {'yield' if self.ductile else 'tensile'} strength"
                )
            return governing / factor
        # __post_init__ refuses a material with neither allowable_stress, strengths nor max_rim_speed
        if self.max_rim_speed is None:
            raise RuntimeError(f"material {shorten(self.name)}: no allowable stress, strengths or rim speed")
        return self.density * self.max_rim_speed**2

    def rim_speed_limit(self, thickness: float | None = None, safety_factor: float | None = None) -> float:
        """Safe rim speed v_max [m/s] for the textbook rim-speed criterion: flyopt's one rule.

        Every path (solve, sweep, trade-off, Pareto, drive, report) takes the
        limit from here with the design's safety factor
        (:func:`flyopt.design.designer.rim_speed_limit`).

        Parameters
        ----------
        thickness : float, optional
            Section thickness [m] for a strength table.
        safety_factor : float, optional
            The design's factor on strength (> 1); it wins over the
            material's :attr:`safety_factor`, as in :meth:`allowable`.

        Returns
        -------
        float
            For a material given by strengths, when a thickness or a safety
            factor is given or no :attr:`max_rim_speed` is stored:
            sqrt(allowable(thickness, safety_factor) / rho), so that the
            design's factor replaces the rim speed derived at construction
            from the material's own factor. Otherwise :attr:`max_rim_speed`
            (a textbook limit, the user's, or the one derived at construction
            from an explicit allowable stress or the material's factor),
            which no design factor changes.

        Raises
        ------
        ValueError
            If a material given by strengths has no safety factor.
        """
        if self.is_strength_based and (
            thickness is not None or safety_factor is not None or self.max_rim_speed is None
        ):
            return rim_speed_from_stress(self.allowable(thickness, safety_factor), self.density)
        if self.max_rim_speed is None:
            raise BrokenInvariant("a material has its max_rim_speed, given or derived by __post_init__")
        return self.max_rim_speed


_FIELDS = tuple(f.name for f in fields(Material))
#: Keys a data-file entry may have: the Material fields but its name, and the default flag.
_KNOWN_KEYS = frozenset(_FIELDS[1:]) | {"default"}


def rim_speed_from_stress(allowable_stress: float, density: float) -> float:
    """Safe rim speed of a thin ring from its allowable hoop stress.

    Parameters
    ----------
    allowable_stress : float
        Allowable hoop stress sigma [Pa].
    density : float
        Density rho [kg/m^3].

    Returns
    -------
    float
        v_max = sqrt(sigma / rho) [m/s].

    Notes
    -----
    The hoop stress of a thin rotating ring is sigma = rho v^2 [1]_.
    """
    return math.sqrt(allowable_stress / density)


def make_material(
    name: str,
    density: float,
    max_rim_speed: float | None = None,
    allowable_stress: float | None = None,
    cost: float | None = None,
    source: str = "",
    *,
    elastic_modulus: float | None = None,
    poisson_ratio: float | None = None,
    tensile_strength: float | None = None,
    yield_strength: float | None = None,
    ductile: bool | None = None,
    safety_factor: float | None = None,
    strength_by_thickness: Iterable[Any] = (),
    thickness_rule: str | None = None,
    min_wall: float | None = None,
    bearing_pressure: float | None = None,
    hub_rule: str | None = None,
    display: str | None = None,
    **unknown: Any,
) -> Material:
    """Build a user material, checking every field; the rim speed may be derived.

    Parameters
    ----------
    name : str
        Material name.
    density : float
        Density [kg/m^3].
    max_rim_speed : float, optional
        Safe rim speed [m/s]. If omitted, v_max = sqrt(sigma / rho) from
        ``allowable_stress``, else from the strengths over the safety factor
        (None when the material gives strengths but no safety factor).
    allowable_stress : float, optional
        Allowable hoop stress [Pa]. When both it and ``max_rim_speed`` are
        given, the rim speed is used as given and the stress gives the
        reported safety factor.
    cost : float, optional
        Cost per kilogram [currency/kg].
    source : str, optional
        Where the numbers come from.
    elastic_modulus, poisson_ratio, tensile_strength, yield_strength, ductile,
    safety_factor, strength_by_thickness, thickness_rule, min_wall,
    bearing_pressure, hub_rule, display
        As :class:`Material`, in SI units ([Pa], [-], [m]); keyword only.

    Returns
    -------
    Material

    Raises
    ------
    ValueError
        If neither ``max_rim_speed``, ``allowable_stress`` nor a strength is
        given, a field is unknown, or a value is out of its range; the
        message names the material, the field and what is allowed.
    """
    if unknown:
        allowed = [f for f in _FIELDS if f != "name"]
        hints = {key: closest(key, allowed) for key in unknown}
        hint = "; ".join(
            f"{key!r} (did you mean {close!r}?)" if close else repr(key) for key, close in sorted(hints.items())
        )
        raise ValueError(f"material {shorten(name)}: unknown field {hint}; allowed are {allowed}")
    density = _positive_finite(density, "density [kg/m^3]", name)
    return Material(
        name=name,
        density=density,
        max_rim_speed=max_rim_speed,
        allowable_stress=allowable_stress,
        cost=cost,
        source=source,
        elastic_modulus=elastic_modulus,
        poisson_ratio=poisson_ratio,
        tensile_strength=tensile_strength,
        yield_strength=yield_strength,
        ductile=ductile,
        safety_factor=safety_factor,
        # any rows as the user gave them: Material.__post_init__ checks them and stores a tuple of StrengthRow
        strength_by_thickness=cast("tuple[StrengthRow, ...]", strength_by_thickness),
        thickness_rule=thickness_rule,
        min_wall=min_wall,
        bearing_pressure=bearing_pressure,
        hub_rule=hub_rule,
        display=display,
    )


def _material_from_table(name, table, origin):
    """Build a Material from one TOML table, naming ``origin`` on error."""
    if not isinstance(table, Mapping):
        raise ValueError(f"{origin}: material {name!r} must be a table of fields, got {shorten(table)}")
    unknown = set(table) - _KNOWN_KEYS
    if unknown:
        raise ValueError(
            f"{origin}: material {name!r} has unknown keys {sorted(unknown)}; allowed are {sorted(_KNOWN_KEYS)}"
        )
    if "density" not in table:
        raise ValueError(f"{origin}: material {name!r} has no density")
    values = {key: value for key, value in table.items() if key != "default"}
    try:
        return make_material(name, **values)
    except ValueError as err:
        raise ValueError(f"{origin}: {err}") from err


@functools.lru_cache(maxsize=1)
def _load_builtin():
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    origin = f"flyopt/data/{_DATA_FILE}"
    materials, defaults = {}, set()
    for name, table in data.items():
        material = _material_from_table(name, table, origin)
        if not material.source:
            raise ValueError(f"{origin}: built-in material {name!r} cites no source")
        flag = table.get("default", False)
        if not isinstance(flag, bool):
            raise ValueError(f"{origin}: material {name!r}: default must be true or false, got {shorten(flag)}")
        if flag:
            defaults.add(name)
        materials[name] = material
    return materials, frozenset(defaults)


def builtin_materials(default_only: bool = True) -> dict[str, Material]:
    """The built-in materials, read once from ``flyopt/data/materials.toml``.

    Parameters
    ----------
    default_only : bool
        True (the default, and what this function returned before the
        standard grades were added): only those flagged ``default = true`` in
        the data file, the set a design uses when the scene names no materials
        (the textbook ``cast_iron`` and ``cast_steel``), each with its own rim
        speed limit. False: every built-in material, the standard grades too
        (what :func:`material_library` and :func:`get_material` look in).

    Returns
    -------
    dict of str to Material
        A fresh dictionary (safe to modify) keyed by material name.
    """
    materials, defaults = _load_builtin()
    if default_only:
        return {name: m for name, m in materials.items() if name in defaults}
    return dict(materials)


def default_materials(library: Mapping[str, Material] | None = None) -> dict[str, Material]:
    """The materials a design uses when the scene names none.

    Parameters
    ----------
    library : mapping of str to Material, optional
        A material library (:func:`material_library`); every built-in
        material by default.

    Returns
    -------
    dict of str to Material
        Every entry of ``library`` except the built-in materials the data file
        does not flag ``default = true``: the default built-ins (the textbook
        ``cast_iron`` and ``cast_steel``) and every user material, including
        one that replaces a built-in. This is the set a design used before the
        standard grades were added to the data file, so adding data does not
        change a scene's default design.
    """
    if library is None:
        library = builtin_materials(default_only=False)
    builtins, defaults = _load_builtin()
    return {name: m for name, m in library.items() if name in defaults or name not in builtins or m != builtins[name]}


def design_material_names(library: Mapping[str, Material], names: Iterable[str] | None = None) -> tuple:
    """The names of the materials a design may use: ``names`` (a scene's ``[design] materials``), else the default set."""
    return tuple(names) if names else tuple(default_materials(library))


def material_library(user_materials: Iterable[Material] | Mapping[str, Material] = ()) -> dict[str, Material]:
    """Every built-in material, extended or overridden by the user's.

    Parameters
    ----------
    user_materials : iterable of Material or mapping of name to Material
        User materials. One with the name of a built-in material replaces it.

    Returns
    -------
    dict of str to Material

    Raises
    ------
    ValueError
        If an entry is not a Material or two user materials share a name.
    """
    if isinstance(user_materials, Mapping):
        user_materials = list(user_materials.values())
    library = builtin_materials(default_only=False)
    seen = set()
    for material in user_materials:
        if not isinstance(material, Material):
            raise ValueError(f"user materials must be Material objects, got {shorten(material)}")
        if material.name in seen:
            raise ValueError(f"user material {material.name!r} is given twice")
        seen.add(material.name)
        library[material.name] = material
    return library


def _fold(name):
    """Names compare without case, and with spaces and hyphens as underscores ("Cast Iron" = cast_iron)."""
    return str(name).casefold().replace(" ", "_").replace("-", "_")


def get_material(name: str, library: Mapping[str, Material] | None = None) -> Material:
    """Look a material up by name (case-insensitive), suggesting close names.

    Parameters
    ----------
    name : str
        Material name; case, spaces and hyphens do not matter
        ("EN-GJS-400-18" finds ``en_gjs_400_18``).
    library : mapping of str to Material, optional
        Where to look; every built-in material by default.

    Returns
    -------
    Material

    Raises
    ------
    ValueError
        If no material has that name; the message lists the closest matches.
    """
    if library is None:
        library = builtin_materials(default_only=False)
    if name in library:
        return library[name]
    folded = {_fold(key): key for key in library}
    key = _fold(name)
    if key in folded:
        return library[folded[key]]
    close = closest(key, folded)
    hint = f"; did you mean {shorten(folded[close])}?" if close else f"; known materials are {sorted(library)}"
    raise ValueError(f"material {shorten(name)} is not known{hint}")
