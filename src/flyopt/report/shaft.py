"""The mounting shaft's checks in the text of ``flyopt solve`` (docs/flywheel-design.md, section 26)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from flyopt.design.combination import shaft_label
from flyopt.design.shaft.check import JSON_NAMES
from flyopt.report.display import DEFAULT, DEFAULT_DIGITS, quantity_text
from flyopt.report.text import formatters, number, table

if TYPE_CHECKING:
    from flyopt.design.shaft.check import ShaftCheck, ShaftLimit
    from flyopt.design.shaft.cycle import ShaftReport

__all__ = ["shaft_report", "limit_value", "train_lines"]


def limit_value(limit: ShaftLimit, value: float, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A limit's value (or allowed value) in the unit system, by its quantity's field, to ``digits`` figures."""
    q, _ = formatters(units, digits)
    scale = math.pi / 30.0 if limit.unit == "rpm" else 1.0
    return q(value * scale, JSON_NAMES[limit.kind])  # the output field it is shown as, as --json names it


def shaft_report(reports: Sequence[ShaftReport], units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """Each described shaft's limits with the chosen wheel: value, allowed, utilisation; the loads; the binding
    limit's sensitivity to the wheel's mass; numbers to ``digits`` significant figures."""
    q, _ = formatters(units, digits)
    lines: list[str] = []
    for rep in reports:
        c = rep.check
        lines += [
            "",
            f"Shaft check: the {shaft_label(rep.shaft)} ({rep.material_name or rep.material}) with the chosen wheel "
            "(a post-check of each design: a combination whose shaft fails is infeasible)",
            f"  loads: weight {q(c.weight, 'weight')}, permissible unbalance force "
            f"{q(c.unbalance, 'unbalance_force')} (ISO 21940-11), torque midrange "
            f"{q(c.torque_mean, 'torque_mean')} and alternating {q(c.torque_alternating, 'torque_alternating')}",
            f"  running range {q(c.speed_range_rpm[0] * math.pi / 30.0, 'speed_range')} to "
            f"{q(c.speed_range_rpm[1] * math.pi / 30.0, 'speed_range')}",
        ]
        rows = [
            [
                lim.kind,
                lim.where,
                limit_value(lim, lim.value, units, digits),
                limit_value(lim, lim.allowed, units, digits),
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
        lines += train_lines(c, units, digits)
    return lines


def train_lines(check: ShaftCheck, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The drive train's nodes, every elastic mode with its shape and nearest critical speed, and the forced
    response's alternating torque in each elastic element (nothing without a train)."""
    train, torsional = check.train, check.torsional
    if train is None or torsional is None:
        return []
    q, _ = formatters(units, digits)
    built = train.built
    lines = [
        f"  torsional train, seen from this shaft ({len(built.nodes)} inertias, motor end first; the net "
        f"torque enters at the {built.nodes[built.load_node]}): " + " | ".join(built.nodes),
    ]
    rows = []
    for m, f in enumerate(train.modes.frequencies_hz, start=1):
        own = [cs for cs in torsional.critical if cs.mode == m]
        near = min(own, key=lambda cs: cs.margin, default=None)
        where = (
            "-"
            if near is None
            else (
                f"order {near.order:.4g}: {q(near.speed_rpm * math.pi / 30.0, 'critical_speed')}"
                + (" (in the range)" if near.in_range else f" ({number(100 * near.margin, 3)} % clear)")
            )
        )
        shape = ", ".join(f"{v:+.2f}" for v in train.shapes[:, m - 1])
        rows.append([str(m), f"{number(float(f), digits)} Hz", shape, where])
    lines += [
        "  " + line
        for line in table(["mode", "frequency", "shape (each inertia, largest 1)", "nearest critical speed"], rows)
    ]
    lines.append(
        f"  forced response at the mean speed {q(train.speed_rpm * math.pi / 30.0, 'speed_range')} to "
        f"{train.orders.size} orders (modal damping {number(100 * train.damping_ratio, 3)} %), on each "
        "element's own shaft:"
    )
    bound = train.torque_bound
    rows = []
    for e, (name, kind, k) in enumerate(built.springs):
        row = train.shaft_torques[e]
        top = int(np.argmax(row)) if row.size else -1
        rows.append(
            [
                name,
                kind,
                quantity_text(k, "torsional_stiffness", units, digits),
                q(float(bound[e]), "torque_alternating"),
                "-" if top < 0 else f"{train.orders[top]:.4g}: {q(float(row[top]), 'torque_largest_order')}",
            ]
        )
    lines += [
        "  " + line
        for line in table(
            ["element", "kind", "stiffness", "sum |T_q|", "largest order"],
            rows,
            ["<", "<", ">", ">", "<"],
        )
    ]
    return lines
