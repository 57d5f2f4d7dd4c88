"""The mounting shaft's checks in the text of ``flyopt solve`` (docs/flywheel-design.md, section 26)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from flyopt.design.combination import shaft_label
from flyopt.report.display import DEFAULT
from flyopt.report.text import formatters, number, table

if TYPE_CHECKING:
    from flyopt.design.shaft.check import ShaftLimit
    from flyopt.design.shaft.cycle import ShaftReport

__all__ = ["shaft_report", "limit_value"]

#: The output field (flyopt.outputs.quantities) each kind of limit is shown as.
_FIELDS = {
    "fatigue": "fatigue_factor",
    "yield": "yield_factor",
    "slope": "slope",
    "deflection": "deflection",
    "lateral": "critical_speed",
    "torsional": "critical_speed",
}


def limit_value(limit: ShaftLimit, value: float, units: str = DEFAULT) -> str:
    """A limit's value (or allowed value) in the unit system, by its quantity's field."""
    q, _ = formatters(units)
    scale = math.pi / 30.0 if limit.unit == "rpm" else 1.0
    return q(value * scale, _FIELDS[limit.kind], 4)


def shaft_report(reports: Sequence[ShaftReport], units: str = DEFAULT) -> list[str]:
    """Each described shaft's limits with the chosen wheel: value, allowed, utilisation; the loads; the binding
    limit's sensitivity to the wheel's mass."""
    q, _ = formatters(units)
    lines: list[str] = []
    for rep in reports:
        c = rep.check
        lines += [
            "",
            f"Shaft check: the {shaft_label(rep.shaft)} ({rep.material}) with the chosen wheel "
            "(a post-check of each design: a combination whose shaft fails is infeasible)",
            f"  loads: weight {q(c.weight, 'weight', 4)}, permissible unbalance force "
            f"{q(c.unbalance, 'unbalance_force', 4)} (ISO 21940-11), torque midrange "
            f"{q(c.torque_mean, 'torque_mean', 4)} and alternating {q(c.torque_alternating, 'torque_alternating', 4)}",
            f"  running range {q(c.speed_range_rpm[0] * math.pi / 30.0, 'speed_range', 4)} to "
            f"{q(c.speed_range_rpm[1] * math.pi / 30.0, 'speed_range', 4)}",
        ]
        rows = [
            [
                lim.kind,
                lim.where,
                limit_value(lim, lim.value, units),
                limit_value(lim, lim.allowed, units),
                number(lim.utilisation, 3),
                "holds" if lim.holds else "FAILS",
            ]
            for lim in c.limits
        ]
        lines += [
            "  " + line
            for line in table(
                ["limit", "where", "value", "allowed", "utilisation", ""], rows, ["<", "<", ">", ">", ">", "<"]
            )
        ]
        binding = c.binding
        lines.append(
            f"  binding: {binding.kind} {binding.where}, utilisation {number(binding.utilisation, 3)}; "
            f"d(utilisation)/d(wheel mass) {number(rep.sensitivity, 3)} per kg"
        )
    return lines
