"""Reduction of a drive train to one shaft: speed ratios and efficiencies.

Domain page, sections 3 and 11. A speed ratio ``j`` is ω_motor / ω_shaft
(the electric-drive convention of section 3); an efficiency η ≤ 1 belongs to
a transmission stage.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass


@dataclass(frozen=True)
class Shaft:
    """A shaft a flywheel may sit on.

    Attributes
    ----------
    name : str
    speed_ratio : float
        ω_shaft / ω_reference [-].
    efficiency : float
        Efficiency of the transmission from the motor to this shaft [-].
    diameter : float or None
        The shaft seat [m] (sets a wheel's bore, hub and key), when given.
    inertia : float
        Inertia already turning with this shaft (a motor rotor, pulleys,
        gears), about its axis [kg*m^2]; it counts towards the machine's J_c
        as inertia * speed_ratio² at the reference shaft.
    """

    name: str
    speed_ratio: float
    efficiency: float = 1.0
    diameter: float | None = None
    inertia: float = 0.0


def series_efficiency(stages: Iterable[float]) -> float:
    """Efficiency of transmission stages in series: η = η_1 η_2 ⋯ η_k.

    Parameters
    ----------
    stages : iterable of float
        Efficiencies of the stages [-], each in (0, 1].

    Returns
    -------
    float
    """
    stages = list(stages)
    for eta in stages:
        if not 0 < eta <= 1:
            raise ValueError(f"a stage efficiency must lie in (0, 1], got {eta!r}")
    return math.prod(stages)


def motor_power(branches: Iterable[tuple[float, float | Iterable[float]]]) -> float:
    """Motor power for machines driven in parallel branches: Σ P_k / η_path,k.

    Parameters
    ----------
    branches : iterable of (power, efficiencies)
        Power each branch must deliver at its end [W] and the efficiencies of
        the stages on its path from the motor (a float or a list in series).

    Returns
    -------
    float
        Motor power [W].

    Notes
    -----
    A single branch is the series case, P / (η_1 ⋯ η_k).
    """
    total = 0.0
    for power, path in branches:
        path = [path] if isinstance(path, (int, float)) else path
        total += power / series_efficiency(path)
    return total


def reduced_inertia(
    j_motor: float = 0.0,
    shafts: Iterable[tuple[float, float]] = (),
    masses: Iterable[tuple[float, float]] = (),
    omega_motor: float | None = None,
    efficiencies: Iterable[float] | None = None,
) -> float:
    """Inertia of a drive reduced to the motor shaft.

    J = J_M + Σ_k J_k / j_k² + Σ_i m_i v_i² / ω_M²  (docs/flywheel-design.md, section 3).

    Parameters
    ----------
    j_motor : float
        Inertia of the motor rotor and what turns with it [kg*m^2].
    shafts : iterable of (j_k, ratio_k)
        Inertia on shaft k [kg*m^2] and its speed ratio j_k = ω_M/ω_k [-].
    masses : iterable of (m_i, v_i)
        Translating masses [kg] and their speeds [m/s] at motor speed ``omega_motor``.
    omega_motor : float, optional
        Motor speed [rad/s]; needed only when ``masses`` is given.
    efficiencies : iterable of float, optional
        Efficiency of the path to each shaft. When given, each reduced shaft
        inertia is divided by it (the convention some texts use for the
        acceleration torque); by default no efficiency is applied.

    Returns
    -------
    float
        Reduced inertia [kg*m^2].
    """
    shafts = list(shafts)
    etas = [1.0] * len(shafts) if efficiencies is None else list(efficiencies)
    if len(etas) != len(shafts):
        raise ValueError("give one efficiency per shaft")
    total = j_motor + sum(j / ratio**2 / eta for (j, ratio), eta in zip(shafts, etas))
    masses = list(masses)
    if masses:
        if not omega_motor:
            raise ValueError("omega_motor is needed to reduce translating masses")
        total += sum(m * v**2 for m, v in masses) / omega_motor**2
    return total


def reduced_load_torque(torque: float, ratio: float, efficiency: float = 1.0) -> float:
    """Static load torque reduced to the motor shaft: T_L' = T_L / (j η) [N*m]."""
    return torque / (ratio * efficiency)


def inertia_on_shaft(j_reference: float, speed_ratio: float) -> float:
    """Inertia a flywheel needs on a shaft to replace J at the reference shaft.

    Equal kinetic energy, ½ J' ω'² = ½ J ω², gives J' = J (ω/ω')² (domain
    page, section 8).

    Parameters
    ----------
    j_reference : float
        Inertia at the reference shaft [kg*m^2].
    speed_ratio : float
        ω'/ω, shaft speed over reference speed [-].

    Returns
    -------
    float
        J' [kg*m^2].
    """
    return j_reference / (speed_ratio * speed_ratio)


def inertia_at_reference(j_shaft: float, speed_ratio: float) -> float:
    """Inertia of a flywheel on a shaft, moved to the reference shaft: J = J' (ω'/ω)² [kg*m^2]."""
    return j_shaft * speed_ratio * speed_ratio
