"""The flywheel of the dynamic model in one Newton solve (compiled fixed-step shooting).

The dynamic model (docs/flywheel-design.md, section 7) asks for the smallest
flywheel J_F whose periodic steady state of

    d(½ J(φ) ω²)/dφ = M(φ, ω)

keeps (ω_max − ω_min)/ω_mean = δ. :func:`flyopt.sizing.periodic.dynamic_requirement`
used to nest two iterations: a search on J_F, each trial a periodic solution
by CVODES shooting at rtol 1e-11 with a Newton iteration of its own. Here the
flywheel is one more unknown and δ one more equation, and everything is one
Newton solve:

    unknowns  v = log ω_ref   (E(0) = ½ J(0) ω_ref², J = J_e + J_F),
              u = log(J_F + min J_e),
              w = c / M_s     (only when an unknown constant torque holds the
                               mean speed: the correction c of that constant);
    equations y(Φ) = 0                      (the orbit is periodic; automatic when the
                                             torques depend on the angle only, and
                                             then checked, not solved),
              log δ(v, u, w) = log δ_allowed,
              ω_mean / ω_m − 1 = 0          (with the balancing constant, and for torques
                                             of the angle only: the mean speed is given).

One cycle is integrated by the classical fourth-order Runge–Kutta method with
fixed steps on :class:`flyopt.sizing.periodic_model.PeriodicModel`'s output grid (the same
pieces, cut at every knot of the torque or the inertia, and the same scaled
energy y = (E − E_ref)/W_s), compiled once per machine structure with CasADi.
The Jacobian is exact for the discrete cycle (the forward sensitivities of y
to J_F, E_ref and c, carried with y through the same steps, so that one
compiled SX loop computes both) except for δ, whose extremes move between grid points: its
derivative is taken at the grid point of each extreme (the envelope theorem
makes that the exact derivative where the extreme is a smooth maximum), which
costs Newton nothing but a little of its quadratic rate.

Accuracy is checked, not assumed: the converged state is integrated again with
twice the steps; when δ or the periodicity moves by more than
:data:`STEP_RTOL` the steps are doubled and Newton continues (up to
:data:`MAX_SUBSTEPS` steps between grid points). The extremes are those of the
cubic Hermite interpolant through the grid (exact slopes), as for the CVODES
solution, so the two agree to the integration error (tested to 1e-8).

Anything this solve cannot settle — no steady state near the estimate, a
flywheel below which the machine stalls, a machine that needs no flywheel, a
stiff motor that needs more steps than allowed — raises :class:`NotSettled`,
and the caller falls back on the CVODES search, which handles every case and
stays the independent verifier (``--verify``).
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from flyopt.cycle.numerics import hermite_extremes
from flyopt.errors import BrokenInvariant, SolverFailed
from flyopt.sizing._numerics import EPS, FloatArray, call

if TYPE_CHECKING:  # annotations only: periodic_model imports this module
    from flyopt.sizing.periodic_model import PeriodicModel

BUILDS: Counter[str] = Counter()
"""CasADi structures built, by kind; :data:`flyopt.sizing.periodic.BUILDS` is this counter."""

STEP_RTOL = 1e-11
"""Largest change of log δ, and of y(Φ) relative to the swing, when the steps are halved."""

SUBSTEPS = 1
MAX_SUBSTEPS = 16
"""Runge–Kutta steps between two grid points: the first try, and the most tried."""

STIFFNESS = 1.0
"""Largest |∂(dy/dτ)/∂y| Δτ of one Runge–Kutta step (the classical method is stable up to 2.78):
the steps are refined to it before Newton trusts them. A motor that needs more than
:data:`MAX_SUBSTEPS` steps per grid interval (a stiff motor on a very small flywheel) is left
to CVODES, whose implicit method does not care."""

MAX_ITERATIONS = 40
"""Newton iterations (with any step doubling) before giving up."""

STALLED = 4
"""Newton gives up when its residual has not halved over this many iterations."""

LINE_SEARCH = 12
"""Halvings of a Newton step that does not reduce the residual."""

DELTA_RTOL = 1e-10
"""|log δ − log δ_allowed| at convergence (δ to 1e-10 relative)."""

PERIODIC_RTOL = 1e-11
"""|y(Φ)| at convergence, relative to the swing of y."""

MEAN_RTOL = 1e-12
"""|ω_mean/ω_m − 1| at convergence (with a balancing constant)."""


class NotSettled(SolverFailed):
    """The one-solve did not settle; the CVODES search takes over (the reason in the message)."""


_STRUCTURES: dict[Any, Any] = {}
"""Compiled fixed-step functions by structure (see :func:`_functions`): shared by every machine
of the same torque law and inertia, so a sweep over δ, the envelope or the material, or a second
reduction of the same scene, builds nothing again."""

MAX_STRUCTURES = 32
"""Structures kept (the least recently used is dropped)."""


def _functions(model, substeps):
    """CasADi functions of one chunk of pieces with ``substeps`` RK4 steps per grid interval (cached).

    ``"plain", size``: (y0, q, data) -> (y_end, Y) with Y the scaled energy at
    every output of every piece (1 × size·outputs); ``"jacobian", size``: the
    same with y carrying its forward sensitivities, x = [y, ∂y/∂J_F, ∂y/∂E_ref,
    ∂y/∂c] (4 rows), and ∂y/∂θ₀ (5 rows) when the net torque has parameters θ
    (the first is the one a search varies: a drive's motor ratio). q = [J_F,
    E_ref, W_s, c, θ...]; data = [φ_a, φ_b, M_a, M_b] of each piece (4 × size).
    """
    key = model.structure + (substeps,)
    if key in _STRUCTURES:
        _STRUCTURES[key] = _STRUCTURES.pop(key)  # most recently used last
        return _STRUCTURES[key]
    if len(_STRUCTURES) >= MAX_STRUCTURES:
        _STRUCTURES.pop(next(iter(_STRUCTURES)))
    BUILDS["fixed-step function"] += 1
    rhs = model.rhs(False)
    # y alone: the stall measure (the model's second state) never enters dy/dτ and is not used here
    f = ca.Function("f", [rhs["t"], rhs["x"], rhs["p"]], [rhs["ode"][0]])
    outputs = len(model.tau) - 1
    h = 1.0 / (outputs * substeps)
    n_p = 8 + model.n_theta
    y, p, t = ca.SX.sym("y"), ca.SX.sym("p", n_p), ca.SX.sym("t")

    def dydt(tau, value):
        return f(tau, ca.vertcat(value, 0), p)

    k1 = dydt(t, y)
    k2 = dydt(t + h / 2, y + h / 2 * k1)
    k3 = dydt(t + h / 2, y + h / 2 * k2)
    k4 = dydt(t + h, y + h * k3)
    y_next = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    # the same step with its tangent: s' = ∂y'/∂y s + ∂y'/∂(J_F, E_ref, c), exactly the forward
    # derivative of the discrete steps, carried as states so that one SX loop computes both
    # (an MX Jacobian of the chained steps costs several times more)
    with_theta = model.n_theta > 0
    sens = ca.SX.sym("s", 4 if with_theta else 3)
    wrt = [p[2], p[3], p[5] if model.balanced else None, p[8] if with_theta else None]
    source = ca.vertcat(*(0 if v is None else ca.jacobian(y_next, v) for v in wrt[: sens.shape[0]]))
    s_next = ca.jacobian(y_next, y) * sens + source
    steps = {
        "plain": (y, ca.Function("rk4", [y, p, t], [y_next])),
        "jacobian": (
            ca.vertcat(y, sens),
            ca.Function("rk4_tangent", [ca.vertcat(y, sens), p, t], [ca.vertcat(y_next, s_next)]),
        ),
    }
    _STRUCTURES[key] = {
        "steps": steps,
        "outputs": outputs,
        "h": h,
        "substeps": substeps,
        "n_q": 4 + model.n_theta,
        "chunks": {},
    }
    return _STRUCTURES[key]


def _piece(functions, kind):
    """One piece of ``kind`` (built on first use: the check with twice the steps needs no tangent)."""
    if kind not in functions:
        state, rk4 = functions["steps"][kind]
        n, outputs, h, substeps = state.shape[0], functions["outputs"], functions["h"], functions["substeps"]
        if substeps == 1:
            interval = rk4
        else:  # the steps of one grid interval, expanded into one SX function (the same operations, bit
            # for bit, without the MX loop's cost per step: 1.5-2.5 times faster); the grid's intervals
            # stay a loop, so the graph stays small
            loop = rk4.mapaccum("steps", substeps)
            xm, pm, t0 = ca.MX.sym("x", n), ca.MX.sym("p", 4 + functions["n_q"]), ca.MX.sym("t0")
            times = t0 + ca.DM(np.arange(substeps, dtype=float).reshape(1, -1) * h)
            interval = ca.Function("interval", [xm, pm, t0], [loop(xm, pm, times)[:, -1]]).expand()
        along = interval.mapaccum("along", outputs)
        starts = ca.DM(np.arange(outputs, dtype=float).reshape(1, -1) / outputs)
        n_q = functions["n_q"]
        x0, q, data = ca.MX.sym("x0", n), ca.MX.sym("q", n_q), ca.MX.sym("data", 4)
        states = along(x0, ca.vertcat(data[0], data[1], q[:4], data[2], data[3], q[4:]), starts)
        piece = ca.Function("piece", [x0, q, data], [states[:, -1], ca.horzcat(x0, states)])
        functions[kind] = piece.expand() if substeps == 1 else piece
    return functions[kind]


def _chunk(model, substeps, kind, size):
    functions = _functions(model, substeps)
    key = (kind, size)
    if key not in functions["chunks"]:
        functions["chunks"][key] = _piece(functions, kind).mapaccum(f"pieces_{kind}_{size}", size)
    return functions["chunks"][key]


def cycle(
    model: PeriodicModel,
    substeps: int,
    j_flywheel: float,
    e_ref: float,
    w_s: float,
    offset: float,
    derivatives: bool,
) -> tuple[FloatArray, FloatArray | None]:
    """One cycle by fixed-step RK4 from y = 0.

    Returns
    -------
    y : ndarray (pieces, outputs + 1)
        The scaled energy on the model's grid.
    jac : ndarray (pieces, outputs + 1, 3 or 4) or None
        ∂y/∂(J_F, E_ref, c[, θ₀]) on the grid (with ``derivatives``; θ₀ when the model has parameters).
    """
    q = np.array([[j_flywheel], [e_ref], [w_s], [offset], *([v] for v in model.theta)])  # the same for every piece
    kind = "jacobian" if derivatives else "plain"
    n_sens = 4 if model.n_theta else 3
    x = np.zeros(1 + n_sens if derivatives else 1)  # the sensitivities start at zero with y
    parts = []
    for _, data in model.chunked():
        size = data.shape[1]
        end, states = call(_chunk(model, substeps, kind, size), x, np.repeat(q, size, axis=1), data)
        states = states.reshape(len(x), -1, order="F")
        parts.append(states)
        x = states[:, -1]
    states = np.concatenate(parts, axis=1)
    shape = (len(model.pieces), len(model.tau))
    y = states[0].reshape(shape)
    jac = states[1:].T.reshape(shape + (n_sens,)) if derivatives else None
    return y, jac


class _State:
    """The cycle at one point (v, u, w) of the unknowns: residuals and their Jacobian."""

    def __init__(self, solve, x, substeps, derivatives):
        model = solve.model
        v, u = x[0], x[1]
        w = x[2] if solve.balanced else 0.0
        self.x = x
        self.omega_ref = math.exp(v)
        self.j_total0 = math.exp(u) - solve.j_low + solve.j0
        self.j_flywheel = math.exp(u) - solve.j_low
        self.e_ref = 0.5 * self.j_total0 * self.omega_ref**2
        self.offset = w * solve.m_scale
        self.y, jac = cycle(model, substeps, self.j_flywheel, self.e_ref, solve.w_s, self.offset, derivatives)
        self.ok = bool(np.all(np.isfinite(self.y)))
        if not self.ok:
            return
        phi, q, dq, energy = model.speed_profile(self.y, self.j_flywheel, self.e_ref, solve.w_s, 0.0, self.offset)
        self.phi, self.q, self.dq = phi, q, dq
        if q is None or not np.all(np.isfinite(dq)):
            self.ok = False
            return
        hi, lo = hermite_extremes(phi, q, dq)
        if not lo[1] > 0:
            self.ok = False
            return
        self.hi, self.lo = hi, lo
        w_max, w_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
        self.omega_max, self.omega_min = w_max, w_min
        self.omega_mean = 0.5 * (w_max + w_min)
        self.delta = (w_max - w_min) / self.omega_mean
        self.y_end = float(self.y[-1, -1])
        self.swing = float(np.ptp(self.y))
        if not self.delta > 0:
            self.ok = False
            return
        log_delta = math.log(self.delta) - solve.log_delta
        mean = self.omega_mean / solve.omega_m - 1
        self.r = np.array(
            {"motor": [self.y_end, log_delta], "balanced": [self.y_end, log_delta, mean], "angle": [mean, log_delta]}[
                solve.mode
            ]
        )
        if model.speed_dependent:
            # |∂(dy/dτ)/∂y| Δτ = |∂M/∂ω| Δφ/(J ω) per grid interval
            h = np.diff(phi, axis=1)
            slope = model.torque_slope(phi[:, :-1], np.sqrt(2 * q[:, :-1]))
            self.stiffness = float(
                np.max(np.abs(slope) * h / (j_total(model, phi[:, :-1], self.j_flywheel) * np.sqrt(2 * q[:, :-1])))
            )
        else:
            self.stiffness = 0.0
        if not derivatives:
            return
        if jac is None:
            raise BrokenInvariant("cycle gives the sensitivities when asked for them")
        if not np.all(np.isfinite(jac)):  # the steps are unstable for the derivatives
            self.ok = False
            return
        # d(J_F, E_ref, c)/d(v, u, w)
        e_u = math.exp(u)
        chain = np.array(
            [[0.0, e_u, 0.0], [2 * self.e_ref, 0.5 * self.omega_ref**2 * e_u, 0.0], [0.0, 0.0, solve.m_scale]]
        )
        dy = jac[..., :3] @ chain  # ∂y/∂(v, u, w) on the grid
        j_grid = model.inertia(phi) + self.j_flywheel
        dj = np.array([0.0, e_u, 0.0])  # ∂J/∂(v, u, w)
        de = chain[1]  # ∂E_ref/∂(v, u, w)

        self.raw_jac = jac

        def d_omega(where):
            # at the grid point nearest to the extreme, where q = (E_ref + W_s y)/J
            i = np.unravel_index(np.argmin(np.abs(phi - where[0])), q.shape)
            d_q = (de + solve.w_s * dy[i] - q[i] * dj) / j_grid[i]
            return d_q / math.sqrt(2 * where[1])

        dw_max, dw_min = d_omega(hi), d_omega(lo)
        s = w_max + w_min
        d_delta = (4 * w_min * dw_max - 4 * w_max * dw_min) / s**2
        d_mean = 0.5 * (dw_max + dw_min) / solve.omega_m
        rows = {
            "motor": [dy[-1, -1], d_delta / self.delta],
            "balanced": [dy[-1, -1], d_delta / self.delta, d_mean],
            "angle": [d_mean, d_delta / self.delta],
        }[solve.mode]
        self.jac = np.array(rows)[:, : len(x)]


def j_total(model: PeriodicModel, phi: FloatArray, j_flywheel: float) -> FloatArray:
    """J_e(φ) + J_F [kg*m^2]."""
    return model.inertia(phi) + j_flywheel


class _Solve:
    def __init__(self, model, delta, omega_m, w_s, j_low, j0, m_scale):
        self.model = model
        self.balanced = model.balanced
        self.mode = "balanced" if model.balanced else "motor" if model.speed_dependent else "angle"
        self.log_delta = math.log(delta)
        self.omega_m = omega_m
        self.w_s = w_s
        self.j_low = j_low
        self.j0 = j0  # J_e(0)
        self.m_scale = m_scale

    def settled(self, state):
        """Whether Newton is done: δ, and the periodicity or the mean speed, to their tolerances."""
        done = abs(state.r[1]) <= DELTA_RTOL
        if self.mode != "angle":
            done = done and abs(state.y_end) <= PERIODIC_RTOL * max(state.swing, EPS)
        if self.mode != "motor":
            done = done and abs(state.omega_mean / self.omega_m - 1) <= MEAN_RTOL
        return done

    def moved(self, state, finer):
        """How far the result moves with twice the steps: log δ, y(Φ)/swing and the mean speed."""
        if not finer.ok:
            return math.inf
        swing = max(state.swing, EPS)
        return max(
            abs(finer.r[1] - state.r[1]),
            abs(finer.y_end - state.y_end) / swing,
            abs(finer.omega_mean / state.omega_mean - 1),
        )


def required_flywheel(model: PeriodicModel, delta: float, omega_guess: float, j_initial_total: float) -> dict[str, Any]:
    """J_F, the periodic grid and the iteration count of the one-solve.

    Parameters
    ----------
    model : PeriodicModel
        A speed-dependent machine (a motor, or a speed-dependent load against
        an unknown constant torque: ``model.balanced``).
    delta : float
        Allowed δ [-].
    omega_guess : float
        The scene's speed [rad/s]: the prescribed mean speed with a balancing
        constant, otherwise where the search for the torque–speed balance starts.
    j_initial_total : float
        The constant-inertia estimate of J_F + J_e [kg*m^2].

    Returns
    -------
    dict
        j_flywheel [kg*m^2], e_ref [J], w_s [J], offset [N*m], y (the scaled
        energy on the grid), iterations, substeps, periodicity (|y(Φ)|/swing).

    Raises
    ------
    NotSettled
        The solve did not converge to a verified steady state.
    """
    phi = model.grid_angles()
    j_grid = model.inertia(phi)
    j_low = float(j_grid.min())
    j0 = float(model.inertia(0.0))
    omega0 = _mean_balance(model, omega_guess) if model.speed_dependent and not model.balanced else omega_guess
    energy = energy_swing(model, omega0)
    if not energy > 0:
        raise NotSettled("the net torque does no work to store over the cycle at the estimated speed")
    w_s = energy
    m_scale = energy / model.cycle
    solve = _Solve(model, delta, omega_guess, w_s, j_low, j0, m_scale)
    j_total = j_initial_total if j_initial_total > 0 else energy / (omega0**2 * delta)
    u = math.log(max(j_total - float(np.mean(j_grid[:, :-1])) + j_low, 1e-3 * j_total))
    x = np.array([math.log(omega0), u] + ([0.0] if solve.balanced else []))
    substeps = SUBSTEPS
    state = _State(solve, x, substeps, True)
    if not state.ok:
        raise NotSettled(
            f"the cycle cannot be integrated at the estimate (J_F = {state.j_flywheel:.6g} kg*m^2, "
            f"ω = {omega0:.6g} rad/s)"
        )
    norms = []
    for iteration in range(1, MAX_ITERATIONS + 1):
        needed = SUBSTEPS
        while state.stiffness * 1.0 / needed > STIFFNESS:
            needed *= 2
        if needed > MAX_SUBSTEPS:
            raise NotSettled(
                f"the motor is too stiff for fixed steps at J_F = {state.j_flywheel:.6g} kg*m^2: "
                f"{needed} steps per grid interval would be needed"
            )
        if needed > substeps:
            substeps = needed
            state = _State(solve, state.x, substeps, True)
            if not state.ok:
                raise NotSettled("the cycle cannot be integrated with finer steps")
            continue
        if solve.settled(state):
            finer = _State(solve, state.x, 2 * substeps, False)
            moved = solve.moved(state, finer)
            if moved <= STEP_RTOL:
                return _result(solve, state, iteration, substeps)
            if 2 * substeps > MAX_SUBSTEPS:
                raise NotSettled(
                    f"the fixed steps do not resolve the cycle: the result moves by {moved:.3g} "
                    f"(relative) with {2 * substeps} steps per grid interval"
                )
            substeps *= 2
            state = _State(solve, state.x, substeps, True)
            if not state.ok:
                raise NotSettled("the cycle cannot be integrated with finer steps")
            continue
        try:
            step = -np.linalg.solve(state.jac, state.r)
        except np.linalg.LinAlgError:
            raise NotSettled(f"singular Newton system at J_F = {state.j_flywheel:.6g} kg*m^2") from None
        if not np.all(np.isfinite(step)):
            raise NotSettled(f"no Newton step at J_F = {state.j_flywheel:.6g} kg*m^2")
        scale = min(1.0, 0.5 / max(abs(step[0]), 1e-300), 2.0 / max(abs(step[1]), 1e-300))
        norm = float(np.linalg.norm(state.r))
        norms.append(norm)
        if len(norms) > STALLED and norm > 0.5 * norms[-1 - STALLED]:
            raise NotSettled(
                f"Newton stalls at |r| = {norm:.3g} (J_F = {state.j_flywheel:.6g} kg*m^2): the "
                f"extremes of the speed do not move smoothly with the flywheel"
            )
        for _ in range(LINE_SEARCH):
            trial = _State(solve, state.x + scale * step, substeps, True)
            if trial.ok and (np.linalg.norm(trial.r) < norm or scale == 1.0 and norm < 1e-6):
                break
            scale *= 0.5
        else:
            raise NotSettled(
                f"Newton's steps do not reduce the residual (|r| = {norm:.3g}) at J_F = {state.j_flywheel:.6g} kg*m^2"
            )
        state = trial
    raise NotSettled(f"no convergence in {MAX_ITERATIONS} Newton iterations (residuals {state.r})")


def _result(solve, state, iterations, substeps):
    # dE(Φ)/dE(0) at a fixed flywheel; exactly 1 when the torques do not depend on speed
    multiplier = 1.0 if solve.mode == "angle" else 1.0 + solve.w_s * float(state.raw_jac[-1, -1, 1])
    if solve.mode == "motor" and not multiplier < 1.0:  # as the CVODES path: a motor's orbit must attract
        raise NotSettled(f"the steady state found is unstable (Floquet multiplier {multiplier:.6g} >= 1)")
    return {
        "j_flywheel": state.j_flywheel,
        "e_ref": state.e_ref,
        "w_s": solve.w_s,
        "offset": state.offset,
        "y": state.y,
        "iterations": iterations,
        "substeps": substeps,
        "multiplier": multiplier,
        "periodicity": abs(state.y_end) / max(state.swing, EPS),
    }


def _mean_balance(model, omega_guess):
    """The speed where the cycle's mean net torque falls through zero [rad/s] (the starting speed).

    The mean over the grid of M(φ, ω) at a frozen speed: where a flywheel large
    enough to hold the speed would run. Searched outward from the guess.
    """
    phi = model.grid_angles()
    h = np.diff(phi, axis=1)

    def mean(omega):
        m = model.torque(phi, omega)
        return float(np.sum(0.5 * (m[:, 1:] + m[:, :-1]) * h)) / model.cycle

    try:  # a starting point: Newton refines it
        return speed_balance(mean, omega_guess, rtol=1e-6)
    except SolverFailed as err:
        raise NotSettled(f"the cycle's mean torque: {err}") from None


def speed_balance(torque: Callable[[float], float], omega_guess: float, rtol: float = 4 * EPS) -> float:
    """The speed where a torque of speed alone, M(ω), falls through zero (a stable balance) [rad/s].

    Bracketed outward from the guess by factors of 2, then refined by Brent's method to ``rtol``.

    Raises
    ------
    SolverFailed
        No fall through zero within 2⁶⁰ of the guess: the machine runs away or stalls.
    """
    lo = hi = float(omega_guess)
    m_lo = m_hi = torque(lo)
    for _ in range(60):
        if m_lo > 0 > m_hi:
            break
        if m_hi >= 0:  # still gains energy: the balance lies faster
            lo, m_lo = hi, m_hi
            hi *= 2.0
            m_hi = torque(hi)
        else:  # loses energy: it lies slower
            hi, m_hi = lo, m_lo
            lo *= 0.5
            m_lo = torque(lo)
    else:
        raise SolverFailed(
            f"no steady speed: the net torque does not fall through zero between "
            f"{lo:.6g} and {hi:.6g} rad/s (it is {m_lo:.6g} and {m_hi:.6g} N*m there): the "
            f"machine runs away or stalls"
        )
    if m_lo == 0:
        return lo
    # scipy's brentq, operation for operation, without importing scipy.optimize (~0.3 s of a process)
    from flyopt.cycle.numerics import brentq_many

    def at(x, index):
        return np.array([torque(float(v)) for v in x])

    return float(
        brentq_many(at, np.array([lo]), np.array([hi]), np.array([m_lo]), np.array([m_hi]), 1e-15 * hi, rtol, 500)[0]
    )


def energy_swing(model: PeriodicModel, omega: float) -> float:
    """max − min of ∫ (M − mean M) dφ on the grid at a frozen speed [J] (the energy method's A_max)."""
    phi = model.grid_angles()
    m = model.torque(phi, omega)
    h = np.diff(phi, axis=1)
    e = np.concatenate(([0.0], np.cumsum(0.5 * (m[:, 1:] + m[:, :-1]) * h)))
    e -= (e[-1] / model.cycle) * np.concatenate(([0.0], np.cumsum(h)))
    return float(e.max() - e.min())
