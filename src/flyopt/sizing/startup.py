"""Run-up from rest: the time a motor takes to bring the machine to speed.

The equation of motion in the angle, as the periodic model
(flyopt.sizing.periodic; docs/flywheel-design.md, section 7), integrated from
rest with the time as a third state (:func:`startup_time`); for a constant
inertia on an induction motor's Kloss curve with no load, in closed form
(:func:`kloss_runup_time`, :func:`kloss_runup_angle`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from flyopt.cycle.numerics import hermite, hermite_extremes
from flyopt.errors import SolverFailed
from flyopt.said import said
from flyopt.sizing._numerics import EDGE, EPS, InertiaLike, NetTorqueLike, check_speed_delta, quiet
from flyopt.sizing.periodic_model import periodic_model

#: The speed at the start of the output interval where the target is reached, relative to its end, above
#: which the time is interpolated by a cubic (below it the interval is integrated again, finer).
SMOOTH_SPEED_RATIO = 0.999

#: Cycles a run-up may take before it is reported as not reaching its target.
MAX_CYCLES = 100000


def kloss_runup_time(
    inertia: Any,
    ratio: Any,
    efficiency: Any,
    breakdown_torque: Any,
    breakdown_slip: Any,
    synchronous_speed: float,
    omega: Any,
    lib: Any = math,
) -> Any:
    """Run-up time from rest to ``omega`` of a constant inertia on an induction motor's Kloss curve, no load [s].

    J dω/dt = i η M(i ω), M = 2 M_b s s_b/(s² + s_b²), s = 1 − i ω/ω_0, so with
    dω_motor = −ω_0 ds,

        t = J/(i² η) ∫ dω_motor/M = J/(i² η) · ω_0/(2 M_b s_b) [(1 − s_e²)/2 + s_b² ln(1/s_e)],

    s_e = 1 − i ω/ω_0 the slip at the target speed (which must be positive).
    ``lib``: math, numpy or casadi (the drive relaxation's symbols).
    """
    s_e = 1 - ratio * omega / synchronous_speed
    return (
        inertia
        / (ratio**2 * efficiency)
        * synchronous_speed
        / (2 * breakdown_torque * breakdown_slip)
        * ((1 - s_e**2) / 2 + breakdown_slip**2 * lib.log(1 / s_e))
    )


def kloss_runup_angle(
    inertia: float,
    ratio: float,
    efficiency: float,
    breakdown_torque: float,
    breakdown_slip: float,
    synchronous_speed: float,
    omega: float,
) -> float:
    """Angle the crank turns in :func:`kloss_runup_time`'s run-up [rad].

    dφ = ω dt = J ω dω/(i η M(i ω)); with ω = ω_0 (1 − s)/i,

        φ = J ω_0²/(2 η i³ M_b s_b) [F(1) − F(s_e)],  F(s) = s²/2 + s_b² ln s − s³/3 − s_b² s,

    the antiderivative of (1 − s)(s² + s_b²)/s = s + s_b²/s − s² − s_b².
    """
    s_b, s_e = breakdown_slip, 1 - ratio * omega / synchronous_speed

    def antiderivative(s: float) -> float:
        return s * s / 2 + s_b * s_b * math.log(s) - s**3 / 3 - s_b * s_b * s

    scale = inertia * synchronous_speed**2 / (2 * efficiency * ratio**3 * breakdown_torque * s_b)
    return scale * (antiderivative(1.0) - antiderivative(s_e))


@dataclass(frozen=True)
class Startup:
    """Run-up from rest.

    Attributes
    ----------
    time : float
        From rest to the first moment the speed reaches ``omega_target`` [s].
    angle : float
        Angle turned meanwhile [rad].
    cycles : float
        The same in cycles [-].
    omega_target : float
        [rad/s]
    """

    time: float
    angle: float
    cycles: float
    omega_target: float


def startup_time(
    net_torque: NetTorqueLike,
    j_machine: InertiaLike,
    cycle_angle: float,
    omega_target: float,
    j_flywheel: float = 0.0,
    knots: Iterable[float] = (),
    phi_start: float = 0.0,
    max_cycles: int = MAX_CYCLES,
) -> Startup:
    """Time from rest until the speed first reaches ``omega_target``.

    Parameters
    ----------
    net_torque : callable (phi, omega) -> torque
        M_d − M_r [N*m], accepting CasADi symbols; for an induction motor use
        its Kloss curve (:meth:`flyopt.machine.motor.InductionMotor.torque` with
        ``model="kloss"``), since the linear line overstates the torque at
        low speed.
    j_machine, cycle_angle, knots
        As for :func:`periodic_solution`.
    omega_target : float
        Speed to reach [rad/s], e.g. the steady state's ``omega_mean``. Since
        the steady state is approached asymptotically, its mean speed is
        first reached on a peak of the fluctuation.
    j_flywheel : float
        J_F [kg*m^2]; a flywheel slows the start.
    phi_start : float
        Angle at rest [rad], in [0, Φ).
    max_cycles : int
        Give up after this many cycles.

    Returns
    -------
    Startup

    Raises
    ------
    SolverFailed
        When the machine cannot start, stalls, or settles below the target.

    Notes
    -----
    Integrated in the angle, as the periodic model: dE/dφ = M(φ, ω),
    dt/dφ = 1/ω. Near rest E ≈ M(φ_0, 0)(φ − φ_0), t ≈ sqrt(2 J (φ − φ_0)/M)
    (constant acceleration) over the first 1e-9 of the first piece.
    """
    check_speed_delta(omega_target, None)
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    cycle = model.cycle
    if not 0 <= phi_start < cycle:
        raise ValueError(f"phi_start must lie in [0, {cycle!r}) rad, got {phi_start!r}")
    seg = model.segments
    model.check_finite(omega_target)
    m0 = float(model.torque(phi_start + 1e-12 * cycle, 0.0))
    j0 = float(model.inertia(phi_start)) + j_flywheel
    if not j0 > 0:
        raise ValueError(f"the total inertia at phi_start must be positive, got {j0!r} kg*m^2")
    if not m0 > 0:
        raise SolverFailed(
            said(
                "the machine cannot start from rest at phi = {phi}: the net torque at rest there is {torque} (the "
                "motor's starting torque does not exceed the load)",
                phi=(phi_start, "angle", f"{phi_start!r} rad"),
                torque=(m0, "torque", f"{m0:.4g} N·m"),
            )
        )
    j_mean = float(np.mean(model.inertia(model.grid_angles()))) + j_flywheel
    e_target = 0.5 * j_mean * omega_target**2
    t_scale = cycle / omega_target
    # first piece: from phi_start (plus a tiny constant-acceleration start) to its segment end
    k0 = int(np.searchsorted(seg[:, 1], phi_start, side="right"))
    first = seg[k0, 1] - phi_start
    dphi = 1e-9 * first
    x = np.array([m0 * dphi / e_target, 0.0, math.sqrt(2 * j0 * dphi / m0) / t_scale])
    angle = dphi  # turned in the constant-acceleration start
    pieces = [(phi_start + dphi, seg[k0, 1])] + [tuple(s) for s in seg[k0 + 1 :]]
    peaks = []
    for n in range(int(max_cycles) + 1):
        peak = 0.0
        for (a, b), (m_a, m_b) in zip(pieces, model.table_at(*np.transpose(pieces))):
            try:
                with quiet():
                    xf = np.asarray(
                        model.piece_timed(
                            x0=x, p=[a, b, j_flywheel, 0.0, e_target, 0.0, m_a, m_b, t_scale, *model.theta]
                        )["xf"]
                    )
            except RuntimeError as err:
                raise SolverFailed(
                    said(
                        f"start-up integration failed near phi = {{phi}} in cycle {n}: "
                        + str(err).splitlines()[-1].replace("{", "{{").replace("}", "}}"),
                        phi=(a, "angle", f"{a:.6g} rad"),
                    )
                ) from err
            if xf[1, -1] > 0:
                raise SolverFailed(
                    said(
                        "the machine stalls during start-up between phi = {a} and {b} "
                        f"(cycle {n}): the load there exceeds the motor torque and the stored energy",
                        a=(a, "angle", f"{a:.6g}"),
                        b=(b, "angle", f"{b:.6g} rad"),
                    )
                )
            phi, omega, gap, slope = _piece_gap(model, a, b, e_target * xf[0], j_flywheel, omega_target)
            reach = _first_reach(phi, gap, slope)
            start_of_piece = a
            while (
                reach is not None
                and omega[reach[0]] < SMOOTH_SPEED_RATIO * omega[reach[0] + 1]
                and phi[reach[0] + 1] - phi[reach[0]] > 1e-12 * first
            ):
                # reached where the speed still changes fast across an output interval (near rest ω ~
                # sqrt(φ − φ_0), and dt/dφ = 1/ω is singular at the start): the cubic through the ends of
                # the time is no interpolant there (a run-up of 0.075 s was read as 5.9 s). That interval
                # is integrated again from its start, with outputs as close again.
                i = reach[0]
                x_i, a, b = xf[:, i], float(phi[i]), float(phi[i + 1])
                m_a, m_b = model.table_at(a, b)[0]  # the table is linear inside a piece
                with quiet():
                    xf = np.asarray(
                        model.piece_timed(
                            x0=x_i, p=[a, b, j_flywheel, 0.0, e_target, 0.0, m_a, m_b, t_scale, *model.theta]
                        )["xf"]
                    )
                phi, omega, gap, slope = _piece_gap(model, a, b, e_target * xf[0], j_flywheel, omega_target)
                reach = _first_reach(phi, gap, slope)
            if reach is not None:
                i, s = reach
                d = phi[i + 1] - phi[i]
                t0, t1 = xf[2, i] * t_scale, xf[2, i + 1] * t_scale
                g0, g1 = d / omega[i], d / omega[i + 1]  # dt/ds at the ends (s = (φ − φ_i)/d)
                t_hit = hermite(t0, t1, g0, g1, s)
                angle += phi[i] + s * d - start_of_piece
                return Startup(
                    time=float(t_hit), angle=float(angle), cycles=float(angle / cycle), omega_target=float(omega_target)
                )
            peak = max(peak, float(np.max(omega)))
            angle += b - a
            x = xf[:, -1]
        pieces = [tuple(s) for s in seg]
        peaks.append(peak)
        limit = _settled_peak(peaks, omega_target)
        if limit is not None:
            raise SolverFailed(
                said(
                    "the machine settles below the target speed {target} during start-up: its peak speed "
                    "converges to about {limit}",
                    target=(omega_target, "angular_speed", f"{omega_target!r} rad/s"),
                    limit=(limit, "angular_speed", f"{limit:.6g} rad/s"),
                )
            )
    raise SolverFailed(
        said(
            f"the target speed {{target}} was not reached in {max_cycles} cycles",
            target=(omega_target, "angular_speed", f"{omega_target!r} rad/s"),
        )
    )


def _piece_gap(model, a, b, energy, j_flywheel, target):
    """Speed, and E − ½ J ω_t² with its slope M − ½ J' ω_t², at the outputs of one piece.

    The gap is smooth even at rest, where ω ~ sqrt(φ − φ_0) is not.
    """
    phi = a + model.tau * (b - a)
    j = model.inertia(phi) + j_flywheel
    omega = np.sqrt(2 * np.maximum(energy, 0.0) / j)
    m = model.torque(a + np.clip(model.tau, EDGE, 1 - EDGE) * (b - a), omega)
    gap = energy - 0.5 * j * target**2
    slope = m - 0.5 * model.inertia.derivative(phi) * target**2
    return phi, omega, gap, slope


def _first_reach(phi, gap, slope):
    """First (interval, s) where the Hermite interpolant of ``gap`` reaches 0, or None."""
    if gap[0] >= 0:
        return 0, 0.0
    d = np.diff(phi)
    f0, f1, m0, m1 = gap[:-1], gap[1:], slope[:-1] * d, slope[1:] * d
    peak = hermite_extremes(phi[None, :], gap[None, :], slope[None, :])[0][1]
    if peak < 0:
        return None
    for i in np.flatnonzero(np.maximum(f0, f1) + np.abs(m0) + np.abs(m1) >= 0):
        a3, b2, c1 = 2 * (f0[i] - f1[i]) + m0[i] + m1[i], 3 * (f1[i] - f0[i]) - 2 * m0[i] - m1[i], m0[i]
        crit = [
            r.real
            for r in np.atleast_1d(np.roots([3 * a3, 2 * b2, c1]) if (a3 or b2) else [])
            if abs(r.imag) < 1e-12 and 0 < r.real < 1
        ]
        points = sorted([0.0, *crit, 1.0])
        for lower, upper in zip(points[:-1], points[1:]):
            if hermite(f0[i], f1[i], m0[i], m1[i], upper) >= 0:
                from scipy import optimize  # scipy.optimize costs ~0.3 s to import: only where needed

                s = optimize.brentq(
                    lambda t, i=i: hermite(f0[i], f1[i], m0[i], m1[i], t), lower, upper, xtol=1e-15, rtol=4 * EPS
                )
                return int(i), float(s)
    return None


def _settled_peak(peaks, target):
    """Limit of the cycle peak speeds when they settle clearly below ``target``, else None.

    The peaks of the last cycles must rise geometrically with a steady ratio
    (the asymptotic approach to a steady state), and the rise still to come
    (Aitken's extrapolation) must be small against the gap to the target.
    """
    if len(peaks) < 5:
        return None
    d = np.diff(peaks[-5:])
    if np.all(d <= 0):
        limit = peaks[-1]
    else:
        if not np.all(d > 0):
            return None
        q = d[1:] / d[:-1]
        if not (np.all((q > 0) & (q < 1)) and np.ptp(q) <= 1e-3 * q[-1]):
            return None
        limit = peaks[-1] + d[-1] * q[-1] / (1 - q[-1])
    return limit if limit - peaks[-1] <= 0.01 * (target - limit) else None
