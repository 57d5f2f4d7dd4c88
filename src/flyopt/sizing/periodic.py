"""The periodic steady state of the equation of motion, when a torque depends on speed.

The equation of motion in the angle (docs/flywheel-design.md, section 7),

    d(½ J(φ) ω²)/dφ = M(φ, ω),   M = M_d − M_r,

whose periodic steady state :func:`periodic_solution` finds by shooting
(CasADi/CVODES with exact sensitivities, a safeguarded Newton iteration on
the periodicity condition); :func:`dynamic_requirement` finds the smallest
flywheel whose periodic solution keeps δ, and :func:`verify` checks a chosen
flywheel. Verification lives here because it is one periodic solution with a
chosen flywheel, compared with the allowed δ: it shares this module's model,
cache and tolerances and adds no physics of its own.

Maxima and minima over the continuous angle are exact, not sampled: each is
the extremum of the cubic Hermite interpolant through the integrator's
states and exact slopes.

Net torques are given as callables ``(phi, omega) -> torque`` that accept
CasADi symbols (numbers come from the compiled CasADi function); inertias as
a number, an :class:`flyopt.machine.mechanism.EquivalentInertia`, or a CasADi-capable
callable of φ. Results are SI: [rad], [rad/s], [kg*m^2], [J], [s].

When neither the torques nor the inertia vary with the angle nothing
fluctuates: the speed is constant, whatever the inertia (even none). An
unknown constant torque that balances the cycle while another torque depends
on speed holds the scene's mean speed; only a motor's characteristic makes
the mean speed an outcome.

A machine's model is built once (:func:`flyopt.sizing.periodic_model.periodic_model`,
cached on its net torque; :data:`BUILDS` counts the builds), and a torque table enters it as
its values at the ends of each piece, so time and memory grow linearly with
the table's length.

The equation of motion is integrated in the kinetic energy E = ½ J ω²,
written as E = E_ref + W_s y with y of order one (E_ref a reference energy,
W_s the energy swing of the cycle), so the integrator's tolerances act on the
fluctuation, whatever the speed (1 rpm or 20,000 rpm) and δ (1e-4 or 0.3).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from typing import Any, cast

import numpy as np

from flyopt.cycle.balance import BALANCE_TOLERANCE
from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.numerics import hermite_extremes
from flyopt.errors import NonPeriodicCycle, SceneError, SolverFailed
from flyopt.sizing import shooting
from flyopt.sizing._numerics import (
    EDGE,
    EPS,
    InertiaLike,
    NetTorqueLike,
    check_speed_delta,
    quiet,
)
from flyopt.sizing.periodic_model import ABSTOL, BUILDS, RELTOL, PeriodicModel, periodic_model
from flyopt.sizing.shooting import NotSettled

PERIODIC_RTOL = 1e-9
"""Largest accepted |E(Φ) − E(0)| of a periodic solution, relative to the energy swing."""

DELTA_RTOL = 1e-6
"""Relative accuracy of a simulated δ that flyopt reports as the simulation tolerance.

Tests hold the simulation to 1e-6 of the exact energy methods' δ (it reaches
about 1e-9 on smooth cycles)."""

MAX_NEWTON = 60
"""Newton iterations on the periodicity condition before giving up."""

MAX_DYNAMIC = 80
"""Periodic solutions the search for the required flywheel may compute."""

VANISHING_INERTIA = 1e-9
"""Smallest total inertia the search for the flywheel tries, relative to the machine's (or to the
first estimate): δ below the allowed value there means that no flywheel is needed."""

STALL_RTOL = 1e-4
"""Relative width of the total inertia J_F + min J_e (the width in u, its logarithm) to which a stall limit (see
:class:`DynamicRequirement`) is located."""

MEAN_TARGET = 1e-13
MEAN_RTOL = 1e-10
"""Relative accuracy to which a balancing constant holds the prescribed mean speed: the
iteration aims at MEAN_TARGET and fails beyond MEAN_RTOL."""


def angle_torque(excess_work: ExcessWork) -> NetTorqueLike:
    """The net torque M_d − M_r of an ExcessWork as a CasADi callable (phi, omega).

    For simulating angle-only cycles with :func:`periodic_solution` and
    :func:`verify`; pass ``excess_work.knots`` as the knots.
    """
    # the TorqueCurve protocol does not name .casadi; every curve of an ExcessWork flyopt builds has it
    driving, resisting = cast(Any, excess_work.driving), cast(Any, excess_work.resisting)

    def net(phi: Any, omega: Any) -> Any:
        return driving.casadi(phi) - resisting.casadi(phi)

    return net


@dataclass(frozen=True)
class PeriodicSolution:
    """The periodic steady state of the equation of motion.

    Attributes
    ----------
    phi, omega : ndarray
        Simulation grid [rad] (knots repeated at piece ends) and speed [rad/s].
    omega_max, omega_min, omega_mean : float
        [rad/s]; omega_mean = (ω_max + ω_min)/2.
    delta : float
        (ω_max − ω_min)/ω_m [-].
    phi_omega_max, phi_omega_min : float
        Where the extremes are reached [rad].
    converged : bool
        Always True for a returned solution (failures raise).
    status : str
        How the solution was obtained.
    periodicity_residual : float
        |E(Φ) − E(0)| of the returned solution [J].
    periodicity_tolerance : float
        The largest accepted residual [J].
    tolerance : float
        Accuracy of ``delta`` [-] (``DELTA_RTOL`` relative).
    multiplier : float
        dE(Φ)/dE(0) (Floquet multiplier): < 1 for a stable steady state,
        1 when the torques do not depend on speed.
    speed_dependent : bool
        Whether the net torque depends on ω; if not, ω_m was prescribed,
        otherwise it follows from the torque–speed balance.
    iterations : int
        Newton iterations on the periodicity condition.
    j_flywheel : float
        J_F [kg*m^2].
    e0 : float
        Kinetic energy at φ = 0 [J].
    period : float
        Time of one cycle, ∫ dφ/ω [s].
    torque_offset : float
        The correction added to an unknown constant torque so that the
        cycle balances at the prescribed mean speed (0 unless
        ``net_torque.balanced``) [N*m].
    """

    phi: np.ndarray
    omega: np.ndarray
    omega_max: float
    omega_min: float
    omega_mean: float
    delta: float
    phi_omega_max: float
    phi_omega_min: float
    converged: bool
    status: str
    periodicity_residual: float
    periodicity_tolerance: float
    tolerance: float
    multiplier: float
    speed_dependent: bool
    iterations: int
    j_flywheel: float
    e0: float
    period: float
    torque_offset: float = 0.0


def _simpson_time(phi, omega):
    """∫ dφ/ω over the cycle by Simpson's rule on each piece [s]."""
    h = np.diff(phi, axis=1)[:, :1]
    g = 1.0 / omega
    w = np.ones(omega.shape[1])
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    return float(np.sum(h[:, 0] / 3 * (g @ w)))


def periodic_solution(
    net_torque: NetTorqueLike,
    j_machine: InertiaLike,
    cycle_angle: float,
    omega_mean: float,
    j_flywheel: float = 0.0,
    knots: Iterable[float] = (),
) -> PeriodicSolution:
    """Periodic steady state of d(½ J(φ) ω²)/dφ = M(φ, ω) over one cycle.

    Parameters
    ----------
    net_torque : callable (phi, omega) -> torque
        M_d − M_r at the reference shaft [N*m], accepting CasADi symbols
        (e.g. :meth:`flyopt.machine.reduce.Machine.net_torque`, or built from
        :mod:`flyopt.machine.motor` and :mod:`flyopt.cycle.torque`, or
        :func:`angle_torque`).
    j_machine : float, EquivalentInertia or callable
        The machine's J_e(φ) [kg*m^2].
    cycle_angle : float
        Φ [rad].
    omega_mean : float
        The prescribed mean speed (ω_max + ω_min)/2 [rad/s] when the torque
        depends on the angle only (every initial speed is then periodic and
        this one is picked) or when an unknown constant torque balances the
        cycle (``net_torque.balanced``: the constant is solved with the
        steady state). Otherwise (a motor) a first guess: the mean speed
        follows from the torque–speed balance.
    j_flywheel : float
        J_F added to the machine [kg*m^2].
    knots : sequence of float
        Angles where the torque steps or kinks [rad]; the integration stops
        and restarts there.

    Returns
    -------
    PeriodicSolution

    Raises
    ------
    SolverFailed
        No periodic steady state was found (the status says why: the
        machine stalls, runs away, the orbit is unstable, or the iteration
        did not converge). A solution that is not periodic to
        :data:`PERIODIC_RTOL` of the energy swing is never returned.
    NonPeriodicCycle
        Angle-only torques whose work does not balance over the cycle.

    Notes
    -----
    When neither the torques nor the inertia vary with the angle, nothing
    fluctuates: the speed is constant (δ = 0, whatever the inertia, even
    none) and is the root of M(ω) = 0 (or the prescribed one).

    Otherwise shooting: from E(0) = E_ref the cycle is integrated with CVODES
    (BDF, exact forward sensitivities), and Newton's method on E(Φ) − E(0) = 0,
    kept inside a bracket of the sign change, moves E_ref; a torque that
    rises with speed somewhere (a motor past breakdown) adds a scan of speeds
    when Newton finds no gain (see :func:`_periodic_energy`). A solution must
    be stable (Floquet multiplier dE(Φ)/dE(0) < 1). With a balancing
    constant, Newton moves the constant c instead (y(Φ) grows with c) and a
    secant on √E_ref holds the mean speed. The extremes of
    ω = sqrt(2q) are those of the cubic Hermite interpolant of q = E/J through
    the states and the exact slopes dq/dφ = (M J − E J')/J² at the 2048+
    outputs per cycle (q stays smooth where ω is small).
    """
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    return _periodic(model, float(j_flywheel), omega_mean)


def _periodic(model, j_flywheel, omega_guess):
    check_speed_delta(omega_guess, None)
    if model.steady:
        return _steady(model, j_flywheel, omega_guess)
    phi_grid = model.grid_angles()
    j_min = float(np.min(model.inertia(phi_grid))) + j_flywheel
    if not j_min > 0:
        raise ValueError(
            f"the total inertia J_F + J_e(φ) must be positive; with J_F = {j_flywheel!r} kg*m^2 "
            f"it reaches {j_min!r} kg*m^2"
        )
    j_ref = float(model.inertia(0.0)) + j_flywheel
    model.check_finite(omega_guess)
    if model.balanced:
        return _periodic_balanced(model, j_flywheel, omega_guess, j_ref)
    if model.speed_dependent:
        return _periodic_speed_dependent(model, j_flywheel, omega_guess, j_ref)
    return _periodic_angle_only(model, j_flywheel, omega_guess, j_ref)


def _steady(model, j_flywheel, omega_guess):
    """Neither the torques nor the inertia vary with the angle: a constant speed, δ = 0.

    Angle-only torques must balance (|M| Φ within :data:`BALANCE_TOLERANCE`
    of the torques' work); a balancing constant holds the prescribed speed;
    otherwise the speed is the root of M(ω) = 0 where M falls with speed
    (a stable balance), searched outward from the guess.
    """
    j = float(model.inertia(0.0)) + j_flywheel
    if j < 0:
        raise ValueError(
            f"the total inertia J_F + J_e must not be negative; with J_F = {j_flywheel!r} kg*m^2 it is {j!r} kg*m^2"
        )
    model.check_finite(omega_guess)

    def torque(omega):
        return float(model.torque(0.0, omega))

    omega, offset, multiplier = omega_guess, 0.0, 1.0
    if not model.speed_dependent:
        m = torque(omega)
        imbalance = m * model.cycle
        if abs(imbalance) > BALANCE_TOLERANCE * max(model.work, abs(imbalance)):
            raise NonPeriodicCycle(imbalance, model.work)
        status = "steady: the torques balance and do not vary with the angle, so the speed is constant"
    elif model.balanced:
        offset = -torque(omega)
        status = (
            "steady: the torques do not vary with the angle; the unknown constant torque balances them "
            "at the prescribed speed"
        )
    else:
        omega = shooting.speed_balance(torque, omega_guess)
        slope = float(model.torque_slope(0.0, omega))
        multiplier = math.exp(model.cycle * slope / (j * omega)) if j > 0 else 0.0
        status = "steady: the torques do not vary with the angle; the torque-speed balance sets the speed"
    phi = model.grid_angles().reshape(-1)
    return PeriodicSolution(
        phi=phi,
        omega=np.full(phi.shape, float(omega)),
        omega_max=float(omega),
        omega_min=float(omega),
        omega_mean=float(omega),
        delta=0.0,
        phi_omega_max=0.0,
        phi_omega_min=0.0,
        converged=True,
        status=status,
        periodicity_residual=0.0,
        periodicity_tolerance=0.0,
        tolerance=0.0,
        multiplier=multiplier,
        speed_dependent=model.speed_dependent,
        iterations=0,
        j_flywheel=j_flywheel,
        e0=0.5 * j * omega**2,
        period=model.cycle / omega,
        torque_offset=offset,
    )


def _finish(model, y, j_flywheel, e_ref, w_s, shift, status, residual, tol, multiplier, iterations, offset=0.0):
    phi, q, dq, energy = model.speed_profile(y, j_flywheel, e_ref, w_s, shift, offset)
    if q is None:
        raise SolverFailed(
            f"the speed reaches zero within the cycle (status: {status}); "
            f"the machine stalls: more flywheel inertia or a stronger motor is needed"
        )
    hi, lo = hermite_extremes(phi, q, dq)
    if lo[1] <= 0.0:
        # the grid's ω²/2 is positive but its cubic interpolant dips below zero: the speed is
        # far too stiff between output points to be resolved (a vanishing flywheel)
        raise SolverFailed(
            f"the periodic speed is not resolved with J_F = {j_flywheel:.3g} kg·m² (status: {status}): "
            f"ω²/2 lies in [{float(np.min(q)):.4g}, {float(np.max(q)):.4g}] rad²/s² on the output grid, but "
            f"its interpolant reaches {lo[1]:.3g} at φ = {lo[0]:.4g} rad (slopes up to "
            f"{float(np.max(np.abs(dq))):.3g} rad²/s² per rad)"
        )
    w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
    omega = np.sqrt(2 * q)
    w_mean = 0.5 * (w_max + w_min)
    delta = (w_max - w_min) / w_mean
    return PeriodicSolution(
        phi=phi.reshape(-1),
        omega=omega.reshape(-1),
        omega_max=w_max,
        omega_min=w_min,
        omega_mean=w_mean,
        delta=delta,
        phi_omega_max=hi[0],
        phi_omega_min=lo[0],
        converged=True,
        status=status,
        periodicity_residual=abs(residual),
        periodicity_tolerance=tol,
        tolerance=DELTA_RTOL * delta,
        multiplier=multiplier,
        speed_dependent=model.speed_dependent,
        iterations=iterations,
        j_flywheel=j_flywheel,
        e0=float(energy[0, 0]),
        period=_simpson_time(phi, omega),
        torque_offset=offset,
    )


def _periodic_angle_only(model, j_flywheel, omega_mean, j_ref):
    e_ref = 0.5 * j_ref * omega_mean**2
    # the swing of E at a frozen speed (exact for a constant inertia, near it otherwise), so that
    # y swings by about one at the first integration; a swing far from one is integrated again
    w_s = shooting.energy_swing(model, omega_mean)
    if not w_s > 0:
        w_s = model.work_scale(omega_mean)
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    swing = float(y.max() - y.min())
    if swing > 0 and not 0.5 <= swing <= 2.0:  # rescale so that y swings by one
        w_s *= swing
        y, stall = model.trajectory(j_flywheel, e_ref, w_s)
        swing = float(y.max() - y.min())
    residual = float(y[-1, -1] - y[0, 0])
    tol = _angle_only_tolerance(model, y, omega_mean, w_s)
    if abs(residual) > tol:
        raise NonPeriodicCycle(residual * w_s, max(model.absolute_work(omega_mean), model.work))
    y_min = float(y.min())

    def mismatch(shift):
        phi, q, dq, _ = model.speed_profile(y, j_flywheel, e_ref, w_s, shift)
        if q is None:
            return -1.0
        hi, lo = hermite_extremes(phi, q, dq)
        return (math.sqrt(2 * hi[1]) + math.sqrt(2 * max(lo[1], 0.0))) / (2 * omega_mean) - 1

    low = -e_ref / w_s - y_min  # the speed touches zero
    low += 1e-12 * max(1.0, abs(low))
    if mismatch(low) > 0:
        raise SolverFailed(
            f"with J_F = {j_flywheel!r} kg*m^2 the machine cannot keep the mean speed "
            f"{omega_mean!r} rad/s: its speed would fall to zero within the cycle"
        )
    high = 1.0
    for _ in range(200):
        if mismatch(high) >= 0:
            break
        high = 2 * high + 1
    from flyopt.cycle.numerics import brentq  # scipy's, ported: scipy.optimize costs ~0.3 s to import

    shift = brentq(mismatch, low, high, xtol=1e-15 * (e_ref / w_s + 1), rtol=4 * EPS, maxiter=500)
    return _finish(
        model,
        y,
        j_flywheel,
        e_ref,
        w_s,
        shift,
        "periodic: torques of the angle only, the mean speed prescribed",
        residual * w_s,
        tol * w_s,
        1.0,
        0,
    )


def _angle_only_tolerance(model, y, omega_mean, w_s):
    """Largest y(Φ) − y(0) of angle-only torques that balance [W_s].

    The cycle module's balance tolerance on the work of the torques (not of their
    difference, which is round-off for a steady machine), or the integration's accuracy:
    on the swing, and CVODES's tolerance accumulated over the pieces (a table of many
    points makes many).
    """
    swing = float(y.max() - y.min())
    cycle_work = max(model.absolute_work(omega_mean), model.work)
    integration = len(model.pieces) * (ABSTOL + RELTOL * float(np.max(np.abs(y))))
    return max(PERIODIC_RTOL * max(swing, EPS), BALANCE_TOLERANCE * cycle_work / w_s, integration)


def _swing_scale(w_s, swing, e_ref):
    """(W_s, y's swing at it): the work scale [J] rescaled so that y = (E − E_ref)/W_s swings by about one
    over the cycle (``swing``, its swing at ``w_s``), but no further than where the integrator's absolute
    tolerance on y, ABSTOL·W_s joules, meets the rounding of the energy E_ref + W_s·y itself: below it CVODES
    cannot meet its tolerance on a torque of the speed and shrinks its steps without end (an energy that
    swings by less than about 1e-4 of its mean: a flywheel far larger than a speed-stiff torque needs, tried
    on the way to the one that is). There y swings by less than one, and :func:`_y_tolerance` says how far
    it can be held."""
    if not swing > 0:
        return w_s, 1.0
    scaled = max(w_s * swing, EPS * e_ref / ABSTOL)
    return scaled, w_s * swing / scaled


ROUNDING = 16
"""The energy's rounding, ε E_ref, in multiples of which a periodicity condition on y can be held."""


def _y_tolerance(relative, swing, e_ref, w_s):
    """The tolerance on y [W_s] of a condition held to ``relative`` of y's ``swing``, but not finer than
    ROUNDING times the energy's rounding ε E_ref in units of W_s (which only a work scale held up by
    :func:`_swing_scale` brings within reach)."""
    return max(relative * swing, ROUNDING * EPS * e_ref / w_s)


def _periodic_speed_dependent(model, j_flywheel, omega_guess, j_ref):
    w_s = model.work_scale(omega_guess)
    e_guess = 0.5 * j_ref * omega_guess**2

    def shoot(e_ref):
        try:
            with quiet():
                y_end, stall, dy = model.shoot(j_flywheel, e_ref, w_s)
        except RuntimeError:
            return None
        if stall > 0:
            return None
        return float(y_end), float(dy)

    def gain(e_ref):
        """y(Φ) from E_ref without its sensitivity (a fifth of a shot's cost), or None where the cycle stalls."""
        try:
            y, stall = model.trajectory(j_flywheel, e_ref, w_s)
        except SolverFailed:
            return None
        return None if stall > 0 else float(y[-1, -1])

    # First pass: find the speed, then rescale W_s to the swing and polish.
    e_ref, iterations, status = _periodic_energy(
        shoot, e_guess, 1e-8, lambda: model.falls_with_speed(omega_guess), gain
    )
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    w_s, scaled_swing = _swing_scale(w_s, float(y.max() - y.min()), e_ref)
    tol = PERIODIC_RTOL
    e_ref, more, status = _newton_energy(shoot, e_ref, _y_tolerance(0.1 * tol, scaled_swing, e_ref, w_s))
    iterations += more
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    residual = float(y[-1, -1] - y[0, 0])
    swing = float(y.max() - y.min())
    tol_abs = _y_tolerance(tol, max(swing, EPS), e_ref, w_s)
    if stall > 0 or abs(residual) > tol_abs:
        raise SolverFailed(
            f"periodic solution not found: after {iterations} Newton iterations E(Φ) − E(0) = "
            f"{residual * w_s:.3g} J exceeds the tolerance {tol_abs * w_s:.3g} J ({status})"
        )
    with quiet():
        dy = model.shoot(j_flywheel, e_ref, w_s)[2]
    multiplier = 1.0 + w_s * dy
    if not multiplier < 1.0:
        raise SolverFailed(
            f"the periodic solution found (mean energy {e_ref:.6g} J) is unstable: its Floquet "
            f"multiplier dE(Φ)/dE(0) = {multiplier:.6g} >= 1, so the machine would not settle "
            f"there (a motor beyond its breakdown torque?)"
        )
    return _finish(model, y, j_flywheel, e_ref, w_s, 0.0, status, residual * w_s, tol_abs * w_s, multiplier, iterations)


def _periodic_balanced(model, j_flywheel, omega_mean, j_ref):
    """The periodic steady state at the prescribed mean speed, an unknown constant torque balancing it.

    The constant was first solved at the frozen mean speed (the net torque's
    value); with the speed fluctuating, the work of a torque of speed
    differs a little, so a correction c is solved with the steady state. Two
    unknowns, √E_ref (E_ref the energy at φ = 0) and c, and two conditions:
    the orbit is periodic, y(Φ) = 0, and (ω_max + ω_min)/2 = ω_m. Broyden's
    method, started from the exact sensitivities of y(Φ) (CVODES) and
    ∂ω_m/∂√E = ω_m/√E (ω grows like √E); each step integrates one cycle.
    """
    w_s = model.work_scale(omega_mean)

    def stalls():
        return SolverFailed(
            f"the speed reaches zero within the cycle at the mean speed {omega_mean:.6g} rad/s "
            f"with J_F = {j_flywheel:.6g} kg*m^2: more flywheel inertia is needed"
        )

    def shoot(e_ref, offset, balancing):
        try:
            with quiet():
                out = model.shoot(j_flywheel, e_ref, w_s, offset, balancing=balancing)
        except RuntimeError as err:
            raise SolverFailed(
                f"the integration of the cycle failed at E_ref = {e_ref:.6g} J, c = {offset:.6g} "
                f"N*m (CVODES: {str(err).strip().splitlines()[-1]})"
            ) from err
        if out[1] > 0:
            raise stalls()
        return out

    def conditions(x):
        """[y(Φ), mean speed / ω_m − 1] of the cycle from E_ref = x[0]², with c = x[1]; and y on the grid."""
        e_ref, offset = x[0] ** 2, x[1]
        y, stall = model.trajectory(j_flywheel, e_ref, w_s, offset)
        phi, q, dq, _ = model.speed_profile(y, j_flywheel, e_ref, w_s, 0.0, offset)
        if q is None or stall > 0:
            raise stalls()
        hi, lo = hermite_extremes(phi, q, dq)
        w_mean = 0.5 * (math.sqrt(2 * hi[1]) + math.sqrt(2 * lo[1]))
        return np.array([y[-1, -1], w_mean / omega_mean - 1]), y

    x = np.array([math.sqrt(0.5 * j_ref * omega_mean**2), 0.0])
    _, y = conditions(x)
    w_s, scaled_swing = _swing_scale(w_s, float(y.max() - y.min()), x[0] ** 2)
    _, _, d_e, d_c = shoot(x[0] ** 2, 0.0, True)
    if not d_c > 0:
        raise SolverFailed(
            f"the balancing constant cannot be solved: dE(Φ)/dc = {d_c * w_s:.6g} J/(N*m) is not positive"
        )
    jac = np.array([[2 * x[0] * d_e, d_c], [1 / x[0], 0.0]])
    ftol = _y_tolerance(0.1 * PERIODIC_RTOL, scaled_swing, x[0] ** 2, w_s)
    values, y = conditions(x)
    for iterations in range(1, MAX_NEWTON + 1):  # noqa: B007 -- the count is reported after the loop
        if abs(values[0]) <= ftol and abs(values[1]) <= MEAN_TARGET:
            break
        try:
            step = -np.linalg.solve(jac, values)
        except np.linalg.LinAlgError:  # the mean speed no longer moves with E_ref or c: no step is defined
            raise SolverFailed(
                f"periodic solution at the mean speed {omega_mean:.6g} rad/s not found: the balance's Jacobian "
                f"became singular after {iterations - 1} iterations (the mean speed no longer answers the energy "
                "or the balancing torque: a torque that depends steeply on the speed)"
            ) from None
        x = x + step
        new, y = conditions(x)
        jac += np.outer(new - values - jac @ step, step) / (step @ step)
        values = new
    y_end, f = values
    residual = float(y[-1, -1] - y[0, 0])
    swing = float(y.max() - y.min())
    tol_abs = _y_tolerance(PERIODIC_RTOL, max(swing, EPS), x[0] ** 2, w_s)
    if abs(f) > MEAN_RTOL or abs(residual) > tol_abs:
        raise SolverFailed(
            f"periodic solution at the mean speed {omega_mean:.6g} rad/s not found in "
            f"{iterations} iterations: E(Φ) − E(0) = {residual * w_s:.3g} J (tolerance "
            f"{tol_abs * w_s:.3g} J), mean speed off by {f:.3g} (tolerance {MEAN_RTOL:g})"
        )
    e_ref, offset = x[0] ** 2, float(x[1])
    multiplier = 1.0 + w_s * shoot(e_ref, offset, False)[2]
    status = (
        f"periodic: the mean speed prescribed, the unknown constant torque corrected by {offset:.6g} N*m "
        f"to balance the cycle ({iterations} iterations)"
    )
    return _finish(
        model, y, j_flywheel, e_ref, w_s, 0.0, status, residual * w_s, tol_abs * w_s, multiplier, iterations, offset
    )


class _NoGain(SolverFailed):
    """Every trial lost energy over the cycle or stalled."""


SCAN_STEPS = 49
"""Speeds tried on each side of the guess (2 % apart) when Newton finds no energy gain."""


def _periodic_energy(shoot, e0, ftol, monotone, gain_at):
    """The energy at φ = 0 of a stable periodic solution, near the guess ``e0``.

    Newton (:func:`_newton_energy`) is global when the energy gained over a
    cycle falls with speed everywhere, which holds when the net torque falls
    with speed (comparison of solutions). A torque that rises with speed
    somewhere (an induction motor beyond its breakdown slip) can give a
    narrow band of speeds where the machine gains energy between two where it
    loses it, and Newton's steps may jump over it. When no trial gained
    energy and the torque is not ``monotone()`` (falling with speed), speeds
    2 %, 4 %, … above and below the guess are tried in turn;
    the first that gains, with the nearest speed above it that loses,
    brackets the stable solution for Newton. The scan reads only the energy
    gained, from ``gain_at(E_ref)`` (None where the cycle stalls), which need
    not integrate the sensitivities.
    """
    try:
        return _newton_energy(shoot, e0, ftol, gain_at=gain_at)
    except _NoGain as err:
        failure = SolverFailed(str(err))
    if monotone():
        raise failure
    count = 0

    def gain(k):
        """Energy gained over the cycle from the speed (1 + 0.02 k) × guess (−inf: stalls)."""
        nonlocal count
        count += 1
        e = e0 * (1 + 0.02 * k) ** 2
        r = gain_at(e) if e > 0 else None
        return -math.inf if r is None else r

    def bracket_from(k):
        """Newton in the bracket from a gaining speed k to the nearest losing speed above it."""
        for above in np.arange(k + 1, k + SCAN_STEPS + 1):
            if gain(above) < 0:
                lower = max(k, above - 1)
                e_lo, e_hi = e0 * (1 + 0.02 * lower) ** 2, e0 * (1 + 0.02 * above) ** 2
                e_ref, iterations, status = _newton_energy(shoot, e_lo, ftol, bracket=(e_lo, e_hi))
                return e_ref, iterations + count, status + f" (bracketed by a scan of {count} speeds)"
        raise failure

    ks = np.arange(-SCAN_STEPS, SCAN_STEPS + 1)
    values = np.full(len(ks), -math.inf)
    maximized: set[int] = set()

    def peak_gains(j):
        """Whether the gain peaks above zero within a step of speed k[j] (a band narrower than the step)."""
        from flyopt.cycle.minimize import bounded_minimum  # scipy's, ported: scipy.optimize costs ~0.3 s to import

        maximized.add(j)
        res = bounded_minimum(lambda k: -max(gain(k), -1e100), ks[j] - 1, ks[j] + 1, xatol=1e-6, maxiter=60)
        return float(res.x) if -res.fun > 0 else None

    for j in sorted(range(len(ks)), key=lambda i: abs(ks[i])):
        values[j] = gain(ks[j])
        if values[j] > 0:
            return bracket_from(float(ks[j]))
        if ks[j] == 1:
            # the guess (the speed of a flywheel near this one, in a search) is a peak: a band of gain
            # around it, narrower than the step, is the likeliest (near a fold, where the orbit is lost)
            middle = SCAN_STEPS
            if values[middle] >= max(values[middle - 1], values[middle + 1]) and np.isfinite(values[middle]):
                at = peak_gains(middle)
                if at is not None:
                    return bracket_from(at)
    # A band narrower than the scan step: maximize the gain around the best local maxima.
    finite = np.isfinite(values)
    peaks = [
        j
        for j in range(1, len(ks) - 1)
        if finite[j] and values[j] >= values[j - 1] and values[j] >= values[j + 1] and j not in maximized
    ]
    for j in sorted(peaks, key=lambda i: -values[i])[:3]:
        at = peak_gains(j)
        if at is not None:
            return bracket_from(at)
    raise failure


OPEN_STEP = 4.0
"""Largest step in u = log(J_F + min J_e) of the flywheel search's secant while δ's crossing is not yet bracketed
(a factor of e^4, some 55, in the total inertia a trial)."""


NARROW = 1e-3
"""Relative width of a bracket between a stall and a loss of energy below which :func:`_newton_energy` bisects
it on the energy gained alone (``gain_at``)."""


def _newton_energy(shoot, e0, ftol, bracket=(0.0, math.inf), gain_at=None):
    """Safeguarded Newton on y(Φ; E_ref) = 0 for the energy E_ref at φ = 0.

    y(Φ) > 0 (or a stall, where the speed reaches zero) means the machine
    gains energy over the cycle: the periodic energy is higher. The iterate
    stays inside the bracket of the sign change once one is known, and
    expands by factors of 4 in energy (2 in speed) until then.

    A bracket between a stall and a loss, with no gain seen, is bisected
    toward the stall's edge, where a narrow band of gain may lie (a machine
    that barely passes its load). Once it is narrower than :data:`NARROW`,
    its trials read only the energy gained, from ``gain_at(E_ref)`` (None:
    a stall), which needs no sensitivity (a fifth of a shot's cost); a trial
    that does not clearly lose is shot in full.
    """
    lo, hi = bracket
    e = e0
    last = None
    gains = False  # whether any trial gained energy over the cycle
    lo_stalls = False  # whether lo is a stall
    for it in range(1, MAX_NEWTON + 1):
        if gain_at is not None and lo_stalls and not gains and math.isfinite(hi) and hi - lo <= NARROW * hi:
            probe = gain_at(e)
            if probe is None:  # stalls
                lo = e
            elif probe < -ftol:  # clearly loses
                hi = e
            if probe is None or probe < -ftol:
                if (hi - lo) <= 1e-12 * hi:
                    break
                e = math.sqrt(lo * hi)
                continue
        r = shoot(e)
        if r is None:  # stalls: the energy is too low
            lo, lo_stalls = max(lo, e), lo_stalls or e >= lo
            e_next = 4 * e if math.isinf(hi) else math.sqrt(lo * hi) if lo > 0 else 0.5 * hi
        else:
            f, df = r
            last = f
            if f > 0:
                lo, lo_stalls = max(lo, e), False
                gains = True
            elif f < 0:
                hi = min(hi, e)
            if abs(f) <= ftol:
                return e, it, f"converged in {it} Newton iteration(s), |E(Φ) − E(0)| <= {ftol:g} W_s"
            step = -f / df if df < 0 else math.nan
            e_next = e + step
            if not (math.isfinite(e_next) and lo < e_next < hi and e / 16 < e_next < 16 * e):
                if lo > 0 and math.isfinite(hi):
                    e_next = math.sqrt(lo * hi)
                elif f > 0:
                    e_next = 4 * e
                else:
                    e_next = e / 4
        if e_next > 1e12 * e0:
            raise SolverFailed(
                "no periodic steady state: the machine keeps gaining energy over every cycle "
                "(it runs away: the driving torque exceeds the load at every speed tried, up "
                "to 1e6 times the guessed speed)"
            )
        if e_next < 1e-12 * e0 or (math.isfinite(hi) and hi < 1e-10 * e0):
            raise SolverFailed(
                "no periodic steady state: the machine loses energy over every cycle down to a "
                "stall (the load exceeds what the drive gives at every speed tried)"
            )
        if math.isfinite(hi) and lo > 0 and (hi - lo) <= 1e-12 * hi:
            break
        e = e_next
    if not gains and math.isfinite(hi):
        raise _NoGain(
            f"no periodic steady state: at every speed the machine passes the cycle at, it loses "
            f"energy over the cycle, and slower it stalls (the speed reaches zero); the load "
            f"exceeds what the drive gives (bracket [{lo:.6g}, {hi:.6g}] J of kinetic energy)"
        )
    raise SolverFailed(
        f"periodic solution not found: Newton on E(Φ) − E(0) did not converge in "
        f"{MAX_NEWTON} iterations (last residual {last!r} W_s, bracket [{lo:.6g}, {hi:.6g}] J)"
    )


# -- required flywheel with the dynamic model -------------------------------------


@dataclass(frozen=True)
class DynamicRequirement:
    """Smallest flywheel whose periodic steady state keeps δ.

    Attributes
    ----------
    j_required : float
        J_F [kg*m^2] (<= 0: the machine's own inertia suffices; with ``limit`` "none" it is the bound
        −min J_e, where the machine would have no inertia left, not a flywheel at which δ is reached).
    solution : PeriodicSolution
        The periodic solution with that flywheel where it is needed, or where δ reaches the allowed
        value at it (``limit`` "delta"); with none (J_F = 0), the machine as it will run, where δ stays
        below the allowed value at any flywheel ("none", a "stall" below 0); a machine with no inertia
        of its own and none needed has the limit its vanishing inertia tends to.
    iterations : int
        Periodic solutions computed.
    held : str
        What was held: the prescribed mean speed (angle-only torques) or
        nothing but the torque laws (speed-dependent: ω_m is an outcome).
    j_initial : float
        The constant-inertia estimate the iteration started from [kg*m^2].
    limit : {"delta", "stall", "none"}
        "delta": the flywheel reaches the allowed δ. "stall": δ stays below
        the allowed value down to the smallest flywheel that still has a
        periodic steady state (below it the machine stalls, e.g. the motor
        breaks down in the working stroke); ``j_required`` is that limit
        (to :data:`STALL_RTOL`) and ``solution.delta`` is below δ. "none":
        δ stays below the allowed value however small the inertia (nothing
        fluctuates, or a motor's slip alone holds the speed): no flywheel is
        needed and δ reaches the allowed value at none.
    """

    j_required: float
    solution: PeriodicSolution
    iterations: int
    held: str
    j_initial: float
    limit: str


def _found(solution):
    """A periodic solution the search has found (its bracket's high end is set before it is read)."""
    if solution is None:
        raise RuntimeError("the search ended on a bracket whose periodic solution was never found")
    return solution


def dynamic_requirement(
    net_torque: NetTorqueLike,
    j_machine: InertiaLike,
    cycle_angle: float,
    omega_mean: float,
    delta: float,
    knots: Iterable[float] = (),
    rtol: float = 1e-10,
    *,
    slip_first: bool = False,
) -> DynamicRequirement:
    """Smallest J_F whose periodic solution keeps (ω_max − ω_min)/ω_mean <= δ.

    Parameters
    ----------
    net_torque, j_machine, cycle_angle, knots
        As for :func:`periodic_solution`.
    omega_mean : float
        Prescribed mean speed for angle-only torques; a guess otherwise
        (then ω_m is what the torque–speed balance gives with the flywheel
        found, reported in ``solution.omega_mean``) [rad/s].
    delta : float
        Allowed coefficient of speed fluctuation [-].
    rtol : float
        Relative tolerance on δ achieved.
    slip_first : bool
        Ask first whether a motor's slip alone keeps δ (:func:`_held_by_balance`), then
        the one Newton solve: for a caller that knows the machine keeps δ with no
        flywheel (the drive's chosen motor, :mod:`flyopt.drive.codesign`), for which the
        one solve would search toward a vanishing inertia and give up. Default: the one
        solve first.

    Returns
    -------
    DynamicRequirement

    Raises
    ------
    SolverFailed
        When the iteration does not converge or no periodic solution exists.

    Notes
    -----
    δ falls like 1/(J_F + J) (section 2: an equilateral hyperbola), so the
    secant method runs on log δ against log(J_F + min J): it is exact in one
    step for constant J and angle-only torques and takes a few otherwise.
    It starts from the constant-inertia estimate at ω_mean, keeps a bracket
    of the sign change once one is known and steps back toward the larger
    flywheel when a trial stalls.
    """
    check_speed_delta(omega_mean, delta)
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    phi = model.grid_angles()
    j_grid = model.inertia(phi)
    j_low = float(j_grid.min())
    if model.steady:  # nothing fluctuates: the machine's own inertia (even none) suffices
        return DynamicRequirement(
            j_required=0.0 - j_low,
            solution=_steady(model, 0.0, omega_mean),
            iterations=1,
            held=_held(model),
            j_initial=0.0 - j_low,
            limit="none",
        )
    j_mean = float(np.mean(j_grid[:, :-1]))  # an estimate only, for the start
    # constant-inertia estimate at the guessed speed
    j_tot0 = shooting.energy_swing(model, omega_mean) / (omega_mean**2 * delta)
    j_initial = j_tot0 - j_mean
    # with no inertia at all, the balance is asked first: the one solve below would integrate ever stiffer cycles
    no_inertia = not float(j_grid.max()) > 0
    balance_first = slip_first or (model.speed_dependent and no_inertia)
    if balance_first:
        try:
            first = _held_by_balance(model, omega_mean, delta, j_low, j_initial, no_inertia)
        except SolverFailed:
            first = None  # the machine as it is has no steady state: the search below says why
        if first is not None:
            return first
    try:  # the one Newton solve; the search below settles what it cannot
        return _as_fitted(model, _one_solve(model, delta, omega_mean, j_tot0, j_initial), j_low)
    except NotSettled:
        BUILDS["fallback to the CVODES search"] += 1
    held = None if balance_first else _held_by_balance(model, omega_mean, delta, j_low, j_initial, no_inertia)
    if held is not None:
        return held
    # unknown u = log(J_F + j_low)
    u = math.log(max(j_tot0 - (j_mean - j_low), 0.25 * j_tot0, 1e-300) if j_tot0 > 0 else max(j_mean, 1e-300))
    target = math.log(delta)
    # the smallest total inertia tried: if δ stays below the allowed value down to it, a motor's
    # stiffness alone keeps δ, and no flywheel is needed (J_F + J_e would otherwise round to 0)
    u_floor = max(u, math.log(max(j_mean, 1e-300))) + math.log(VANISHING_INERTIA)
    lo, hi = -math.inf, math.inf  # u where δ is too large (or no steady state) / small enough
    lo_failed = False  # whether lo is a flywheel without a periodic steady state
    failure = None
    stalled = model.stalls.get(model.theta)
    if stalled is not None:  # a search at another δ found none there: this one starts above it
        lo, lo_failed = math.log(stalled + j_low), True
        failure = f"a search at another δ found no periodic steady state at J_F = {stalled:.6g} kg*m^2"
        u = max(u, lo + 10 * STALL_RTOL)
    hi_solution = None
    stable: list[tuple[float, float]] = []  # (u, 1 − multiplier) of each new hi
    guided, fold = 0, None  # trials in a row aimed at the fold by _toward_fold, its last estimate
    secant = False  # whether the last trial's secant on δ stepped inside the bracket
    checked = False  # whether the drive's best work over the cycle was asked (_best_work)
    previous = None
    guess = omega_mean
    for it in range(1, MAX_DYNAMIC + 1):
        j_f = math.exp(u) - j_low
        try:
            sol = _periodic(model, j_f, guess)
        except SolverFailed as err:
            sol, failure = None, str(err)
        if sol is not None and sol.delta <= 0:  # no fluctuation at all: any flywheel will do
            found = DynamicRequirement(
                j_required=-j_low, solution=sol, iterations=it, held=_held(model), j_initial=j_initial, limit="none"
            )
            return _as_fitted(model, found, j_low)
        if sol is None:
            model.stalls[model.theta] = max(j_f, model.stalls.get(model.theta, -math.inf))
            if math.isinf(hi) and not checked:
                # no flywheel has run yet: is there any speed at which the drive can make up the load's work?
                checked = True
                work, (_, top) = _best_work(model, omega_mean)
                if work < 0:
                    raise SolverFailed(
                        f"no flywheel gives a periodic steady state: even at the most favourable speed at each "
                        f"angle (0 to {top:.4g} rad/s) the drive falls {-work:.4g} J short of the load's work over "
                        f"the cycle; a flywheel only evens the speed out: a stronger drive is needed"
                    )
            if u > lo:
                lo, lo_failed = u, True
            u_next = u + 1.0 if math.isinf(hi) else 0.5 * (lo + hi)
        else:
            # a motor's next trial starts from this orbit's speed at φ = 0, where its energy is asked for (its
            # mean speed lies off the orbit's energy there by up to δ); a prescribed mean speed stays as it is
            guess = float(sol.omega[0]) if model.speed_dependent and not model.balanced else sol.omega_mean
            f = math.log(sol.delta) - target
            if abs(f) <= rtol:
                found = DynamicRequirement(
                    j_required=j_f, solution=sol, iterations=it, held=_held(model), j_initial=j_initial, limit="delta"
                )
                return _as_fitted(model, found, j_low)
            if f > 0 and u > lo:
                lo, lo_failed = u, False
            elif f < 0 and u < hi:
                hi, hi_solution = u, sol
                stable.append((u, 1.0 - sol.multiplier))
            if previous is not None and previous[0] != u and previous[1] != f:
                slope = (f - previous[1]) / (u - previous[0])
            else:
                slope = -math.exp(u) / (math.exp(u) + max(j_mean - j_low, 0.0))
            previous = (u, f)
            u_next = u - f / slope if slope < 0 else math.nan
            if math.isfinite(u_next) and not (math.isfinite(lo) and math.isfinite(hi)):
                # a bracket still open: a secant on a δ nearly flat in J_F leaped to e^1.3e11 (an overflow); it
                # moves at most OPEN_STEP in u a trial, as the expansion without it does
                u_next = min(max(u_next, u - OPEN_STEP), u + OPEN_STEP)
            secant = math.isfinite(u_next) and lo < u_next < hi
            if not secant:
                if math.isfinite(lo) and math.isfinite(hi):
                    u_next = 0.5 * (lo + hi)
                else:
                    u_next = u + (2.0 if f > 0 else -2.0)
        if lo_failed and math.isfinite(hi) and hi - lo > STALL_RTOL and (sol is None or not secant):
            # toward the fold where the secant on δ has no step inside the bracket (δ's crossing lies in the
            # stall, or is not bracketed) or the last trial stalled
            aim, fold = _toward_fold(lo, hi, stable, guided, fold)
            guided = guided + 1 if aim is not None else 0
            u_next = u_next if aim is None else aim
        if math.isfinite(lo) and math.isfinite(hi) and lo_failed and hi - lo <= STALL_RTOL:
            # δ stays below the allowed value down to where the steady state ceases to exist
            found = DynamicRequirement(
                j_required=math.exp(hi) - j_low,
                solution=_found(hi_solution),
                iterations=it,
                held=_held(model),
                j_initial=j_initial,
                limit="stall",
            )
            return _as_fitted(model, found, j_low)
        if u_next < u_floor:
            if hi <= u_floor:  # δ is below the allowed value even at a vanishing inertia
                found = DynamicRequirement(
                    j_required=0.0 - j_low,
                    solution=_found(hi_solution),
                    iterations=it,
                    held=_held(model),
                    j_initial=j_initial,
                    limit="none",
                )
                return _as_fitted(model, found, j_low)
            u_next = max(u_floor, 0.5 * (lo + u_floor)) if math.isfinite(lo) else u_floor
        u = u_next
    raise SolverFailed(
        f"the flywheel for delta = {delta!r} was not found in {MAX_DYNAMIC} periodic solutions "
        f"(bracket J_F in [{math.exp(lo) - j_low:.6g}, {math.exp(hi) - j_low:.6g}] kg*m^2; "
        f"last failure: {failure})"
    )


RUN_SPEEDS = 257
"""Speeds from 0 to 4 ω at which :func:`_best_work` reads each angle's most favourable torque."""

BEST_WORK_VALUES = 2**20
"""Torques :func:`_best_work` evaluates at a time (angles × speeds), so that a table of many points (up to
2**17 outputs a cycle) does not hold 33 million of them at once."""


def _best_work(model, omega):
    """(W, speeds): the work over the cycle of the most favourable net torque at each angle, the largest of
    M(φ, ω') over speeds ω' in [0, 4 ω] (:data:`RUN_SPEEDS` of them) [J], and the speeds' range.

    A periodic steady state with any inertia returns to its energy, ∮ M(φ, ω(φ)) dφ = 0, so W >= 0 for every
    one whose speed stays in that range: W < 0 means the drive cannot make up the load's work at any speed,
    whatever the flywheel. Between two speeds of the grid the torque may rise by up to half the step times the
    larger of its slopes at them, which is added (the maximum of a smooth torque between grid points).
    """
    speeds = np.linspace(0.0, 4.0 * omega, RUN_SPEEDS)
    step = speeds[1] - speeds[0]
    inner = model.inner_angles
    rows = max(1, BEST_WORK_VALUES // (inner.shape[1] * RUN_SPEEDS))  # pieces at a time: memory stays bounded
    best = np.empty(inner.shape)
    for k in range(0, inner.shape[0], rows):
        phi = inner[k : k + rows, :, None]
        m = model.torque(phi, speeds)
        slope = np.abs(model.torque_slope(phi, speeds)) if model.speed_dependent else np.zeros_like(m)
        rise = 0.5 * step * np.maximum(slope[..., 1:], slope[..., :-1])
        best[k : k + rows] = np.maximum(m.max(axis=-1), (np.maximum(m[..., 1:], m[..., :-1]) + rise).max(axis=-1))
    h = np.diff(model.grid_angles(), axis=1)
    return float(np.sum(0.5 * (best[:, 1:] + best[:, :-1]) * h)), (0.0, 4.0 * omega)


FOLD_AIM = 0.3
"""Where :func:`_toward_fold` aims beside the fold it estimates, in parts of :data:`STALL_RTOL`."""


MAX_GUIDED = 6
"""Trials in a row :func:`_toward_fold` may aim before the search bisects once."""


def _toward_fold(lo, hi, stable, guided, previous):
    """(The next trial u = log(J_F + min J_e) toward a stall limit or None (bisect), the fold estimated).

    Between a flywheel that has no periodic steady state (``lo``) and the smallest that has one (``hi``),
    the steady state is lost at a fold u*, where it meets the unstable one: its Floquet multiplier m tends
    to 1 like the square root of the distance, 1 − m = a s + b s² with s = √(u − u*). The three smallest
    flywheels that ran (``stable``: (u, 1 − m) of each new hi) give a, b and u* (u* where the curve through
    two of them meets the third). Such an estimate from flywheels far from the fold falls short of it, and a
    trial that stalls costs more than one that runs (the search for a gain at every speed): the trial aims
    above u* (expected to run, and to sharpen u*) by twice the estimate's change from the ``previous`` one,
    at most halfway to hi, and once hi is within 2 :data:`FOLD_AIM` of :data:`STALL_RTOL` above u*, FOLD_AIM
    of it below u* (expected to stall: the bracket then closes), where bisection takes a trial for each
    halving. After :data:`MAX_GUIDED` trials in a row it bisects once, so a limit that is not a fold (a
    torque that steps) is still bracketed.
    """
    if len(stable) < 3 or guided >= MAX_GUIDED:
        return None, previous
    (u1, g1), (u2, g2), (u3, g3) = stable[-3:]  # u1 > u2 > u3 = hi

    def mismatch(fold):
        """The third point's 1 − m less that of the curve through the first two, with the fold at ``fold``."""
        s1, s2, s3 = (math.sqrt(u - fold) for u in (u1, u2, u3))
        det = s1 * s2 * s2 - s2 * s1 * s1
        if det == 0:
            return math.nan
        a = (g1 * s2 * s2 - g2 * s1 * s1) / det
        b = (s1 * g2 - s2 * g1) / det
        return a * s3 + b * s3 * s3 - g3

    low = lo if math.isfinite(lo) else u3 - 1.0
    f_low, f_high = mismatch(low), mismatch(u3)
    if not (math.isfinite(f_low) and math.isfinite(f_high) and f_low * f_high < 0):
        return None, previous
    from flyopt.cycle.numerics import brentq  # scipy's, ported: scipy.optimize costs ~0.3 s to import

    fold = brentq(mismatch, low, u3, xtol=1e-3 * STALL_RTOL)
    if hi - fold <= 2 * FOLD_AIM * STALL_RTOL:
        aim = fold - FOLD_AIM * STALL_RTOL
    else:
        # above the fold by twice the estimate's last change (its error), at most halfway to hi
        change = abs(fold - previous) if previous is not None else math.inf
        aim = fold + min(0.5 * (hi - fold), max(2 * change, 2 * FOLD_AIM * STALL_RTOL))
    return (aim if lo < aim < hi else None), fold


def _held_by_balance(
    model: PeriodicModel, omega_mean: float, delta: float, j_low: float, j_initial: float, no_inertia: bool
) -> DynamicRequirement | None:
    """The requirement of a machine whose torque–speed balance alone keeps δ, or None.

    Such a machine (a motor's slip, a load falling steeply with speed: the speed at a vanishing inertia,
    :func:`_quasi_static`, within δ) needs no flywheel of any size: δ only falls as the inertia grows. With
    no inertia at all that balance is how it runs; with some, the machine as it is is simulated once. The
    search of :func:`dynamic_requirement` would walk down to a vanishing inertia to find the same, through
    ever stiffer cycles, and read CVODES giving up on them as a stall. None also where the machine's least
    inertia is zero but not all of it (a slider with no crank): neither limit is its motion. ``no_inertia``:
    whether the machine has none at any angle (as :func:`dynamic_requirement` found it on the grid).
    """
    if not model.speed_dependent:
        return None
    if not (no_inertia or j_low > 0):
        return None
    # the grid's extremes first: the refined ones lie beyond them, so a δ over the allowed value on the grid
    # is over it refined; with inertia the balance only tells whether δ can hold (the simulation says what it is)
    still = _quasi_static(model, omega_mean, 0)
    if still is None or still.delta > delta:
        return None
    sol = _quasi_static(model, omega_mean) if no_inertia else _as_it_is(model, omega_mean, still)
    if sol is None or sol.delta > delta:
        return None
    return DynamicRequirement(
        j_required=0.0 - j_low, solution=sol, iterations=1, held=_held(model), j_initial=j_initial, limit="none"
    )


RELAXED = 1e-8
"""The angle within which a machine's own inertia lets its speed relax to the torques' balance, in parts of the
cycle's shortest piece, below which that balance is taken as its motion: a feature of the torque as narrow as a
piece is followed to about that part of its height (a smooth one far closer: the square of the angle times its
harmonics). CVODES gives up long before (1e7 N*m per rad/s on 1e-6 kg*m^2 at 3000 rpm: 3e-11 rad, over pieces
of 0.2 rad)."""


def _as_it_is(model, omega_mean, still):
    """The periodic solution of the machine with no flywheel, whose torque balance ``still`` keeps δ; None
    where it cannot be integrated (the search then goes on).

    Its inertia J lets a disturbance of the balance's speed decay within J ω/|∂M/∂ω| radians of the cycle;
    where that is below :data:`RELAXED` of the shortest piece at every angle, the balance (refined) is its
    motion, with its energy.
    """
    phi = model.inner_angles
    omega = still.omega.reshape(phi.shape)
    with np.errstate(divide="ignore"):
        lag = float(np.max(model.inertia(phi) * omega / np.abs(model.torque_slope(phi, omega))))
    if lag <= RELAXED * float(np.min(model.pieces[:, 1] - model.pieces[:, 0])):
        refined = _quasi_static(model, omega_mean)
        if refined is not None:
            e0 = 0.5 * float(model.inertia(0.0)) * refined.omega[0] ** 2
            return replace(
                refined,
                e0=e0,
                status=(
                    f"{refined.status}; the machine's inertia lets its speed relax to that balance within "
                    f"{lag:.2g} rad of the cycle: the balance is its motion"
                ),
            )
    try:
        return _periodic(model, 0.0, omega_mean)
    except SolverFailed:
        return None


def _as_fitted(model: PeriodicModel, found: DynamicRequirement, j_low: float) -> DynamicRequirement:
    """``found`` with the periodic solution of the machine as it will run, where δ reaches the allowed value
    at no flywheel the search settled on (limit "none" or "stall").

    A flywheel that is needed is fitted: its solution is the one found. Where δ stays below the allowed value
    down to a vanishing inertia ("none") or to a stall below J_F = 0, the search's solution is a machine with
    less inertia than it has, so it is solved again with none (J_F = 0): its speed extremes, their angles and
    its δ are what the analysis reports. A machine with no inertia of its own (min J_e = 0) keeps the limit
    its vanishing inertia tends to. Where δ reaches the allowed value at a J_F < 0 (limit "delta") the solution
    stays the one at that J_F, which the solvers are checked against (tests/sizing/test_shooting.py);
    :meth:`flyopt.analysis.Analysis.speed_curve` draws that machine with J_F = 0.
    """
    if found.limit == "delta" or found.j_required > 0 or found.solution.j_flywheel == 0.0 or not j_low > 0:
        return found
    return replace(found, solution=_periodic(model, 0.0, found.solution.omega_mean))


NUDGE = 1e-6
"""The relative step the balance's Newton takes, toward where the torque would vanish, from a speed at which
the torque does not change with speed (a cubic damper centred on its speed: no Newton step is defined)."""


def _balance_speeds(model, phi, omega_guess, offset=0.0, max_iterations=100):
    """ω at each angle of ``phi`` where the net torque (plus ``offset``) vanishes, on the branch where
    it falls with speed (a motor's stable branch) [rad/s]; None when that branch is left (past a motor's
    breakdown: the machine would stall) or Newton does not settle to 1e-13 (a triple root, where the torque
    is flat in speed, settles linearly: up to some 50 steps)."""
    phi = np.asarray(phi, dtype=float)
    omega = np.broadcast_to(np.asarray(omega_guess, dtype=float), phi.shape).copy()
    for _ in range(max_iterations):
        torque, slope = model.torque(phi, omega) + offset, model.torque_slope(phi, omega)
        if not np.all(slope <= 0):
            return None
        flat = slope == 0
        step = np.where(flat, np.sign(torque) * NUDGE * omega, -torque / np.where(flat, -1.0, slope))
        step = np.clip(step, -0.5 * omega, omega)
        omega = omega + step
        if not np.any(flat & (torque != 0)) and np.max(np.abs(step) / omega) <= 1e-13:
            return omega
    return None


def quasi_static_delta(model: PeriodicModel, omega_guess: float) -> float | None:
    """δ of the speed at which the net torque vanishes at every angle (the limit of a vanishing inertia) [-]:
    that of :func:`_quasi_static`, None where the speed leaves the branch where the torque falls with it."""
    still = _quasi_static(model, omega_guess)
    return None if still is None else still.delta


ZOOMS = 6
"""Rounds of the search for a quasi-static speed extreme, each over 33 angles around the best so far."""


def _balance_extreme(model, omega, sign, offset, zooms):
    """(φ, ω) of the quasi-static speed's maximum (``sign`` 1) or minimum (-1), from ``omega`` on the inner grid.

    The grid's extreme is refined between its neighbours in its piece (a piece's ends are knots of the
    torque, where an extreme may sit): each round takes the best of 33 angles across the bracket and
    narrows it to that angle's neighbours, so six rounds place it to 1e-7 of a grid step and its speed to
    the balance's own 1e-13 (``zooms`` rounds: 0 keeps the grid's). None when the balance is left inside the
    bracket.
    """
    inner = model.inner_angles
    i, j = np.unravel_index(int(np.argmax(sign * omega)), omega.shape)
    n = inner.shape[1]
    best_phi, best = float(inner[i, j]), float(omega[i, j])
    a, b = float(inner[i, max(j - 1, 0)]), float(inner[i, min(j + 1, n - 1)])
    for _ in range(zooms):
        trial = np.linspace(a, b, 33)
        speeds = _balance_speeds(model, trial, best, offset)
        if speeds is None:
            return None
        k = int(np.argmax(sign * speeds))
        if sign * speeds[k] > sign * best:
            best_phi, best = float(trial[k]), float(speeds[k])
        width = (b - a) / 32
        a, b = max(a, best_phi - width), min(b, best_phi + width)
    # an extreme at a piece's end (a plateau of the speed begins or ends at a knot of the torque) is read
    # EDGE inside the piece, for the torque's side of the knot; its angle is the knot's (it was printed as
    # 1.071e-09 deg for a plateau that begins at 0)
    start, end = (float(v) for v in model.pieces[i])
    inside = 2 * EDGE * (end - start)
    if best_phi - start <= inside:
        best_phi = start
    elif end - best_phi <= inside:
        best_phi = end
    return best_phi, best


def _quasi_static(model, omega_mean, zooms=ZOOMS):
    """:func:`_balanced_motion`, kept with the model: a solve asks it of each requirement (the analysis and
    the δ-sensitivity's two), some 7 ms each on motor-press's 2,000 angles."""
    key = ("balance", float(omega_mean), zooms, model.balanced)
    known = model._known(key)
    if known is None:
        known = model._keep(key, (_balanced_motion(model, omega_mean, zooms),))
    return known[0]


def _balanced_motion(model, omega_mean, zooms):
    """The motion of a machine with no inertia at all: at each angle the speed at which its torques balance.

    With no inertia the equation of motion, J ω dω/dφ = M(φ, ω), leaves M = 0: the limit a vanishing
    inertia tends to, which a simulation can only approach through ever stiffer cycles. An unknown
    constant torque is corrected by c so that (ω_max + ω_min)/2 is the prescribed mean speed
    (Newton on c: dω/dc = −1/(∂M/∂ω) at each extreme). None when the speed leaves the branch where the
    torque falls with it (the machine would stall) or the mean speed is not settled. ``zooms``: the rounds
    that refine each extreme between the grid's angles (:func:`_balance_extreme`).
    """
    offset, status, omega = 0.0, None, omega_mean
    for iterations in range(1, MAX_NEWTON + 1):  # noqa: B007 -- the count is reported after the loop
        omega = _balance_speeds(model, model.inner_angles, omega, offset)  # from the last offset's speeds
        if omega is None:
            return None
        hi, lo = _balance_extreme(model, omega, 1, offset, zooms), _balance_extreme(model, omega, -1, offset, zooms)
        if hi is None or lo is None:
            return None
        w_mean = 0.5 * (hi[1] + lo[1])
        if not model.balanced:
            status = "quasi-static: the speed where the torque-speed balance holds at each angle (no inertia's motion)"
            break
        miss = w_mean / omega_mean - 1
        if abs(miss) <= MEAN_TARGET:
            status = (
                f"quasi-static: the speed where the torques balance at each angle (no inertia's motion); the "
                f"unknown constant torque corrected by {offset:.6g} N*m to hold the mean speed"
            )
            break
        slopes = model.torque_slope(np.array([hi[0], lo[0]]), np.array([hi[1], lo[1]]))
        offset -= miss * omega_mean / float(np.mean(-1.0 / slopes))
    if status is None:
        return None
    phi = model.grid_angles()
    return PeriodicSolution(
        phi=phi.reshape(-1),
        omega=omega.reshape(-1),
        omega_max=hi[1],
        omega_min=lo[1],
        omega_mean=w_mean,
        delta=(hi[1] - lo[1]) / w_mean,
        phi_omega_max=hi[0],
        phi_omega_min=lo[0],
        converged=True,
        status=f"{status} ({iterations} iteration(s))",
        periodicity_residual=0.0,
        periodicity_tolerance=0.0,
        tolerance=DELTA_RTOL * (hi[1] - lo[1]) / w_mean,
        multiplier=0.0,
        speed_dependent=True,
        iterations=iterations,
        j_flywheel=0.0,
        e0=0.0,
        period=_simpson_time(phi, omega),
        torque_offset=offset,
    )


def _one_solve(model, delta, omega_mean, j_tot0, j_initial):
    """:func:`flyopt.sizing.shooting.required_flywheel` as a DynamicRequirement."""
    found = shooting.required_flywheel(model, delta, omega_mean, j_tot0)
    y, w_s = found["y"], found["w_s"]
    swing = float(np.ptp(y))
    residual = float(y[-1, -1] - y[0, 0])
    if not model.speed_dependent and abs(residual) > _angle_only_tolerance(model, y, omega_mean, w_s):
        raise NotSettled("the angle-only torques do not balance over the cycle")  # the search says by how much
    status = (
        f"periodic, flywheel and steady state in one Newton solve ({found['iterations']} iterations, "
        f"fixed-step RK4 with {found['substeps']} step(s) per grid interval, checked against twice as many)"
    )
    sol = _finish(
        model,
        y,
        found["j_flywheel"],
        found["e_ref"],
        w_s,
        0.0,
        status,
        residual * w_s,
        shooting.PERIODIC_RTOL * max(swing, EPS) * w_s,
        found["multiplier"],
        found["iterations"],
        found["offset"],
    )
    return DynamicRequirement(
        j_required=found["j_flywheel"],
        solution=sol,
        iterations=found["iterations"],
        held=_held(model),
        j_initial=j_initial,
        limit="delta",
    )


def _held(model):
    if model.balanced:
        return "mean speed prescribed: the unknown constant torque balances the cycle at it"
    if model.speed_dependent:
        return "torque-speed balance: the mean speed is an outcome (the scene's speed was the first guess)"
    return "mean speed prescribed (torques of the angle only)"


# -- verification ---------------------------------------------------------------


@dataclass(frozen=True)
class Verification:
    """A periodic simulation of the machine with a chosen flywheel.

    Attributes
    ----------
    method : str
    achieved_delta, delta_allowed : float
        [-]
    omega_max, omega_min, omega_mean : float
        [rad/s]
    tolerance : float
        Accuracy of ``achieved_delta`` [-].
    flagged : bool
        True when achieved_delta exceeds delta_allowed by more than the tolerance.
    j_flywheel : float
        The flywheel simulated, at the reference shaft [kg*m^2].
    solution : PeriodicSolution or None
        The simulated speed over the cycle (None where nothing was simulated: net areas).
    """

    method: str
    achieved_delta: float
    delta_allowed: float
    omega_max: float
    omega_min: float
    omega_mean: float
    tolerance: float
    flagged: bool
    j_flywheel: float
    solution: PeriodicSolution | None = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        """The fields of the report's "verification" entry (SI)."""
        return {
            "method": self.method,
            "achieved_delta": self.achieved_delta,
            "delta_allowed": self.delta_allowed,
            "omega_max": self.omega_max,
            "omega_min": self.omega_min,
            "omega_mean": self.omega_mean,
            "tolerance": self.tolerance,
            "flagged": self.flagged,
            "j_at_reference": self.j_flywheel,  # the name of the flywheel's inertia at the reference shaft
        }


def verify(
    net_torque: NetTorqueLike,
    j_machine: InertiaLike,
    cycle_angle: float,
    omega_mean: float,
    delta_allowed: float,
    j_flywheel: float,
    knots: Iterable[float] = (),
) -> Verification:
    """Simulate the periodic steady state with a chosen flywheel and compare δ.

    Parameters
    ----------
    net_torque, j_machine, cycle_angle, omega_mean, knots
        As for :func:`periodic_solution`.
    delta_allowed : float
        The allowed coefficient of speed fluctuation [-].
    j_flywheel : float
        The chosen flywheel J_F [kg*m^2].

    Returns
    -------
    Verification
        When neither the torques nor the inertia vary with the angle, the
        speed does not fluctuate: achieved δ = 0 whatever the inertia (even
        none), and the method says so.

    Raises
    ------
    SceneError
        Field ``machine.inertia``: the machine and flywheel have no inertia
        while the torque or the inertia varies with the angle (the speed
        would jump), unless the torques fall with speed and balance at every
        angle (their balance is then the motion: :func:`_quasi_static`).
    """
    check_speed_delta(omega_mean, delta_allowed)
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    j_grid = model.inertia(model.grid_angles())
    j_low = float(np.min(j_grid)) + float(j_flywheel)
    # with no inertia at all, torques that fall with speed hold it where they balance (the requirement's answer)
    still = None
    if not model.steady and j_low == 0 and not float(np.max(j_grid)) + float(j_flywheel) > 0:
        still = _quasi_static(model, omega_mean) if model.speed_dependent else None
    if not model.steady and j_low == 0 and still is None:
        raise SceneError(
            "machine.inertia",
            "the machine and its flywheel have no inertia (J = 0 kg*m^2) while "
            "its torque varies with the angle: the speed would jump, so δ is undefined; give the "
            "machine's inertia (> 0)",
        )
    sol = still if still is not None else _periodic(model, float(j_flywheel), omega_mean)
    method = (
        "no fluctuation: neither the torques nor the inertia vary with the angle, so the speed is constant "
        "(δ = 0 whatever the inertia)"
        if model.steady
        else "no inertia: the speed where the torques balance at each angle (they fall with speed)"
        if still is not None
        else "periodic simulation (CVODES shooting, Newton on the periodicity condition)"
    )
    return Verification(
        method=method,
        achieved_delta=sol.delta,
        delta_allowed=float(delta_allowed),
        omega_max=sol.omega_max,
        omega_min=sol.omega_min,
        omega_mean=sol.omega_mean,
        tolerance=sol.tolerance,
        flagged=bool(sol.delta - delta_allowed > sol.tolerance),
        j_flywheel=float(j_flywheel),
        solution=sol,
    )
