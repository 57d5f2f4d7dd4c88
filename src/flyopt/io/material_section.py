"""The scene's own [[material]]s, extending or overriding the built-in ones."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from flyopt.design.castability import WALL_RANGE, WALL_WHY
from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SAFETY_RANGE, SAFETY_WHY, Table, check_count, check_magnitude
from flyopt.units import MAGNITUDES

if TYPE_CHECKING:
    from flyopt.design.materials import Material

#: The strength fields of a [[material]] (beyond density, rim speed, allowable stress and cost).
_MATERIAL_STRENGTH = {
    "elastic_modulus": "stress",
    "poisson_ratio": "dimensionless",
    "tensile_strength": "stress",
    "yield_strength": "stress",
    "ductile": "bool",
    "safety_factor": "dimensionless",
    "min_wall": "length",
    "bearing_pressure": "stress",
}


#: Fastest safe rim speed a material may have [m/s]: beyond any rotor's burst speed.
MAX_RIM_SPEED = 1e4

#: Bounds of a [[material]]'s numbers (SI): beyond them no flywheel material lies and the sizing overflows.
MATERIAL_MAGNITUDES = {
    "density": (*MAGNITUDES["density"][:2], "kg/m^3", MAGNITUDES["density"][2]),  # every density's
    "max_rim_speed": (1e-3, MAX_RIM_SPEED, "m/s", "a millimetre a second to 10 km/s, beyond any rotor's burst"),
    "allowable_stress": (1.0, 1e11, "Pa", "1 Pa to 100 GPa, beyond any material's strength"),
    # what a solid a wheel is made of has: beyond them a value is one written in other units (169000 meaning
    # N/mm^2 is 169 kPa as a plain number), which the Lame stresses would take as given
    "elastic_modulus": (1e8, 1.2e12, "Pa", "from a polymer's 0.1 GPa to beyond diamond's 1,050 GPa"),
    "tensile_strength": (1e5, 1e11, "Pa", "0.1 MPa to 100 GPa, beyond any material's strength"),
    "yield_strength": (1e5, 1e11, "Pa", "0.1 MPa to 100 GPa, beyond any material's strength"),
    "bearing_pressure": (1e5, 1e11, "Pa", "0.1 MPa to 100 GPa, beyond any material's strength"),
    # the bounds of design.castability.min_wall (a plain 6 meaning mm is 6 m)
    "min_wall": (*WALL_RANGE, "m", WALL_WHY),
}


def _check_rim_speed(material: Material, where: str) -> None:
    """Refuse a material whose safe rim speed, given or from σ = ρ v², is beyond any rotor's (it overflows)."""
    try:
        speed = material.rim_speed_limit()
    except ValueError:
        return  # strengths without a safety factor: no rim speed until a design's factor gives one
    if not speed <= MAX_RIM_SPEED:
        raise SceneError(
            where,
            f"its safe rim speed sqrt(allowable_stress / density) = {speed:.3g} m/s is beyond any rotor's "
            f"(allowed: up to {MAX_RIM_SPEED:g} m/s): check its density and allowable stress",
        )


MAX_MATERIALS = 256
"""Most [[material]] tables a scene may give: each a design is made in (2,000 took 10 s; a scene file's 100 MB
would hold 300,000)."""


def read_materials(raw: object) -> tuple[Material, ...]:
    """The [[material]] tables: the scene's own materials (none when it gives none)."""
    if raw is None:
        return ()
    if not isinstance(raw, list):
        raise SceneError("material", "must be an array of tables: [[material]] with name and density")
    check_count(raw, "material", MAX_MATERIALS, "[[material]] tables")
    seen: set[str] = set()
    return tuple(read_material(item, k, seen) for k, item in enumerate(raw))


def read_material(item: object, k: int, seen: set[str]) -> Material:
    """The k-th [[material]] table (from 0) read alone; ``seen`` holds the names of those before it, and takes
    this one's (a name given twice is refused). ``flyopt check`` reads each table so, to name every wrong one."""
    from flyopt.design.materials import make_material

    where = f"material[{k}]"
    table = Table(
        item,
        where,
        {
            "name",
            "density",
            "max_rim_speed",
            "allowable_stress",
            "cost",
            "source",
            "description",
            "hub_rule",
            *_MATERIAL_STRENGTH,
        },
    )
    name = table.unique_name("material", seen)
    strength = "tensile_strength" if table.get("ductile") is not True else "yield_strength"
    if not (table.has("max_rim_speed") or table.has("allowable_stress") or table.has(strength)):
        raise SceneError(
            where,
            f"give max_rim_speed, allowable_stress (v_max then follows from σ = ρ v²) "
            f"or {strength} (the allowable stress is it over the safety factor)",
        )
    values: dict[str, Any] = {  # make_material's keywords: numbers, a flag, a hub rule
        "density": table.quantity("density", "density", required=True, own_range=True),
        "max_rim_speed": table.quantity("max_rim_speed", "speed", own_range=True),
        "allowable_stress": table.quantity("allowable_stress", "stress", own_range=True),
        "cost": table.quantity("cost", "cost_per_mass"),
    }
    for key, value in values.items():
        if value is not None and (value < 0 or (value == 0 and key != "cost")):
            raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table.raw(key))}")
        if value is not None and key in MATERIAL_MAGNITUDES:
            check_magnitude(value, f"{where}.{key}", table.raw(key), *MATERIAL_MAGNITUDES[key])
    for key, dimension in _MATERIAL_STRENGTH.items():
        if not table.has(key):
            continue
        if dimension == "bool":
            if not isinstance(table.get(key), bool):
                raise SceneError(f"{where}.{key}", f"must be true or false, got {shorten(table.raw(key))}")
            values[key] = table.get(key)
            continue
        value = table.quantity(
            key, dimension, required=True, own_range=key in MATERIAL_MAGNITUDES or key == "safety_factor"
        )
        if key == "poisson_ratio":
            if not 0.0 <= value < 0.5:
                raise SceneError(f"{where}.{key}", f"must be in [0, 0.5), got {shorten(table.raw(key))}")
        elif key == "safety_factor":
            if value < 1.0:
                raise SceneError(f"{where}.{key}", f"must be >= 1, got {shorten(table.raw(key))}")
            check_magnitude(value, f"{where}.{key}", table.raw(key), *SAFETY_RANGE, "", SAFETY_WHY)
        elif value <= 0:
            raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table.raw(key))}")
        if key in MATERIAL_MAGNITUDES:
            check_magnitude(value, f"{where}.{key}", table.raw(key), *MATERIAL_MAGNITUDES[key])
        values[key] = value
    if table.has("hub_rule"):
        from flyopt.design.hub import hub_rules

        rule = table.get("hub_rule")
        if not isinstance(rule, str) or rule not in hub_rules():
            raise SceneError(
                f"{where}.hub_rule", f"{shorten(rule)} is not a hub rule (allowed: {', '.join(hub_rules())})"
            )
        values["hub_rule"] = rule
    source = table.get("source", "scene file")
    if not isinstance(source, str):
        raise SceneError(f"{where}.source", f"must be text (where the values come from), got {shorten(source)}")
    try:
        material = make_material(name, source=source, **values)
    except ValueError as err:
        raise SceneError(where, str(err)) from None
    _check_rim_speed(material, where)
    return material
