"""The [[shaft]]s a flywheel may sit on, and the efficiencies from the motor to the reference shaft."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_magnitude
from flyopt.machine.transmission import Shaft, series_efficiency
from flyopt.units import inertia_from_gd2, quantity

if TYPE_CHECKING:
    from collections.abc import Iterable

RATIO_RANGE = (1e-6, 1e6)
"""Allowed speed ratio ω_shaft/ω_reference of a [[shaft]]: inertias scale as its square, beyond it they overflow."""


def read_shafts(raw: object) -> tuple[Shaft, ...]:
    """The [[shaft]] tables (the reference shaft alone when the scene gives none)."""
    if raw is None:
        return (Shaft("reference", 1.0),)
    if not isinstance(raw, list) or not raw:
        raise SceneError("shaft", "must be an array of tables: [[shaft]] with name and speed_ratio")
    shafts, seen = [], set()
    for k, item in enumerate(raw):
        where = f"shaft[{k}]"
        table = Table(item, where, {"name", "speed_ratio", "efficiency", "diameter", "inertia", "gd2", "description"})
        name = table.require("name")
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{where}.name", f"must be a non-empty string, got {shorten(name)}")
        if name in seen:
            raise SceneError(f"{where}.name", f"shaft {shorten(name)} is given twice")
        seen.add(name)
        ratio = table.quantity("speed_ratio", "dimensionless", required=True)
        if ratio <= 0:
            raise SceneError(f"{where}.speed_ratio", f"must be positive (ω_shaft/ω_reference), got {shorten(ratio)}")
        check_magnitude(
            ratio,
            f"{where}.speed_ratio",
            table.raw("speed_ratio"),
            *RATIO_RANGE,
            "",
            "ω_shaft/ω_reference of a gear train",
        )
        eff = read_efficiency(table.get("efficiency"), f"{where}.efficiency") if table.has("efficiency") else 1.0
        diameter = table.quantity("diameter", "length")
        if diameter is not None and diameter <= 0:
            raise SceneError(
                f"{where}.diameter", f"must be positive (the shaft seat), got {shorten(table.raw('diameter'))}"
            )
        shafts.append(Shaft(name, ratio, eff, diameter, _shaft_inertia(table, where)))
    return tuple(shafts)


def _shaft_inertia(table, where):
    """The inertia already on a [[shaft]], about its axis [kg*m^2]: ``inertia``, or ``gd2`` (GD² = 4 g J), or 0."""
    if table.has("inertia") and table.has("gd2"):
        raise SceneError(f"{where}.gd2", "give either inertia or gd2, not both (the same inertia, GD² = 4 g J)")
    key = "gd2" if table.has("gd2") else "inertia"
    if not table.has(key):
        return 0.0
    value = table.quantity(key, "flywheel_moment" if key == "gd2" else "inertia")
    if not (math.isfinite(value) and value >= 0):
        raise SceneError(
            f"{where}.{key}",
            f"must be a finite number >= 0 (the inertia already turning with the shaft), got {shorten(table.raw(key))}",
        )
    return inertia_from_gd2(value) if key == "gd2" else value


def reference_efficiency(shafts: Iterable[Shaft]) -> float:
    """Efficiency from the motor to the reference shaft: that of the shaft turning at ratio 1."""
    at_reference = {s.efficiency for s in shafts if s.speed_ratio == 1.0}
    if len(at_reference) > 1:
        raise SceneError(
            "machine.efficiency",
            "several shafts turn at the reference speed with different "
            "efficiencies; say which applies with machine.efficiency",
        )
    return at_reference.pop() if at_reference else 1.0


def read_efficiency(raw: object, where: str) -> float:
    """An efficiency in (0, 1], or a list of stage efficiencies in series (their product)."""
    return series_efficiency(read_stages(raw, where))


def read_stages(raw: object, where: str) -> tuple[float, ...]:
    """Stage efficiencies in series: one number in (0, 1], or a non-empty list of them, each named in an error."""
    stages = raw if isinstance(raw, list) else [raw]
    if not stages:
        raise SceneError(where, "must be a number in (0, 1] or a non-empty list of stage efficiencies")
    etas = []
    for k, s in enumerate(stages):
        label = f"{where}[{k}]" if isinstance(raw, list) else where
        eta = quantity(s, "dimensionless", label)
        if not 0 < eta <= 1:
            raise SceneError(label, f"must lie in (0, 1], got {shorten(s)}")
        etas.append(eta)
    return tuple(etas)
