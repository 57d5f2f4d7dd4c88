"""The torsional check of the drive train against the cycle's own torque (issue 30, item 4).

The model itself - reflected inertias and shafts, the modes, the orders of a
torque, the forced response and the critical speeds with their margins - is
:mod:`flyopt.machine.torsion` (docs/flywheel-design.md, section 22), the one
place each of those is decided. This module joins it to the rest of flyopt:

- the excitation is the net torque M_d - M_r of the cycle, from the same
  torque curves (:mod:`flyopt.cycle.torque`) the energy method integrates,
  sampled by :func:`flyopt.cycle.difference.sample` at N equal steps over the
  cycle angle Phi (4 pi for a four-stroke engine: half orders), the mean of the
  left and right limits at a step (the value a Fourier series takes there);
  or any callable T(phi);
- the running range is the cycle's n_min..n_max, from omega_m (1 -/+ delta/2)
  (:func:`flyopt.cycle.indicator.speed_extremes`);
- the orders present (|c_q| at least a share of the largest) against every
  mode give the critical speeds n_c = 60 f_m / q and their margins;
- the Campbell diagram's data: the modes' frequencies (a torsional train has no
  gyroscopic term: they do not depend on speed), the order lines f = q n / 60
  and where they cross the modes;
- the forced response over a range of speeds: each shaft's twisting torque per
  order and its bound sum_q |T_e,q|.

A described shaft's check (:mod:`flyopt.design.shaft.check`) calls it with the wheel
and the inertia already on the shaft (docs/flywheel-design.md, sections 25 and 26).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from flyopt.cycle.balance import solve_unknown_constant
from flyopt.cycle.difference import sample
from flyopt.cycle.indicator import speed_extremes
from flyopt.machine.torsion import (
    CriticalSpeed,
    Modes,
    TorqueOrders,
    TorsionalModel,
    critical_speeds,
    forced_response,
    modes,
    torque_orders,
)
from flyopt.units import rad_s_to_rpm

__all__ = [
    "SAMPLES",
    "Campbell",
    "SpeedResponse",
    "TorsionalCheck",
    "campbell",
    "function_orders",
    "net_torque_orders",
    "present_orders",
    "response_over_speed",
    "running_range_rpm",
    "torsional_check",
]

SAMPLES = 4096
"""Samples of a torque over one cycle: orders up to (SAMPLES - 1) // 2 per cycle are resolved."""


def _cycle_grid(cycle_angle: float, samples: int) -> np.ndarray:
    if isinstance(cycle_angle, bool) or not isinstance(cycle_angle, (int, float, np.floating, np.integer)):
        raise ValueError(f"cycle_angle [rad] must be a number, got {cycle_angle!r}")
    if not (math.isfinite(cycle_angle) and cycle_angle > 0.0):
        raise ValueError(f"cycle_angle [rad] = {float(cycle_angle)!r} must be a finite number > 0")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 4:
        raise ValueError(f"samples must be an integer >= 4, got {samples!r}")
    return np.arange(int(samples)) * (float(cycle_angle) / int(samples))


def function_orders(
    torque: Callable[[np.ndarray], Any],
    cycle_angle: float,
    *,
    samples: int = SAMPLES,
    max_order: float | None = None,
) -> TorqueOrders:
    """The orders of a periodic torque given as a function of the shaft angle.

    Parameters
    ----------
    torque : callable
        T(phi) [N*m] for an array of angles phi [rad] (vectorised), periodic over ``cycle_angle``.
    cycle_angle : float
        Phi, the angle of one cycle [rad] (2 pi per revolution; 4 pi for a four-stroke engine).
    samples : int
        N equal steps over the cycle (the series is exact for orders below N / 2 per cycle).
    max_order : float, optional
        Keep the orders up to this one (per revolution).

    Returns
    -------
    TorqueOrders
        T(phi) = mean + sum_q Re(c_q e^{i q phi}), q = k 2 pi / Phi.
    """
    phi = _cycle_grid(cycle_angle, samples)
    values = np.broadcast_to(np.asarray(torque(phi), dtype=float), phi.shape)
    return torque_orders(phi, values, cycle_revolutions=float(cycle_angle) / (2.0 * math.pi), max_order=max_order)


def net_torque_orders(
    driving: Any,
    resisting: Any,
    cycle_angle: float,
    *,
    samples: int = SAMPLES,
    max_order: float | None = None,
) -> TorqueOrders:
    """The orders of the cycle's net torque M_d - M_r at the reference shaft.

    Parameters
    ----------
    driving, resisting : TorqueCurve
        The reduced driving and resisting torques of the cycle (:mod:`flyopt.cycle.torque`,
        the machine's reduced curves), as the energy method takes them; an unknown constant is
        solved from the work balance first (:func:`flyopt.cycle.balance.solve_unknown_constant`).
    cycle_angle : float
        Phi [rad]: 2 pi per revolution of the reference shaft, 4 pi for a four-stroke cycle.
    samples, max_order
        As :func:`function_orders`.

    Notes
    -----
    At a step of a table the mean of its two limits is taken, so the sampled series is the
    trapezoidal rule of the Fourier integral; a step off the grid adds an error of order
    |jump| / N to each c_q.
    """
    driving, resisting = solve_unknown_constant(driving, resisting, cycle_angle)

    def net(phi: np.ndarray) -> np.ndarray:
        d_left, d_right = sample(driving, phi)
        r_left, r_right = sample(resisting, phi)
        return 0.5 * (np.asarray(d_left) + np.asarray(d_right)) - 0.5 * (np.asarray(r_left) + np.asarray(r_right))

    return function_orders(net, cycle_angle, samples=samples, max_order=max_order)


def running_range_rpm(omega_mean: float, delta: float, *, ratio: float = 1.0) -> tuple[float, float]:
    """The cycle's speed range (n_min, n_max) [rpm] of a shaft turning ``ratio`` times the reference.

    omega_max, omega_min = omega_m (1 +/- delta/2) (:func:`flyopt.cycle.indicator.speed_extremes`).

    Parameters
    ----------
    omega_mean : float
        omega_m of the reference shaft [rad/s], > 0.
    delta : float
        The coefficient of fluctuation delta [-], 0 <= delta < 2.
    ratio : float
        omega_shaft / omega_reference, > 0.
    """
    for name, value in (("omega_mean [rad/s]", omega_mean), ("ratio", ratio)):
        if not (isinstance(value, (int, float, np.floating)) and math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} = {value!r} must be a finite number > 0")
    if not (isinstance(delta, (int, float, np.floating)) and 0.0 <= delta < 2.0):
        raise ValueError(f"delta = {delta!r} must be a number in [0, 2)")
    high, low = speed_extremes(float(omega_mean) * float(ratio), float(delta))
    return rad_s_to_rpm(low), rad_s_to_rpm(high)


def present_orders(excitation: TorqueOrders, significant: float = 0.01) -> np.ndarray:
    """The orders whose amplitude |c_q| is at least ``significant`` times the largest one."""
    if not (isinstance(significant, (int, float)) and 0.0 <= significant <= 1.0):
        raise ValueError(f"significant = {significant!r} must be a share in [0, 1]")
    size = np.abs(excitation.amplitudes)
    if size.size == 0 or size.max() == 0.0:
        return np.empty(0)
    return excitation.orders[size >= significant * size.max()]


@dataclass(frozen=True)
class TorsionalCheck:
    """The modes of a train and the critical speeds of the orders present against the running range.

    Attributes
    ----------
    modes : Modes
        The undamped modes (:func:`flyopt.machine.torsion.modes`).
    orders : ndarray
        The orders present in the excitation (:func:`present_orders`).
    speed_range_rpm : tuple of float
        (n_min, n_max) of the shaft the orders belong to [rpm].
    critical : list of CriticalSpeed
        Every (mode, order) pair, by mode then order.
    """

    modes: Modes
    orders: np.ndarray
    speed_range_rpm: tuple[float, float]
    critical: list[CriticalSpeed]

    @property
    def in_range(self) -> list[CriticalSpeed]:
        """The critical speeds inside the running range (a resonance run through in service)."""
        return [c for c in self.critical if c.in_range]

    @property
    def nearest(self) -> CriticalSpeed | None:
        """The critical speed of smallest margin (None without elastic modes or orders)."""
        return min(self.critical, key=lambda c: c.margin, default=None)


def torsional_check(
    model: TorsionalModel,
    excitation: TorqueOrders,
    speed_range_rpm: tuple[float, float],
    *,
    significant: float = 0.01,
    max_mode: int | None = None,
) -> TorsionalCheck:
    """Modes, and the critical speeds of the orders present in ``excitation`` with their margins.

    Parameters
    ----------
    model : TorsionalModel
        The train reflected to the shaft whose orders ``excitation`` holds.
    excitation : TorqueOrders
        :func:`net_torque_orders`, :func:`function_orders` or :func:`flyopt.machine.torsion.torque_orders`.
    speed_range_rpm : tuple of float
        (n_min, n_max) [rpm]: :func:`running_range_rpm` or given.
    significant : float
        An order is present when |c_q| >= significant * max |c_q|.
    max_mode : int, optional
        Check only the first ``max_mode`` elastic modes.
    """
    found = modes(model)
    frequencies = found.frequencies_hz if max_mode is None else found.frequencies_hz[: int(max_mode)]
    orders = present_orders(excitation, significant)
    critical = critical_speeds(frequencies, orders, speed_range_rpm)
    return TorsionalCheck(found, orders, (float(speed_range_rpm[0]), float(speed_range_rpm[1])), critical)


@dataclass(frozen=True)
class Campbell:
    """The data of a Campbell diagram: frequency against shaft speed.

    Attributes
    ----------
    speeds_rpm : ndarray
        The speed axis n [rpm].
    frequencies_hz : ndarray
        The elastic modes f_m [Hz]: horizontal lines (no gyroscopic term in torsion).
    orders : ndarray
        q of each order line.
    order_lines_hz : ndarray
        f = q n / 60 [Hz], [order, speed].
    crossings : list of CriticalSpeed
        Where an order line meets a mode inside the speed axis, with its margin against the running range.
    """

    speeds_rpm: np.ndarray
    frequencies_hz: np.ndarray
    orders: np.ndarray
    order_lines_hz: np.ndarray
    crossings: list[CriticalSpeed]


def campbell(
    model: TorsionalModel,
    orders: Sequence[float] | np.ndarray,
    speeds_rpm: Sequence[float] | np.ndarray,
    speed_range_rpm: tuple[float, float],
) -> Campbell:
    """The Campbell diagram's data of ``model`` for ``orders`` over ``speeds_rpm`` [rpm]."""
    n = np.asarray(speeds_rpm, dtype=float)
    if n.ndim != 1 or n.size < 2 or not np.all(np.isfinite(n)) or n.min() < 0.0 or not np.all(np.diff(n) > 0.0):
        raise ValueError("speeds_rpm must be at least two increasing finite speeds >= 0 [rpm]")
    q = np.asarray(orders, dtype=float)
    frequencies = modes(model).frequencies_hz
    every = critical_speeds(frequencies, q, speed_range_rpm)
    crossings = [c for c in every if n[0] <= c.speed_rpm <= n[-1]]
    return Campbell(n, frequencies, q, np.multiply.outer(q, n) / 60.0, crossings)


@dataclass(frozen=True)
class SpeedResponse:
    """The forced response at each of a set of speeds.

    Attributes
    ----------
    speeds_rpm : ndarray
        n of the shaft the torque acts on [rpm].
    orders : ndarray
        q of each harmonic.
    shaft_torques : ndarray
        |T_e,q| of each spring on its own shaft, [spring, order, speed] [N*m].
    angles : ndarray
        |x_i,q| of each node in reference coordinates, [node, order, speed] [rad].
    """

    speeds_rpm: np.ndarray
    orders: np.ndarray
    shaft_torques: np.ndarray
    angles: np.ndarray

    @property
    def shaft_torque_bound(self) -> np.ndarray:
        """sum_q |T_e,q|, [spring, speed] [N*m]: the alternating torque whatever the phases, at most."""
        return self.shaft_torques.sum(axis=1)


def response_over_speed(
    model: TorsionalModel,
    excitation: TorqueOrders,
    node: int,
    speeds_rpm: Sequence[float] | np.ndarray,
    *,
    ratio: float = 1.0,
    damping: np.ndarray | None = None,
) -> SpeedResponse:
    """The amplitudes of twist and shaft torque per order at each speed (:func:`flyopt.machine.torsion.forced_response`).

    ``node``, ``ratio`` and ``damping`` as there: the torque acts at ``node`` on a shaft turning ``ratio``
    times the reference.
    """
    n = np.atleast_1d(np.asarray(speeds_rpm, dtype=float))
    if n.ndim != 1 or n.size == 0:
        raise ValueError("speeds_rpm must be one or more speeds [rpm]")
    results = [forced_response(model, excitation, node, float(speed), ratio=ratio, damping=damping) for speed in n]
    torques = np.stack([np.abs(r.shaft_torques) for r in results], axis=-1)
    angles = np.stack([np.abs(r.angles) for r in results], axis=-1)
    return SpeedResponse(n, excitation.orders.copy(), torques, angles)
