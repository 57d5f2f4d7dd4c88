"""Flywheel materials: density, safe rim speed, allowable stress and cost.

The built-in materials live in the package data file
``flyopt/data/materials.toml``, each with its source; nothing numeric about a
material is written in this module. Users extend or override them with their
own materials (:func:`make_material`, :func:`material_library`).

A rotating thin ring carries the hoop stress

    sigma ~ rho v^2,

with v the peripheral speed at the outer diameter, so a material has a safe
rim speed v_max = sqrt(sigma_allow / rho) when only its allowable stress is
known.

References
----------
.. [1] flyopt domain notes, docs/flywheel-design.md, section 10 (rim speed
   limits: cast iron 36 m/s, cast steel 50 m/s).
"""

from __future__ import annotations

import difflib
import functools
import math
import sys
from dataclasses import dataclass
from importlib import resources
from typing import Iterable, Mapping

from flyopt.errors import shorten

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised only on Python 3.10
    import tomli as tomllib

__all__ = [
    "Material",
    "builtin_materials",
    "make_material",
    "material_library",
    "get_material",
    "rim_speed_from_stress",
]

_DATA_FILE = "materials.toml"
_KNOWN_KEYS = {"density", "max_rim_speed", "allowable_stress", "cost", "source"}


def _positive_finite(value, what, name):
    """Return ``value`` as a float, raising ValueError unless finite and > 0."""
    try:
        number = float(value)
    except (TypeError, ValueError) as err:
        raise ValueError(
            f"material {shorten(name)}: {what} must be a positive number, got {shorten(value)}"
        ) from err
    if not math.isfinite(number) or number <= 0.0:
        raise ValueError(
            f"material {name!r}: {what} must be a positive finite number, got {value!r}"
        )
    return number


@dataclass(frozen=True)
class Material:
    """A flywheel material.

    Parameters
    ----------
    name : str
        Name used in scenes and reports, e.g. ``"cast_iron"``.
    density : float
        Density rho [kg/m^3].
    max_rim_speed : float
        Safe peripheral speed at the outer diameter v_max [m/s].
    allowable_stress : float or None
        Allowable hoop stress [Pa]; when known the design reports a safety
        factor sigma_allow / (rho v^2).
    cost : float or None
        Cost per kilogram [currency/kg], needed for the ``cost`` objective.
    source : str
        Where the numbers come from.

    Raises
    ------
    ValueError
        If a number is not positive and finite, or the name is empty.
    """

    name: str
    density: float
    max_rim_speed: float
    allowable_stress: float | None = None
    cost: float | None = None
    source: str = ""

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"material name must be a non-empty string, got {self.name!r}")
        object.__setattr__(self, "density",
                           _positive_finite(self.density, "density [kg/m^3]", self.name))
        object.__setattr__(self, "max_rim_speed",
                           _positive_finite(self.max_rim_speed, "max_rim_speed [m/s]", self.name))
        if self.allowable_stress is not None:
            object.__setattr__(self, "allowable_stress", _positive_finite(
                self.allowable_stress, "allowable_stress [Pa]", self.name))
        if self.cost is not None:
            try:
                cost = float(self.cost)
            except (TypeError, ValueError) as err:
                raise ValueError(f"material {self.name!r}: cost [1/kg] must be a number "
                                 f">= 0, got {self.cost!r}") from err
            if not math.isfinite(cost) or cost < 0.0:
                raise ValueError(f"material {self.name!r}: cost [1/kg] must be a finite "
                                 f"number >= 0, got {self.cost!r}")
            object.__setattr__(self, "cost", cost)
        if not isinstance(self.source, str):
            raise ValueError(f"material {self.name!r}: source must be a string, "
                             f"got {self.source!r}")


def rim_speed_from_stress(allowable_stress, density):
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


def make_material(name, density, max_rim_speed=None, allowable_stress=None,
                  cost=None, source=""):
    """Build a user material; the rim speed may come from the allowable stress.

    Parameters
    ----------
    name : str
        Material name.
    density : float
        Density [kg/m^3].
    max_rim_speed : float, optional
        Safe rim speed [m/s]. If omitted, v_max = sqrt(sigma / rho) from
        ``allowable_stress``.
    allowable_stress : float, optional
        Allowable hoop stress [Pa]. At least one of ``max_rim_speed`` and
        ``allowable_stress`` must be given; when both are, the rim speed is
        used as given and the stress gives the reported safety factor.
    cost : float, optional
        Cost per kilogram [currency/kg].
    source : str, optional
        Where the numbers come from.

    Returns
    -------
    Material

    Raises
    ------
    ValueError
        If neither ``max_rim_speed`` nor ``allowable_stress`` is given, or a
        value is not a positive finite number.
    """
    density = _positive_finite(density, "density [kg/m^3]", name)
    if max_rim_speed is None:
        if allowable_stress is None:
            raise ValueError(
                f"material {name!r}: give max_rim_speed [m/s] or allowable_stress [Pa] "
                f"(the rim speed then follows from sigma = rho v^2); neither was given")
        allowable_stress = _positive_finite(allowable_stress, "allowable_stress [Pa]", name)
        max_rim_speed = rim_speed_from_stress(allowable_stress, density)
    return Material(name=name, density=density, max_rim_speed=max_rim_speed,
                    allowable_stress=allowable_stress, cost=cost, source=source)


def _material_from_table(name, table, origin):
    """Build a Material from one TOML table, naming ``origin`` on error."""
    unknown = set(table) - _KNOWN_KEYS
    if unknown:
        raise ValueError(f"{origin}: material {name!r} has unknown keys {sorted(unknown)}; "
                         f"allowed are {sorted(_KNOWN_KEYS)}")
    if "density" not in table:
        raise ValueError(f"{origin}: material {name!r} has no density")
    return make_material(name, table["density"],
                         max_rim_speed=table.get("max_rim_speed"),
                         allowable_stress=table.get("allowable_stress"),
                         cost=table.get("cost"), source=table.get("source", ""))


@functools.lru_cache(maxsize=1)
def _load_builtin():
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    origin = f"flyopt/data/{_DATA_FILE}"
    materials = {}
    for name, table in data.items():
        material = _material_from_table(name, table, origin)
        if not material.source:
            raise ValueError(f"{origin}: built-in material {name!r} cites no source")
        materials[name] = material
    return materials


def builtin_materials() -> dict[str, Material]:
    """The built-in materials, read once from ``flyopt/data/materials.toml``.

    Returns
    -------
    dict of str to Material
        A fresh dictionary (safe to modify) keyed by material name.
    """
    return dict(_load_builtin())


def material_library(user_materials: Iterable[Material] | Mapping[str, Material] = ()
                     ) -> dict[str, Material]:
    """Built-in materials extended or overridden by the user's.

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
    library = builtin_materials()
    seen = set()
    for material in user_materials:
        if not isinstance(material, Material):
            raise ValueError(f"user materials must be Material objects, got {material!r}")
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
        Material name.
    library : mapping of str to Material, optional
        Where to look; the built-in materials by default.

    Returns
    -------
    Material

    Raises
    ------
    ValueError
        If no material has that name; the message lists the closest matches.
    """
    if library is None:
        library = builtin_materials()
    if name in library:
        return library[name]
    folded = {_fold(key): key for key in library}
    key = _fold(name)
    if key in folded:
        return library[folded[key]]
    close = difflib.get_close_matches(key, list(folded), n=3, cutoff=0.5)
    hint = (f"; best matches are {[folded[c] for c in close]}" if close
            else f"; known materials are {sorted(library)}")
    raise ValueError(f"material {name!r} not recognised{hint}")
