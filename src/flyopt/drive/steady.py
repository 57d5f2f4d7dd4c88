"""A motor's steady running, its ratio and the least flywheel, by Newton on the compiled shooting.

For one motor of the catalogue the drive search needs the ratio i_m that
runs the crank at the scene's mean speed ω_m = (ω_max + ω_min)/2 and the
least flywheel J_F that keeps δ and the motor's thermal limit
(docs/flywheel-design.md, sections 7 and 14). Both are unknowns of one
Newton solve on the compiled fixed-step periodic model
(:mod:`flyopt.sizing.shooting`), whose net torque takes the motor's ratio and
Kloss curve as parameters θ = (i_m, ω_0, M_b, s_b): one build serves every
motor size and ratio, and a size starts from its neighbour's solution.

    unknowns  v = ln ω_ref            (E(0) = ½ J(0) ω_ref²),
              u = ln(J_F + J_s)       (J_s > 0 a fixed scale: J_F may fall below 0 in a step),
              ρ = ln i_m,
    equations y(Φ) = 0                (the orbit is periodic),
              the binding limit       (ln δ = ln δ_allowed, or T_rms/T_n − 1 = 0),
              ω_mean/ω_m − 1 = 0.

The rotor's inertia J_rot i_m² is part of the constant inertia at the crank
(it enters with J_F). Without a flywheel (J_F = 0) u is dropped with the
limit's equation. The Jacobian is the forward sensitivity of the discrete
cycle (∂y/∂J, ∂y/∂E_ref, ∂y/∂i_m carried through the steps), with the speed's
extremes differentiated at their grid points (the envelope theorem, as in
:mod:`flyopt.sizing.shooting`) and the RMS torque differentiated term by term.

The steps are refined as the one-solve refines them: until the stiffest
step is stable, and at convergence until twice the steps move the result by
less than :data:`flyopt.sizing.shooting.STEP_RTOL`. Whatever this solve
cannot settle raises :class:`flyopt.sizing.shooting.NotSettled`; the caller
then falls back on the CVODES search, which is also the verifier of the
chosen drive.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import casadi as ca
import numpy as np

from flyopt.cycle.numerics import hermite_extremes
from flyopt.errors import BrokenInvariant
from flyopt.machine.motor import kloss_torque
from flyopt.said import said
from flyopt.sizing import shooting
from flyopt.sizing._numerics import EPS, FloatArray, evaluate
from flyopt.sizing.shooting import NotSettled

if TYPE_CHECKING:
    from flyopt.machine.catalogue import CatalogueMotor
    from flyopt.machine.reduce import NetTorque
    from flyopt.sizing.periodic_model import PeriodicModel

#: Newton iterations of one solve (with any refinement of the steps).
MAX_ITERATIONS = 40

#: Halvings of a Newton step that does not reduce the residual.
LINE_SEARCH = 12

#: Convergence: |y(Φ)| relative to the swing of y, |ln δ − ln δ_allowed|, |T_rms/T_n − 1|, |ω_mean/ω_m − 1|.
PERIODIC_RTOL, DELTA_RTOL, THERMAL_RTOL, MEAN_RTOL = 1e-11, 1e-10, 1e-10, 1e-12

#: Largest relative move of δ, the mean speed, the RMS torque and y(Φ) when the steps are halved: the
#: drive's figures to about 1e-10, tighter than the CVODES search held them (mean speed 1e-7, flywheel
#: 1e-6); the one-solve's 1e-11 would ask a motor on a small flywheel for more steps than it allows.
STEP_RTOL = 1e-9


def rms_of(phi: FloatArray, omega: FloatArray, torque: FloatArray) -> tuple[float, float]:
    """(RMS, mean) in time of a torque along a speed curve [N*m].

    T_rms² = ∫ M² dt / T with dt = dφ/ω, by the trapezoidal rule on the points
    given (flattened; a repeated point adds nothing).
    """
    phi, omega, torque = (np.asarray(a, float).reshape(-1) for a in (phi, omega, torque))
    h = np.diff(phi)
    period = float(np.sum(h * 0.5 * (1.0 / omega[1:] + 1.0 / omega[:-1])))
    squares = float(np.sum(h * 0.5 * (torque[1:] ** 2 / omega[1:] + torque[:-1] ** 2 / omega[:-1])))
    means = float(np.sum(h * 0.5 * (torque[1:] / omega[1:] + torque[:-1] / omega[:-1])))
    return math.sqrt(squares / period), means / period


class MotorLoad:
    """The net torque of a drive: the load at the crank plus an induction motor on its Kloss curve.

    The motor's torque at the crank is η i_m M(i_m ω) with M the Kloss curve of
    parameters θ = (i_m, ω_0, M_b, s_b) (:func:`flyopt.machine.motor.kloss_torque`),
    which the periodic model takes as symbols (``parameters``).

    Parameters
    ----------
    load : flyopt.machine.reduce.NetTorque
        The load's net torque at the crank (the motor not in it).
    efficiency : float
        η of the transmission from the motor to the crank [-].
    theta : sequence of float
        The parameters' first values.
    """

    parameters = 4
    balanced = False

    def __init__(self, load: NetTorque, efficiency: float, theta: Sequence[float]) -> None:
        self.load = load
        self.table = load.table
        self.work = load.work
        self.efficiency = float(efficiency)
        self._theta = tuple(float(v) for v in theta)

    def parameter_values(self) -> tuple[float, ...]:
        """θ = (i_m, ω_0, M_b, s_b) the model starts from."""
        return self._theta

    def rest(self, phi: Any, omega: Any, ratio: Any, w0: Any, m_b: Any, s_b: Any) -> Any:
        """The load's parts that are not tables, plus the motor at the crank [N*m] (CasADi)."""
        return self.load.rest(phi, omega) + self.efficiency * ratio * kloss_torque(ratio * omega, w0, m_b, s_b)

    def __call__(self, phi: Any, omega: Any, *theta: Any) -> Any:
        return self.table.casadi(phi) + self.rest(phi, omega, *theta)


def motor_parameters(motor: CatalogueMotor, ratio: float) -> tuple[float, float, float, float]:
    """θ = (i_m, ω_0, M_b, s_b) of a catalogue motor at a ratio."""
    m = motor.motor()
    return (float(ratio), float(m.synchronous_speed), float(m.breakdown_torque), float(m.breakdown_slip))


class Unreachable(NotSettled):
    """The limit cannot be met by any flywheel (the message says why): the motor is refused, not searched again.

    ``limit`` names the limit ("thermal"): the kind of the size's refusal (:attr:`flyopt.drive.codesign.MotorRun.refusal`).
    """

    def __init__(self, message: str, limit: str) -> None:
        super().__init__(message)
        self.limit = limit

    def __reduce__(self) -> tuple[Any, ...]:  # pickled whole (a worker process may raise it)
        return (type(self), (self.args[0], self.limit))


_W, _W0, _MB, _SB = (ca.SX.sym(name) for name in ("w", "w0", "m_b", "s_b"))
_KLOSS = kloss_torque(_W, _W0, _MB, _SB)
KLOSS_SLOPE = ca.Function("kloss_slope", [_W, _W0, _MB, _SB], [_KLOSS, ca.jacobian(_KLOSS, _W)])
"""(M, dM/dω) of the Kloss curve at the motor's speed (the same formula, differentiated by CasADi)."""
_KLOSS_MAPS: dict[Any, Any] = {}


@dataclass(frozen=True)
class Steady:
    """A motor's steady running found by :func:`steady_running`.

    Attributes
    ----------
    ratio : float
        i_m = ω_motor/ω_crank [-].
    j_flywheel : float
        J_F at the crank [kg*m^2] (0 without a flywheel).
    omega_mean, omega_max, omega_min, delta : float
        Of the crank [rad/s] and δ [-].
    rms_torque, mean_torque : float
        Of the motor shaft over the cycle, in time [N*m].
    phi, omega : ndarray
        The crank's speed on the simulation grid, flattened.
    iterations, substeps : int
    x : tuple of float
        (v, u, ρ) at the solution, a start for a neighbour (u = nan without a flywheel).
    """

    ratio: float
    j_flywheel: float
    omega_mean: float
    omega_max: float
    omega_min: float
    delta: float
    rms_torque: float
    mean_torque: float
    phi: FloatArray
    omega: FloatArray
    iterations: int
    substeps: int
    x: tuple[float, float, float]


class DriveModel:
    """The drive's periodic model, built once per scene: the load, the motor's parameters θ.

    Parameters
    ----------
    model : PeriodicModel
        Of a :class:`MotorLoad` (its ``n_theta`` is 4).
    omega_mean, delta : float
        The scene's mean speed [rad/s] and allowed δ [-].
    efficiency : float
        η of the motor's transmission [-].
    """

    def __init__(self, model: PeriodicModel, omega_mean: float, delta: float, efficiency: float) -> None:
        if model.n_theta != MotorLoad.parameters:
            raise ValueError("the drive's model takes the motor's four parameters")
        self.model = model
        self.omega_m = float(omega_mean)
        self.delta = float(delta)
        self.efficiency = float(efficiency)
        phi = model.grid_angles()
        self.j_grid = model.inertia(phi)
        self.j_low = float(self.j_grid.min())
        self.j0 = float(model.inertia(0.0))
        # the energy scale: the swing of the net work at the mean speed (a motor's torque of the speed
        # alone is a constant along the cycle there, and drops out of it)
        #: Steps per grid interval the last solve of each limit needed for a stable step (the next starts at them).
        self.substeps: dict[str, int] = {}
        self.w_s = shooting.energy_swing(model, self.omega_m)
        if not self.w_s > 0:
            raise NotSettled("the load stores no energy over the cycle: nothing for a flywheel to do")

    def steady(
        self,
        motor: CatalogueMotor,
        limit: str,
        start: tuple[float, float, float],
        *,
        ratio: float | None = None,
    ) -> Steady:
        """The steady running of ``motor`` with the flywheel that ``limit`` sets.

        Parameters
        ----------
        limit : {"none", "delta", "thermal", "fixed"}
            "none": no flywheel (unknowns v, ρ); "fixed": the flywheel of ``start``'s u,
            held (unknowns v, ρ: see :meth:`with_flywheel`); "delta": the least J_F for δ;
            "thermal": the J_F whose RMS torque is the motor's rating.
        start : (v, u, ρ)
            Where Newton starts (u ignored for "none"; a nan u starts from the energy estimate).
        ratio : float, optional
            Hold the motor ratio at this value instead of the mean speed
            (unknowns v, u; equations y(Φ) and the limit).
        """
        return _Newton(self, motor, limit, ratio).solve(start)

    def with_flywheel(self, motor: CatalogueMotor, ratio: float, j_flywheel: float, v: float | None = None) -> Steady:
        """The steady running of ``motor`` at ``ratio`` with a given flywheel J_F at the crank [kg*m^2].

        One unknown, v = ln ω_ref, and one equation, y(Φ) = 0, with the steps refined as for
        :meth:`steady` (the δ a flywheel gives the chosen drive, for the analysis' comparison of
        the models). ``v``: where Newton starts (default the scene's mean speed).
        """
        newton = _Newton(self, motor, "fixed", ratio)
        if not j_flywheel + newton.j_s > 0:
            raise NotSettled(f"a flywheel of {j_flywheel:.6g} kg*m^2 leaves the machine no inertia")
        start = math.log(self.omega_m) if v is None else v
        return newton.solve((start, math.log(j_flywheel + newton.j_s), math.log(ratio)))


class _Newton:
    def __init__(self, drive: DriveModel, motor: CatalogueMotor, limit: str, ratio: float | None) -> None:
        self.drive, self.motor, self.limit = drive, motor, limit
        self.fixed_ratio = ratio
        m = motor.motor()
        self.theta_motor = (float(m.synchronous_speed), float(m.breakdown_torque), float(m.breakdown_slip))
        self.rated = float(motor.rated_torque)
        self.j_rot = float(motor.rotor_inertia)
        self.log_delta = math.log(drive.delta)
        # the unknowns solved and the residuals kept, by name
        held = limit in ("none", "fixed")  # no flywheel, or one held: no unknown u, no limit's equation
        unknowns = ["v"] + ([] if held else ["u"]) + ([] if ratio is not None else ["rho"])
        rows = ["periodic"] + ([] if held else [limit]) + ([] if ratio is not None else ["mean"])
        self.columns = [("v", "u", "rho").index(k) for k in unknowns]
        self.rows = rows
        self.w_s = drive.w_s
        # u = ln(J_F + J_s): J_F may fall below zero in a step, as far as the machine's own least inertia
        self.j_s = drive.j_low if drive.j_low > 0 else drive.w_s / (drive.omega_m**2 * drive.delta) * 1e-6

    # -- one point ------------------------------------------------------------
    def state(self, full: FloatArray, substeps: int, derivatives: bool) -> _Point | None:
        return _Point.at(self, full, substeps, derivatives)

    def settled(self, p: _Point) -> bool:
        done = abs(p.y_end) <= PERIODIC_RTOL * max(p.swing, EPS)
        if "mean" in self.rows:
            done = done and abs(p.omega_mean / self.drive.omega_m - 1) <= MEAN_RTOL
        if self.limit == "delta":
            done = done and abs(math.log(p.delta) - self.log_delta) <= DELTA_RTOL
        if self.limit == "thermal":
            done = done and abs(p.rms / self.rated - 1) <= THERMAL_RTOL
        return done

    def moved(self, p: _Point, finer: _Point | None) -> float:
        if finer is None:
            return math.inf
        swing = max(p.swing, EPS)
        return max(
            abs(math.log(finer.delta / p.delta)),
            abs(finer.y_end - p.y_end) / swing,
            abs(finer.omega_mean / p.omega_mean - 1),
            abs(finer.rms / p.rms - 1),
        )

    def solve(self, start: tuple[float, float, float]) -> Steady:
        drive = self.drive
        v, u, rho = start
        if self.fixed_ratio is not None:
            rho = math.log(self.fixed_ratio)
        if self.limit != "none" and not math.isfinite(u):  # the energy method's flywheel, at least a little
            j_total = drive.w_s / (drive.omega_m**2 * drive.delta)
            j_flywheel = max(j_total - float(np.mean(drive.j_grid)) - self.j_rot * math.exp(2 * rho), 1e-3 * j_total)
            u = math.log(j_flywheel + self.j_s)
        full = np.array([v, u if self.limit != "none" else math.nan, rho])
        # Newton with its Jacobian computed at the coarsest steps that settle the cycle and kept while
        # the steps are refined (a chord method): the sensitivities cost four cycles, and finer steps
        # move the solution, not the Jacobian, by a little; they are computed again where the residual
        # stops falling fast. It starts at the steps the last solve of this limit needed for stability
        # (not for accuracy: a Jacobian there costs several times one at the coarsest stable steps)
        substeps = max(shooting.SUBSTEPS, self.drive.substeps.get(self.limit, 1))
        point = self.state(full, substeps, True)
        if point is None:
            raise NotSettled(f"the cycle cannot be integrated at the start (ratio {math.exp(rho):.6g})")
        jac = point.jacobian()
        fresh = True  # the Jacobian is of this point
        norms: list[float] = []
        for iteration in range(1, MAX_ITERATIONS + 1):
            needed = shooting.SUBSTEPS
            while point.stiffness / needed > shooting.STIFFNESS:
                needed *= 2
            if needed > shooting.MAX_SUBSTEPS:
                raise NotSettled(f"the motor is too stiff for fixed steps ({needed} steps per grid interval)")
            if needed > substeps:
                substeps = needed
                point = self.state(point.full, substeps, False)
                if point is None:
                    raise NotSettled("the cycle cannot be integrated with finer steps")
                fresh, norms = False, []
                continue
            if self.settled(point):
                finer = self.state(point.full, 2 * substeps, False)
                moved = self.moved(point, finer)
                if moved <= STEP_RTOL:
                    self.drive.substeps[self.limit] = needed
                    return self.result(point, iteration, substeps)
                if 2 * substeps > shooting.MAX_SUBSTEPS:
                    raise NotSettled(f"the fixed steps do not resolve the cycle (it moves by {moved:.3g})")
                if finer is None:
                    raise BrokenInvariant("a point that moved by a finite amount has its state on the finer steps")
                # RK4's error falls 16-fold a doubling of the steps: as many doublings as should bring the move
                # within STEP_RTOL, at most to the most steps allowed (then checked against twice as many, as always)
                doublings = max(1, math.ceil(math.log(moved / STEP_RTOL) / math.log(16.0)))
                while doublings > 1 and 2 * substeps * 2 ** (doublings - 1) > shooting.MAX_SUBSTEPS:
                    doublings -= 1
                substeps *= 2**doublings
                if doublings == 1:
                    point = finer
                else:
                    jumped = self.state(point.full, substeps, False)
                    if jumped is None:
                        raise NotSettled("the cycle cannot be integrated with finer steps")
                    point = jumped
                fresh, norms = False, []
                continue
            if self.limit == "thermal" and point.mean_torque > self.rated * (1 + 1e-9):
                # T_rms >= its mean, which a flywheel hardly moves (the work balance sets it)
                raise Unreachable(
                    said(
                        "its mean torque {mean} exceeds its rated torque {rated}, and its RMS torque "
                        "stays above that for any flywheel",
                        mean=(point.mean_torque, "torque", f"{point.mean_torque:.4g} N·m"),
                        rated=(self.rated, "torque", f"{self.rated:.4g} N·m"),
                    ),
                    self.limit,
                )
            r = point.residuals()
            norm = float(np.linalg.norm(r))
            if not fresh and norms and norm > 0.25 * norms[-1]:  # the kept Jacobian no longer serves
                refreshed = self.state(point.full, substeps, True)
                if refreshed is None:
                    raise NotSettled("the cycle's sensitivities cannot be integrated")
                point, jac, fresh = refreshed, refreshed.jacobian(), True
            norms.append(norm)
            if len(norms) > shooting.STALLED and norm > 0.5 * norms[-1 - shooting.STALLED]:
                raise NotSettled(f"Newton stalls at |r| = {norm:.3g}")
            try:
                step = -np.linalg.solve(jac, r)
            except np.linalg.LinAlgError:
                raise NotSettled("singular Newton system") from None
            if not np.all(np.isfinite(step)):
                raise NotSettled("no Newton step")
            scale = min(1.0, 0.5 / max(float(np.max(np.abs(step))), 1e-300))
            for _ in range(LINE_SEARCH):
                trial_full = point.full.copy()
                trial_full[self.columns] += scale * step
                trial = self.state(trial_full, substeps, fresh and scale == 1.0 and norm > 1e-3)
                if trial is not None and (np.linalg.norm(trial.residuals()) < norm or scale == 1.0 and norm < 1e-6):
                    break
                scale *= 0.5
            else:
                if not fresh:  # try again from this point with its own Jacobian
                    refreshed = self.state(point.full, substeps, True)
                    if refreshed is not None:
                        point, jac, fresh = refreshed, refreshed.jacobian(), True
                        continue
                raise NotSettled(f"Newton's steps do not reduce the residual (|r| = {norm:.3g})")
            point = trial
            if point.jac_y is not None:  # far from the solution Newton's own steps: the Jacobian of the new point
                jac, fresh = point.jacobian(), True
            else:
                fresh = False
        raise NotSettled(f"no convergence in {MAX_ITERATIONS} Newton iterations")

    def result(self, p: _Point, iterations: int, substeps: int) -> Steady:
        return Steady(
            ratio=p.ratio,
            j_flywheel=p.j_flywheel,
            omega_mean=p.omega_mean,
            omega_max=p.omega_max,
            omega_min=p.omega_min,
            delta=p.delta,
            rms_torque=p.rms,
            mean_torque=p.mean_torque,
            phi=p.phi.reshape(-1),
            omega=p.omega.reshape(-1),
            iterations=iterations,
            substeps=substeps,
            x=(float(p.full[0]), float(p.full[1]), float(p.full[2])),
        )


class _Point:
    """The cycle at one point (v, u, ρ): speeds, δ, RMS torque, and their derivatives."""

    @classmethod
    def at(cls, newton: _Newton, full: FloatArray, substeps: int, derivatives: bool) -> _Point | None:
        point = cls(newton, np.asarray(full, float), substeps, derivatives)
        return point if point.ok else None

    def __init__(self, newton: _Newton, full: FloatArray, substeps: int, derivatives: bool) -> None:
        self.newton, self.full, self.ok = newton, full, False
        drive = newton.drive
        v, u, rho = full
        self.ratio = i = math.exp(rho)
        self.omega_ref = math.exp(v)
        self.j_flywheel = 0.0 if newton.limit == "none" else math.exp(u) - newton.j_s
        j_model = self.j_flywheel + newton.j_rot * i * i  # the rotor turns with the crank at i²
        if not drive.j_low + j_model > 0:
            return
        self.e_ref = 0.5 * (drive.j0 + j_model) * self.omega_ref**2
        model = drive.model.bind((i, *newton.theta_motor))
        w_s = newton.w_s
        y, jac = shooting.cycle(model, substeps, j_model, self.e_ref, w_s, 0.0, derivatives)
        if not np.all(np.isfinite(y)):
            return
        phi, q, dq, _ = model.speed_profile(y, j_model, self.e_ref, w_s)
        if q is None or dq is None or not np.all(np.isfinite(dq)):
            return
        hi, lo = hermite_extremes(phi, q, dq)
        if not lo[1] > 0:
            return
        self.phi, self.q = phi, q
        self.omega = np.sqrt(2 * q)
        self.omega_max, self.omega_min = math.sqrt(2 * hi[1]), math.sqrt(2 * lo[1])
        self.omega_mean = 0.5 * (self.omega_max + self.omega_min)
        self.delta = (self.omega_max - self.omega_min) / self.omega_mean
        if not self.delta > 0:
            return
        self.y_end = float(y[-1, -1])
        self.swing = float(np.ptp(y))
        w_motor = i * self.omega
        self.motor_torque, self.motor_slope = evaluate(KLOSS_SLOPE, _KLOSS_MAPS, w_motor, *newton.theta_motor)
        self.rms, self.mean_torque = rms_of(phi, self.omega, self.motor_torque)
        # |∂(dy/dτ)/∂y| Δτ = |∂M/∂ω| Δφ/(J ω) per grid interval
        slope = model.torque_slope(phi[:, :-1], self.omega[:, :-1])
        j = drive.j_grid + j_model
        self.stiffness = float(np.max(np.abs(slope) * np.diff(phi, axis=1) / (j[:, :-1] * self.omega[:, :-1])))
        self.hi, self.lo, self.jac_y, self.j_model = hi, lo, jac, j_model
        self.ok = True
        if derivatives and (jac is None or not np.all(np.isfinite(jac))):
            self.ok = False

    def residuals(self) -> FloatArray:
        n = self.newton
        values = {
            "periodic": self.y_end,
            "delta": math.log(self.delta) - n.log_delta,
            "thermal": self.rms / n.rated - 1,
            "mean": self.omega_mean / n.drive.omega_m - 1,
        }
        return np.array([values[row] for row in n.rows])

    def jacobian(self) -> FloatArray:
        n, drive = self.newton, self.newton.drive
        if self.jac_y is None:
            raise BrokenInvariant("a point for Newton carries its sensitivities")
        v, u, rho = self.full
        i = self.ratio
        e_u = 0.0 if n.limit == "none" else math.exp(u)
        # d(J_model, E_ref, i)/d(v, u, ρ)
        d_j = np.array([0.0, e_u, 2 * n.j_rot * i * i])
        d_e = np.array([2 * self.e_ref, 0.5 * self.omega_ref**2 * d_j[1], 0.5 * self.omega_ref**2 * d_j[2]])
        d_i = np.array([0.0, 0.0, i])
        sens = self.jac_y  # ∂y/∂(J, E_ref, c, i) on the grid
        dy = sens[..., 0, None] * d_j + sens[..., 1, None] * d_e + sens[..., 3, None] * d_i
        j = (drive.j_grid + self.j_model)[..., None]
        dq = (d_e + n.w_s * dy - self.q[..., None] * d_j) / j  # ∂(ω²/2)/∂(v, u, ρ) on the grid
        d_omega_grid = dq / self.omega[..., None]

        def d_extreme(where: tuple[float, float]) -> FloatArray:
            k = np.unravel_index(np.argmin(np.abs(self.phi - where[0])), self.q.shape)
            return dq[k] / math.sqrt(2 * where[1])

        dw_max, dw_min = d_extreme(self.hi), d_extreme(self.lo)
        s = self.omega_max + self.omega_min
        d_log_delta = (4 * self.omega_min * dw_max - 4 * self.omega_max * dw_min) / s**2 / self.delta
        d_mean = 0.5 * (dw_max + dw_min) / drive.omega_m
        # the RMS torque: T² = S/T with S = ∫ M²/ω dφ, T = ∫ 1/ω dφ (trapezoid), M = M(i ω)
        h = np.diff(self.phi.reshape(-1))
        w, m = self.omega.reshape(-1), self.motor_torque.reshape(-1)
        dw = d_omega_grid.reshape(-1, 3)
        dm = self.motor_slope.reshape(-1)[:, None] * (i * dw + w[:, None] * d_i)
        g_t = -dw / w[:, None] ** 2  # ∂(1/ω)
        g_s = 2 * m[:, None] * dm / w[:, None] - (m**2 / w**2)[:, None] * dw  # ∂(M²/ω)
        period = float(np.sum(h * 0.5 * (1 / w[1:] + 1 / w[:-1])))
        squares = float(np.sum(h * 0.5 * (m[1:] ** 2 / w[1:] + m[:-1] ** 2 / w[:-1])))
        d_period = np.sum(h[:, None] * 0.5 * (g_t[1:] + g_t[:-1]), axis=0)
        d_squares = np.sum(h[:, None] * 0.5 * (g_s[1:] + g_s[:-1]), axis=0)
        d_rms = 0.5 / self.rms * (d_squares / period - squares * d_period / period**2) / n.rated
        rows = {
            "periodic": dy[-1, -1],
            "delta": d_log_delta,
            "thermal": d_rms,
            "mean": d_mean,
        }
        return np.array([rows[row] for row in n.rows])[:, n.columns]
