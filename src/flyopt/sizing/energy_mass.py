"""The energy–mass (Wittenbauer) method: a machine whose inertia varies with the angle.

Torques of the angle only, J_e(φ) = J_c + J_v(φ) (docs/flywheel-design.md,
section 6): :func:`energy_mass_requirement` gives the flywheel in closed
form, :func:`achieved_speed` the speed fluctuation a given flywheel achieves
(its forward use).

Maxima and minima over the continuous angle are exact, not sampled: a dense
grid that contains every knot (where a torque steps or kinks) brackets them,
and each bracket is refined by Brent's method on the derivative.
Results are SI: [rad], [rad/s], [kg*m^2], [J].
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from flyopt.sizing._numerics import EPS, Inertia, check_speed_delta

GRID = 4096
"""Points per cycle of the grid that brackets maxima and minima (knots added)."""

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)
_GL_NODES = 0.5 * (_GL_NODES + 1.0)
_GL_WEIGHTS = 0.5 * _GL_WEIGHTS


def _curve_limits(curve, phi):
    left, right = curve.limits(phi)
    return np.asarray(left, dtype=float), np.asarray(right, dtype=float)



# -- exact extremes of a piecewise-smooth function --------------------------------


def _extreme(x, f, d_right, d_left, slope, value, find_max, span):
    """Largest (or smallest) value of a piecewise-smooth function on [x_0, x_n].

    Parameters
    ----------
    x, f : ndarray
        Grid (containing every point where the function kinks) and values.
    d_right, d_left : ndarray
        Right and left limits of the derivative (or of a function with the
        same sign) at the grid points.
    slope : callable (t, k) -> float
        That derivative inside grid interval k.
    value : callable (t, k) -> float
        The function inside grid interval k.
    find_max : bool
    span : float
        Length of the whole interval, for the root tolerance.

    Returns
    -------
    (float, float)
        Location and value of the extreme.
    """
    s = 1.0 if find_max else -1.0
    fs = s * f
    i = int(np.argmax(fs))
    best_x, best = float(x[i]), float(fs[i])
    h = np.diff(x)
    dr, dl = s * d_right[:-1], s * d_left[1:]
    cand = np.flatnonzero((dr > 0) & (dl < 0) & (h > 0))
    bulge = h[cand] * np.maximum(np.abs(dr[cand]), np.abs(dl[cand]))
    cand = cand[np.maximum(fs[cand], fs[cand + 1]) + 2 * bulge >= best]
    for k in cand:
        a, b, da, db = x[k], x[k + 1], d_right[k], d_left[k + 1]

        def g(t, k=k, a=a, b=b, da=da, db=db):
            return da if t <= a else db if t >= b else slope(t, k)
        root = optimize.brentq(g, a, b, xtol=1e-15 * span, rtol=4 * EPS, maxiter=200)
        v = s * value(root, k)
        if v > best:
            best_x, best = float(root), float(v)
    return best_x, s * best


class _CycleGrid:
    """ΔE, M and J of an angle-only cycle on a dense grid with every knot."""

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
            self.delta_e = np.asarray(excess_work(x), dtype=float)
        else:  # composite 8-point Gauss-Legendre between grid points (smooth there)
            h = np.diff(x)
            nodes = x[:-1, None] + h[:, None] * _GL_NODES[None, :]
            parts = (excess_work.net_torque(nodes) * _GL_WEIGHTS[None, :]).sum(axis=1) * h
            self.delta_e = np.concatenate(([0.0], np.cumsum(parts, dtype=np.longdouble))).astype(float)
        self.j = inertia(x)
        eps = 1e-12 * cycle
        self.dj_right = inertia.derivative(x + eps)
        self.dj_left = inertia.derivative(x - eps)
        self.linear = linear

    def delta_e_at(self, t, k):
        """ΔE at t inside grid interval k (the knot value plus an exact quadrature)."""
        a = self.x[k]
        h = t - a
        nodes = a + h * _GL_NODES
        return float(self.delta_e[k] + h * np.dot(self.ew.net_torque(nodes), _GL_WEIGHTS))

    def torque_at(self, t):
        return float(self.ew.net_torque(np.array([t]))[0])

    def mean_inertia(self):
        """Cycle mean of J (exact quadrature between grid points) [kg*m^2]."""
        x = self.x
        h = np.diff(x)
        nodes = x[:-1, None] + h[:, None] * _GL_NODES[None, :]
        return float(((self.inertia(nodes) * _GL_WEIGHTS[None, :]).sum(axis=1) * h).sum() / self.cycle)


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
        to keep the machine turning.
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
    delta_constant_inertia: float | None

    @property
    def j_error(self):
        """Relative error of the constant-inertia J_F against the exact one [-]."""
        return (self.j_constant_inertia - self.j_required) / self.j_required if self.j_required else math.nan


def energy_mass_requirement(excess_work, j_machine, omega_mean, delta):
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
    inertia = Inertia(j_machine)
    grid = _CycleGrid(excess_work, inertia)
    w_max, w_min = omega_mean * (1 + delta / 2), omega_mean * (1 - delta / 2)
    half_max, half_min = 0.5 * w_max**2, 0.5 * w_min**2

    upper = _energy_mass_extreme(grid, half_min, find_max=True)
    lower = _energy_mass_extreme(grid, half_max, find_max=False)
    j_required = (upper[1] - lower[1]) / (half_max - half_min)
    e0 = lower[1] + half_max * j_required

    de_max = _energy_mass_extreme(grid, 0.0, find_max=False)[1] * -1.0  # max ΔE = −min(−ΔE)
    de_min = _energy_mass_extreme(grid, 0.0, find_max=True)[1] * -1.0
    a_max = de_max - de_min
    j_mean = grid.mean_inertia()
    j_ci = a_max / (omega_mean**2 * delta) - j_mean
    try:
        delta_ci = _achieved(grid, j_ci, omega_mean).delta
    except ValueError:
        delta_ci = None
    return EnergyMassRequirement(
        j_required=float(j_required), e0=float(e0), phi_omega_max=lower[0], phi_omega_min=upper[0],
        omega_mean=float(omega_mean), delta=float(delta), omega_max=w_max, omega_min=w_min, a_max=float(a_max),
        j_machine_mean=j_mean, j_constant_inertia=float(j_ci), delta_constant_inertia=delta_ci)


def _energy_mass_extreme(grid, half_omega2, find_max):
    """Extreme over φ of ½ ω² J(φ) − ΔE(φ) (of −ΔE alone when ``half_omega2`` is 0)."""
    if half_omega2 == 0.0:
        f, d_right, d_left = -grid.delta_e, -grid.m_right, -grid.m_left

        def slope(t, k):
            return -grid.torque_at(t)

        def value(t, k):
            return -grid.delta_e_at(t, k)
        return _extreme(grid.x, f, d_right, d_left, slope, value, find_max, grid.cycle)
    f = half_omega2 * grid.j - grid.delta_e
    d_right = half_omega2 * grid.dj_right - grid.m_right
    d_left = half_omega2 * grid.dj_left - grid.m_left

    def slope(t, k):
        return half_omega2 * float(grid.inertia.derivative(t)) - grid.torque_at(t)

    def value(t, k):
        return half_omega2 * float(grid.inertia(t)) - grid.delta_e_at(t, k)
    return _extreme(grid.x, f, d_right, d_left, slope, value, find_max, grid.cycle)


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


def achieved_speed(excess_work, j_machine, omega_mean, j_flywheel=0.0):
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
    inertia = Inertia(j_machine)
    grid = _CycleGrid(excess_work, inertia)
    return _achieved(grid, float(j_flywheel), omega_mean)


def _achieved(grid, j_flywheel, omega_mean):
    j = grid.j + j_flywheel
    if not np.all(j > 0):
        raise ValueError(f"the total inertia J_F + J_e(φ) must be positive; with J_F = {j_flywheel!r} kg*m^2 "
                         f"it reaches {float(j.min())!r} kg*m^2")
    de_min = -_energy_mass_extreme(grid, 0.0, find_max=True)[1]
    de_max = -_energy_mass_extreme(grid, 0.0, find_max=False)[1]

    def extremes(e0):
        e = e0 + grid.delta_e
        d_right = grid.m_right * j - e * grid.dj_right
        d_left = grid.m_left * j - e * grid.dj_left

        def slope(t, k):
            return grid.torque_at(t) * (j_flywheel + float(grid.inertia(t))) - \
                (e0 + grid.delta_e_at(t, k)) * float(grid.inertia.derivative(t))

        def value(t, k):
            return (e0 + grid.delta_e_at(t, k)) / (j_flywheel + float(grid.inertia(t)))
        hi = _extreme(grid.x, e / j, d_right, d_left, slope, value, True, grid.cycle)
        lo = _extreme(grid.x, e / j, d_right, d_left, slope, value, False, grid.cycle)
        return hi, lo

    def mismatch(e0):
        hi, lo = extremes(e0)
        return (math.sqrt(2 * hi[1]) + math.sqrt(2 * max(lo[1], 0.0))) / (2 * omega_mean) - 1

    e_low = -de_min
    scale = max(de_max - de_min, EPS * 0.5 * float(j.max()) * omega_mean**2)
    if mismatch(e_low) > 0:
        raise ValueError(f"with J_F = {j_flywheel!r} kg*m^2 the machine cannot keep the mean speed "
                         f"{omega_mean!r} rad/s: its speed would fall to zero within the cycle")
    e_high = 0.5 * float(j.max()) * omega_mean**2 - de_min + scale
    e0 = optimize.brentq(mismatch, e_low, e_high, xtol=1e-16 * e_high, rtol=4 * EPS, maxiter=500)
    hi, lo = extremes(e0)
    w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
    w_mean = 0.5 * (w_max + w_min)
    omega = np.sqrt(2 * np.maximum(e0 + grid.delta_e, 0.0) / j)
    return SpeedFluctuation(phi=grid.x, omega=omega, omega_max=w_max, omega_min=w_min, omega_mean=w_mean,
                            delta=(w_max - w_min) / w_mean, phi_omega_max=hi[0], phi_omega_min=lo[0], e0=e0)
