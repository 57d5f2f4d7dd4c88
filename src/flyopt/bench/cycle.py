"""The cycle section: A_max from tabulated torque curves, flyopt's exact path against sampled rules.

flyopt's exact piecewise integration (:func:`flyopt.cycle.indicator.energy_indicator`)
against what spreadsheets and student codes do (:mod:`flyopt.bench.peers`):
resample the table at N equally spaced angles (64 ... 100,000), take the mean
torque from the same samples, chain the excess work by the rectangle,
trapezoid, ``cumulative_trapezoid`` or ``cumulative_simpson`` rule, and read
max − min; plus the trapezoid rule on the table's own points. Reference:
exact rational arithmetic (:mod:`flyopt.bench.references`) on the float
table, so the reference error is zero. The cycle cases here also feed the
hard set (:mod:`flyopt.bench.hard`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.typing import NDArray

from flyopt.bench.peers import SAMPLED_RULES, integrate_samples, sampled_a_max
from flyopt.bench.references import exact_a_max_against_mean, exact_a_max_tables
from flyopt.bench.timing import Config, Row, measure, set_ratios
from flyopt.cycle.expression import Expression
from flyopt.cycle.indicator import energy_indicator
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear

__all__ = [
    "TWO_PI",
    "CurveSpec",
    "CycleCase",
    "flyopt_curve",
    "flyopt_a_max",
    "reference_a_max",
    "table_noisy",
    "table_spike",
    "table_staircase",
    "table_ripple",
    "case_near_tangent",
    "main_cycle_cases",
    "section_cycle",
]

TWO_PI = 2.0 * math.pi
"""The cycle angle of one turn [rad]."""


CurveSpec = tuple[Any, ...]
"""A case's curve: ``("mean",)``, ``("table", x, y)`` or ``("expr", text, closed_form_a_max[, scale])``."""


@dataclass
class CycleCase:
    """A cycle to analyse and its exact answer.

    ``driving`` and ``resisting`` are ``("mean",)`` (the unknown constant
    that balances the other curve), ``("table", x, y)`` or
    ``("expr", text, closed_form_a_max)``. ``reference`` is A_max [J],
    exact up to its final rounding to float.
    """

    name: str
    driving: CurveSpec
    resisting: CurveSpec
    cycle_angle: float = TWO_PI
    kind: str = ""
    reference: float | None = None
    reference_how: str = ""

    @property
    def points(self) -> int:
        return max((len(c[1]) for c in (self.driving, self.resisting) if c[0] == "table"), default=0)

    def scaled(self, power: int) -> CycleCase:
        """The same cycle with every torque times 2**power (exact in floats)."""
        factor = math.ldexp(1.0, power)

        def scale(curve):
            if curve[0] == "table":
                return ("table", curve[1], curve[2] * factor)
            if curve[0] == "expr":
                return ("expr", curve[1], curve[2], (curve[3] if len(curve) > 3 else 1.0) * factor)
            return curve

        return CycleCase(
            self.name,
            scale(self.driving),
            scale(self.resisting),
            self.cycle_angle,
            self.kind,
            None if self.reference is None else self.reference * factor,
            self.reference_how,
        )


def flyopt_curve(curve: CurveSpec) -> Constant | PiecewiseLinear | ExpressionTorque:
    """flyopt's torque object of a case's curve (``("mean",)``, ``("table", x, y)`` or ``("expr", ...)``)."""
    if curve[0] == "mean":
        return Constant(None)
    if curve[0] == "table":
        return PiecewiseLinear(np.asarray(curve[1], float), np.asarray(curve[2], float))
    return ExpressionTorque(Expression(curve[1]), curve[3] if len(curve) > 3 else 1.0)


def flyopt_a_max(case: CycleCase) -> float:
    """A_max by flyopt's exact energy indicator (the torque objects built anew)."""
    return energy_indicator(flyopt_curve(case.driving), flyopt_curve(case.resisting), case.cycle_angle).a_max


def reference_a_max(case: CycleCase) -> float:
    """The exact A_max of a case (cached on it): rationals for tables, else the closed form."""
    if case.reference is not None:
        return case.reference
    d, r = case.driving, case.resisting
    if d[0] == "mean" and r[0] == "table":
        value, how = exact_a_max_against_mean(r[1], r[2]), "exact rational (fractions)"
    elif d[0] == "table" and r[0] == "table":
        value, how = exact_a_max_tables(d[1], d[2], r[1], r[2])[0], "exact rational (fractions)"
    elif r[0] == "expr":
        value, how = Fraction(r[2]) * Fraction(r[3] if len(r) > 3 else 1.0), "closed form"
    else:
        raise ValueError(f"no reference for cycle case {case.name!r}")
    case.reference, case.reference_how = float(value), how
    return case.reference


def table_noisy(
    n: int, rng: np.random.Generator, noise: float = 40.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """500 + 300 sin 2φ plus Gaussian noise, n equally spaced points over one turn."""
    x = np.linspace(0.0, TWO_PI, n)
    return x, 500.0 + 300.0 * np.sin(2.0 * x) + rng.normal(0.0, noise, n)


def table_spike(
    offset: float = 0.0, idle: float = 100.0, stroke_fraction: float = 0.02, peak: float = 50.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A press: a working stroke of 2 % of the cycle at 50 × the idle torque, with steps."""
    stroke = stroke_fraction * TWO_PI
    x = np.array([0.0, 1.0, 1.0, 1.0 + stroke, 1.0 + stroke, TWO_PI])
    y = offset + np.array([idle, idle, peak * idle, peak * idle, idle, idle])
    return x, y


def table_staircase(steps: int = 200) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A staircase: ``steps`` vertical steps, every crossing at a step."""
    k = np.arange(steps)
    x = np.repeat(np.linspace(0.0, TWO_PI, steps + 1), 2)[1:-1]
    y = np.repeat(1000.0 + 500.0 * np.sin(3 * k * TWO_PI / steps) + 37.0 * (k % 7), 2)
    return x, y


def table_ripple(offset: float, n: int, rng: np.random.Generator) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``offset`` N·m plus a ±1 N·m random ripple at n random angles."""
    x = np.concatenate(([0.0], np.sort(rng.uniform(0.0, TWO_PI, n - 2)), [TWO_PI]))
    return x, offset + rng.uniform(-1.0, 1.0, x.size)


def case_near_tangent(gap: float, level: float = 300.0) -> CycleCase:
    """A peak that touches (gap 0) or nearly touches a constant driving level.

    The work is balanced by a block over [5, 6] rad whose height is the exact
    surplus, so the peak at 3 rad keeps its exact distance to the level.
    """
    x = np.array([0, 1, 2, 3, 4, 5, 5, 6, 6, TWO_PI], dtype=float)

    def table(c):
        return np.array([100.0, 200.0, 100.0, level - gap, 100.0, 100.0, 100.0 + c, 100.0 + c, 100.0, 100.0])

    drive = (np.array([0.0, TWO_PI]), np.array([level, level]))
    _, net = exact_a_max_tables(*drive, x, table(0.0))
    return CycleCase(
        f"near-tangent gap {gap:g}", ("table", *drive), ("table", x, table(float(net))), kind="near-tangent"
    )


def main_cycle_cases(config: Config, rng: np.random.Generator) -> list[CycleCase]:
    """The cases of the cycle section: all a table against its balancing mean."""
    n = config.table_points
    x, y = table_noisy(n, rng)
    xs, ys = table_spike()
    xr, yr = table_ripple(1e6, 1000, rng)
    return [
        CycleCase(f"table-{n // 1000}k" if n >= 1000 else f"table-{n}", ("mean",), ("table", x, y), kind="noisy table"),
        CycleCase("press-spike", ("mean",), ("table", xs, ys), kind="spike with steps"),
        CycleCase("offset-1e6", ("mean",), ("table", xr, yr), kind="1e6 N*m + 1 N*m ripple"),
    ]


def section_cycle(config: Config) -> list[Row]:
    """A_max from tables: flyopt's exact path against sampled rules, error vs rationals."""
    rng = np.random.default_rng(config.seed)
    rows = []
    for case in main_cycle_cases(config, rng):
        ref = reference_a_max(case)
        x, y = case.resisting[1], case.resisting[2]

        def record(method, setting, fn):
            value = fn()
            timing = measure(fn, config.repeats, config.min_time)
            err = abs(value - ref) / ref
            rows.append(
                Row.timed(
                    "cycle",
                    case.name,
                    method,
                    setting,
                    timing,
                    error=err,
                    error_median=err,
                    reference=case.reference_how,
                    note=f"{case.points} points, {case.kind}; A_max {value:.15g} J (exact {ref:.15g} J)",
                )
            )

        record("flyopt-exact", "exact", lambda: flyopt_a_max(case))
        record("trapezoid-table", f"{len(x)}", lambda: sampled_a_max(x, y, case.cycle_angle, None, "trapezoid"))
        for rule in SAMPLED_RULES:
            for n in config.samples:
                record(rule, n, lambda n=n, rule=rule: sampled_a_max(x, y, case.cycle_angle, n, rule))
        for n in config.samples:  # the integration alone, samples given (no resampling in the time)
            phi = np.linspace(0.0, case.cycle_angle, n)
            m = np.interp(phi, x, y)
            record(
                "trapezoid-presampled", n, lambda phi=phi, m=m: integrate_samples(phi, m, case.cycle_angle, "trapezoid")
            )
    set_ratios(rows, lambda r: r.method == "flyopt-exact")
    return rows
