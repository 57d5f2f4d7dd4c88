"""Cycle analysis: work balance, the energy indicator diagram and A_max.

The excess work from the start of the cycle is

    ΔE(φ) = ∫_0^φ (M_d − M_r) dφ,

its largest span over the cycle is the maximum fluctuation of energy
A_max = max ΔE − min ΔE, reached at crossings of the two torque curves
(docs/flywheel-design.md, section 4). flyopt computes it exactly rather than by sampling:

- where both curves are piecewise linear (tables and constants), the
  difference is linear between the union of their breakpoints; the crossing
  inside a piece is at t = a/(a − b) and every area is a closed-form
  trapezoid, summed in extended precision;
- where an expression is involved, crossings are found by bracketing on a
  fine grid plus a search for near-tangent dips, refined with Brent's method,
  the kinks of ``abs``, ``min`` and ``max`` likewise, and the areas between
  them by adaptive Gauss–Kronrod quadrature to 1e-13 relative (or to the
  round-off of the torques as evaluated, where that is larger). The pieces
  are sampled, their crossings refined and their areas integrated all at
  once, in vectorized calls of the torques (:mod:`flyopt.cycle.difference`).

A cycle whose net work does not vanish is refused (non-periodic fluctuation,
:mod:`flyopt.cycle.balance`). From A_max follow the constant-inertia method's
J_F = A_max/(ω_m² δ) − J_c and the speeds ω_m (1 ± δ/2) (:func:`required_inertia`,
:func:`speed_extremes`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

import numpy as np
from numpy.typing import ArrayLike

from flyopt.cycle.balance import check_balance, solve_unknown_constant, work
from flyopt.cycle.difference import sample, segments
from flyopt.cycle.numerics import EPS, accurate_cumsum, quad_many
from flyopt.cycle.torque import Array, TorqueCurve

Value = TypeVar("Value", float, np.ndarray)
"""A number or an array of them: the closed forms below hold elementwise (a sweep's points at once)."""


@dataclass(frozen=True)
class EnergyIndicator:
    """The energy indicator diagram of one cycle and what follows from it.

    Attributes
    ----------
    cycle_angle : float
        Angle of one cycle Φ [rad].
    work_driving, work_resisting : float
        Work of each torque over one cycle [J].
    chain_angle : ndarray or None
        Angles of the chain points [rad]: the cycle start, every crossing of
        the curves, the cycle end (None for scenes given as net areas).
    chain_delta_e : ndarray
        Excess work ΔE at the chain points [J].
    a_max : float
        Maximum fluctuation of energy [J].
    index_max, index_min : int
        Chain points where ΔE is largest (ω_max) and smallest (ω_min).
    imbalance : float
        Net work over the cycle left by round-off [J].
    """

    cycle_angle: float
    work_driving: float
    work_resisting: float
    chain_angle: np.ndarray | None
    chain_delta_e: np.ndarray
    a_max: float
    index_max: int
    index_min: int
    imbalance: float

    @property
    def driving_mean(self) -> float:
        """Mean driving torque M_d = W_d/Φ [N*m]."""
        return self.work_driving / self.cycle_angle

    @property
    def resisting_mean(self) -> float:
        """Mean resisting torque M_r = W_r/Φ [N*m]."""
        return self.work_resisting / self.cycle_angle

    @property
    def angle_omega_max(self) -> float | None:
        """Angle of the highest speed [rad] (None for net-area scenes)."""
        return None if self.chain_angle is None else float(self.chain_angle[self.index_max])

    @property
    def angle_omega_min(self) -> float | None:
        """Angle of the lowest speed [rad] (None for net-area scenes)."""
        return None if self.chain_angle is None else float(self.chain_angle[self.index_min])

    @property
    def areas(self) -> Array:
        """Signed areas between consecutive chain points [J] (+ surplus, − deficit)."""
        return np.diff(self.chain_delta_e)


def energy_indicator(driving: TorqueCurve, resisting: TorqueCurve, cycle_angle: float) -> EnergyIndicator:
    """Exact energy indicator diagram of two torque curves over one cycle.

    Parameters
    ----------
    driving, resisting : PiecewiseLinear, Constant or ExpressionTorque
        Equivalent torques at the reference shaft [N*m]; a Constant may be
        unknown and is then solved from the work balance.
    cycle_angle : float
        Angle of one cycle Φ [rad].

    Returns
    -------
    EnergyIndicator

    Raises
    ------
    NonPeriodicCycle
        When |W_d − W_r| exceeds ``BALANCE_TOLERANCE`` of the cycle work.
    """
    driving, resisting = solve_unknown_constant(driving, resisting, cycle_angle)
    w_d, w_r = work(driving, cycle_angle), work(resisting, cycle_angle)
    pieces = segments(driving, resisting, cycle_angle)
    fast = pieces.linear_chain() if pieces.linear else None
    if fast is not None:
        chain_angle, chain_de = fast
        imbalance = float(chain_de[-1])
    else:
        angle, sign, delta_e = pieces.events()
        imbalance = float(delta_e[-1])
        crossings = _crossings(sign)
        chain = np.concatenate(([0], crossings, [len(angle) - 1]))
        chain = chain[np.concatenate(([True], np.diff(angle[chain]) > 0))] if len(chain) > 2 else chain
        chain_angle, chain_de = angle[chain], delta_e[chain]
    check_balance(imbalance, max(abs(w_d), abs(w_r)), pieces.scale())
    # Extremes of ΔE are at crossings (or the cycle ends): take them from the chain.
    return _from_chain(cycle_angle, w_d, w_r, chain_angle, chain_de, imbalance, pieces.scale())


def energy_indicator_from_areas(areas: Sequence[float] | Array, cycle_angle: float) -> EnergyIndicator:
    """Energy indicator diagram from the signed net areas between the curves.

    Parameters
    ----------
    areas : sequence of float
        Signed areas between the torque curves in their order over the cycle,
        already converted to energy [J] (+ surplus, − deficit).
    cycle_angle : float
        Angle of one cycle Φ [rad]; the crossing angles are not known.

    Returns
    -------
    EnergyIndicator
        With ``chain_angle`` None; works are the sums of surpluses/deficits.
    """
    areas = np.asarray(areas, dtype=float)
    chain = np.concatenate(([0.0], np.cumsum(areas.astype(np.longdouble)).astype(float)))
    surplus = math.fsum(a for a in areas if a > 0)
    deficit = -math.fsum(a for a in areas if a < 0)
    imbalance = math.fsum(areas)
    check_balance(imbalance, max(surplus, deficit), surplus + deficit)
    return _from_chain(cycle_angle, surplus, deficit, None, chain, imbalance, surplus + deficit)


class ExcessWork:
    """ΔE(φ) = ∫_0^φ (M_d − M_r) dφ as an exact function of the angle.

    Piecewise-linear torques give a piecewise-quadratic ΔE, evaluated in
    closed form; with an expression, ΔE is the knot value plus an adaptive
    quadrature from the piece's start.

    Attributes
    ----------
    knots : ndarray
        Angles where M_d − M_r may jump or change slope [rad]; ΔE is smooth
        between them.
    driving, resisting : torque curves (an unknown constant already solved)
    """

    def __init__(self, driving: TorqueCurve, resisting: TorqueCurve, cycle_angle: float) -> None:
        self.driving, self.resisting = solve_unknown_constant(driving, resisting, cycle_angle)
        self._segments = segments(self.driving, self.resisting, cycle_angle)
        self.knots = self._segments.knots
        self._at_knots = np.concatenate(([0.0], accurate_cumsum(self._segments.integrals())))
        self.cycle_angle = cycle_angle

    def __call__(self, phi: ArrayLike) -> Array:
        """ΔE at the angles ``phi`` in [0, Φ] [J] (vectorized)."""
        phi = np.asarray(phi, dtype=float)
        k = np.clip(np.searchsorted(self.knots, phi, side="right") - 1, 0, len(self.knots) - 2)
        seg = self._segments
        h = np.diff(self.knots)[k]
        dx = phi - self.knots[k]
        if seg.linear:
            a, b = seg.start[k], seg.end[k]
            slope = np.where(h > 0, (b - a) / np.where(h > 0, h, 1.0), 0.0)
            return self._at_knots[k] + a * dx + 0.5 * slope * dx * dx
        flat = np.atleast_1d(phi).ravel()
        ks = np.atleast_1d(k).ravel()
        parts = quad_many(lambda t, i: seg.difference_many(t, ks[i]), self.knots[ks], flat, seg.scale(), seg.noise)
        return (self._at_knots[ks] + parts).reshape(phi.shape)

    @property
    def at_knots(self) -> Array:
        """ΔE at :attr:`knots` [J] (sums of the pieces' integrals, in extended precision)."""
        return self._at_knots

    def scale(self) -> float:
        """Work scale of the cycle, peak |M_d − M_r| times Φ, for tolerances [J]."""
        return self._segments.scale()

    def net_torque(self, phi: ArrayLike) -> Array:
        """M_d − M_r at ``phi`` [N*m] (right limits at steps; vectorized)."""
        phi = np.asarray(phi, dtype=float)
        return (sample(self.driving, phi)[1] - sample(self.resisting, phi)[1]).astype(float)


def required_inertia(
    a_max: Value, omega_mean: Value | float, delta: Value | float, j_constant: Value | float = 0.0
) -> Value:
    """Flywheel inertia at the reference shaft by the constant-inertia method.

    J_F = A_max / (ω_m² δ) − J_c  (docs/flywheel-design.md, section 5).

    Parameters
    ----------
    a_max : float
        Maximum fluctuation of energy [J].
    omega_mean : float
        Mean speed of the reference shaft [rad/s].
    delta : float
        Allowed coefficient of speed fluctuation [-].
    j_constant : float
        Machine's own constant equivalent inertia J_c [kg*m^2].

    Returns
    -------
    float
        J_F [kg*m^2]; zero or negative means no flywheel is needed. A machine whose torques balance at every
        angle (A_max = 0) needs none at any δ, 0 included (the δ a given wheel leaves it).
    """
    if isinstance(a_max, (int, float)) and a_max == 0.0:
        return 0.0 - j_constant
    return a_max / (omega_mean**2 * delta) - j_constant


def speed_extremes(omega_mean: Value, delta: Value | float) -> tuple[Value, Value]:
    """Highest and lowest speed of a cycle of mean speed ω_m and fluctuation δ [rad/s].

    ω_max = ω_m (1 + δ/2), ω_min = ω_m (1 − δ/2), from δ = (ω_max − ω_min)/ω_m
    and ω_m = (ω_max + ω_min)/2 (docs/flywheel-design.md, section 2): the
    speeds of the energy method, where the rim speed is checked.

    Parameters
    ----------
    omega_mean : float or ndarray
        ω_m [rad/s].
    delta : float or ndarray
        δ [-].

    Returns
    -------
    tuple
        (ω_max, ω_min) [rad/s].
    """
    return omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)


def _from_chain(cycle_angle, work_driving, work_resisting, chain_angle, chain, imbalance, scale):
    """The indicator of a ΔE chain: A_max is the span between its extremes (:func:`_extremes`)."""
    index_max, index_min = _extremes(chain, scale)
    return EnergyIndicator(
        cycle_angle=cycle_angle,
        work_driving=work_driving,
        work_resisting=work_resisting,
        chain_angle=chain_angle,
        chain_delta_e=chain,
        a_max=float(chain[index_max] - chain[index_min]),
        index_max=index_max,
        index_min=index_min,
        imbalance=imbalance,
    )


def _extremes(chain, scale):
    """First chain points of largest and smallest ΔE; ties within round-off go to the earlier one."""
    tie = 64 * EPS * scale
    return int(np.argmax(chain >= chain.max() - tie)), int(np.argmax(chain <= chain.min() + tie))


def _crossings(sign):
    """Indices of the events where the sign of M_d − M_r changes.

    A flip is placed at the first event after the last one of the old sign:
    a zero of a linear piece, the first point of a run where the curves
    coincide, or the right side of a vertical step.
    """
    nonzero = np.flatnonzero(sign)
    if len(nonzero) < 2:
        return np.empty(0, dtype=int)
    flips = np.flatnonzero(sign[nonzero[1:]] != sign[nonzero[:-1]])
    return nonzero[flips] + 1
