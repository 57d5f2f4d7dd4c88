"""The mounting shaft's checks in the text of ``flyopt solve`` (docs/flywheel-design.md, section 26)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from flyopt.design.combination import shaft_label
from flyopt.report.display import (
    DEFAULT,
    DEFAULT_DIGITS,
    UTILISATION_DIGITS,
    mode_shape,
    quantity_text,
    said_text,
    unit,
)
from flyopt.report.text import formatters, number, table
from flyopt.units import rpm_to_rad_s

if TYPE_CHECKING:
    from flyopt.design.shaft.check import ShaftCheck, ShaftLimit
    from flyopt.design.shaft.cycle import ShaftReport
    from flyopt.machine.torsion import CriticalSpeed

__all__ = [
    "ModeRow",
    "SpringRow",
    "shaft_report",
    "limit_row",
    "limit_value",
    "seat_words",
    "train_lines",
    "train_rows",
]


@dataclass(frozen=True)
class ModeRow:
    """One torsional mode of a drive train as the text and the report show it (SI)."""

    mode: int
    frequency_hz: float
    shape: tuple[float, ...]  # each inertia's, scaled to a largest entry of 1
    nearest: CriticalSpeed | None  # the critical speed of this mode nearest the running range


@dataclass(frozen=True)
class SpringRow:
    """One elastic element of a drive train and its forced response at the mean speed (SI)."""

    name: str
    kind: str
    stiffness: float  # [N*m/rad] on its own shaft
    torque_bound: float  # sum over the orders of |T_q| [N*m]
    top_order: float | None  # the order of the largest |T_q|
    top_torque: float | None  # that |T_q| [N*m]


def train_rows(check: ShaftCheck) -> tuple[list[ModeRow], list[SpringRow]] | None:
    """The drive train's modes and springs with what each shows (None without a train): the one place the
    text (:func:`train_lines`) and the report (``ShaftSection.train_tables``) read them from."""
    train, torsional = check.train, check.torsional
    if train is None or torsional is None:
        return None
    modes = [
        ModeRow(
            m,
            float(f),
            tuple(float(v) for v in train.shapes[:, m - 1]),
            min((cs for cs in torsional.critical if cs.mode == m), key=lambda cs: cs.margin, default=None),
        )
        for m, f in enumerate(train.modes.frequencies_hz, start=1)
    ]
    springs = []
    for e, (name, kind, k) in enumerate(train.built.springs):
        row = train.shaft_torques[e]
        top = int(np.argmax(row)) if row.size else -1
        springs.append(
            SpringRow(
                name,
                kind,
                float(k),
                float(train.torque_bound[e]),
                None if top < 0 else float(train.orders[top]),
                None if top < 0 else float(row[top]),
            )
        )
    return modes, springs


def limit_value(limit: ShaftLimit, value: float, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """A limit's value (or allowed value) in the unit system, by its quantity's field, to ``digits`` figures."""
    from flyopt.design.shaft.check import JSON_NAMES  # here: a report without a described shaft needs no checks

    q, _ = formatters(units, digits)
    return q(limit.si(value), JSON_NAMES[limit.kind])  # the output field it is shown as, as --json names it


def limit_row(limit: ShaftLimit, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """A limit's row of the shaft check's table, the text's and the report's: kind, where, value, allowed,
    utilisation, verdict. A key's place names the torque it is checked at, the train's peak on the wheel as
    built: the design's key line gives the key at the flywheel the cycle requires, a slightly different torque
    (four-cylinder-engine-shaft: 386.2 against 386 N·m, 25.02 against 25.01 MPa)."""
    where = said_text(limit.where, units, digits)
    if limit.kind == "key":
        q, _ = formatters(units, digits)
        where += f", at the wheel's peak torque as built {q(limit.torque, 'key_torque')}"
    return [
        limit.kind,
        where,
        limit_value(limit, limit.value, units, digits),
        limit_value(limit, limit.allowed, units, digits),
        number(limit.utilisation, UTILISATION_DIGITS),
        "holds" if limit.holds else "FAILS",
    ]


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
            *seat_lines(rep, units, digits),
            f"  loads: weight {q(c.weight, 'weight')}, permissible unbalance force "
            f"{q(c.unbalance, 'unbalance_force')} (ISO 21940-11), torque midrange "
            f"{q(c.torque_mean, 'torque_mean')} and alternating {q(c.torque_alternating, 'torque_alternating')}"
            + (
                f" (the train's forced response at the seat, its orders superposed; rigid body "
                f"{q(c.torque_alternating_rigid, 'torque_alternating')})"
                if c.torque_source == "forced response"
                else ""
            ),
            f"  running range {q(rpm_to_rad_s(c.speed_range_rpm[0]), 'speed_range')} to "
            f"{q(rpm_to_rad_s(c.speed_range_rpm[1]), 'speed_range')}",
        ]
        rows = [limit_row(lim, units, digits) for lim in c.limits]
        lines += [
            "  " + line
            for line in table(
                ["limit", "where", "value", "allowed", "utilisation", ""], rows, ["<", "<", ">", ">", ">", "<"]
            )
        ]
        lines.append(f"  binding: {binding_words(c, rep.sensitivity, units, digits)}")
        lines += train_lines(c, units, digits)
    return lines


def binding_words(check: ShaftCheck, sensitivity: float, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """The binding limit of a shaft's check, its utilisation and d(utilisation)/d(wheel mass) per the system's
    unit of mass (``sensitivity`` [1/kg]), the text's and the report's words: "fatigue at the shoulder at
    480 mm, utilisation 0.595; d(utilisation)/d(wheel mass) 4.24e-05 per lb"."""
    label, kilograms = unit("mass", units)  # a wheel mass unit is this many kg
    return (
        f"{check.binding.kind} {said_text(check.binding.where, units, digits)}, utilisation {number(check.binding.utilisation, UTILISATION_DIGITS)}; "
        f"d(utilisation)/d(wheel mass) {number(sensitivity * kilograms, 3)} per {label}"
    )


def seat_words(rep: ShaftReport, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str | None:
    """What a designed seat diameter is, in words (None where the scene gives the seat)."""
    if rep.seat_diameter is None:
        return None
    q, _ = formatters(units, digits)
    return f"seat diameter {q(rep.seat_diameter, 'seat_diameter')}, {seat_choice_words(rep, units, digits)}"


def seat_choice_words(rep: ShaftReport, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> str:
    """How a designed seat was chosen (docs/flywheel-design.md, section 26), the text's and the report's words
    after its diameter: the NLP's continuous d* rounded up to the series, the first value from there the
    shaft's post-check passes, and what set it (with the NLP row's d(mass)/d(required factor) where one did)."""
    q, _ = formatters(units, digits)
    words = 'designed (the steps marked "design"): '

    d_star = rep.seat_continuous
    if d_star is not None and math.isfinite(d_star):
        words += (
            f"the NLP's continuous optimum d* {q(d_star, 'seat_diameter_continuous')} rounded up to ISO 3 "
            f"{rep.seat_series}, then the first value from there at which this shaft carries the wheel designed on it"
        )
    else:
        words += (
            f"the smallest of ISO 3 {rep.seat_series} at which this shaft carries the wheel designed on it "
            "(no continuous optimum from the NLP: walked from the torque-only bound)"
        )
    if rep.seat_set_by:
        words += f"; set by {said_text(rep.seat_set_by, units, digits)}"
    if rep.seat_sensitivity is not None and math.isfinite(rep.seat_sensitivity):
        words += (
            f"; +1 on its required safety factor adds {q(rep.seat_sensitivity, 'seat_dmass_dfactor')} (the seat torque "
            "held)"
        )
    return words


def seat_lines(rep: ShaftReport, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The designed seat's line of the text (none where the scene gives the seat)."""
    words = seat_words(rep, units, digits)
    return [] if words is None else [f"  {words}"]


def train_lines(check: ShaftCheck, units: str = DEFAULT, digits: int = DEFAULT_DIGITS) -> list[str]:
    """The drive train's nodes, every elastic mode with its shape and nearest critical speed, and the forced
    response's alternating torque in each elastic element (nothing without a train)."""
    found = train_rows(check)
    if found is None or check.train is None:
        return []
    modes, springs = found
    train = check.train
    q, _ = formatters(units, digits)
    built = train.built
    lines = [
        f"  torsional train, seen from this shaft ({len(built.nodes)} inertias, motor end first; the net "
        f"torque enters at the {built.nodes[built.load_node]}): " + " | ".join(built.nodes),
    ]
    rows = []
    for mode in modes:
        near = mode.nearest
        where = (
            "-"
            if near is None
            else (
                f"order {near.order:.4g}: {q(rpm_to_rad_s(near.speed_rpm), 'critical_speed')}"
                + (" (in the range)" if near.in_range else f" ({number(100 * near.margin, 3)} % clear)")
            )
        )
        shape = mode_shape(mode.shape)
        rows.append([str(mode.mode), f"{number(mode.frequency_hz, digits)} Hz", shape, where])
    lines += [
        "  " + line
        for line in table(["mode", "frequency", "shape (each inertia, largest 1)", "nearest critical speed"], rows)
    ]
    lines.append(
        f"  forced response at the mean speed {q(rpm_to_rad_s(train.speed_rpm), 'speed_range')} to "
        f"{train.orders.size} orders (modal damping {number(100 * train.damping_ratio, 3)} %), on each "
        "element's own shaft:"
    )
    rows = [
        [
            spring.name,
            spring.kind,
            quantity_text(spring.stiffness, "torsional_stiffness", units, digits),
            q(spring.torque_bound, "torque_alternating"),
            "-"
            if spring.top_order is None
            else f"{spring.top_order:.4g}: {q(spring.top_torque, 'torque_largest_order')}",
        ]
        for spring in springs
    ]
    lines += [
        "  " + line
        for line in table(
            ["element", "kind", "stiffness", "sum |T_q|", "largest order"],
            rows,
            ["<", "<", ">", ">", "<"],
        )
    ]
    return lines
