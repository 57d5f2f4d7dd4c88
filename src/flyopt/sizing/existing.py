"""A flywheel that exists: the speed fluctuation it leaves, and what else a course asks of it.

Given the wheel (a scene's [flywheel]), find δ, ω_max and ω_min, the angles
where they occur, the largest angular acceleration and deceleration over the
cycle, A_max and the energy swing (docs/flywheel-design.md, "A flywheel that
exists"). For a constant inertia and torques of the angle alone the energy
method is exact and inverts in closed form, δ = A_max / (ω_m² (J_c + J_F)),
and the acceleration is M(φ)/J at every angle; otherwise the periodic
simulation with the wheel gives them (:func:`flyopt.sizing.periodic.verify`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from flyopt.machine.flywheel import ExistingFlywheel
    from flyopt.machine.reduce import Machine
    from flyopt.sizing.periodic import PeriodicSolution

#: Golden-section steps that refine an extreme of a smooth net torque inside its bracket (to ~1e-13 of the bracket).
REFINE_STEPS = 64


@dataclass(frozen=True)
class FlywheelCheck:
    """What a flywheel that exists does to the machine's speed (all SI, angles in rad).

    ``delta_allowed``, ``j_required``, ``suffices`` and ``margin`` are None
    unless the scene gives machine.delta; ``margin`` is J_F given / J_F
    required − 1 (None when no flywheel is required). The accelerations are
    None for a scene given as net areas (no torques over the angle).
    """

    flywheel: ExistingFlywheel
    j_machine: float  # J_c at the reference shaft, the wheel left out (its cycle mean where it varies)
    achieved_delta: float
    omega_mean: float
    omega_max: float
    omega_min: float
    angle_omega_max: float | None
    angle_omega_min: float | None
    a_max: float
    energy_swing: float
    acceleration_max: float | None
    angle_acceleration_max: float | None
    acceleration_min: float | None
    angle_acceleration_min: float | None
    method: str
    tolerance: float
    delta_allowed: float | None = None
    j_required: float | None = None
    suffices: bool | None = None
    margin: float | None = None
    accelerations_at: tuple[tuple[float, float], ...] = ()  # (angle [rad], dω/dt [rad/s²]) at flywheel.angles

    def to_dict(self) -> dict[str, Any]:
        """The "flywheel" object of ``flyopt solve --json`` (SI)."""
        out = {k: v for k, v in self.__dict__.items() if k != "flywheel"}
        out["given"] = self.flywheel.to_dict()
        out["accelerations_at"] = [{"angle": a, "angular_acceleration": e} for a, e in self.accelerations_at]
        return out


def energy_delta(a_max: float, omega_mean: float, j_total: float) -> float:
    """δ = A_max / (ω_m² J), the energy method inverted (docs/flywheel-design.md, section 5) [-]."""
    return a_max / (omega_mean * omega_mean * j_total)


def net_torque_extremes(machine: Machine) -> tuple[float, float, float, float]:
    """(largest M_d − M_r, its angle, smallest, its angle) over the cycle at the reference shaft [N*m, rad].

    On :meth:`flyopt.machine.reduce.Machine.net_torque_grid` (every knot, both sides of a step, so
    a step's value is reached exactly, as in a table's corners); an extreme
    strictly between grid points of a smooth stretch is refined by golden
    section within its two neighbours. Speed-dependent torques are taken at
    the mean speed (the caller uses this for torques of the angle only).
    """
    balanced = machine.angle_only()
    knots = np.asarray(balanced.knots, dtype=float)
    phi, left, right = machine.net_torque_grid()

    def net(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        d, r = balanced.driving.limits(x), balanced.resisting.limits(x)
        return d[0] - r[0], d[1] - r[1]

    found: list[float] = []
    for sign in (1.0, -1.0):
        values = np.maximum(sign * left, sign * right)
        k = int(np.argmax(values))
        best, angle = float(values[k]), float(phi[k])
        if 0 < k < len(phi) - 1 and not np.any((knots > phi[k - 1]) & (knots < phi[k + 1])):
            x, value = _golden(lambda x: sign * float(net(np.array([x]))[0][0]), phi[k - 1], phi[k + 1])
            if value > best:
                best, angle = value, x
        found += [sign * best, angle]
    return found[0], found[1], found[2], found[3]


def _golden(f: Any, low: float, high: float) -> tuple[float, float]:
    """(x, f(x)) of the largest value of a unimodal f on [low, high], by golden-section search."""
    ratio = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = float(low), float(high)
    c, d = b - ratio * (b - a), a + ratio * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(REFINE_STEPS):
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - ratio * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + ratio * (b - a)
            fd = f(d)
    return (c, fc) if fc >= fd else (d, fd)


def net_torque_at(machine: Machine, angles: Any) -> np.ndarray:
    """M_d − M_r at the reference shaft at ``angles`` [N*m] (the value just after a step, where a torque steps),
    speed-dependent torques at the mean speed as in :func:`net_torque_extremes`."""
    balanced = machine.angle_only()
    x = np.asarray(angles, dtype=float)
    return np.asarray(balanced.driving.limits(x)[1] - balanced.resisting.limits(x)[1], dtype=float)


def solution_acceleration_at(solution: PeriodicSolution, angles: Any) -> np.ndarray:
    """dω/dt = d(ω²/2)/dφ along a simulated cycle at ``angles`` [rad/s²], interpolated on the differences of
    :func:`solution_accelerations` (within each piece of the grid, none across a step)."""
    phi, omega = np.asarray(solution.phi, dtype=float), np.asarray(solution.omega, dtype=float)
    cuts = np.flatnonzero(np.diff(phi) <= 0.0) + 1
    pieces = [
        (p, np.gradient(0.5 * w**2, p, edge_order=2))
        for p, w in zip(np.split(phi, cuts), np.split(omega, cuts))
        if len(p) >= 3
    ]
    out = []
    for x in np.atleast_1d(np.asarray(angles, dtype=float)):
        # the piece that holds x (the later one at a shared knot: the value just after a step)
        piece = next((p for p in reversed(pieces) if p[0][0] <= x <= p[0][-1]), pieces[-1])
        out.append(float(np.interp(x, piece[0], piece[1])))
    return np.asarray(out)


def solution_accelerations(solution: PeriodicSolution) -> tuple[float, float, float, float]:
    """(largest dω/dt, its angle, smallest, its angle) along a simulated cycle [rad/s², rad].

    dω/dt = ω dω/dφ = d(ω²/2)/dφ, by second-order differences within each
    piece of the simulation grid (a knot is repeated at a piece's ends, where
    a torque may step, and no difference is taken across it).
    """
    phi, omega = np.asarray(solution.phi, dtype=float), np.asarray(solution.omega, dtype=float)
    cuts = np.flatnonzero(np.diff(phi) <= 0.0) + 1
    angles, values = [], []
    for piece_phi, piece_omega in zip(np.split(phi, cuts), np.split(omega, cuts)):
        if len(piece_phi) < 3:
            continue
        values.append(np.gradient(0.5 * piece_omega**2, piece_phi, edge_order=2))
        angles.append(piece_phi)
    a, v = np.concatenate(angles), np.concatenate(values)
    high, low = int(np.argmax(v)), int(np.argmin(v))
    return float(v[high]), float(a[high]), float(v[low]), float(a[low])


def kinetic_energy_swing(solution: PeriodicSolution, inertia: Any) -> float:
    """max − min over the cycle of ½ J(φ) ω² (the wheel's inertia included in ``inertia``) [J]."""
    phi, omega = np.asarray(solution.phi, dtype=float), np.asarray(solution.omega, dtype=float)
    j = inertia(phi) if callable(inertia) else np.full(phi.shape, float(inertia))
    energy = 0.5 * j * omega**2
    return float(energy.max() - energy.min())
