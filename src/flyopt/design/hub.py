"""The hub of a flywheel: its outer diameter and length from the machine-design proportions.

:func:`hub_proportions` gives the ranges of a hub's outer diameter and length
for a shaft seat from the rules of thumb (cast iron, steel, the flywheel
textbook's). These are proportions from experience, not a strength check: the
key (:mod:`flyopt.design.key`) bounds the hub's length from below on its own.

The proportions live in the package data file ``flyopt/data/keys.toml`` with
their sources; every argument and result here is SI [m].
"""

from __future__ import annotations

import functools
import math
from importlib import resources
from typing import NamedTuple

from flyopt._toml import tomllib
from flyopt.names import unknown
from flyopt.validate import positive

__all__ = ["HubProportions", "hub_proportions", "hub_rules"]

_DATA_FILE = "keys.toml"
_ORIGIN = f"flyopt/data/{_DATA_FILE}"


def _ratio_pair(table, key, kind):
    pair = table.get(key)
    if (
        not isinstance(pair, list)
        or len(pair) != 2
        or not all(isinstance(x, (int, float)) and math.isfinite(x) and x > 0 for x in pair)
        or pair[0] > pair[1]
    ):
        raise ValueError(
            f"{_ORIGIN}: hub_proportions.{kind}.{key} must be [min, max] with 0 < min <= max, got {pair!r}"
        )
    return float(pair[0]), float(pair[1])


@functools.lru_cache(maxsize=1)
def _load():
    """Read and check the hub proportions of ``keys.toml`` once: kind -> (d ratios, l ratios, source)."""
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    proportions = {}
    for kind, entry in data["hub_proportions"].items():
        if not entry.get("source", "").strip():
            raise ValueError(f"{_ORIGIN}: hub_proportions.{kind} cites no source")
        proportions[kind] = (_ratio_pair(entry, "d_ratio", kind), _ratio_pair(entry, "l_ratio", kind), entry["source"])
    return proportions


class HubProportions(NamedTuple):
    """Ranges of a hub's outer diameter and length [m]."""

    d_hub_min: float
    d_hub_max: float
    l_hub_min: float
    l_hub_max: float


def hub_rules() -> tuple[str, ...]:
    """The names of the hub proportions of ``keys.toml`` (a material's ``hub_rule``)."""
    return tuple(_load())


def hub_proportions(d: float, kind: str = "cast_iron") -> HubProportions:
    """Outer diameter and length of a hub from the machine-design rules of thumb.

    Parameters
    ----------
    d : float
        Shaft seat diameter [m].
    kind : str
        Which rule of ``flyopt/data/keys.toml``: ``"cast_iron"`` (grey cast
        iron hub with a parallel key, D/d 1.8-2, L/d 1.5-2), ``"steel"`` (steel
        or cast steel hub with a parallel key, D/d 1.6-1.8, L/d 1.2-1.8) or
        ``"cast_iron_flywheel"`` (the flywheel textbook rule D = 2 d,
        L = 2-2.5 d).

    Returns
    -------
    HubProportions
        (d_hub_min, d_hub_max, l_hub_min, l_hub_max) [m].

    Raises
    ------
    ValueError
        If ``d`` is not a positive finite number or ``kind`` is unknown (the
        message lists the closest names).

    Notes
    -----
    These are proportions from experience, not a strength check: the key
    check (:func:`flyopt.design.key.hub_length_for_key`) bounds the length from below on its own.
    """
    d = positive(d, "shaft diameter d [m]")
    proportions = _load()
    if kind not in proportions:
        raise ValueError(f"hub proportions kind {unknown(kind, proportions)}")
    (d_lo, d_hi), (l_lo, l_hi), _ = proportions[kind]
    return HubProportions(d_lo * d, d_hi * d, l_lo * d, l_hi * d)
