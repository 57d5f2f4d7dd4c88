"""Reduction of a drive train to one shaft: speed ratios and efficiencies.

Domain page, sections 3 and 11. A speed ratio ``j`` is ω_motor / ω_shaft
(the electric-drive convention of section 3); an efficiency η ≤ 1 belongs to
a transmission stage.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from flyopt.machine.shaft_layout import ShaftLayout


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
    layout : ShaftLayout or None
        The shaft described as a part (steps, bearings, wheel seat, material, loads), when given.
    """

    name: str
    speed_ratio: float
    efficiency: float = 1.0
    diameter: float | None = None
    inertia: float = 0.0
    layout: ShaftLayout | None = None


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
    return reflected(j_shaft, speed_ratio)


def reflected(value: float, speed_ratio: float) -> float:
    """An inertia, torsional stiffness or damping on a shaft turning ``speed_ratio`` times the reference shaft,
    reflected to the reference shaft: value (ω'/ω)² (the same kinetic or strain energy, or power dissipated,
    at the reference shaft's angle). The one ratio-squared transfer: :func:`inertia_at_reference` and the
    torsional chain's matrices (:mod:`flyopt.machine.torsion`) use it."""
    return value * speed_ratio * speed_ratio


@dataclass(frozen=True)
class PowerBranch:
    """A branch of a power chain ([power_chain], docs/flywheel-design.md, section 21).

    Its stages in series, then either the branches it splits into (parallel, each
    with its own stages) or, at a leaf, the machine it drives, delivering ``power``.
    A tree of them is a series chain (one leaf), a parallel set-up (a trunk splitting
    into leaves) or a mixed one (branches splitting again).

    Attributes
    ----------
    name : str
    stages : tuple of float
        Efficiencies of its stages in series from its start [-], each in (0, 1]; a
        leaf's last is, as the books write it, its machine's own efficiency.
    branches : tuple of PowerBranch
        The branches it splits into at its end; empty at a leaf.
    power : float or None
        At a leaf, the power its machine delivers [W]; None at a split.
    """

    name: str
    stages: tuple[float, ...] = ()
    branches: tuple[PowerBranch, ...] = ()
    power: float | None = None

    def leaves(self) -> tuple[tuple[float, tuple[float, ...]], ...]:
        """Each leaf below (or at) this branch: its power [W] and the stages from this branch's start to it."""
        if self.power is not None:
            return ((self.power, self.stages),)
        return tuple((p, self.stages + path) for child in self.branches for p, path in child.leaves())


@dataclass(frozen=True)
class BranchFlow:
    """The powers of one branch of a power chain, driven from the motor (SI, W).

    Attributes
    ----------
    branch : PowerBranch
    stage_powers : tuple of float
        Power entering each of its stages [W] (the first: what the branch draws at its start).
    power : float
        Power at its end [W]: a leaf's delivered power; at a split, what its branches draw.
    efficiency : float
        Its own stages in series [-].
    path_efficiency : float
        From the motor to its end [-].
    motor_power : float
        What it draws at the motor [W]: Σ P_k / η_path,k over the leaves below it (the books' P_d).
    delivered : float
        Σ P_k delivered by the leaves below it [W].
    branches : tuple of BranchFlow
    """

    branch: PowerBranch
    stage_powers: tuple[float, ...]
    power: float
    efficiency: float
    path_efficiency: float
    motor_power: float
    delivered: float
    branches: tuple[BranchFlow, ...] = ()

    @property
    def losses(self) -> float:
        """What the power it delivers loses on its way from the motor, the shared stages' share included [W]."""
        return self.motor_power - self.delivered

    def to_dict(self) -> dict[str, Any]:
        """The branch in ``flyopt solve --json`` of a [power_chain] (SI)."""
        out: dict[str, Any] = {
            "name": self.branch.name,
            "stages": [
                {"efficiency": eta, "power": p} for eta, p in zip(self.branch.stages, self.stage_powers, strict=True)
            ],
            "efficiency": self.efficiency,
            "path_efficiency": self.path_efficiency,
            "power": self.power,
            "motor_power": self.motor_power,
            "load_power": self.delivered,
            "losses": self.losses,
        }
        if self.branches:
            out["branches"] = [b.to_dict() for b in self.branches]
        return out


@dataclass(frozen=True)
class PowerFlow:
    """A power chain's answer: the motor's power, the power delivered, the overall efficiency (SI, W)."""

    trunk: BranchFlow

    @property
    def motor_power(self) -> float:
        """P_in, what the motor gives [W]."""
        return self.trunk.motor_power

    @property
    def delivered(self) -> float:
        """Σ P_out, what the machines at the leaves deliver [W]."""
        return self.trunk.delivered

    @property
    def efficiency(self) -> float:
        """The chain's overall efficiency Σ P_out / P_in [-]."""
        return self.delivered / self.motor_power

    @property
    def losses(self) -> float:
        """P_in − Σ P_out [W]."""
        return self.trunk.losses

    def to_dict(self) -> dict[str, Any]:
        """The fields of ``flyopt solve --json`` for a [power_chain] (SI)."""
        return {
            "motor_power": self.motor_power,
            "load_power": self.delivered,
            "efficiency": self.efficiency,
            "losses": self.losses,
            "trunk": self.trunk.to_dict(),
        }


def power_flow(trunk: PowerBranch) -> PowerFlow:
    """The powers of a power chain driven by one motor at the start of ``trunk``.

    Parameters
    ----------
    trunk : PowerBranch
        The stages from the motor and what they drive.

    Returns
    -------
    PowerFlow
        The motor's power, Σ P_out, the overall efficiency Σ P_out / P_in, and the
        powers of every branch.

    Raises
    ------
    ValueError
        An efficiency outside (0, 1], a leaf's power not positive, a branch with
        both or neither of a power and branches.

    Notes
    -----
    Every power is :func:`motor_power` of the leaves below the point it is taken at:
    the power entering a stage is Σ P_k / η_k over the leaves k it feeds, η_k the
    product of the stages between (the books' P_d = P_r / (η_1 η_2 ⋯), added over
    the branches).
    """
    return PowerFlow(_flow(trunk, ()))


def _flow(branch: PowerBranch, upstream: tuple[float, ...]) -> BranchFlow:
    if (branch.power is None) == (not branch.branches):
        raise ValueError(f"branch {branch.name!r} must have either a power or branches, not both or neither")
    if branch.power is not None and not (math.isfinite(branch.power) and branch.power > 0):
        raise ValueError(f"branch {branch.name!r}: the power delivered must be positive, got {branch.power!r}")
    leaves = branch.leaves()
    own = len(branch.stages)
    return BranchFlow(
        branch=branch,
        stage_powers=tuple(motor_power((p, path[k:]) for p, path in leaves) for k in range(own)),
        power=motor_power((p, path[own:]) for p, path in leaves),
        efficiency=series_efficiency(branch.stages),
        path_efficiency=series_efficiency(upstream + branch.stages),
        motor_power=motor_power((p, upstream + path) for p, path in leaves),
        delivered=math.fsum(p for p, _ in leaves),
        branches=tuple(_flow(child, upstream + branch.stages) for child in branch.branches),
    )
