"""The largest torque the flywheel exchanges with its own shaft over a cycle.

A cycle quantity: the analysis computes it from the torque curves and the
inertia, and the design sizes the hub's key and the arms' bending from it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from flyopt.validate import finite_array, positive


def flywheel_peak_torque(
    j_flywheel_ref: float, j_total_ref: ArrayLike, torque_difference_ref: ArrayLike, speed_ratio: float
) -> float:
    """The largest torque the flywheel's hub transmits to its own shaft over a cycle.

    Parameters
    ----------
    j_flywheel_ref : float
        The flywheel's inertia moved to the reference shaft, J_F [kg*m^2].
    j_total_ref : float or array_like
        Total inertia at the reference shaft, flywheel included, J(phi)
        [kg*m^2]: a number for a constant-inertia machine, or its values at
        the angles of ``torque_difference_ref`` (same shape, or broadcastable).
    torque_difference_ref : float or array_like
        M_d - M_r at the reference shaft over the cycle [N*m].
    speed_ratio : float
        r = omega_shaft / omega_ref of the flywheel's shaft [-].

    Returns
    -------
    float
        max over the cycle of (J_F / J(phi)) |M_d - M_r| / r [N*m].

    Raises
    ------
    ValueError
        If J_F, J or r is not positive and finite, J < J_F anywhere, a torque
        difference is not finite, or the arrays do not broadcast.

    Notes
    -----
    The net torque M_d - M_r accelerates all the inertia at the reference
    shaft, J dω/dt = M_d - M_r; the flywheel takes its share of it,
    J_F dω/dt = (J_F / J)(M_d - M_r). On its own shaft the flywheel has
    J_F / r² and turns r times as fast, so its torque is (J_F / J)(M_d - M_r) / r:
    power is conserved and torque divides by the speed ratio. This is the
    torque its hub, key and shaft seat carry.

    For a variable inertia J(phi) the equation of motion is J dω/dt =
    (M_d - M_r) - ½ (dJ/dphi) ω²; the share taken here at each angle neglects
    the ½ (dJ/dphi) ω² term, exact only where dJ/dphi = 0.
    """
    j_flywheel = positive(j_flywheel_ref, "j_flywheel_ref [kg*m^2]")
    speed_ratio = positive(speed_ratio, "speed_ratio [-]")
    j_total = finite_array(j_total_ref, "j_total_ref [kg*m^2]")
    if np.any(j_total <= 0.0):
        raise ValueError(f"j_total_ref must be positive [kg*m^2]; its smallest value is {float(np.min(j_total))!r}")
    if np.any(j_total < j_flywheel):
        raise ValueError(
            f"j_total_ref must include the flywheel, j_total_ref >= j_flywheel_ref = "
            f"{j_flywheel!r} kg*m^2; its smallest value is {float(np.min(j_total))!r}"
        )
    difference = finite_array(torque_difference_ref, "torque_difference_ref [N*m]")
    try:
        j_total, difference = np.broadcast_arrays(j_total, difference)
    except ValueError as err:
        raise ValueError(
            f"j_total_ref (shape {j_total.shape}) and torque_difference_ref "
            f"(shape {difference.shape}) must have the same shape, or one be a "
            f"number"
        ) from err
    return float(np.max(j_flywheel / j_total * np.abs(difference))) / speed_ratio


def flywheel_torque_curve(
    j_flywheel_ref: float, j_total_ref: ArrayLike, torque_difference_ref: ArrayLike, speed_ratio: float
) -> np.ndarray:
    """The torque the flywheel exchanges with its own shaft at each angle, with its sign [N*m].

    (J_F / J(phi)) (M_d - M_r) / r, the curve whose largest magnitude is
    :func:`flywheel_peak_torque` (the same arguments, the same Notes); its
    extremes give the shaft's midrange and alternating torque (issue 30).
    """
    flywheel_peak_torque(j_flywheel_ref, j_total_ref, torque_difference_ref, speed_ratio)  # validates
    j_total, difference = np.broadcast_arrays(
        np.asarray(j_total_ref, dtype=float), np.asarray(torque_difference_ref, dtype=float)
    )
    curve: np.ndarray = float(j_flywheel_ref) / j_total * difference / float(speed_ratio)
    return curve
