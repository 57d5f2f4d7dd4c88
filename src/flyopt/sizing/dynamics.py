"""Speed fluctuation beyond the constant-inertia method.

Three models, from the cheapest to the most general (docs/flywheel-design.md, sections
5–7):

- variable inertia J_e(φ) = J_c + J_v(φ), torques of the angle only: the
  energy–mass (Wittenbauer) closed form, :func:`energy_mass_requirement`,
  and its forward use, :func:`achieved_speed`;
- torques that depend on speed too: the equation of motion in the angle,

      d(½ J(φ) ω²)/dφ = M(φ, ω),   M = M_d − M_r,

  whose periodic steady state :func:`periodic_solution` finds by shooting
  (CasADi/CVODES with exact sensitivities, a safeguarded Newton iteration on
  the periodicity condition), :func:`dynamic_requirement` the smallest
  flywheel whose periodic solution keeps δ, :func:`startup_time` the run-up
  from rest, and :func:`verify` the check of a chosen flywheel.

:func:`cheapest_model` names the cheapest exact model for a machine.

Maxima and minima over the continuous angle are exact, not sampled: a dense
grid that contains every knot (where a torque steps or kinks) brackets them,
and each bracket is refined by Brent's method on the derivative (closed-form
methods) or by the extremum of the cubic Hermite interpolant through the
integrator's states and exact slopes (simulation).

Net torques are given as callables ``(phi, omega) -> torque`` that accept
CasADi symbols (numbers come from the compiled CasADi function); inertias as
a number, an :class:`flyopt.machine.mechanism.EquivalentInertia`, or a CasADi-capable
callable of φ. Results are SI: [rad], [rad/s], [kg*m^2], [J], [s].

The equation of motion is integrated in the kinetic energy E = ½ J ω²,
written as E = E_ref + W_s y with y of order one (E_ref a reference energy,
W_s the energy swing of the cycle), so the integrator's tolerances act on the
fluctuation, whatever the speed (1 rpm or 20,000 rpm) and δ (1e-4 or 0.3).
"""

import math
from dataclasses import dataclass, field
from functools import cached_property, lru_cache

import casadi as ca
import numpy as np
from scipy import optimize

from flyopt.cycle.indicator import BALANCE_TOLERANCE
from flyopt.errors import NonPeriodicCycle, SolverFailed

GRID = 4096
"""Points per cycle of the grid that brackets maxima and minima (knots added)."""

PIECES_PER_CYCLE = 32
"""The simulation splits the cycle at every knot and into at least this many pieces."""

OUTPUTS_PER_PIECE = 64
"""Integrator outputs per piece (the simulation grid: at least 2048 per cycle)."""

RELTOL = 1e-11
ABSTOL = 1e-12
"""CVODES tolerances on the scaled energy y = (E − E_ref)/W_s, of order one."""

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

STALL_RTOL = 1e-4
"""Relative width in J_F to which a stall limit (see :class:`DynamicRequirement`) is located."""
_EPS = float(np.finfo(float).eps)
_EDGE = 1e-10
"""Torques are evaluated this fraction of a piece inside its ends, so a step at
a knot is seen from the correct side."""

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)
_GL_NODES = 0.5 * (_GL_NODES + 1.0)
_GL_WEIGHTS = 0.5 * _GL_WEIGHTS


# -- inputs ----------------------------------------------------------------------


class _Inertia:
    """J(φ) from a number, an EquivalentInertia or a CasADi-capable callable."""

    def __init__(self, j, what="j_machine"):
        phi = ca.SX.sym("phi")
        if isinstance(j, (int, float)) and not isinstance(j, bool):
            if not (math.isfinite(j) and j >= 0):
                raise ValueError(f"{what} must be a finite number >= 0 [kg*m^2], got {j!r}")
            expr, self.knots, self.is_constant = ca.SX(float(j)), np.empty(0), True
        elif hasattr(j, "casadi"):
            expr = ca.SX(j.casadi(phi))
            self.knots = np.asarray(getattr(j, "knots", np.empty(0)), dtype=float)
            self.is_constant = bool(getattr(j, "is_constant", False))
        elif callable(j):
            try:
                expr = ca.SX(j(phi))
            except Exception as err:  # noqa: BLE001 -- any failure means "not CasADi-capable"
                raise ValueError(f"{what} must accept a CasADi symbol (use numpy-free arithmetic or "
                                 f"an EquivalentInertia): {err}") from err
            self.knots, self.is_constant = np.empty(0), False
        else:
            raise ValueError(f"{what} must be a number [kg*m^2] or a function of phi, got {j!r}")
        if not self.is_constant:
            self.is_constant = not ca.depends_on(expr, phi)
        self.source = j
        self.function = ca.Function("J", [phi], [expr, ca.jacobian(expr, phi)])
        self._maps = {}

    def casadi(self, phi):
        return self.function(phi)[0]

    def __call__(self, phi):
        return self._eval(phi, 0)

    def derivative(self, phi):
        return self._eval(phi, 1)

    def _eval(self, phi, which):
        return _evaluate(self.function, self._maps, phi)[which]


def _evaluate(function, maps, *args):
    """Evaluate a scalar CasADi Function elementwise on broadcast numpy arrays.

    The mapped function for each size is built once and kept in ``maps``.
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
    shape = arrays[0].shape
    n = arrays[0].size
    if n == 0:
        return tuple(np.zeros(shape) for _ in range(function.n_out()))
    if n not in maps:
        if len(maps) > 64:
            maps.clear()
        maps[n] = function.map(n) if n > 1 else function
    out = maps[n](*(a.reshape(1, -1) for a in arrays))
    out = out if isinstance(out, tuple) else (out,)
    return tuple(np.asarray(o, dtype=float).reshape(shape) for o in out)


def _check_speed_delta(omega_mean, delta, delta_max=2.0):
    if not (isinstance(omega_mean, (int, float)) and math.isfinite(omega_mean) and omega_mean > 0):
        raise ValueError(f"omega_mean must be a positive finite speed [rad/s], got {omega_mean!r}")
    if delta is not None and not (isinstance(delta, (int, float)) and math.isfinite(delta) and 0 < delta < delta_max):
        raise ValueError(f"delta must lie in (0, {delta_max:g}), got {delta!r}")


def _check_cycle(cycle_angle):
    if not (isinstance(cycle_angle, (int, float)) and math.isfinite(cycle_angle) and cycle_angle > 0):
        raise ValueError(f"cycle_angle must be a positive finite angle [rad], got {cycle_angle!r}")
    return float(cycle_angle)


def _curve_limits(curve, phi):
    left, right = curve.limits(phi)
    return np.asarray(left, dtype=float), np.asarray(right, dtype=float)


# -- which model ----------------------------------------------------------------------

MODEL_ENERGY = "energy"
MODEL_ENERGY_MASS = "energy_mass"
MODEL_PERIODIC = "dynamic"


def cheapest_model(j_machine, net_torque=None):
    """The cheapest model that is exact for a machine (issue, section 5).

    Parameters
    ----------
    j_machine : float, EquivalentInertia or callable
        J_e(φ) [kg*m^2].
    net_torque : callable (phi, omega), optional
        M_d − M_r accepting CasADi symbols; None for torques of the angle only.

    Returns
    -------
    str
        :data:`MODEL_PERIODIC` when the torque depends on speed,
        :data:`MODEL_ENERGY_MASS` when J_e varies with the angle, else
        :data:`MODEL_ENERGY` (the constant-inertia method of flyopt.cycle.indicator).
    """
    if net_torque is not None:
        phi, omega = ca.SX.sym("phi"), ca.SX.sym("omega")
        try:
            m = ca.SX(net_torque(phi, omega))
        except Exception as err:  # noqa: BLE001 -- any failure means "not CasADi-capable"
            raise ValueError(f"net_torque(phi, omega) must accept CasADi symbols: {err}") from err
        if ca.depends_on(m, omega):
            return MODEL_PERIODIC
    return MODEL_ENERGY if _Inertia(j_machine).is_constant else MODEL_ENERGY_MASS


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
        root = optimize.brentq(g, a, b, xtol=1e-15 * span, rtol=4 * _EPS, maxiter=200)
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
    _check_speed_delta(omega_mean, delta)
    inertia = _Inertia(j_machine)
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
    _check_speed_delta(omega_mean, None)
    inertia = _Inertia(j_machine)
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
    scale = max(de_max - de_min, _EPS * 0.5 * float(j.max()) * omega_mean**2)
    if mismatch(e_low) > 0:
        raise ValueError(f"with J_F = {j_flywheel!r} kg*m^2 the machine cannot keep the mean speed "
                         f"{omega_mean!r} rad/s: its speed would fall to zero within the cycle")
    e_high = 0.5 * float(j.max()) * omega_mean**2 - de_min + scale
    e0 = optimize.brentq(mismatch, e_low, e_high, xtol=1e-16 * e_high, rtol=4 * _EPS, maxiter=500)
    hi, lo = extremes(e0)
    w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
    w_mean = 0.5 * (w_max + w_min)
    omega = np.sqrt(2 * np.maximum(e0 + grid.delta_e, 0.0) / j)
    return SpeedFluctuation(phi=grid.x, omega=omega, omega_max=w_max, omega_min=w_min, omega_mean=w_mean,
                            delta=(w_max - w_min) / w_mean, phi_omega_max=hi[0], phi_omega_min=lo[0], e0=e0)


# -- the periodic dynamic model ---------------------------------------------------


def angle_torque(excess_work):
    """The net torque M_d − M_r of an ExcessWork as a CasADi callable (phi, omega).

    For simulating angle-only cycles with :func:`periodic_solution` and
    :func:`verify`; pass ``excess_work.knots`` as the knots.
    """
    driving, resisting = excess_work.driving, excess_work.resisting

    def net(phi, omega):
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


class PeriodicModel:
    """The equation of motion of one machine, built once for CasADi.

    d(½ J ω²)/dφ = M(φ, ω) over one cycle, cut at every knot and into at
    least :data:`PIECES_PER_CYCLE` pieces. Each piece is integrated by CVODES
    in a normalized time τ ∈ [0, 1] with the piece's ends, the flywheel and
    the energy scales as parameters, so one integrator serves every piece,
    flywheel and speed. Build it through :func:`periodic_model` (cached).

    Parameters
    ----------
    net_torque : callable (phi, omega) -> torque
        M_d − M_r at the reference shaft [N*m]; must accept CasADi symbols.
    j_machine : float, EquivalentInertia or callable
        J(φ) of the machine [kg*m^2].
    cycle_angle : float
        Φ [rad].
    knots : sequence of float
        Angles where the torque steps or kinks [rad].
    """

    def __init__(self, net_torque, j_machine, cycle_angle, knots=()):
        self.cycle = _check_cycle(cycle_angle)
        self.inertia = _Inertia(j_machine)
        knots = np.asarray(list(knots), dtype=float).reshape(-1)
        if not np.all(np.isfinite(knots)):
            raise ValueError("knots must be finite angles [rad]")
        inner = np.concatenate((knots, self.inertia.knots))
        inner = inner[(inner > 0) & (inner < self.cycle)]
        edges = np.union1d([0.0, self.cycle], inner)
        pieces = []
        for a, b in zip(edges[:-1], edges[1:]):
            n = max(1, math.ceil((b - a) / self.cycle * PIECES_PER_CYCLE - 1e-9))
            cuts = np.linspace(a, b, n + 1)
            pieces += list(zip(cuts[:-1], cuts[1:]))
        self.pieces = np.array(pieces)
        self.segments = np.column_stack((edges[:-1], edges[1:]))
        self.net_torque = net_torque
        self.tau = np.linspace(0.0, 1.0, OUTPUTS_PER_PIECE + 1)

        phi, omega = ca.SX.sym("phi"), ca.SX.sym("omega")
        try:
            m = ca.SX(net_torque(phi, omega))
        except Exception as err:  # noqa: BLE001 -- any failure means "not CasADi-capable"
            raise ValueError(f"net_torque(phi, omega) must accept CasADi symbols: {err}") from err
        if m.shape != (1, 1):
            raise ValueError(f"net_torque must return a scalar, got shape {m.shape}")
        self.speed_dependent = bool(ca.depends_on(m, omega))
        self.torque_function = ca.Function("M", [phi, omega], [m])
        self.torque_slope_function = ca.Function("dM", [phi, omega], [ca.jacobian(m, omega)])
        self._maps = {}

    # -- CasADi building blocks --------------------------------------------------
    def _rhs(self, with_time):
        """States [y, stall(, t)], parameters [φ_a, φ_b, J_F, E_ref, W_s(, T_s)]."""
        tau = ca.SX.sym("tau")
        x = ca.SX.sym("x", 3 if with_time else 2)
        p = ca.SX.sym("p", 6 if with_time else 5)
        a, b, j_f, e_ref, w_s = p[0], p[1], p[2], p[3], p[4]
        h = b - a
        phi = a + tau * h
        phi_torque = a + ca.fmin(ca.fmax(tau, _EDGE), 1 - _EDGE) * h
        j = self.inertia.casadi(phi) + j_f
        energy = e_ref + w_s * x[0]
        omega = ca.sqrt(ca.fmax(2 * energy / j, 1e-300))
        torque = self.torque_function(phi_torque, omega)
        ode = [h * torque / w_s, h * ca.fmax(-energy / w_s, 0)]
        if with_time:
            ode.append(h / (omega * p[5]))
        return {"x": x, "p": p, "t": tau, "ode": ca.vertcat(*ode)}

    def _integrator(self, with_time):
        opts = {"abstol": ABSTOL, "reltol": RELTOL, "max_num_steps": 200000,
                "disable_internal_warnings": True}
        return ca.integrator("piece_t" if with_time else "piece", "cvodes", self._rhs(with_time),
                             0.0, self.tau, opts)

    @cached_property
    def piece(self):
        """CVODES over one piece: states [y, stall], outputs at ``tau``."""
        return self._integrator(False)

    @cached_property
    def piece_timed(self):
        """CVODES over one piece with time: states [y, stall, t]."""
        return self._integrator(True)

    @cached_property
    def cycle_function(self):
        """(y0, [J_F, E_ref, W_s]) -> states at every output of every piece."""
        x0 = ca.MX.sym("x0", 2)
        q = ca.MX.sym("q", 3)
        x, outs = x0, []
        for a, b in self.pieces:
            xf = self.piece(x0=x, p=ca.vertcat(a, b, q))["xf"]
            outs.append(xf)
            x = xf[:, -1]
        return ca.Function("cycle", [x0, q], [ca.horzcat(*outs)])

    @cached_property
    def shooting_function(self):
        """([J_F, E_ref, W_s]) -> (y(Φ), stall(Φ), dy(Φ)/dE_ref), starting from y = 0."""
        j_f, e_ref, w_s = ca.MX.sym("j_f"), ca.MX.sym("e_ref"), ca.MX.sym("w_s")
        q = ca.vertcat(j_f, e_ref, w_s)
        x = ca.MX.zeros(2)
        for a, b in self.pieces:
            x = self.piece(x0=x, p=ca.vertcat(a, b, q))["xf"][:, -1]
        return ca.Function("shoot", [j_f, e_ref, w_s], [x[0], x[1], ca.jacobian(x[0], e_ref)])

    # -- numbers --------------------------------------------------------------
    def grid_angles(self):
        """Angles of the simulation outputs, piece by piece, shape (pieces, outputs)."""
        a, b = self.pieces[:, :1], self.pieces[:, 1:]
        return a + self.tau[None, :] * (b - a)

    def torque(self, phi, omega):
        """Net torque at numpy arrays (broadcast) [N*m]."""
        return _evaluate(self.torque_function, self._maps, phi, omega)[0]

    def falls_with_speed(self, omega):
        """Whether ∂M/∂ω <= 0 on the grid for speeds up to 4 ω (sampled; the torque
        then has a unique periodic solution, see :func:`_periodic_energy`)."""
        if not self.speed_dependent:
            return True
        phi = self.grid_angles()[:, :-1].reshape(-1)
        speeds = np.linspace(0.0, 4 * omega, 65)[1:]
        slope = _evaluate(self.torque_slope_function, self._maps, phi[:, None], speeds[None, :])[0]
        return bool(np.all(slope <= 0))

    def check_finite(self, omega):
        """Raise ValueError when the net torque is not finite on the grid at speed ``omega``."""
        phi = self.grid_angles()
        m = self.torque(phi, omega)
        bad = ~np.isfinite(m)
        if bad.any():
            raise ValueError(f"net_torque is not finite at phi = {float(phi[bad][0]):.6g} rad, omega = {omega:.6g} "
                             f"rad/s; it must accept CasADi symbols (casadi functions, not math or numpy) and "
                             f"be finite over the cycle")

    def work_scale(self, omega):
        """Φ · max |M(φ, ω)| over the cycle at speed ``omega`` [J], an upper bound of the energy swing."""
        phi = self.grid_angles()[:, :-1].reshape(-1)
        m = self.torque(phi, omega)
        scale = self.cycle * float(np.max(np.abs(m)))
        return scale if scale > 0 else 1.0

    def absolute_work(self, omega):
        """∫ |M(φ, ω)| dφ over the cycle at speed ``omega`` [J] (trapezoid on the simulation grid)."""
        phi = self.grid_angles()
        h = self.pieces[:, 1] - self.pieces[:, 0]
        m = np.abs(self.torque(self.pieces[:, :1] + np.clip(self.tau, _EDGE, 1 - _EDGE)[None, :] * h[:, None],
                               omega))
        return float(np.sum(0.5 * (m[:, 1:] + m[:, :-1]) * np.diff(phi, axis=1)))

    def trajectory(self, j_flywheel, e_ref, w_s, x0=None):
        """Integrate one cycle; returns y (pieces, outputs) and the stall measure.

        Raises
        ------
        SolverFailed
            When CVODES fails (its status in the message).
        """
        x0 = [0.0, 0.0] if x0 is None else x0
        try:
            out = np.asarray(self.cycle_function(x0, [j_flywheel, e_ref, w_s]), dtype=float)
        except RuntimeError as err:
            raise SolverFailed(f"the integration of the cycle failed (CVODES: "
                               f"{str(err).strip().splitlines()[-1]})") from err
        y = out[0].reshape(len(self.pieces), len(self.tau))
        return y, float(out[1, -1])

    def speed_profile(self, y, j_flywheel, e_ref, w_s, shift=0.0):
        """q = E/J = ω²/2 and its slope dq/dφ = (M J − E J')/J² on the simulation grid.

        q is smooth even where ω is small (ω itself has a square-root
        singularity at zero speed), so extremes are located on q.

        Returns
        -------
        phi, q, dq, energy : ndarray (pieces, outputs)
            q and dq are None when the energy is not positive everywhere.
        """
        phi = self.grid_angles()
        h = self.pieces[:, 1] - self.pieces[:, 0]
        j = self.inertia(phi) + j_flywheel
        dj = self.inertia.derivative(phi)
        energy = e_ref + w_s * (y + shift)
        if np.any(energy <= 0):
            return phi, None, None, energy
        q = energy / j
        # torques seen from inside each piece (a step at a knot from the correct side)
        tau_t = np.clip(self.tau, _EDGE, 1 - _EDGE)
        phi_t = self.pieces[:, :1] + tau_t[None, :] * h[:, None]
        m = self.torque(phi_t, np.sqrt(2 * q))
        return phi, q, (m * j - energy * dj) / j**2, energy


def _hermite_extremes(phi, f, df):
    """Max and min of the piecewise cubic Hermite interpolant, with their angles.

    ``phi``, ``f``, ``df`` have shape (pieces, outputs); each row is
    interpolated on its own (slopes are one-sided at piece ends).
    """
    h = np.diff(phi, axis=1)
    f0, f1 = f[:, :-1], f[:, 1:]
    m0, m1 = df[:, :-1] * h, df[:, 1:] * h
    c = m0
    b = 3 * (f1 - f0) - 2 * m0 - m1
    a = 2 * (f0 - f1) + m0 + m1
    # p'(t) = 3a t² + 2b t + c = 0
    qa, qb, qc = 3 * a, 2 * b, c
    disc = qb * qb - 4 * qa * qc
    sq = np.sqrt(np.where(disc >= 0, disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        big = np.abs(qa) > 1e-14 * (np.abs(qb) + np.abs(qc))
        r1 = np.where(big, (-qb + sq) / (2 * qa), np.where(qb != 0, -qc / np.where(qb != 0, qb, 1), -1.0))
        r2 = np.where(big, (-qb - sq) / (2 * qa), -1.0)
    best_hi = (float(np.max(f)), np.unravel_index(np.argmax(f), f.shape))
    best_lo = (float(np.min(f)), np.unravel_index(np.argmin(f), f.shape))
    hi_val, hi_phi = best_hi[0], float(phi[best_hi[1]])
    lo_val, lo_phi = best_lo[0], float(phi[best_lo[1]])
    for r in (r1, r2):
        ok = (disc >= 0) & (r > 0) & (r < 1)
        t = np.where(ok, r, 0.0)
        p = f0 + t * (c + t * (b + t * a))
        where = phi[:, :-1] + t * h
        if np.any(ok):
            pm = np.where(ok, p, -np.inf)
            i = np.unravel_index(np.argmax(pm), pm.shape)
            if pm[i] > hi_val:
                hi_val, hi_phi = float(pm[i]), float(where[i])
            pm = np.where(ok, p, np.inf)
            i = np.unravel_index(np.argmin(pm), pm.shape)
            if pm[i] < lo_val:
                lo_val, lo_phi = float(pm[i]), float(where[i])
    return (hi_phi, hi_val), (lo_phi, lo_val)


def _simpson_time(phi, omega):
    """∫ dφ/ω over the cycle by Simpson's rule on each piece [s]."""
    h = np.diff(phi, axis=1)[:, :1]
    g = 1.0 / omega
    w = np.ones(omega.shape[1])
    w[1:-1:2], w[2:-1:2] = 4.0, 2.0
    return float(np.sum(h[:, 0] / 3 * (g @ w)))


@lru_cache(maxsize=32)
def _cached_model(net_torque, j_machine, cycle_angle, knots):
    return PeriodicModel(net_torque, j_machine, cycle_angle, knots)


def periodic_model(net_torque, j_machine, cycle_angle, knots=()):
    """The (cached) :class:`PeriodicModel` of one machine structure.

    The CasADi integrators and cycle functions are built once per
    (net_torque, j_machine, cycle_angle, knots) and reused for every
    flywheel and speed.
    """
    knots = tuple(float(k) for k in np.asarray(list(knots), dtype=float).reshape(-1))
    try:
        return _cached_model(net_torque, j_machine, float(cycle_angle), knots)
    except TypeError:  # an unhashable argument: build without the cache
        return PeriodicModel(net_torque, j_machine, cycle_angle, knots)


def periodic_solution(net_torque, j_machine, cycle_angle, omega_mean, j_flywheel=0.0, knots=()):
    """Periodic steady state of d(½ J(φ) ω²)/dφ = M(φ, ω) over one cycle.

    Parameters
    ----------
    net_torque : callable (phi, omega) -> torque
        M_d − M_r at the reference shaft [N*m], accepting CasADi symbols
        (e.g. built from :mod:`flyopt.machine.motor` and :mod:`flyopt.machine.torque`, or
        :func:`angle_torque`).
    j_machine : float, EquivalentInertia or callable
        The machine's J_e(φ) [kg*m^2].
    cycle_angle : float
        Φ [rad].
    omega_mean : float
        When the torque depends on the angle only: the prescribed mean speed
        (ω_max + ω_min)/2 [rad/s] — every initial speed is then periodic and
        this one is picked. When it depends on speed: a first guess; the
        mean speed follows from the torque–speed balance.
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
    Shooting: from E(0) = E_ref the cycle is integrated with CVODES
    (BDF, exact forward sensitivities), and Newton's method on E(Φ) − E(0) = 0,
    kept inside a bracket of the sign change, moves E_ref; a torque that
    rises with speed somewhere (a motor past breakdown) adds a scan of speeds
    when Newton finds no gain (see :func:`_periodic_energy`). A solution must
    be stable (Floquet multiplier dE(Φ)/dE(0) < 1). The extremes of
    ω = sqrt(2q) are those of the cubic Hermite interpolant of q = E/J through
    the states and the exact slopes dq/dφ = (M J − E J')/J² at the 2048+
    outputs per cycle (q stays smooth where ω is small).
    """
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    return _periodic(model, float(j_flywheel), omega_mean)


def _periodic(model, j_flywheel, omega_guess):
    _check_speed_delta(omega_guess, None)
    phi_grid = model.grid_angles()
    j_min = float(np.min(model.inertia(phi_grid))) + j_flywheel
    if not j_min > 0:
        raise ValueError(f"the total inertia J_F + J_e(φ) must be positive; with J_F = {j_flywheel!r} kg*m^2 "
                         f"it reaches {j_min!r} kg*m^2")
    j_ref = float(model.inertia(0.0)) + j_flywheel
    model.check_finite(omega_guess)
    if model.speed_dependent:
        return _periodic_speed_dependent(model, j_flywheel, omega_guess, j_ref)
    return _periodic_angle_only(model, j_flywheel, omega_guess, j_ref)


def _finish(model, y, j_flywheel, e_ref, w_s, shift, status, residual, tol, multiplier, iterations):
    phi, q, dq, energy = model.speed_profile(y, j_flywheel, e_ref, w_s, shift)
    if q is None:
        raise SolverFailed(f"the speed reaches zero within the cycle (status: {status}); "
                           f"the machine stalls: more flywheel inertia or a stronger motor is needed")
    hi, lo = _hermite_extremes(phi, q, dq)
    w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
    omega = np.sqrt(2 * q)
    w_mean = 0.5 * (w_max + w_min)
    delta = (w_max - w_min) / w_mean
    return PeriodicSolution(
        phi=phi.reshape(-1), omega=omega.reshape(-1), omega_max=w_max, omega_min=w_min, omega_mean=w_mean,
        delta=delta, phi_omega_max=hi[0], phi_omega_min=lo[0], converged=True, status=status,
        periodicity_residual=abs(residual), periodicity_tolerance=tol, tolerance=DELTA_RTOL * delta,
        multiplier=multiplier, speed_dependent=model.speed_dependent, iterations=iterations,
        j_flywheel=j_flywheel, e0=float(energy[0, 0]), period=_simpson_time(phi, omega))


def _periodic_angle_only(model, j_flywheel, omega_mean, j_ref):
    e_ref = 0.5 * j_ref * omega_mean**2
    w_s = model.work_scale(omega_mean)
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    swing = float(y.max() - y.min())
    if swing > 0:  # rescale so that y swings by one
        w_s *= swing
        y, stall = model.trajectory(j_flywheel, e_ref, w_s)
        swing = float(y.max() - y.min())
    residual = float(y[-1, -1] - y[0, 0])
    # the cycle module's balance tolerance, or the integration's accuracy on the swing
    cycle_work = model.absolute_work(omega_mean)
    tol = max(PERIODIC_RTOL * max(swing, _EPS), BALANCE_TOLERANCE * cycle_work / w_s)
    if abs(residual) > tol:
        raise NonPeriodicCycle(residual * w_s, cycle_work)
    y_min = float(y.min())

    def mismatch(shift):
        phi, q, dq, _ = model.speed_profile(y, j_flywheel, e_ref, w_s, shift)
        if q is None:
            return -1.0
        hi, lo = _hermite_extremes(phi, q, dq)
        return (math.sqrt(2 * hi[1]) + math.sqrt(2 * max(lo[1], 0.0))) / (2 * omega_mean) - 1

    low = -e_ref / w_s - y_min  # the speed touches zero
    low += 1e-12 * max(1.0, abs(low))
    if mismatch(low) > 0:
        raise SolverFailed(f"with J_F = {j_flywheel!r} kg*m^2 the machine cannot keep the mean speed "
                           f"{omega_mean!r} rad/s: its speed would fall to zero within the cycle")
    high = 1.0
    for _ in range(200):
        if mismatch(high) >= 0:
            break
        high = 2 * high + 1
    shift = optimize.brentq(mismatch, low, high, xtol=1e-15 * (e_ref / w_s + 1), rtol=4 * _EPS, maxiter=500)
    return _finish(model, y, j_flywheel, e_ref, w_s, shift, "periodic: torques of the angle only, the mean "
                   "speed prescribed", residual * w_s, tol * w_s, 1.0, 0)


def _periodic_speed_dependent(model, j_flywheel, omega_guess, j_ref):
    w_s = model.work_scale(omega_guess)
    e_guess = 0.5 * j_ref * omega_guess**2

    function = model.shooting_function

    def shoot(e_ref):
        try:
            y_end, stall, dy = function(j_flywheel, e_ref, w_s)
        except RuntimeError:
            return None
        if float(stall) > 0:
            return None
        return float(y_end), float(dy)

    # First pass: find the speed, then rescale W_s to the swing and polish.
    e_ref, iterations, status = _periodic_energy(shoot, e_guess, 1e-8, lambda: model.falls_with_speed(omega_guess))
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    swing = float(y.max() - y.min())
    if swing > 0:
        w_s *= swing
    tol = PERIODIC_RTOL
    e_ref, more, status = _newton_energy(shoot, e_ref, 0.1 * tol)
    iterations += more
    y, stall = model.trajectory(j_flywheel, e_ref, w_s)
    residual = float(y[-1, -1] - y[0, 0])
    swing = float(y.max() - y.min())
    tol_abs = tol * max(swing, _EPS)
    if stall > 0 or abs(residual) > tol_abs:
        raise SolverFailed(f"periodic solution not found: after {iterations} Newton iterations E(Φ) − E(0) = "
                           f"{residual * w_s:.3g} J exceeds the tolerance {tol_abs * w_s:.3g} J ({status})")
    dy = float(function(j_flywheel, e_ref, w_s)[2])
    multiplier = 1.0 + w_s * dy
    if not multiplier < 1.0:
        raise SolverFailed(f"the periodic solution found (mean energy {e_ref:.6g} J) is unstable: its Floquet "
                           f"multiplier dE(Φ)/dE(0) = {multiplier:.6g} >= 1, so the machine would not settle "
                           f"there (a motor beyond its breakdown torque?)")
    return _finish(model, y, j_flywheel, e_ref, w_s, 0.0, status, residual * w_s, tol_abs * w_s,
                   multiplier, iterations)


class _NoGain(SolverFailed):
    """Every trial lost energy over the cycle or stalled."""


SCAN_STEPS = 49
"""Speeds tried on each side of the guess (2 % apart) when Newton finds no energy gain."""


def _periodic_energy(shoot, e0, ftol, monotone=lambda: False):
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
    brackets the stable solution for Newton.
    """
    try:
        return _newton_energy(shoot, e0, ftol)
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
        r = shoot(e) if e > 0 else None
        return -math.inf if r is None else r[0]

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
    for j in sorted(range(len(ks)), key=lambda i: abs(ks[i])):
        if ks[j] == 0:
            continue
        values[j] = gain(ks[j])
        if values[j] > 0:
            return bracket_from(float(ks[j]))
    # A band narrower than the scan step: maximize the gain around the best local maxima.
    finite = np.isfinite(values)
    peaks = [j for j in range(1, len(ks) - 1)
             if finite[j] and values[j] >= values[j - 1] and values[j] >= values[j + 1]]
    for j in sorted(peaks, key=lambda i: -values[i])[:3]:
        res = optimize.minimize_scalar(lambda k: -max(gain(k), -1e100), bounds=(ks[j] - 1, ks[j] + 1),
                                       method="bounded",
                                       options={"xatol": 1e-6, "maxiter": 60})
        if -res.fun > 0:
            return bracket_from(float(res.x))
    raise failure


def _newton_energy(shoot, e0, ftol, bracket=(0.0, math.inf)):
    """Safeguarded Newton on y(Φ; E_ref) = 0 for the energy E_ref at φ = 0.

    y(Φ) > 0 (or a stall, where the speed reaches zero) means the machine
    gains energy over the cycle: the periodic energy is higher. The iterate
    stays inside the bracket of the sign change once one is known, and
    expands by factors of 4 in energy (2 in speed) until then.
    """
    lo, hi = bracket
    e = e0
    last = None
    gains = False  # whether any trial gained energy over the cycle
    for it in range(1, MAX_NEWTON + 1):
        r = shoot(e)
        if r is None:  # stalls: the energy is too low
            lo = max(lo, e)
            e_next = 4 * e if math.isinf(hi) else math.sqrt(lo * hi) if lo > 0 else 0.5 * hi
        else:
            f, df = r
            last = f
            if f > 0:
                lo = max(lo, e)
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
            raise SolverFailed("no periodic steady state: the machine keeps gaining energy over every cycle "
                               "(it runs away: the driving torque exceeds the load at every speed tried, up "
                               "to 1e6 times the guessed speed)")
        if e_next < 1e-12 * e0 or (math.isfinite(hi) and hi < 1e-10 * e0):
            raise SolverFailed("no periodic steady state: the machine loses energy over every cycle down to a "
                               "stall (the load exceeds what the drive gives at every speed tried)")
        if math.isfinite(hi) and lo > 0 and (hi - lo) <= 1e-12 * hi:
            break
        e = e_next
    if not gains and math.isfinite(hi):
        raise _NoGain(f"no periodic steady state: at every speed the machine passes the cycle at, it loses "
                           f"energy over the cycle, and slower it stalls (the speed reaches zero); the load "
                           f"exceeds what the drive gives (bracket [{lo:.6g}, {hi:.6g}] J of kinetic energy)")
    raise SolverFailed(f"periodic solution not found: Newton on E(Φ) − E(0) did not converge in "
                       f"{MAX_NEWTON} iterations (last residual {last!r} W_s, bracket [{lo:.6g}, {hi:.6g}] J)")


# -- required flywheel with the dynamic model -------------------------------------


@dataclass(frozen=True)
class DynamicRequirement:
    """Smallest flywheel whose periodic steady state keeps δ.

    Attributes
    ----------
    j_required : float
        J_F [kg*m^2] (<= 0: the machine's own inertia suffices).
    solution : PeriodicSolution
        The periodic solution with that flywheel.
    iterations : int
        Periodic solutions computed.
    held : str
        What was held: the prescribed mean speed (angle-only torques) or
        nothing but the torque laws (speed-dependent: ω_m is an outcome).
    j_initial : float
        The constant-inertia estimate the iteration started from [kg*m^2].
    limit : {"delta", "stall"}
        "delta": the flywheel reaches the allowed δ. "stall": δ stays below
        the allowed value down to the smallest flywheel that still has a
        periodic steady state (below it the machine stalls, e.g. the motor
        breaks down in the working stroke); ``j_required`` is that limit
        (to :data:`STALL_RTOL`) and ``solution.delta`` is below δ.
    """

    j_required: float
    solution: PeriodicSolution
    iterations: int
    held: str
    j_initial: float
    limit: str


def dynamic_requirement(net_torque, j_machine, cycle_angle, omega_mean, delta, knots=(), rtol=1e-10):
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
    _check_speed_delta(omega_mean, delta)
    model = periodic_model(net_torque, j_machine, cycle_angle, knots)
    phi = model.grid_angles()
    j_grid = model.inertia(phi)
    j_low = float(j_grid.min())
    j_mean = float(np.mean(j_grid[:, :-1]))  # an estimate only, for the start
    # constant-inertia estimate at the guessed speed
    m = model.torque(phi, omega_mean)
    h = np.diff(phi, axis=1)
    e = np.concatenate(([0.0], np.cumsum(0.5 * (m[:, 1:] + m[:, :-1]) * h)))
    e -= (e[-1] / model.cycle) * np.concatenate(([0.0], np.cumsum(h)))
    a_est = float(e.max() - e.min())
    j_tot0 = a_est / (omega_mean**2 * delta)
    j_initial = j_tot0 - j_mean
    # unknown u = log(J_F + j_low)
    u = math.log(max(j_tot0 - (j_mean - j_low), 0.25 * j_tot0, 1e-300) if j_tot0 > 0 else max(j_mean, 1e-300))
    target = math.log(delta)
    lo, hi = -math.inf, math.inf  # u where δ is too large (or no steady state) / small enough
    lo_failed = False  # whether lo is a flywheel without a periodic steady state
    hi_solution = None
    previous = None
    guess = omega_mean
    failure = None
    for it in range(1, MAX_DYNAMIC + 1):
        j_f = math.exp(u) - j_low
        try:
            sol = _periodic(model, j_f, guess)
        except SolverFailed as err:
            sol, failure = None, str(err)
        if sol is not None and sol.delta <= 0:  # no fluctuation at all: any flywheel will do
            return DynamicRequirement(j_required=-j_low, solution=sol, iterations=it, held=_held(model),
                                      j_initial=j_initial, limit="delta")
        if sol is None:
            if u > lo:
                lo, lo_failed = u, True
            u_next = u + 1.0 if math.isinf(hi) else 0.5 * (lo + hi)
        else:
            guess = sol.omega_mean
            f = math.log(sol.delta) - target
            if abs(f) <= rtol:
                return DynamicRequirement(j_required=j_f, solution=sol, iterations=it, held=_held(model),
                                          j_initial=j_initial, limit="delta")
            if f > 0 and u > lo:
                lo, lo_failed = u, False
            elif f < 0 and u < hi:
                hi, hi_solution = u, sol
            if previous is not None and previous[0] != u and previous[1] != f:
                slope = (f - previous[1]) / (u - previous[0])
            else:
                slope = -math.exp(u) / (math.exp(u) + max(j_mean - j_low, 0.0))
            previous = (u, f)
            u_next = u - f / slope if slope < 0 else math.nan
            if not (math.isfinite(u_next) and lo < u_next < hi):
                if math.isfinite(lo) and math.isfinite(hi):
                    u_next = 0.5 * (lo + hi)
                else:
                    u_next = u + (2.0 if f > 0 else -2.0)
        if math.isfinite(lo) and math.isfinite(hi) and lo_failed and hi - lo <= STALL_RTOL:
            # δ stays below the allowed value down to where the steady state ceases to exist
            return DynamicRequirement(j_required=math.exp(hi) - j_low, solution=hi_solution, iterations=it,
                                      held=_held(model), j_initial=j_initial, limit="stall")
        u = u_next
    raise SolverFailed(f"the flywheel for delta = {delta!r} was not found in {MAX_DYNAMIC} periodic solutions "
                       f"(bracket J_F in [{math.exp(lo) - j_low:.6g}, {math.exp(hi) - j_low:.6g}] kg*m^2; "
                       f"last failure: {failure})")


def _held(model):
    if model.speed_dependent:
        return "torque-speed balance: the mean speed is an outcome (omega_mean was a guess)"
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
    solution : PeriodicSolution
    """

    method: str
    achieved_delta: float
    delta_allowed: float
    omega_max: float
    omega_min: float
    omega_mean: float
    tolerance: float
    flagged: bool
    solution: PeriodicSolution = field(repr=False)

    def to_dict(self):
        """The fields of the report's "verification" entry."""
        return {"method": self.method, "achieved_delta": self.achieved_delta,
                "delta_allowed": self.delta_allowed, "omega_max": self.omega_max,
                "omega_min": self.omega_min, "omega_mean": self.omega_mean,
                "tolerance": self.tolerance, "flagged": self.flagged}


def verify(net_torque, j_machine, cycle_angle, omega_mean, delta_allowed, j_flywheel, knots=()):
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
    """
    _check_speed_delta(omega_mean, delta_allowed)
    sol = periodic_solution(net_torque, j_machine, cycle_angle, omega_mean, j_flywheel, knots)
    return Verification(
        method="periodic simulation (CVODES shooting, Newton on the periodicity condition)",
        achieved_delta=sol.delta, delta_allowed=float(delta_allowed), omega_max=sol.omega_max,
        omega_min=sol.omega_min, omega_mean=sol.omega_mean, tolerance=sol.tolerance,
        flagged=bool(sol.delta - delta_allowed > sol.tolerance), solution=sol)


# -- start-up ----------------------------------------------------------------------


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


def startup_time(net_torque, j_machine, cycle_angle, omega_target, j_flywheel=0.0, knots=(), phi_start=0.0,
                 max_cycles=100000):
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
    _check_speed_delta(omega_target, None)
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
        raise SolverFailed(f"the machine cannot start from rest at phi = {phi_start!r} rad: the net torque at rest "
                           f"there is {m0:.6g} N*m (the motor's starting torque does not exceed the load)")
    j_mean = float(np.mean(model.inertia(model.grid_angles()))) + j_flywheel
    e_target = 0.5 * j_mean * omega_target**2
    t_scale = cycle / omega_target
    # first piece: from phi_start (plus a tiny constant-acceleration start) to its segment end
    k0 = int(np.searchsorted(seg[:, 1], phi_start, side="right"))
    first = seg[k0, 1] - phi_start
    dphi = 1e-9 * first
    x = np.array([m0 * dphi / e_target, 0.0, math.sqrt(2 * j0 * dphi / m0) / t_scale])
    angle = 0.0
    pieces = [(phi_start + dphi, seg[k0, 1])] + [tuple(s) for s in seg[k0 + 1:]]
    peaks = []
    for n in range(int(max_cycles) + 1):
        peak = 0.0
        for a, b in pieces:
            try:
                xf = np.asarray(model.piece_timed(x0=x, p=[a, b, j_flywheel, 0.0, e_target, t_scale])["xf"])
            except RuntimeError as err:
                raise SolverFailed(f"start-up integration failed near phi = {a:.6g} rad in cycle {n}: "
                                   f"{str(err).splitlines()[-1]}") from err
            if xf[1, -1] > 0:
                raise SolverFailed(f"the machine stalls during start-up between phi = {a:.6g} and {b:.6g} rad "
                                   f"(cycle {n}): the load there exceeds the motor torque and the stored energy")
            phi, omega, gap, slope = _piece_gap(model, a, b, e_target * xf[0], j_flywheel, omega_target)
            reach = _first_reach(phi, gap, slope)
            if reach is not None:
                i, s = reach
                d = phi[i + 1] - phi[i]
                t0, t1 = xf[2, i] * t_scale, xf[2, i + 1] * t_scale
                g0, g1 = d / omega[i], d / omega[i + 1]  # dt/ds at the ends (s = (φ − φ_i)/d)
                t_hit = _hermite(t0, t1, g0, g1, s)
                angle += phi[i] + s * d - a
                return Startup(time=float(t_hit), angle=float(angle), cycles=float(angle / cycle),
                               omega_target=float(omega_target))
            peak = max(peak, float(np.max(omega)))
            angle += b - a
            x = xf[:, -1]
        pieces = [tuple(s) for s in seg]
        peaks.append(peak)
        limit = _settled_peak(peaks, omega_target)
        if limit is not None:
            raise SolverFailed(f"the machine settles below the target speed {omega_target!r} rad/s during start-up: "
                               f"its peak speed converges to about {limit:.6g} rad/s")
    raise SolverFailed(f"the target speed {omega_target!r} rad/s was not reached in {max_cycles} cycles")


def _hermite(f0, f1, m0, m1, t):
    """Cubic Hermite interpolant on [0, 1] with end values f and end slopes m."""
    return f0 + t * (m0 + t * (3 * (f1 - f0) - 2 * m0 - m1 + t * (2 * (f0 - f1) + m0 + m1)))


def _piece_gap(model, a, b, energy, j_flywheel, target):
    """Speed, and E − ½ J ω_t² with its slope M − ½ J' ω_t², at the outputs of one piece.

    The gap is smooth even at rest, where ω ~ sqrt(φ − φ_0) is not.
    """
    phi = a + model.tau * (b - a)
    j = model.inertia(phi) + j_flywheel
    omega = np.sqrt(2 * np.maximum(energy, 0.0) / j)
    m = model.torque(a + np.clip(model.tau, _EDGE, 1 - _EDGE) * (b - a), omega)
    gap = energy - 0.5 * j * target**2
    slope = m - 0.5 * model.inertia.derivative(phi) * target**2
    return phi, omega, gap, slope


def _first_reach(phi, gap, slope):
    """First (interval, s) where the Hermite interpolant of ``gap`` reaches 0, or None."""
    if gap[0] >= 0:
        return 0, 0.0
    d = np.diff(phi)
    f0, f1, m0, m1 = gap[:-1], gap[1:], slope[:-1] * d, slope[1:] * d
    peak = _hermite_extremes(phi[None, :], gap[None, :], slope[None, :])[0][1]
    if peak < 0:
        return None
    for i in np.flatnonzero(np.maximum(f0, f1) + np.abs(m0) + np.abs(m1) >= 0):
        a3, b2, c1 = 2 * (f0[i] - f1[i]) + m0[i] + m1[i], 3 * (f1[i] - f0[i]) - 2 * m0[i] - m1[i], m0[i]
        crit = [r.real for r in np.atleast_1d(np.roots([3 * a3, 2 * b2, c1]) if (a3 or b2) else [])
                if abs(r.imag) < 1e-12 and 0 < r.real < 1]
        points = sorted([0.0, *crit, 1.0])
        for lower, upper in zip(points[:-1], points[1:]):
            if _hermite(f0[i], f1[i], m0[i], m1[i], upper) >= 0:
                s = optimize.brentq(lambda t, i=i: _hermite(f0[i], f1[i], m0[i], m1[i], t), lower, upper,
                                    xtol=1e-15, rtol=4 * _EPS)
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
