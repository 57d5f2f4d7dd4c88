"""The energy–mass (Wittenbauer) method: a machine whose inertia varies with the angle.

Torques of the angle only, J_e(φ) = J_c + J_v(φ) (docs/flywheel-design.md,
section 6): :func:`energy_mass_requirement` gives the flywheel in closed
form, :func:`achieved_speed` the speed fluctuation a given flywheel achieves
(its forward use).

Maxima and minima over the continuous angle are exact, not sampled: a dense
grid that contains every knot (where a torque steps or kinks) brackets them,
and each bracket is refined by Brent's method on the derivative — every
bracket of every extreme that one answer needs in one vectorized run
(:func:`flyopt.cycle.numerics.brentq_many`), with J_e(φ), dJ_e/dφ and the
torques evaluated on arrays.
Results are SI: [rad], [rad/s], [kg*m^2], [J].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from flyopt.cycle.indicator import ExcessWork
from flyopt.cycle.numerics import brentq_many, quad_many
from flyopt.sizing._numerics import EPS, Inertia, InertiaLike, check_speed_delta

GRID = 4096
"""Points per cycle of the grid that brackets maxima and minima (knots added)."""

MEAN_PANELS = 64
"""Panels per cycle (at least) of the quadrature of the cycle mean of J_e."""

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)
_GL_NODES = 0.5 * (_GL_NODES + 1.0)
_GL_WEIGHTS = 0.5 * _GL_WEIGHTS
_GL4_NODES, _GL4_WEIGHTS = np.polynomial.legendre.leggauss(4)
_GL4_NODES = 0.5 * (_GL4_NODES + 1.0)
_GL4_WEIGHTS = 0.5 * _GL4_WEIGHTS

GRID_CHECK_POINTS = 16
"""Angles between knots where the grid's ΔE is checked against the adaptive quadrature."""

GRID_CHECK = 1e-14
"""Largest accepted difference of the grid's ΔE from the adaptive quadrature's, relative to the
cycle's work scale (peak |M_d − M_r| Φ): a few tens of ulps."""


def _curve_limits(curve, phi):
    left, right = curve.limits(phi)
    return np.asarray(left, dtype=float), np.asarray(right, dtype=float)


# -- exact extremes of piecewise-smooth functions ---------------------------------


def _extremes(x, problems, slope, value, span):
    """Largest or smallest values of piecewise-smooth functions on [x_0, x_n], all refined at once.

    For each function the grid's best point is the answer unless a grid
    interval where the derivative changes sign (from + to − for a maximum)
    holds a better one: every such interval that could (its end values plus
    twice the derivative's bulge reach the grid's best) is refined by
    Brent's method on the derivative, the intervals of every function in
    one vectorized run, and the best of the zeros found is taken (the first
    one on ties, the grid's point unless a zero is strictly better).

    Parameters
    ----------
    x : ndarray
        Grid containing every point where the functions kink [rad].
    problems : list of (f, d_right, d_left, find_max)
        Per function: its values on the grid, the right and left limits of
        its derivative (or of a function with the same sign) there, and
        whether its maximum (True) or minimum is wanted.
    slope : callable (t, k, p) -> ndarray
        That derivative at the angles t inside grid intervals k, for the
        functions p (arrays of one length).
    value : callable (t, k, p) -> ndarray
        The functions p at t inside intervals k.
    span : float
        Length of the whole interval, for the root tolerance [rad].

    Returns
    -------
    list of (float, float)
        Location and value of each extreme, in the order of ``problems``.
    """
    h = np.diff(x)
    best, ks, ps, lows, highs = [], [], [], [], []
    for q, (f, d_right, d_left, find_max) in enumerate(problems):
        s = 1.0 if find_max else -1.0
        fs = s * f
        i = int(np.argmax(fs))
        best.append([float(x[i]), float(fs[i])])
        dr, dl = s * d_right[:-1], s * d_left[1:]
        cand = np.flatnonzero((dr > 0) & (dl < 0) & (h > 0))
        bulge = h[cand] * np.maximum(np.abs(dr[cand]), np.abs(dl[cand]))
        cand = cand[np.maximum(fs[cand], fs[cand + 1]) + 2 * bulge >= best[q][1]]
        ks.append(cand)
        ps.append(np.full(len(cand), q))
        lows.append(d_right[cand])
        highs.append(d_left[cand + 1])
    k, p = np.concatenate(ks), np.concatenate(ps)
    if len(k):
        a, b = x[k], x[k + 1]
        da, db = np.concatenate(lows), np.concatenate(highs)

        def g(t, i):
            inside = slope(t, k[i], p[i])
            return np.where(t <= a[i], da[i], np.where(t >= b[i], db[i], inside))

        roots = brentq_many(g, a, b, da, db, xtol=1e-15 * span, rtol=4 * EPS)
        signs = np.array([1.0 if problem[3] else -1.0 for problem in problems])
        values = signs[p] * value(roots, k, p)
        for q in range(len(problems)):
            mine = np.flatnonzero(p == q)
            if len(mine):
                j = mine[int(np.argmax(values[mine]))]
                if values[j] > best[q][1]:
                    best[q] = [float(roots[j]), float(values[j])]
    return [(where, (1.0 if problem[3] else -1.0) * v) for (where, v), problem in zip(best, problems)]


class _CycleGrid:
    """ΔE, M and J of an angle-only cycle on a dense grid with every knot.

    The grid is built once per (ΔE, J_e) pair and kept on the ExcessWork
    (:func:`_grid`): the requirement and the forward use share it.

    ΔE on the grid is closed-form for piecewise-linear torques; otherwise a
    composite Gauss–Legendre rule on every grid interval (``rule``: 4 points,
    or 8 where the 4-point rule fails its check against the adaptive
    quadrature of the ExcessWork).
    """

    def __init__(self, excess_work, inertia, points=GRID):
        cycle = excess_work.cycle_angle
        knots = np.concatenate((excess_work.knots, inertia.knots))
        x = np.union1d(np.linspace(0.0, cycle, points + 1), knots[(knots >= 0) & (knots <= cycle)])
        self.x = x
        self.cycle = cycle
        self.ew = excess_work
        self.inertia = inertia
        d_left, d_right = _curve_limits(excess_work.driving, x)
        r_left, r_right = _curve_limits(excess_work.resisting, x)
        self.m_left, self.m_right = d_left - r_left, d_right - r_right
        linear = excess_work.driving.is_linear and excess_work.resisting.is_linear
        if linear:
            self.delta_e, self.rule = np.asarray(excess_work(x), dtype=float), None
        else:  # composite Gauss-Legendre between grid points (smooth there), checked
            self.delta_e, self.rule = self._composite(_GL4_NODES, _GL4_WEIGHTS), 4
            if not self._agrees_with_excess_work():
                self.delta_e, self.rule = self._composite(_GL_NODES, _GL_WEIGHTS), 8
        # J and dJ/dφ on the grid; where J kinks (its knots) the derivative's one-sided limits
        self.j, dj = inertia.value_and_derivative(x)
        self.dj_right, self.dj_left = dj, dj.copy()
        at = np.flatnonzero(np.isin(x, inertia.knots))
        if len(at):
            eps = 1e-12 * cycle
            sides = inertia.derivative(np.concatenate((x[at] + eps, x[at] - eps)))
            self.dj_right[at], self.dj_left[at] = sides[: len(at)], sides[len(at) :]
        self.linear = linear

    def _composite(self, nodes, weights):
        """ΔE on the grid by a Gauss–Legendre rule on every grid interval, summed in extended precision [J]."""
        x = self.x
        h = np.diff(x)
        at = x[:-1, None] + h[:, None] * nodes[None, :]
        parts = (self.ew.net_torque(at) * weights[None, :]).sum(axis=1) * h
        return np.concatenate(([0.0], np.cumsum(parts, dtype=np.longdouble))).astype(float)

    def _agrees_with_excess_work(self):
        """The grid's ΔE against the ExcessWork's (adaptive Gauss–Kronrod to 1e-13, its own error
        estimate) at every knot and at GRID_CHECK_POINTS angles between, to GRID_CHECK of the
        work scale. The 4-point rule on intervals of Φ/4096 is exact to round-off for any torque
        without harmonics far above the hundredth; where it is not, this says so and the grid
        takes the 8-point rule (exact to round-off up to the thousandth), as it does when the
        adaptive quadrature cannot give the reference to 1e-13."""
        ew, x = self.ew, self.x
        knots = np.searchsorted(x, ew.knots)
        n = len(x) - 1
        inner = np.unique(((np.arange(GRID_CHECK_POINTS) + 0.382) * n / GRID_CHECK_POINTS).astype(int))
        try:
            reference = np.concatenate((ew.at_knots, ew(x[inner])))
        except ArithmeticError:  # the adaptive quadrature cannot reach 1e-13 from a knot to there
            return False
        got = self.delta_e[np.concatenate((knots, inner))]
        return bool(np.all(np.abs(got - reference) <= GRID_CHECK * ew.scale()))

    def delta_e_at(self, t, k):
        """ΔE at the angles t inside grid intervals k (the knot value plus an exact quadrature) [J]."""
        a = self.x[k]
        h = t - a
        nodes = a[:, None] + h[:, None] * _GL_NODES[None, :]
        return self.delta_e[k] + h * (self.ew.net_torque(nodes) * _GL_WEIGHTS).sum(axis=1)

    def torque_at(self, t):
        """M_d − M_r at the angles t (right limits) [N*m]."""
        return self.ew.net_torque(t)

    def torque_and_delta_e_at(self, t, k):
        """M_d − M_r and ΔE at t inside intervals k, with one evaluation of the torques."""
        a = self.x[k]
        h = t - a
        n = len(t)
        nodes = a[:, None] + h[:, None] * _GL_NODES[None, :]
        m = self.ew.net_torque(np.concatenate((t, nodes.ravel())))
        return m[:n], self.delta_e[k] + h * (m[n:].reshape(n, len(_GL_NODES)) * _GL_WEIGHTS).sum(axis=1)

    @cached_property
    def mean_inertia(self):
        """Cycle mean of J [kg*m^2]: adaptive Gauss–Kronrod quadrature to 1e-13 (with its error
        estimate), on at least MEAN_PANELS panels split at J's own knots (smooth between them)."""
        cycle = self.cycle
        knots = self.inertia.knots
        ends = np.union1d([0.0, cycle], knots[(knots > 0) & (knots < cycle)])
        count = np.maximum(1, np.ceil(MEAN_PANELS * np.diff(ends) / cycle)).astype(int)
        piece = np.repeat(np.arange(len(count)), count)
        step = np.arange(len(piece)) - np.repeat(np.cumsum(count) - count, count)
        lo = ends[piece] + step * (np.diff(ends) / count)[piece]
        hi = np.append(lo[1:], cycle)
        scale = cycle * float(np.max(np.abs(self.j)))
        parts = quad_many(lambda phi, i: self.inertia(phi), lo, hi, scale)
        return math.fsum(parts) / cycle

    @cached_property
    def delta_e_extremes(self):
        """(location, value) of the largest and of the smallest ΔE over the cycle [rad], [J]."""
        (phi_max, neg_max), (phi_min, neg_min) = _energy_mass_extremes(self, [(0.0, False), (0.0, True)])
        return (phi_max, -neg_max), (phi_min, -neg_min)


def _grid(excess_work, j_machine):
    """The :class:`_CycleGrid` of ΔE and J_e, built once per pair and kept on the ExcessWork."""
    grids = excess_work.__dict__.setdefault("_energy_mass_grids", {})
    key = ("value", float(j_machine)) if isinstance(j_machine, (int, float)) else ("object", id(j_machine))
    if key not in grids:
        if len(grids) > 8:
            grids.clear()
        grids[key] = (j_machine, _CycleGrid(excess_work, Inertia(j_machine)))  # j_machine kept: its id stays
    return grids[key][1]


# -- the energy–mass method ------------------------------------------------------


@dataclass(frozen=True)
class EnergyMassRequirement:
    """Required flywheel by the exact energy–mass method, with the classical comparison.

    Attributes
    ----------
    j_required : float
        Flywheel inertia J_F at the reference shaft [kg*m^2] (<= 0: none needed).
    e0 : float
        Kinetic energy at φ = 0 with that flywheel [J].
    phi_omega_max, phi_omega_min : float
        Tangent points of the energy–mass diagram: where ω_max and ω_min are
        reached [rad].
    omega_mean, delta : float
        The prescribed mean speed [rad/s] and coefficient of fluctuation [-].
    omega_max, omega_min : float
        ω_m (1 ± δ/2) [rad/s].
    a_max : float
        Largest span of ΔE over the cycle [J].
    j_machine_mean : float
        Cycle mean of the machine's J_e(φ) [kg*m^2].
    j_constant_inertia : float
        What the constant-inertia method gives with J_e replaced by its mean,
        A_max/(ω_m² δ) − mean J_e [kg*m^2].
    delta_constant_inertia : float or None
        The δ that the constant-inertia flywheel really achieves (exact
        forward method) [-]; None when that flywheel is not positive enough
        to keep the machine turning. Computed on first use (a nested root
        search that sizing does not need).
    """

    j_required: float
    e0: float
    phi_omega_max: float
    phi_omega_min: float
    omega_mean: float
    delta: float
    omega_max: float
    omega_min: float
    a_max: float
    j_machine_mean: float
    j_constant_inertia: float
    _grid: object = field(default=None, repr=False, compare=False)
    _lazy: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def delta_constant_inertia(self) -> float | None:
        """The δ the constant-inertia flywheel really achieves [-] (None: it cannot keep the machine
        turning), by the forward use of the energy–mass method (docs/flywheel-design.md, section 6)."""
        if "delta_ci" not in self._lazy:
            try:
                self._lazy["delta_ci"] = _achieved(self._grid, self.j_constant_inertia, self.omega_mean).delta
            except ValueError:
                self._lazy["delta_ci"] = None
        return self._lazy["delta_ci"]

    @property
    def j_error(self) -> float:
        """Relative error of the constant-inertia J_F against the exact one [-]."""
        return (self.j_constant_inertia - self.j_required) / self.j_required if self.j_required else math.nan


def energy_mass_requirement(
    excess_work: ExcessWork, j_machine: InertiaLike, omega_mean: float, delta: float
) -> EnergyMassRequirement:
    """Flywheel for a machine of variable inertia, by the energy–mass closed form.

    With ω_max,min = ω_m (1 ± δ/2) and J(φ) the machine's equivalent inertia
    (docs/flywheel-design.md, section 6):

        J_F = ( max_φ[½ ω_min² J(φ) − ΔE(φ)] − min_φ[½ ω_max² J(φ) − ΔE(φ)] ) / ( ½ (ω_max² − ω_min²) ),
        E_0 = min_φ[½ ω_max² (J_F + J(φ)) − ΔE(φ)].

    (The page writes J_F + J_c with the variable part J_v; J here is the
    whole J_c + J_v, which moves J_c to the left side.) With constant J it is
    the constant-inertia method, J_F = A_max/(ω_m² δ) − J_c.

    Parameters
    ----------
    excess_work : flyopt.cycle.indicator.ExcessWork
        ΔE(φ) of torques that depend on the angle only.
    j_machine : float, EquivalentInertia or callable
        J_e(φ) of the machine at the reference shaft [kg*m^2]; a callable
        must accept CasADi symbols (its derivative is taken exactly).
    omega_mean : float
        Mean speed ω_m = (ω_max + ω_min)/2 [rad/s].
    delta : float
        Allowed coefficient of speed fluctuation (ω_max − ω_min)/ω_m [-].

    Returns
    -------
    EnergyMassRequirement

    Notes
    -----
    The max and min over the continuous angle are exact: a grid of
    :data:`GRID` points plus every knot brackets them and Brent's method
    finds the zero of the derivative ½ ω² J'(φ) − (M_d − M_r)(φ) in each
    bracket; at a knot where the torque steps the derivative changes sign
    there and the knot itself is the extreme.

    References
    ----------
    .. [1] Wittenbauer, F., energy–mass diagram (Wittenbauer diagram), as in
       Shigley & Uicker, *Theory of Machines and Mechanisms*, flywheels.
    """
    check_speed_delta(omega_mean, delta)
    grid = _grid(excess_work, j_machine)
    w_max, w_min = omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)
    half_max, half_min = 0.5 * w_max**2, 0.5 * w_min**2

    # max[½ω_min² J − ΔE], min[½ω_max² J − ΔE], and max ΔE, min ΔE (as min and max of −ΔE): one refinement
    upper, lower, neg_de_max, neg_de_min = _energy_mass_extremes(
        grid, [(half_min, True), (half_max, False), (0.0, False), (0.0, True)]
    )
    grid.__dict__.setdefault(
        "delta_e_extremes",  # the forward use needs them again
        ((neg_de_max[0], -neg_de_max[1]), (neg_de_min[0], -neg_de_min[1])),
    )
    j_required = (upper[1] - lower[1]) / (half_max - half_min)
    e0 = lower[1] + half_max * j_required

    de_max = neg_de_max[1] * -1.0  # max ΔE = −min(−ΔE)
    de_min = neg_de_min[1] * -1.0
    a_max = de_max - de_min
    j_mean = grid.mean_inertia
    j_ci = a_max / (omega_mean**2 * delta) - j_mean
    return EnergyMassRequirement(
        j_required=float(j_required),
        e0=float(e0),
        phi_omega_max=lower[0],
        phi_omega_min=upper[0],
        omega_mean=float(omega_mean),
        delta=float(delta),
        omega_max=w_max,
        omega_min=w_min,
        a_max=float(a_max),
        j_machine_mean=j_mean,
        j_constant_inertia=float(j_ci),
        _grid=grid,
    )


def _energy_mass_extremes(grid, wanted):
    """Extremes over φ of ½ ω² J(φ) − ΔE(φ) (of −ΔE alone where ½ ω² is 0), all in one refinement.

    Parameters
    ----------
    grid : _CycleGrid
    wanted : list of (float, bool)
        ½ ω² [rad^2/s^2] and find_max, per extreme.

    Returns
    -------
    list of (float, float)
        Location [rad] and value [J] of each.
    """
    coefficients = np.array([c for c, _ in wanted])
    problems = []
    for c, find_max in wanted:
        if c == 0.0:
            problems.append((-grid.delta_e, -grid.m_right, -grid.m_left, find_max))
        else:
            problems.append(
                (c * grid.j - grid.delta_e, c * grid.dj_right - grid.m_right, c * grid.dj_left - grid.m_left, find_max)
            )
    need_j = bool(np.any(coefficients != 0.0))

    def slope(t, k, p):
        c = coefficients[p]
        torque = grid.torque_at(t)
        if not need_j:
            return -torque
        return np.where(c == 0.0, -torque, c * grid.inertia.derivative(t) - torque)

    def value(t, k, p):
        c = coefficients[p]
        de = grid.delta_e_at(t, k)
        if not need_j:
            return -de
        return np.where(c == 0.0, -de, c * grid.inertia(t) - de)

    return _extremes(grid.x, problems, slope, value, grid.cycle)


@dataclass(frozen=True)
class SpeedFluctuation:
    """Speed over one cycle of a machine with a given flywheel (exact forward method).

    Attributes
    ----------
    phi, omega : ndarray
        Grid of angles [rad] and the speed there [rad/s] (for plots; the
        extremes below are exact, not taken from the grid).
    omega_max, omega_min, omega_mean : float
        [rad/s]; omega_mean = (omega_max + omega_min)/2 as prescribed.
    delta : float
        (ω_max − ω_min)/ω_m [-].
    phi_omega_max, phi_omega_min : float
        Where the extremes are reached [rad].
    e0 : float
        Kinetic energy at φ = 0 [J].
    """

    phi: np.ndarray
    omega: np.ndarray
    omega_max: float
    omega_min: float
    omega_mean: float
    delta: float
    phi_omega_max: float
    phi_omega_min: float
    e0: float


def achieved_speed(
    excess_work: ExcessWork, j_machine: InertiaLike, omega_mean: float, j_flywheel: float = 0.0
) -> SpeedFluctuation:
    """Speed fluctuation that a given flywheel achieves (energy–mass forward use).

    ω(φ) = sqrt(2 (E_0 + ΔE(φ)) / (J_F + J(φ))), with E_0 chosen so that
    (ω_max + ω_min)/2 = ω_m (docs/flywheel-design.md, section 6).

    Parameters
    ----------
    excess_work : flyopt.cycle.indicator.ExcessWork
        ΔE(φ) of torques of the angle only.
    j_machine : float, EquivalentInertia or callable
        J(φ) of the machine [kg*m^2].
    omega_mean : float
        Mean speed [rad/s].
    j_flywheel : float
        J_F [kg*m^2].

    Returns
    -------
    SpeedFluctuation

    Raises
    ------
    ValueError
        When J_F + J(φ) is not positive, or when no mean speed ω_m is
        possible because the speed would reach zero in the cycle.
    """
    check_speed_delta(omega_mean, None)
    return _achieved(_grid(excess_work, j_machine), float(j_flywheel), omega_mean)


def _achieved(grid, j_flywheel, omega_mean):
    j = grid.j + j_flywheel
    if not np.all(j > 0):
        raise ValueError(
            f"the total inertia J_F + J_e(φ) must be positive; with J_F = {j_flywheel!r} kg*m^2 "
            f"it reaches {float(j.min())!r} kg*m^2"
        )
    (_, de_max), (_, de_min) = grid.delta_e_extremes

    def extremes(e0):
        """Largest and smallest of (E_0 + ΔE)/(J_F + J) = ω²/2, refined together."""
        e = e0 + grid.delta_e
        d_right = grid.m_right * j - e * grid.dj_right
        d_left = grid.m_left * j - e * grid.dj_left

        def slope(t, k, p):
            torque, de = grid.torque_and_delta_e_at(t, k)
            j_t, dj_t = grid.inertia.value_and_derivative(t)
            return torque * (j_flywheel + j_t) - (e0 + de) * dj_t

        def value(t, k, p):
            return (e0 + grid.delta_e_at(t, k)) / (j_flywheel + grid.inertia(t))

        f = e / j
        return _extremes(grid.x, [(f, d_right, d_left, True), (f, d_right, d_left, False)], slope, value, grid.cycle)

    evaluated: dict[float, Any] = {}

    def mismatch(e0):
        """(ω_max + ω_min)/(2 ω_m) − 1 at E_0, its derivative in E_0 [1/J], and the extremes."""
        if e0 not in evaluated:
            hi, lo = extremes(e0)
            j_hi, j_lo = j_flywheel + grid.inertia(np.array([hi[0], lo[0]]))
            w_hi, w_lo = math.sqrt(2 * hi[1]), math.sqrt(2 * max(lo[1], 0.0))
            # envelope theorem: d(max_φ (E_0 + ΔE)/J)/dE_0 = 1/J at the maximum, and dω = dv/ω
            # at E_0 = -min ΔE with ΔE ≡ 0 (balanced constant torques) the top speed is 0 too: dω/dE_0 is infinite there
            top = 1 / (w_hi * j_hi) if w_hi > 0 else math.inf
            slope = (top + (1 / (w_lo * j_lo) if w_lo > 0 else 0.0)) / (2 * omega_mean)
            evaluated.clear()
            evaluated[e0] = ((w_hi + w_lo) / (2 * omega_mean) - 1, slope, hi, lo)
        return evaluated[e0]

    e_low = -de_min
    scale = max(de_max - de_min, EPS * 0.5 * float(j.max()) * omega_mean**2)
    e_high = 0.5 * float(j.max()) * omega_mean**2 - de_min + scale
    e0 = _newton(
        mismatch,
        e_low,
        e_high,
        0.5 * omega_mean**2 * float(np.mean(j)) - float(np.mean(grid.delta_e)),
        j_flywheel,
        omega_mean,
    )
    _, _, hi, lo = mismatch(e0)
    w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
    w_mean = 0.5 * (w_max + w_min)
    omega = np.sqrt(2 * np.maximum(e0 + grid.delta_e, 0.0) / j)
    return SpeedFluctuation(
        phi=grid.x,
        omega=omega,
        omega_max=w_max,
        omega_min=w_min,
        omega_mean=w_mean,
        delta=(w_max - w_min) / w_mean,
        phi_omega_max=hi[0],
        phi_omega_min=lo[0],
        e0=e0,
    )


def _newton(mismatch, e_low, e_high, guess, j_flywheel, omega_mean):
    """E_0 where the mean speed is ω_m: safeguarded Newton on the mismatch, increasing in E_0.

    Newton's step with the exact derivative (the envelope theorem), kept
    inside the bracket [E_low, E_high] that shrinks with every evaluation
    and replaced by bisection where it would leave it or not halve the
    mismatch (rtsafe, Press et al., *Numerical Recipes*, section 9.4). It
    stops when a step is within 1e-16 E_high + 4 eps |E_0|, the tolerance of
    Brent's method in this place before (scipy.optimize.brentq), and
    Newton's quadratic convergence leaves the last step's point far inside
    it. E_low (the speed touching zero) is evaluated only when the iterates
    come down to it: a positive mismatch there means no mean speed ω_m is
    possible.

    Raises
    ------
    ValueError
        The machine cannot keep the mean speed with this flywheel.
    """
    a, b = e_low, e_high
    low_checked = False

    def check_low():
        if mismatch(e_low)[0] > 0:
            raise ValueError(
                f"with J_F = {j_flywheel!r} kg*m^2 the machine cannot keep the mean speed "
                f"{omega_mean!r} rad/s: its speed would fall to zero within the cycle"
            )
        return True

    e = min(max(guess, e_low), e_high)
    if e == e_low:
        e = 0.5 * (e_low + e_high)
    step_before = b - a
    for _ in range(500):
        m, slope = mismatch(e)[:2]
        if m == 0.0:
            return e
        if m < 0:
            a = e
        else:
            b = e
        new = e - m / slope if slope > 0 else a - 1.0
        if not (a < new < b) or abs(2 * m) > abs(step_before * slope):
            if a == e_low and not low_checked:
                low_checked = check_low()
            new = 0.5 * (a + b)
        step_before, e_before, e = abs(new - e), e, new
        if step_before <= 1e-16 * e_high + 4 * EPS * abs(e) or e == e_before:
            if a == e_low and not low_checked:  # never below the root: it may not exist
                low_checked = check_low()
            return e
    raise RuntimeError("the energy–mass forward method did not find E_0 in 500 steps")
