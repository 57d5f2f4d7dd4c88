"""The work balance of one cycle: the work of a torque and the unknown constant that balances it.

W = ∫_0^Φ M dφ; an unknown constant torque is M = W_other/Φ
(docs/flywheel-design.md, section 4); a cycle whose net work does not vanish
is refused (non-periodic fluctuation).
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from flyopt.cycle.difference import segments
from flyopt.cycle.torque import Constant, PiecewiseLinear, TorqueCurve
from flyopt.errors import NonPeriodicCycle

BALANCE_TOLERANCE = 1e-9
"""Largest accepted |net work| per cycle, relative to the cycle work."""


def solve_unknown_constant(
    driving: TorqueCurve, resisting: TorqueCurve, cycle_angle: float
) -> tuple[TorqueCurve, TorqueCurve]:
    """Replace an unknown constant torque by the value that balances the cycle.

    M = W_other / Φ (docs/flywheel-design.md, section 4).

    Returns
    -------
    tuple
        ``(driving, resisting)`` with the unknown one made known.
    """
    if isinstance(driving, Constant) and driving.unknown:
        return _balancing_constant(resisting, cycle_angle), resisting
    if isinstance(resisting, Constant) and resisting.unknown:
        return driving, _balancing_constant(driving, cycle_angle)
    return driving, resisting


def _balancing_constant(curve: TorqueCurve, cycle_angle: float) -> Constant:
    """The constant whose work over the cycle equals that of ``curve``.

    Against a table it is kept as pivot + excess (a two-pass mean): the
    pivot is the plain mean W/Φ, the excess the mean of (table − pivot). For
    a large mean with a small ripple every difference is exact (Sterbenz:
    the values lie within a factor two of the pivot); otherwise the excess is
    a small correction of an already good mean.
    """
    if isinstance(curve, PiecewiseLinear):
        pivot = curve.work(cycle_angle) / cycle_angle
        rel = curve.values - pivot
        excess = float(np.sum((rel[1:] + rel[:-1]) * np.diff(curve.angles))) / (2 * cycle_angle)
        return Constant(pivot + excess, pivot=pivot, excess=excess)
    return Constant(work(curve, cycle_angle) / cycle_angle)


def work(curve: TorqueCurve, cycle_angle: float) -> float:
    """Work of one torque curve over one cycle, ∫_0^Φ M dφ [J].

    Curves are immutable, so the quadrature of a nonlinear one is done once
    per cycle angle and kept on the curve (solving an unknown constant and
    building the indicator diagram both need it).
    """
    if curve.is_linear:  # a table or a constant, or a machine's linear curve: each integrates itself exactly
        return float(cast(Any, curve).work(cycle_angle))
    cache = curve.__dict__.setdefault("_work_per_cycle", {})
    if cycle_angle not in cache:
        zero = Constant(0.0)
        cache[cycle_angle] = float(np.sum(segments(curve, zero, cycle_angle).integrals(), dtype=np.longdouble))
    return cache[cycle_angle]


def check_balance(imbalance: float, cycle_work: float, fluctuation_scale: float) -> None:
    """Refuse a cycle whose net work exceeds BALANCE_TOLERANCE of its work.

    The work is the larger of the cycle work of the torques and the work
    scale of their difference (peak |M_d − M_r| Φ): a zero-mean torque
    (a gravity load, sin φ) against an unknown constant has no cycle work
    to speak of, yet balances.
    """
    scale = max(cycle_work, fluctuation_scale)
    if abs(imbalance) > BALANCE_TOLERANCE * scale:
        raise NonPeriodicCycle(imbalance, cycle_work)
